"""Receding contacts on a rough (compliant) interface (thesis conclusions, future work 8).

``sweep``   points, sweeps over the compliance C and profiles of the lift-off problems on a
            compliant interface, and the tested pairs' measured laws
``cli``     the commands ``rough-sweep``, ``rough-gather``, ``rough-profile``,
            ``rough-pairs`` and ``report-rough``
``report``  the report section (52)

Two parts of the rough interface stay lower, because the layers below this package use them:
the interface laws (smooth, linear, measured; :mod:`contactlab.receding.core.interface`,
with :mod:`~contactlab.receding.core.bridge` and :mod:`~contactlab.receding.core.measured_law`)
are values of every problem's ``Point`` and are read by every solver, and the rows a compliant
interface adds to the lift-off system (:mod:`contactlab.receding.liftoff.compliant`) are
assembled by the lift-off solver itself (``assemble(..., interface=)``).
"""
