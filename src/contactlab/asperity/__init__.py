"""Asperity models of thesis chapter 3.

* :mod:`~contactlab.asperity.single`: single-asperity tangential relations (sec. 3.2,
  eqs 3.1-3.5, 3.8, 3.10) and the Hertz references of Figs 3.4, 3.5 and 3.8.
* :mod:`~contactlab.asperity.tangential`: boundary element partial-slip model of two
  identical spheres (Fig. 3.6) with Coulomb, shear-limit and combined laws.
* :mod:`~contactlab.asperity.multi`: independent asperities with distributed loads
  (sec. 3.3.1, eqs 3.11-3.23, Table 3.1, Fig. 3.10).
* :mod:`~contactlab.asperity.grid`: fixed and expanding grids with interaction through
  Hertz pressures (sec. 3.3.2, eqs 3.24-3.29, Figs 3.12-3.16).
* :mod:`~contactlab.asperity.normal`: FFT boundary element normal contact solver used to
  solve the same grids without the Hertz-independence assumption.
* :mod:`~contactlab.asperity.datasets`, :mod:`~contactlab.asperity.report`,
  :mod:`~contactlab.asperity.cli`: netCDF results, report section, command line.
"""
