"""Frictional receding contacts by distributed dislocations (thesis Part III, chs 4-5).

Layout of the subpackage (pure cores first, I/O at the edge):

``kernels``       Green's functions of a dislocation beneath the free surface (App. B.1)
``quadrature``    Gauss-Chebyshev rules for bounded densities, exact Cauchy transforms
                  on and off the interval, Gauss-Legendre on finite and semi-infinite intervals
``bilateral``     bilateral tractions by integrating Flamant's solution (eqs 5.1-5.2)
``dislocations``  density intervals: influence matrices, densities, relative displacements
``solve``         linear solve for fixed transition points + root finding on leftover equations
``gap``           the semi-infinite pressure patch problem of ch. 5 (the "gap" problem)
``sweep``         parameter sweeps, regime boundaries and profiles as xarray datasets
``loading``       symmetric loads p(x) of chs 6-7 (line, uniform, hertz, punch, table):
                  bilateral tractions and the remote climb form by integration
``preformed``     the preformed climb density A_y and its stresses (Cauchy part exact)
``remote``        remote forms of the densities and the remote slip relation (eq. 6.32)
``liftoff``       the lifting-off problem of secs 6.2-6.4, 7.4 (and the Chaise model)
``line``/``patch``  the line load (ch. 6) and pressure patches (ch. 7)
``frictionless``  their f = 0 limit (whole-line glide density)
``liftoff_sweep`` sweeps over f and w/c, profiles; ``liftoff_cli``/``liftoff_report``
``cli``/``report``  command line and report section

Normalisation used throughout (Part III): lengths in units of the layer thickness c
(``x_hat = x/c``), tractions in units of the applied pressure p, dislocation densities as
``B_bar = 2 mu B / ((kappa + 1) p)`` so that a traction is ``(1/pi) int H(x_hat - xi_hat)
B_bar(xi_hat) dxi_hat`` (eq. 4.1), and relative displacements as
``2 mu g / ((kappa + 1) p c)``. Receding-contact solutions are independent of the load
level, so these dimensionless numbers are the whole answer.
"""
