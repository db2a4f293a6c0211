"""Finite element cross-checks with CalculiX (thesis ch. 8 and sec. 3.2.2).

The common CalculiX layer, here:

``ccx``/``frd``                   running ccx in a scratch directory, reading .frd/.sta/.dat
``mesh2d``/``deck``/``farfield``  plane-strain strip-on-block meshes and input decks, the
                                  half-plane far field on the block's boundary (sec. 8.2)
``compliance``/``interface_law``  compliant interface: C, C_T -> ccx stiffnesses, patch test
``extrapolate``                   results to a vanishing mesh and an infinite domain

The models:

``stuck_asperity``                3D elastic-perfectly plastic stuck asperity (Fig. 3.8)
``receding``                      the receding-contact models of sec. 8.2-8.3 (its own
                                  package: runs, interface profiles, the mesh and domain
                                  study, two materials, the rough interface, the DDT side,
                                  a model along a load path and its comparison)

``report``/``cli``                the report section and the ``contactlab fe`` commands
"""
