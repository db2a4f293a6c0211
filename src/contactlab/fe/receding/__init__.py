"""Finite element receding-contact models (thesis secs 8.2-8.3) against the distributed
dislocations (DDT).

``run``         build one strip-on-block model, run it with CalculiX, post-process it
``profiles``    interface profiles and transition points from an FE solution
``mesh_study``  the mesh and domain study of one problem against the DDT
``materials``   two materials: a, b and K_T per pair
``rough``       a compliant (rough) interface: runs, mesh series, the table against a DDT
``ddt``         the DDT side of the cross-checks: transition points and profiles
``compare``     agreement with the DDT and convergence
``load_path``   one model along a load path (one ccx step per load factor), zones per step
``history_compare``  a load path on a mesh series against the receding history (panels or DDT)

The CalculiX layer they build on (meshes, decks, ccx, result files) is :mod:`contactlab.fe`.
"""
