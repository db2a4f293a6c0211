"""contactlab: contact mechanics of rough Ti-6Al-4V interfaces and receding contacts.

The science follows the thesis in ``shared/seed`` (the spec); modules cite it by
equation, table and figure number.
"""

__version__ = "0.1.0"
