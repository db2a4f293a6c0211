"""The gap problem of ch. 5: a layer pressed on a half-plane by pressure p on |x| >= w.

``solver`` (regimes stick, slip, slip and separation; thresholds f_stick, f_sep),
``sweep`` (CF datasets over (f, w/c), profiles), ``cli`` and ``report`` (Figs 5.4-5.8).
"""
