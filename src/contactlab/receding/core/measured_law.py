"""The measured interface law of a tested pair (thesis Part II) as receding-contact input.

From a stiffness summary (``results/stiffness/summary.nc``, :func:`contactlab.stiffness.
summary.summary_dataset`: per test and direction the normal fit beta_n [1/um] and P0 [kN]
of eq. (2.2), Kn_An [kN/mm^3] at the test's load, Kt0_An [kN/mm^3], f, Cc = Kt0/Kn and the
nominal area An [mm^2]) :func:`law_from_summary` builds a :class:`StiffnessLaw` per unit
nominal area (eqs 2.4, 2.7):

    k_n(p) = beta_n (p + p0),  p0 = -P0 / An,      k_t0(p) = Cc k_n(p),   slip at f p

(p the nominal pressure in kN/mm^2; see ``core.interface`` for the sign of P0). It gives
the dimensionless interface of a receding contact of a layer of thickness c on a
half-plane (their elastic constants ``core.materials.Materials``, whose composite
compliance C* scales the compliance numbers: C = 1 / (C* c k_n)) loaded
with T (the load per thickness, kN/mm^2: P/c for a line load P, 2 w p / c for a patch of
half-width w and pressure p):

``measured``  (:meth:`StiffnessLaw.measured`): C and C_T = C / Cc at p = T and
              pi0 = p0 / T -- refused (ValueError) when p0 <= 0, because k_n <= 0 at the
              low pressures every contact edge meets;
``linear``    (:meth:`StiffnessLaw.linearised`): the stiffness at one stated pressure,
              k_n(p), k_t = Cc k_n(p), for any fit with k_n(p) > 0 there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from contactlab.receding.core.interface import (
    Interface,
    compliance_number,
    linear_interface,
    measured_interface,
)
from contactlab.receding.core.materials import Materials


@dataclass(frozen=True)
class StiffnessLaw:
    """Eqs (2.4), (2.7) per unit nominal area: ``beta_n`` [1/mm], ``p0`` [kN/mm^2]
    (k_n = beta_n (p + p0) [kN/mm^3]), ``cc`` = k_t0 / k_n, ``f``; ``source`` names the
    test and the directions it was taken from."""

    beta_n: float
    p0: float
    cc: float
    f: float
    source: str = ""

    def __post_init__(self) -> None:
        where = f" ({self.source})" if self.source else ""
        if not (np.isfinite(self.beta_n) and self.beta_n > 0):
            raise ValueError(f"beta_n must be positive{where}, got {self.beta_n} 1/mm")
        if not np.isfinite(self.p0):
            raise ValueError(f"p0 must be finite{where}, got {self.p0}")
        if not (np.isfinite(self.cc) and self.cc > 0):
            raise ValueError(f"Cc (k_t0/k_n) must be positive{where}, got {self.cc}")
        if not (np.isfinite(self.f) and self.f >= 0):
            raise ValueError(f"friction coefficient f must be >= 0{where}, got {self.f}")

    @classmethod
    def from_fit(cls, *, beta_n_per_um: float, P0_kN: float, area_mm2: float, cc: float,
                 f: float, source: str = "") -> StiffnessLaw:
        """The law from the thesis's fit numbers (Tables 2.1, 2.7: beta_n [1/um], P0 [kN]
        of eq. 2.2, per nominal area An [mm^2]) and Cc, f: beta_n -> 1/mm, p0 = -P0/An."""
        if not (np.isfinite(area_mm2) and area_mm2 > 0):
            raise ValueError(f"nominal area An must be positive, got {area_mm2} mm^2")
        return cls(beta_n_per_um * 1e3, -P0_kN / area_mm2, cc, f, source)

    def k_n(self, p: np.ndarray | float) -> np.ndarray:
        """Normal stiffness per unit area [kN/mm^3] at the pressure p [kN/mm^2]."""
        return self.beta_n * (np.asarray(p, dtype=float) + self.p0)

    def closure(self, p: np.ndarray | float) -> np.ndarray:
        """Closure [mm] from first touch (p = 0) to p: ln(1 + p/p0) / beta_n (p0 > 0)."""
        self._check_edge()
        return np.log1p(np.asarray(p, dtype=float) / self.p0) / self.beta_n

    def _check_edge(self) -> None:
        if not self.p0 > 0:
            where = f"{self.source}: " if self.source else ""
            raise ValueError(
                f"{where}p0 = {self.p0:.4g} kN/mm^2 (p0 = -P0/An): the normal stiffness "
                f"k_n = beta_n (p + p0) is <= 0 for p <= {-self.p0:.4g} kN/mm^2, which the "
                "edge of every receding contact meets (p -> 0); use the law linearised at a "
                "stated pressure instead")

    def measured(self, *, T: float, materials: Materials, c: float) -> Interface:
        """The dimensionless measured law (eqs 2.4, 2.7: k_n = beta_n (p + p0), k_t0 =
        Cc k_n) of a layer of thickness c [mm] on a half-plane (``materials``, E in
        kN/mm^2) under the load per thickness T [kN/mm^2]: C, C_T = C/Cc at p = T,
        pi0 = p0/T."""
        self._check_edge()
        if not (np.isfinite(T) and T > 0):
            raise ValueError(f"load per thickness T must be positive, got {T}")
        C = compliance_number(materials, c, float(self.k_n(T)))
        return measured_interface(C, C / self.cc, self.p0 / T)

    def linearised(self, *, pressure: float, materials: Materials, c: float) -> Interface:
        """The linear law with the stiffness at ``pressure`` [kN/mm^2]: C at k_n(pressure),
        C_T at Cc k_n(pressure)."""
        k = float(self.k_n(pressure))
        if not k > 0:
            raise ValueError(f"{self.source + ': ' if self.source else ''}normal stiffness "
                             f"k_n = {k:.4g} kN/mm^3 <= 0 at p = {pressure} kN/mm^2")
        C = compliance_number(materials, c, k)
        return linear_interface(C, C / self.cc)


def _value(ds: xr.Dataset, name: str, test: str, **where: str) -> float:
    if name not in ds:
        raise ValueError(f"stiffness summary has no variable {name!r}")
    if test not in list(ds["test"].values):
        raise ValueError(f"stiffness summary has no test {test!r} (tests: "
                         f"{', '.join(map(str, ds['test'].values))})")
    var = ds[name].sel(test=test)
    for dim, label in where.items():
        if label not in list(var[dim].values):
            raise ValueError(f"stiffness summary: {dim} {label!r} not among "
                             f"{', '.join(map(str, var[dim].values))}")
        var = var.sel({dim: label})
    value = float(var)
    if not np.isfinite(value):
        place = ", ".join(f"{k} {v}" for k, v in where.items())
        raise ValueError(f"stiffness summary: {name} of test {test} ({place}) is missing")
    return value


def law_from_summary(ds: xr.Dataset, test: str, *, normal_direction: str,
                     tangential_direction: str, cc_basis: str) -> StiffnessLaw:
    """The law of ``test`` from a stiffness summary dataset (module docstring):
    beta_n and P0 of the normal fit of ``normal_direction`` (loading or unloading; the
    mean rows carry no fit), f of ``tangential_direction`` (loading, unloading,
    combined), Cc of ``cc_basis`` (mean, loading, unloading), An of the test."""
    return StiffnessLaw.from_fit(
        beta_n_per_um=_value(ds, "beta_n", test, normal_direction=normal_direction),
        P0_kN=_value(ds, "P0", test, normal_direction=normal_direction),
        area_mm2=_value(ds, "nominal_area_mm2", test),
        cc=_value(ds, "Cc", test, basis=cc_basis),
        f=_value(ds, "f", test, tangential_direction=tangential_direction),
        source=f"{test} ({normal_direction} normal fit, {tangential_direction} f, Cc on "
               f"the {cc_basis} Kn)")


#: The keys of a tested pair's law given by its fit's numbers (``StiffnessLaw.from_fit``).
FIT_KEYS = ("beta_n_per_um", "P0_kN", "area_mm2", "cc", "f")
PAIR_LAWS = ("measured", "linearised")


def pair_law(name: str, spec: dict, summary: xr.Dataset | None, *, key: str,
             normal_direction: str, tangential_direction: str, cc_basis: str,
             where: str | None = None) -> tuple[StiffnessLaw, float, str]:
    """The law (eqs 2.4, 2.7), mean pressure [kN/mm^2] and kind (``measured`` or
    ``linearised``) of the tested pair ``name`` of a layer study, checked for the pressures
    a receding contact meets (0 at its edges up to about twice the mean).

    ``spec``: ``from_test`` (a test of the stiffness ``summary``, read as
    :func:`law_from_summary` reads it) or the fit's numbers :data:`FIT_KEYS` (thesis units,
    :meth:`StiffnessLaw.from_fit`); ``law`` (default ``measured``); ``pressure`` (default
    for ``from_test``: the test's max normal load over its nominal area). Every refusal
    is a ValueError naming ``key.name`` and the value at fault: a non-positive stiffness
    (beta_n <= 0, Cc <= 0, or k_n <= 0 at the pressure), f < 0, a measured law whose
    stiffness is <= 0 at the low pressures of the contact edge (p0 <= 0), an unknown test;
    ``where`` replaces ``key.name`` in the messages (e.g. a command-line option).
    """
    where = f"{key}.{name}" if where is None else where
    spec = dict(spec)
    kind = spec.pop("law", "measured")
    if kind not in PAIR_LAWS:
        raise ValueError(f"{where}.law = {kind!r}: use one of {', '.join(PAIR_LAWS)}")
    pressure = spec.pop("pressure", None)
    test = spec.pop("from_test", None)
    if test is not None:
        extra = sorted(set(spec) & set(FIT_KEYS))
        if extra:
            raise ValueError(f"{where}: from_test = {test!r} and the fit's numbers "
                             f"{', '.join(extra)} both given; give one")
        if summary is None:
            raise ValueError(f"{where}.from_test = {test!r} needs a stiffness summary "
                             "(results/stiffness/summary.nc; --summary)")
        tests = [str(t) for t in summary["test"].values]
        if str(test) not in tests:
            raise ValueError(f"{where}.from_test = {test!r}: no such test in the stiffness "
                             f"summary (tests: {', '.join(tests)})")
        try:
            law = law_from_summary(summary, str(test), normal_direction=normal_direction,
                                   tangential_direction=tangential_direction,
                                   cc_basis=cc_basis)
        except ValueError as exc:
            raise ValueError(f"{where}.from_test = {test!r}: {exc}") from None
        if pressure is None:
            load = float(summary["max_normal_load_kN"].sel(test=test))
            area = float(summary["nominal_area_mm2"].sel(test=test))
            pressure = load / area
    else:
        missing = [k for k in FIT_KEYS if k not in spec]
        if missing:
            raise ValueError(f"{where}: give from_test or all of {', '.join(FIT_KEYS)} "
                             f"(missing {', '.join(missing)})")
        for k in ("beta_n_per_um", "area_mm2", "cc"):
            value = float(spec[k])
            if not (np.isfinite(value) and value > 0):
                raise ValueError(f"{where}.{k} = {value:g}: must be positive (a positive "
                                 "stiffness)")
        if not (np.isfinite(float(spec["f"])) and float(spec["f"]) >= 0):
            raise ValueError(f"{where}.f = {float(spec['f']):g}: friction coefficient must "
                             "be >= 0")
        if pressure is None:
            raise ValueError(f"{where}: the fit's numbers need the pressure [kN/mm^2]")
        law = StiffnessLaw.from_fit(**{k: float(spec[k]) for k in FIT_KEYS},
                                    source=f"{name} (fit numbers)")
    pressure = float(pressure)
    if not (np.isfinite(pressure) and pressure > 0):
        raise ValueError(f"{where}.pressure = {pressure:g}: must be positive (kN/mm^2)")
    if not law.f >= 0:
        raise ValueError(f"{where}: friction coefficient f = {law.f:g} must be >= 0")
    k_p = float(law.k_n(pressure))
    if not k_p > 0:
        raise ValueError(f"{where}: normal stiffness k_n = {k_p:.4g} kN/mm^3 <= 0 at the "
                         f"pressure {pressure:g} kN/mm^2 ({law.source})")
    if kind == "measured" and not law.p0 > 0:
        raise ValueError(
            f"{where}.law = 'measured': {law.source}: p0 = -P0/An = {law.p0:.4g} kN/mm^2, "
            f"so the stiffness k_n = beta_n (p + p0) is <= 0 for p <= {-law.p0:.4g} "
            "kN/mm^2, which the edge of the contact meets; use law: linearised")
    return law, pressure, kind
