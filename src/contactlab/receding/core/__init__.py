"""The distributed-dislocation method shared by the receding problems (ch. 4).

Kernels (App. B.1), quadrature, bilateral tractions (eqs 5.1-5.2), density intervals, the
linear solve with root finding on the leftover equations, and the solution protocol with
its contact checks (``solution``); interface laws of a rough interface (``interface``,
``measured_law``) and the bridge densities they need (``bridge``); what a problem is
(``problem``) and the sweep engine of every problem (``sweep``).
"""
