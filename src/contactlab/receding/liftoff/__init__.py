"""Lifting-off receding contacts of chs 6-7: the line load and pressure patches.

``loading``, ``preformed``, ``remote`` and ``solver`` (the method of secs 6.2-6.4, 7.4);
``line`` (ch. 6 and the Chaise et al. model), ``patch`` (ch. 7), ``frictionless`` (f = 0);
``sweep``, ``cli`` and ``report`` (Figs 6.3-6.6, 7.2-7.10); ``compliant`` (a rough,
compliant interface in the same solver: its points, sweeps and profiles are
:mod:`contactlab.receding.rough`).
"""
