"""Frictional receding contacts by distributed dislocations (thesis Part III, chs 4-5).

The problems are objects, one module each in ``problems`` (the gap problem, the line load,
the pressure patches and a user's shape: the list every command, the schema's enums and
the report read); the science is in three sub-packages, pure cores first, I/O at the edge:

``core``     the dislocation method every problem shares: ``kernels`` (Green's functions
             of a dislocation beneath the free surface, App. B.1), ``quadrature``
             (Gauss-Chebyshev rules, exact Cauchy transforms, Gauss-Legendre),
             ``bilateral`` (tractions by integrating Flamant's solution, eqs 5.1-5.2),
             ``dislocations`` (density intervals, influence matrices, relative
             displacements), ``solve`` (linear solve for fixed transition points, root
             finding on the leftover equations), ``solution`` (the solution protocol,
             the contact checks and their tolerance, shared by both problems),
             ``interface`` (rough, compliant interface laws), ``bridge`` (densities
             carried through a transition point), ``measured_law`` (a tested pair's law),
             ``problem`` (what a problem is, the values it takes) and ``sweep`` (the one
             sweep engine: continuation, refinement in N, records, gathering)
``gap``      ch. 5, a pressure on |x| >= w: ``solver``, ``sweep`` (regime maps,
             thresholds, profiles), ``cli`` (``receding gap-...``), ``report``
``liftoff``  chs 6-7, the layer lifts off at all remote points: ``loading`` (the loads
             and their bilateral tractions), ``preformed`` (the preformed climb density
             A_y), ``remote`` (remote forms, the remote slip relation), ``solver`` (the
             method of secs 6.2-6.4, 7.4), ``line`` (ch. 6, with the Chaise et al.
             model), ``patch`` (ch. 7), ``frictionless`` (f = 0), ``sweep``, ``cli``
             (``receding line-sweep``, ``patch-sweep``, ``liftoff-...``), ``report``;
             ``compliant``: the same solver's rows for a rough interface
``rough``    the rough interface: ``sweep`` (points, sweeps over the compliance,
             profiles, the tested pairs), ``cli`` (``receding rough-...``), ``report``

``cli`` holds the ``receding`` command group and ``receding solve`` for any problem on any
interface law it takes.

Normalisation used throughout (Part III): lengths in units of the layer thickness c
(``x_hat = x/c``), tractions in units of the applied pressure p, dislocation densities as
``B_bar = 2 mu B / ((kappa + 1) p)`` so that a traction is ``(1/pi) int H(x_hat - xi_hat)
B_bar(xi_hat) dxi_hat`` (eq. 4.1), and relative displacements as
``2 mu g / ((kappa + 1) p c)``. Receding-contact solutions are independent of the load
level, so these dimensionless numbers are the whole answer.
"""
