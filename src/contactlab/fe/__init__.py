"""Finite element cross-checks with CalculiX (thesis ch. 8 and sec. 3.2.2).

``mesh2d``/``deck``/``receding``  plane-strain strip-on-block receding contacts (sec. 8.2)
``asperity``                      3D elastic-perfectly plastic stuck asperity (Fig. 3.8)
``ccx``/``frd``                   running ccx in a scratch directory, reading .frd/.sta/.dat
``interface``                     transition points from interface tractions
``interface_law``/``rough``       compliant (rough) interface: C, C_T -> ccx stiffnesses, the
                                  patch test, runs, mesh series, the table against a DDT
``ddt``/``compare``               distributed-dislocation references, agreement, convergence
``load_path``/``history_compare``  a model along a load path (one *STEP per factor), its
                                  zones per step, against the DDT history
``workflow``/``cli``              rule helpers and the ``contactlab fe`` commands
"""
