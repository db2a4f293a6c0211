"""Predicted beside measured stiffness of every test (Tables 2.1-2.4, 2.7-2.10 quantities).

Per test and material model (``elastic``, ``plastic``) from ``results/prediction/<test>.nc``:
Kn/An at the test's load (tangent of the predicted curve and eq. 2.4 from the fitted
eq. 2.2), beta_n, beta_n * Seq, the fully stuck Kt0/An and Cc, and Kt0/An and Cc with
Coulomb partial slip at the test's measured friction coefficient f.

Partial slip as the test loads it. Each tangential step of the thesis is a fully
reversed cycle between ``-Qmax`` and ``Qmax = r Pn`` with ``r = 1/8`` (sec. 2.3.1), and
Kt0 is the slope of the fitted eq. (2.3) at ``Qt = 0``. Under constant pressure and
decoupled normal and tangential problems (identical materials) Coulomb partial slip
follows Masing's rule for any contact shape (Jäger 1998; Ciavarella 1998): the branch
from ``(-v*, -Qmax)`` is ``Q = -Qmax + 2 F((v + v*)/2)`` with ``F`` the first-loading
curve. So Kt0 at ``Qt = 0`` is the slope of the first-loading curve at ``Qmax/2``
(``Kt0_An_slip``), and eq. (2.3) fitted to 21 points of the branch as the thesis fits a
step gives ``Kt0_An_slip_fit`` and the friction coefficient the fit infers. The
first-loading curve is the per-test ``f = 1`` curve scaled by f (:mod:`.tangential`).

The friction the fit infers. ``|Qs/Pn|`` of eq. (2.3) fitted to a cycle that reaches
only ``r Pn`` extrapolates the asymptote; for the predicted cycles it differs from the
friction coefficient the model was given. So the measured f is itself a fit result, and
the model's friction coefficient that reproduces it through the same fit,
``f_consistent`` with ``f_fit(f_consistent) = f measured``, is found by root finding;
``Kt0_An_consistent`` and ``Cc_consistent`` are the cycle's values at that friction
(NaN where no friction in ``(r / 0.97, 10 f]`` reproduces the measured f).

Measured values come from the stiffness summaries (``results/stiffness/summary.nc``
from raw data and ``summary_from_published_steps.nc``): loading Kn/An and beta_n
(Tables 2.1/2.7 and what Tables 2.3/2.10 use), combined Kt0/An and f (Tables 2.2/2.8)
and Cc on the mean basis (Tables 2.4/2.9); beta_n * Seq uses the scans' Seq, the same
for measured and predicted.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.interpolate import PchipInterpolator

from contactlab.prediction.pair import PER_UM
from contactlab.prediction.validation import SphereCheck

Array = NDArray[np.float64]

#: Points of the reversed branch fitted with eq. (2.3).
BRANCH_POINTS = 21
#: Sources of measured values and the stiffness summary each is read from.
SOURCES = ("raw", "published_steps")


def first_loading(q_over_fpn: Array, displacement_over_f: Array) -> PchipInterpolator:
    """Monotone interpolant of Q/(f Pn) against v/f (um), through the origin."""
    w = np.concatenate([[0.0], np.asarray(displacement_over_f, float)])
    s = np.concatenate([[0.0], np.asarray(q_over_fpn, float)])
    order = np.argsort(w)
    return PchipInterpolator(w[order], s[order], extrapolate=False)


def _inverse(curve: PchipInterpolator, level: float) -> float:
    """Displacement (over f) where the curve reaches ``level``; NaN beyond its end."""
    w = curve.x
    s = curve(w)
    if not 0 <= level <= s[-1]:
        return float("nan")
    from scipy.optimize import brentq

    k = int(np.searchsorted(s, level))
    if k == 0:
        return 0.0
    return float(brentq(lambda x: float(curve(x)) - level, w[k - 1], w[k]))


def cycle_stiffness(q_over_fpn: Array, displacement_over_f: Array, f: float, ratio: float,
                    pressure: float, area_mm2: float) -> dict[str, float]:
    """Kt0 of the reversed cycle ``+-ratio Pn`` at friction ``f`` (module docstring).

    ``pressure``: the test's nominal pressure (kN/mm^2); returns ``Kt0_An_slip``,
    ``Kt0_An_slip_fit`` (kN/mm^3), ``f_fit`` and ``beta_t_fit`` (1/um); NaN when f is
    unknown or the cycle's load is beyond the computed curve (gross slip for
    ``ratio >= f``).
    """
    nan = {"Kt0_An_slip": np.nan, "Kt0_An_slip_fit": np.nan, "f_fit": np.nan,
           "beta_t_fit": np.nan}
    if not (np.isfinite(f) and f > 0):
        return nan
    curve = first_loading(q_over_fpn, displacement_over_f)
    half = _inverse(curve, ratio / (2 * f))
    out = dict(nan)
    if np.isfinite(half):
        out["Kt0_An_slip"] = PER_UM * pressure * float(curve.derivative()(half))
    top = _inverse(curve, ratio / f)
    if not np.isfinite(top):
        return out
    from contactlab.stiffness.fit import fit_step

    load = pressure * area_mm2  # Pn, kN
    v_star = f * top
    v = np.linspace(-v_star, v_star, BRANCH_POINTS)
    q = -ratio * load + 2 * f * load * curve((v + v_star) / (2 * f))
    fit = fit_step(v, q, "tangential", label="predicted reversed cycle")
    if fit.converged:
        beta, qs = fit.values["beta_t"], fit.values["Qs"]
        out.update(Kt0_An_slip_fit=-PER_UM * beta * qs / area_mm2, f_fit=abs(qs) / load,
                   beta_t_fit=beta)
    return out


def consistent_friction(q_over_fpn: Array, displacement_over_f: Array, f_measured: float,
                        ratio: float, pressure: float, area_mm2: float) -> float:
    """The friction coefficient whose cycle, fitted with eq. (2.3), gives ``f_measured``."""
    if not (np.isfinite(f_measured) and f_measured > 0):
        return float("nan")
    reach = float(np.max(q_over_fpn))

    def excess(f: float) -> float:
        fit = cycle_stiffness(q_over_fpn, displacement_over_f, f, ratio, pressure, area_mm2)
        return fit["f_fit"] - f_measured

    lo, hi = 1.001 * ratio / reach, 10.0 * f_measured
    if lo >= hi:
        return float("nan")
    grid = np.geomspace(lo, hi, 25)
    values = np.array([excess(f) for f in grid])
    ok = np.isfinite(values)
    change = np.nonzero(ok[:-1] & ok[1:] & (np.sign(values[:-1]) != np.sign(values[1:])))[0]
    if change.size == 0:
        return float("nan")
    from scipy.optimize import brentq

    k = int(change[0])
    return float(brentq(excess, grid[k], grid[k + 1], xtol=1e-6 * f_measured))


def _measured(summary: xr.Dataset | None, test: str, seq: float) -> dict[str, float]:
    keys = ("Kn_An", "beta_n", "beta_n_Seq", "Kt0_An", "f", "Cc")
    if summary is None or test not in summary["test"].values:
        return dict.fromkeys(keys, np.nan)
    row = summary.sel(test=test)
    beta = float(row["beta_n"].sel(normal_direction="loading"))
    return {"Kn_An": float(row["Kn_An"].sel(normal_direction="loading")),
            "beta_n": beta, "beta_n_Seq": beta * seq,
            "Kt0_An": float(row["Kt0_An"].sel(tangential_direction="combined")),
            "f": float(row["f"].sel(tangential_direction="combined")),
            "Cc": float(row["Cc"].sel(basis="mean"))}


PREDICTED = {
    "Kn_An": ("kN/mm3", "Kn/An at the test's load, tangent of the predicted curve"),
    "Kn_An_fit": ("kN/mm3", "Kn/An at the test's load by eq. (2.4) from the fitted eq. (2.2)"),
    "beta_n": ("1/um", "beta_n of eq. (2.2) fitted to the predicted loading curve"),
    "beta_n_Seq": ("1", "predicted beta_n * Seq"),
    "Kt0_An_stuck": ("kN/mm3", "Kt0/An, fully stuck, along the load"),
    "Kt0_An_stuck_y": ("kN/mm3", "Kt0/An, fully stuck, across the load"),
    "Cc_stuck": ("1", "Cc = Kt0/Kn, fully stuck"),
    "Cc_set": ("1", "stuck Kt over the normal stiffness of the same contact set"),
    "Kt0_An_slip": ("kN/mm3", "Kt0/An of the reversed cycle at the measured f (Masing)"),
    "Kt0_An_slip_fit": ("kN/mm3", "Kt0/An by eq. (2.3) fitted to the reversed cycle"),
    "f_fit": ("1", "friction coefficient |Qs/Pn| of the eq. (2.3) fit to the cycle"),
    "beta_t_fit": ("1/um", "beta_t of the eq. (2.3) fit to the cycle"),
    "Cc_slip": ("1", "Cc = Kt0/Kn with partial slip at the measured f"),
    "f_consistent": ("1", "friction coefficient whose eq. (2.3) fit gives the measured f"),
    "Kt0_An_consistent": ("kN/mm3", "Kt0/An of the cycle at f_consistent"),
    "Cc_consistent": ("1", "Cc = Kt0/Kn with partial slip at f_consistent"),
    "contact_fraction": ("1", "real contact fraction at the test's load"),
    "plastic_fraction": ("1", "plastic contact fraction at the test's load"),
    "converged": ("1", "every solution of the test converged"),
}
MEASURED = {
    "Kn_An": ("kN/mm3", "measured Kn/An, loading (Tables 2.1, 2.7)"),
    "beta_n": ("1/um", "measured beta_n, loading (Tables 2.1, 2.7)"),
    "beta_n_Seq": ("1", "measured loading beta_n times Seq from the scans"),
    "Kt0_An": ("kN/mm3", "measured Kt0/An, combined (Tables 2.2, 2.8)"),
    "f": ("1", "measured friction coefficient, combined (Tables 2.2, 2.8)"),
    "Cc": ("1", "measured Cc, mean basis (Tables 2.4, 2.9)"),
}


def summarize(predictions: list[xr.Dataset], measured: dict[str, xr.Dataset | None],
              ratio: float, check: SphereCheck | None = None) -> xr.Dataset:
    """One dataset: predicted (test, variant) beside measured (test, source), and the
    solvers' check on a sphere (:func:`.validation.sphere`) when given. Tests measured from
    raw data without a prediction (the test sheet names no surfaces for them) are named in
    the attribute ``tests_without_prediction``."""
    if not predictions:
        raise ValueError("no prediction results to summarize")
    if not 0 < ratio < 1:
        raise ValueError(f"tangential load ratio {ratio} must be in (0, 1)")
    tests = [str(ds.attrs["test"]) for ds in predictions]
    variants = list(dict.fromkeys(str(v) for ds in predictions for v in ds["variant"].values))
    pred = {k: np.full((len(tests), len(variants)), np.nan) for k in PREDICTED}
    meas = {k: np.full((len(tests), len(SOURCES)), np.nan) for k in MEASURED}
    f_used = np.full(len(tests), np.nan)
    f_source = []
    for i, ds in enumerate(predictions):
        seq = float(ds["Seq"])
        for j, source in enumerate(SOURCES):
            for key, value in _measured(measured.get(source), tests[i], seq).items():
                meas[key][i, j] = value
        f_i = next((meas["f"][i, j] for j in range(len(SOURCES))
                    if np.isfinite(meas["f"][i, j])), np.nan)
        f_used[i] = f_i
        f_source.append(next((SOURCES[j] for j in range(len(SOURCES))
                              if np.isfinite(meas["f"][i, j])), "none"))
        p_max = float(ds["Pn_An"].values[-1])
        area = float(ds["nominal_area"])
        for v in ds["variant"].values:
            j = variants.index(str(v))
            row = ds.sel(variant=v)
            kn = float(row["Kn_An_max"])
            cycle = cycle_stiffness(row["slip_Q_over_fPn"].values,
                                    row["slip_displacement_over_f"].values, f_i, ratio,
                                    p_max, area)
            f_c = consistent_friction(row["slip_Q_over_fPn"].values,
                                      row["slip_displacement_over_f"].values, f_i, ratio,
                                      p_max, area)
            at_c = cycle_stiffness(row["slip_Q_over_fPn"].values,
                                   row["slip_displacement_over_f"].values, f_c, ratio, p_max,
                                   area)
            values = {
                "f_consistent": f_c, "Kt0_An_consistent": at_c["Kt0_An_slip"],
                "Cc_consistent": at_c["Kt0_An_slip"] / kn,
                "Kn_An": kn, "Kn_An_fit": float(row["Kn_An_fit"]),
                "beta_n": float(row["beta_n"]), "beta_n_Seq": float(row["beta_n_Seq"]),
                "Kt0_An_stuck": float(row["Kt0_An_stuck"].sel(direction="x")),
                "Kt0_An_stuck_y": float(row["Kt0_An_stuck"].sel(direction="y")),
                "Cc_stuck": float(row["Cc_stuck"]), "Cc_set": float(row["Cc_set"]),
                **cycle, "Cc_slip": cycle["Kt0_An_slip"] / kn,
                "contact_fraction": float(row["contact_fraction_max"]),
                "plastic_fraction": float(row["plastic_fraction_max"]),
                "converged": float(all(bool(np.all(row[k].values)) for k in row.data_vars
                                       if k.endswith("converged"))),
            }
            for key, value in values.items():
                pred[key][i, j] = value
    out = xr.Dataset(coords={
        "test": ("test", np.array(tests, dtype=object), {"long_name": "test id"}),
        "variant": ("variant", np.array(variants, dtype=object),
                    {"long_name": "material model of the prediction"}),
        "source": ("source", np.array(SOURCES, dtype=object),
                   {"long_name": "measured values from raw data or from the published steps"}),
    })
    for key, (units, name) in PREDICTED.items():
        out[f"predicted_{key}"] = (("test", "variant"), pred[key],
                                   {"long_name": f"predicted {name}", "units": units})
    for key, (units, name) in MEASURED.items():
        out[f"measured_{key}"] = (("test", "source"), meas[key],
                                  {"long_name": name, "units": units})
    out["f_used"] = ("test", f_used, {"long_name": "measured f used for partial slip",
                                      "units": "1"})
    out["f_source"] = ("test", np.array(f_source, dtype=object),
                       {"long_name": "source of the f used"})
    scalars = {"Seq": ("um", "equivalent roughness Seq, eq. (2.1), from the scans"),
               "Str_composite": ("1", "texture aspect ratio Str of the composite"),
               "Sq_composite": ("um", "Sq of the composite at native resolution"),
               "mindlin_ratio": ("1", "Mindlin ratio 2(1 - nu)/(2 - nu)")}
    for key, (units, name) in scalars.items():
        out[key] = ("test", np.array([float(ds[key]) for ds in predictions]),
                    {"long_name": name, "units": units})
    out.attrs["tangential_load_ratio"] = ratio
    raw = measured.get("raw")
    unpredicted = [str(t) for t in (raw["test"].values if raw is not None else [])
                   if str(t) not in tests]
    if unpredicted:  # the test sheet names no surfaces for them
        out.attrs["tests_without_prediction"] = ", ".join(unpredicted)
    if check is not None:
        out = out.merge(validation_dataset(check))
    return out


def validation_dataset(check: SphereCheck) -> xr.Dataset:
    """The sphere check as variables ``validation_*`` (relative errors, dimensionless)."""
    one = {"units": "1"}
    return xr.Dataset({
        "validation_cells_per_radius": ((), check.cells_per_radius,
                                        {"long_name": "BEM cells per Hertz contact radius", **one}),
        "validation_hertz_error": ((), check.approach_error, {
            "long_name": "relative error of the Hertz approach at the load", **one}),
        "validation_stuck_error": ((), check.stuck_error, {
            "long_name": "relative error of the stuck tangential stiffness 8 G* a", **one}),
        "validation_normal_set_error": ((), check.normal_set_error, {
            "long_name": "relative error of the contact-set normal stiffness 2 E* a", **one}),
        "validation_mindlin_ratio": ((), check.mindlin_ratio, {
            "long_name": "Kt/Kn of the BEM sphere contact (Mindlin ratio)", **one}),
        "validation_compliance_error": (("validation_point",), check.compliance_error, {
            "long_name": "relative error of the tangential compliance against "
                         "Cattaneo-Mindlin", **one}),
        "validation_converged": ((), np.int8(check.converged), {
            "long_name": "every solution of the sphere check converged", **one}),
    }, coords={"validation_point": ("validation_point", check.q_ratio, {
        "long_name": "Q/(f P) of the Cattaneo-Mindlin check point", **one})})
