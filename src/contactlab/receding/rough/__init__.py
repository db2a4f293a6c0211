"""Receding contacts on a rough (compliant) interface, as workflow steps: the commands
(``cli``: ``rough-sweep``, ``rough-gather``, ``rough-profile``, ``rough-pairs``,
``report-rough``) and the report section (``report``). The science is
:mod:`contactlab.receding.liftoff.rough` and :mod:`contactlab.receding.core.interface`.
"""
