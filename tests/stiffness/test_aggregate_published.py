"""The published per-step values through the aggregation code against the thesis tables.

Inputs are the printed per-step fit parameters (Appendix A tables A.2-A.37), the printed
normal-fit parameters (Tables 2.1, 2.7) and Seq from the printed Sq.  Those are rounded to
the printed digits, and the thesis computed its tables from unrounded values, so a
recomputed cell "reproduces" the printed one when

    |ours - printed| <= half a unit of the printed last digit + input-rounding bound,

the bound being the linearised worst case of every input moved by half a unit of its own
printed last digit (:func:`rounding_bound`).  Every cell outside that is listed in
``EXPECTED_DIFFERENCES`` with the reason; the tests fail if any other cell differs or if a
listed cell stops differing.

Error-model finding (see contactlab.stiffness.errors): the published friction margins use
the tangential-step load error with the gauge pressure pn = Pn A / 10 (2.6 MPa at 4 kN)
instead of the text's Pn/A (6.15 MPa), and add the extra 1% of Qs linearly; the Kt0 margins
use the fit margin of Qs only.  ``ErrorModel(tangential_pressure="multiply")`` reproduces
them; the text's formula does not (test_text_pressure_formula_misses_the_published_f_margins).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np
import pandas as pd
import pytest

from contactlab.published import PER_STEP_FIT_TABLES, per_step_fits, read_published
from contactlab.stiffness.aggregate import (
    beta_n_seq,
    coupling,
    normal_stiffness,
    select_steps,
    step_quantities,
    tangential_means,
)
from contactlab.stiffness.compare import (
    THESIS_DISCREPANCIES,
    compare_with_published,
    printed_decimals,
)
from contactlab.stiffness.errors import ErrorModel, kn_margin
from contactlab.surfaces.roughness import published_roughness
from contactlab.surfaces.seq import seq_dataset
from contactlab.testsheet import read_test_sheet

PUBLISHED_MODEL = ErrorModel(tangential_pressure="multiply")

#: (path, table, test, direction or basis, quantity) -> reason.  path "parameters": recomputed
#: from the printed fit parameters; "printed": aggregated from the printed derived values
#: (per-step Kt0/An, f, Kn/An and margins).  Cells not listed must reproduce.
# The "parameters" cells are THESIS_DISCREPANCIES (contactlab.stiffness.compare):
# - 2.1 SU1 unloading Kn_An / Kn_An_moe (and the SU1 mean row, and Cc of 2.4 SU1 mean and
#   unloading with our Kn): the printed Kn/An = 200.040 is beta_n (Pn - alpha_n) =
#   1.389 (4 - 1.120)/20 = 200.02, i.e. the thesis used the printed alpha_n (1.120) as P0;
#   with the printed P0 (2.772) Kn/An = 85.28.  Its margin 38.297 is eq. (2.8) with
#   P0 = 2.772 +/- 0.150 but the relative margin applied to 200.04 (0.1915 * 200.04).
# - 2.1 RU1 unloading Kn_An: the printed 101.490 needs |Pn| - P0 = 3.7800 +/- 0.0035 from
#   beta_n = 0.537 +/- 0.0005, i.e. |Pn| = 3.996 +/- 0.004 kN with P0 = 0.216: evaluated at a
#   measured maximum load just under the nominal 4 kN (0.1%, just beyond the tolerance).
# - 2.1 mean rows beta_n_moe: printed sqrt(d_load^2 + d_unload^2), the margin of the sum,
#   not of the mean, e.g. RU1 sqrt(0.014^2 + 0.035^2) = 0.0377 -> 0.038; ours 0.019.  The
#   Kn_An mean margins of the same rows and the beta_n mean margins of Table 2.7 are /2.
EXPECTED_DIFFERENCES: dict[tuple[str, str, str, str, str], str] = {
    **{("parameters", *key): why for key, why in THESIS_DISCREPANCIES.items()},
    **{("printed", "2.1", test, "mean", "beta_n_moe"): "thesis omitted /2 in the mean margin"
       for test in ("RU1", "RU2", "RU3", "SU1", "SU2", "SU3")},
    # Table 2.7, S1 mean: sqrt(7.579^2 + 6.986^2)/2 = 5.154 from the printed rows, printed
    # 5.161; rounding of the row margins moves it by 0.0005 at most.  Thesis arithmetic slip
    # (5.161 would need 7.599 or 7.007).  From the parameters the tolerance (beta_n_moe
    # printed to 3 decimals, 0.019 +/- 2.6%) covers it.
    ("printed", "2.7", "S1", "mean", "Kn_An_moe"): "thesis arithmetic: 5.154, printed 5.161",
}


# ----------------------------------------------------------------------------- helpers


@pytest.fixture(scope="module")
def tests_sheet(repo) -> pd.DataFrame:
    return read_test_sheet(repo / "config" / "tests.csv")


@pytest.fixture(scope="module")
def steps() -> pd.DataFrame:
    return per_step_fits()


@pytest.fixture(scope="module")
def step_decimals() -> pd.DataFrame:
    return pd.concat([printed_decimals(t) for t in PER_STEP_FIT_TABLES], ignore_index=True)


@pytest.fixture(scope="module")
def normal() -> pd.DataFrame:
    return pd.concat([read_published("2.1"), read_published("2.7")], ignore_index=True)


@pytest.fixture(scope="module")
def normal_decimals() -> pd.DataFrame:
    return pd.concat([printed_decimals("2.1"), printed_decimals("2.7")], ignore_index=True)


def half_unit(decimals: pd.Series) -> np.ndarray:
    d = decimals.to_numpy().astype(float)
    return np.where(d >= 0, 0.5 * 10.0 ** (-d), 0.0)


def rowwise_bound(compute: Callable[[pd.DataFrame], pd.DataFrame], inputs: pd.DataFrame,
                  halves: dict[str, np.ndarray], outputs: list[str]) -> pd.DataFrame:
    """Output with ``<col>_bound`` columns for a row-wise ``compute`` (row i of the output
    depends on row i of the input only): the linearised worst case of each input cell moving
    by its half unit, summed over the input columns."""
    base = compute(inputs)
    bound = pd.DataFrame(0.0, index=base.index, columns=outputs)
    for col, half in halves.items():
        changes = []
        for sign in (1.0, -1.0):
            moved = inputs.copy()
            moved[col] = inputs[col] + sign * half
            changes.append((compute(moved)[outputs] - base[outputs]).abs().fillna(0.0))
        bound = bound + np.maximum(changes[0], changes[1])
    return pd.concat([base, bound.add_suffix("_bound")], axis=1)


def outward_bound(compute: Callable[[pd.DataFrame], pd.DataFrame], inputs: pd.DataFrame,
                  bounds: dict[str, np.ndarray], outputs: list[str]) -> pd.DataFrame:
    """Output with ``<col>_bound`` for means of magnitudes: every input pushed outward
    (|v| + b) and inward (|v| - b, not through zero); the bound is the larger change."""
    base = compute(inputs)
    extremes = []
    for sign in (1.0, -1.0):
        moved = inputs.copy()
        for col, b in bounds.items():
            v = inputs[col].to_numpy(dtype=float)
            mag = np.maximum(np.abs(v) + sign * b, 0.0)
            moved[col] = np.where(v < 0, -mag, mag)
        extremes.append((compute(moved)[outputs] - base[outputs]).abs().fillna(0.0))
    bound = np.maximum(extremes[0], extremes[1])
    return pd.concat([base, bound.add_suffix("_bound")], axis=1)


def corner_bound(compute: Callable[[pd.DataFrame], pd.DataFrame], inputs: pd.DataFrame,
                 bounds: dict[str, np.ndarray], outputs: list[str]) -> pd.DataFrame:
    """Output with ``<col>_bound``: largest change over all 2^k corners of the input box."""
    base = compute(inputs)
    bound = pd.DataFrame(0.0, index=base.index, columns=outputs)
    for signs in itertools.product((1.0, -1.0), repeat=len(bounds)):
        moved = inputs.copy()
        for sign, (col, b) in zip(signs, bounds.items(), strict=True):
            moved[col] = inputs[col] + sign * b
        bound = np.maximum(bound, (compute(moved)[outputs] - base[outputs]).abs().fillna(0.0))
    return pd.concat([base, bound.add_suffix("_bound")], axis=1)


def check(path: str, table: str, ours: pd.DataFrame, published: pd.DataFrame,
          keys: list[str], columns: list[str]) -> list[str]:
    """Cells outside tolerance that are not listed, and listed cells that reproduce."""
    decimals = printed_decimals(table).loc[published.index]
    cmp = compare_with_published(ours, published, keys, columns, decimals)
    bound_cols = [f"{c}_bound" for c in columns if f"{c}_bound" in ours]
    bounds = ours.loc[:, keys + bound_cols].melt(id_vars=keys, var_name="quantity",
                                                 value_name="bound")
    bounds["quantity"] = bounds["quantity"].str.removesuffix("_bound")
    cmp = cmp.merge(bounds.drop_duplicates([*keys, "quantity"]), on=[*keys, "quantity"],
                    how="left")
    cmp["bound"] = cmp["bound"].fillna(0.0)
    problems = []
    for row in cmp.to_dict("records"):
        key = (path, table, *(str(row[k]) for k in keys), row["quantity"])
        key = key if len(keys) == 2 else (*key[:3], "", key[3])
        tolerance = row["half_unit"] + row["bound"] + 1e-9
        ok = abs(row["ours_minus_published"]) <= tolerance
        if key in EXPECTED_DIFFERENCES:
            if ok:
                problems.append(f"{key}: listed as differing but reproduces")
        elif not ok:
            problems.append(f"{key}: ours {row['ours']:.5g}, printed {row['published']:.5g}, "
                            f"tolerance {tolerance:.3g}")
    return problems


# ------------------------------------------------------------------ per-step (Appendix A)

STEP_INPUTS = ["beta_t", "beta_t_moe", "Qs", "Qs_moe"]
STEP_OUTPUTS = ["Kt0_An", "Kt0_An_moe", "f", "f_moe"]


def _step_values(tests_sheet, steps, step_decimals) -> pd.DataFrame:
    def compute(df: pd.DataFrame) -> pd.DataFrame:
        return step_quantities(df, tests_sheet, PUBLISHED_MODEL)

    halves = {c: half_unit(step_decimals[c]) for c in STEP_INPUTS}
    return rowwise_bound(compute, steps, halves, [*STEP_OUTPUTS, "beta_t", "beta_t_moe"])


def test_step_values_reproduce_appendix_a(tests_sheet, steps, step_decimals) -> None:
    """Kt0/An, its margin, f and its margin of all 85 steps from beta_t, Qs and margins."""
    ours = _step_values(tests_sheet, steps, step_decimals)
    for col in STEP_OUTPUTS:
        bad = (ours[col] - steps[col]).abs() > (half_unit(step_decimals[col])
                                                + ours[f"{col}_bound"] + 1e-9)
        assert not bad.any(), (col, steps.loc[bad, ["test", "direction", "step"]].to_numpy())


def test_text_pressure_formula_misses_the_published_f_margins(tests_sheet, steps) -> None:
    """With pn = Pn/A (sec. 2.5.2 text) the f margins of RU1 (4 kN) come out 5-11% low."""
    text = step_quantities(steps, tests_sheet, ErrorModel(tangential_pressure="divide"))
    ru1 = (steps["test"] == "RU1") & (steps["direction"] == "unloading")
    ratio = text.loc[ru1, "f_moe"] / steps.loc[ru1, "f_moe"]
    assert (ratio < 0.96).all()
    assert ((text.loc[ru1, "f_moe"] - steps.loc[ru1, "f_moe"]).abs() > 0.0015).sum() >= 3


def test_kt0_margin_has_no_extra_one_percent(tests_sheet, steps) -> None:
    """Eq. (2.9) uses the fit margin of Qs; adding 1% of Qs misses e.g. RU2 unloading 1."""
    q = step_quantities(steps, tests_sheet, PUBLISHED_MODEL)
    row = q[(q.test == "RU2") & (q.direction == "unloading") & (q.step == 1)].iloc[0]
    with_extra = row.Kt0_An * np.hypot(row.beta_t_moe / row.beta_t,
                                       row.Qs_moe / row.Qs + 0.01)
    printed = steps.loc[row.name, "Kt0_An_moe"]
    assert abs(row.Kt0_An_moe - printed) < 0.03
    assert abs(with_extra - printed) > 0.5


def test_steps_used_match_the_thesis(tests_sheet, steps) -> None:
    means = tangential_means(step_quantities(steps, tests_sheet, PUBLISHED_MODEL, threshold=0.5))
    published = pd.concat([read_published("2.2"), read_published("2.8")])
    merged = means.merge(published[published["direction"] != "combined"],
                         on=["test", "direction"], suffixes=("", "_pub"))
    assert len(merged) == 18
    assert (merged["steps_used"] == merged["steps_used_pub"].fillna("")).all()


# ----------------------------------------------------------------- Tables 2.2 and 2.8

MEAN_COLUMNS = ["Kt0_An", "Kt0_An_moe", "beta_t", "beta_t_moe", "f", "f_moe"]


def _means(values: pd.DataFrame, used: pd.Series) -> pd.DataFrame:
    """tangential_means with every input pushed outward/inward by its ``_bound``."""
    q = values.assign(used=used.to_numpy())
    bounds = {c: q[f"{c}_bound"].to_numpy() for c in MEAN_COLUMNS}
    return outward_bound(tangential_means, q.drop(columns=[f"{c}_bound" for c in MEAN_COLUMNS]),
                         bounds, MEAN_COLUMNS)


def _means_from_parameters(tests_sheet, steps, step_decimals) -> pd.DataFrame:
    values = _step_values(tests_sheet, steps, step_decimals)
    values = values.loc[:, ~values.columns.duplicated()]
    return _means(values, values["used"])


def _means_from_printed(tests_sheet, steps, step_decimals) -> pd.DataFrame:
    q = step_quantities(steps, tests_sheet, PUBLISHED_MODEL)
    for col in MEAN_COLUMNS:
        q[col] = steps[col].to_numpy()
        q[f"{col}_bound"] = half_unit(step_decimals[col])
    return _means(q, select_steps(q)["used"])


@pytest.mark.parametrize("table", ["2.2", "2.8"])
def test_tangential_means_from_fit_parameters(table, tests_sheet, steps, step_decimals) -> None:
    ours = _means_from_parameters(tests_sheet, steps, step_decimals)
    problems = check("parameters", table, ours, read_published(table), ["test", "direction"],
                     MEAN_COLUMNS)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("table", ["2.2", "2.8"])
def test_tangential_means_from_printed_step_values(table, tests_sheet, steps,
                                                   step_decimals) -> None:
    """Same means from the printed per-step Kt0/An, beta_t, f and margins (Appendix A)."""
    ours = _means_from_printed(tests_sheet, steps, step_decimals)
    problems = check("printed", table, ours, read_published(table), ["test", "direction"],
                     MEAN_COLUMNS)
    assert not problems, "\n".join(problems)


def test_pn_an_column(tests_sheet, steps) -> None:
    means = tangential_means(step_quantities(steps, tests_sheet, PUBLISHED_MODEL))
    published = pd.concat([read_published("2.2"), read_published("2.8")])
    merged = means.merge(published, on=["test", "direction"], suffixes=("", "_pub"))
    np.testing.assert_allclose(merged["Pn_An"], merged["Pn_An_pub"])


# ----------------------------------------------------------------- Tables 2.1 and 2.7

KN_COLUMNS = ["Kn_An", "Kn_An_moe", "beta_n", "beta_n_moe"]


def _kn_from_parameters(tests_sheet, normal, normal_decimals) -> pd.DataFrame:
    rows = (normal["direction"] != "mean").to_numpy()
    inputs = normal[rows].reset_index(drop=True)
    decimals = normal_decimals[rows].reset_index(drop=True)
    halves = {c: half_unit(decimals[c]) for c in ("beta_n", "beta_n_moe", "P0", "P0_moe")}

    # row-wise for the loading/unloading rows; the mean rows average two rows whose Kn and
    # margins move the same way with each input, so the column shift is their worst case
    def compute(df: pd.DataFrame) -> pd.DataFrame:
        return normal_stiffness(df, tests_sheet)

    return rowwise_bound(compute, inputs, halves, [*KN_COLUMNS, "Pn_An"])


@pytest.mark.parametrize("table", ["2.1", "2.7"])
def test_normal_stiffness_from_fit_parameters(table, tests_sheet, normal,
                                              normal_decimals) -> None:
    ours = _kn_from_parameters(tests_sheet, normal, normal_decimals)
    problems = check("parameters", table, ours, read_published(table), ["test", "direction"],
                     [*KN_COLUMNS, "Pn_An"])
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("table", ["2.1", "2.7"])
def test_normal_means_from_printed_kn(table) -> None:
    """Mean rows from the printed loading/unloading Kn and beta_n (the averaging rule)."""
    printed = read_published(table)
    rows = printed[printed["direction"] != "mean"]
    means = rows.groupby("test", sort=False).agg(
        Kn_An=("Kn_An", "mean"), beta_n=("beta_n", "mean"),
        Kn_An_moe=("Kn_An_moe", lambda m: np.sqrt((m**2).sum()) / 2),
        beta_n_moe=("beta_n_moe", lambda m: np.sqrt((m**2).sum()) / 2),
    ).reset_index().assign(direction="mean")
    for col in KN_COLUMNS:  # two inputs known to half a unit move a mean by half a unit
        means[f"{col}_bound"] = 0.5 * 10.0 ** (-printed_decimals(table)[col].max())
    problems = check("printed", table, means, printed[printed["direction"] == "mean"],
                     ["test", "direction"], KN_COLUMNS)
    assert not problems, "\n".join(problems)


# ------------------------------------------------------------ Tables 2.4 and 2.9 (Cc)


@pytest.mark.parametrize("kn_source", ["printed", "parameters"])
def test_coupling_tables(kn_source, tests_sheet, steps, step_decimals, normal,
                         normal_decimals) -> None:
    """Cc from the recomputed combined Kt0 means and the printed or recomputed Kn."""
    means = _means_from_parameters(tests_sheet, steps, step_decimals)
    if kn_source == "printed":
        kn = normal.assign(Kn_An_bound=half_unit(normal_decimals["Kn_An"]),
                           Kn_An_moe_bound=half_unit(normal_decimals["Kn_An_moe"]))
    else:
        kn = _kn_from_parameters(tests_sheet, normal, normal_decimals)
    combined = means[means["direction"] == "combined"].set_index("test")
    kn = kn.set_index(["test", "direction"])
    rows = []
    for test in combined.index:
        for basis in ("mean", "loading", "unloading"):
            if (test, basis) in kn.index:
                k = kn.loc[(test, basis)]
                rows.append({"test": test, "direction": basis,
                             **{c: combined.at[test, c] for c in ("Kt0_An", "Kt0_An_moe")},
                             **{f"{c}_b": combined.at[test, f"{c}_bound"] + 0.0
                                for c in ("Kt0_An", "Kt0_An_moe")},
                             **{c: k[c] for c in ("Kn_An", "Kn_An_moe")},
                             **{f"{c}_b": k[f"{c}_bound"] for c in ("Kn_An", "Kn_An_moe")}})
    flat = pd.DataFrame(rows)

    def compute(df: pd.DataFrame) -> pd.DataFrame:
        m = df.assign(direction="combined")
        out = []
        for i in range(len(df)):
            cc = coupling(m.iloc[[i]], df.iloc[[i]].loc[:, ["test", "direction", "Kn_An",
                                                            "Kn_An_moe"]],
                          bases=(df["direction"].iloc[i],))
            out.append(cc)
        return pd.concat(out, ignore_index=True).rename(columns={"basis": "direction"})

    cols = ("Kt0_An", "Kt0_An_moe", "Kn_An", "Kn_An_moe")
    ours = corner_bound(compute, flat, {c: flat[f"{c}_b"].to_numpy() for c in cols},
                        ["Cc", "Cc_moe"]).rename(columns={"direction": "basis"})
    for table in ("2.4", "2.9"):
        problems = check(kn_source, table, ours, read_published(table), ["test", "basis"],
                         ["Cc", "Cc_moe"])
        assert not problems, "\n".join(problems)


# ----------------------------------------------------------- Tables 2.3 and 2.10 (Seq)


@pytest.mark.parametrize("table", ["2.3", "2.10"])
def test_beta_n_seq(table, tests_sheet, normal) -> None:
    ds = seq_dataset(tests_sheet, published_roughness())
    seq = pd.Series(ds["Seq"].values, index=ds["test"].values)
    ours = beta_n_seq(normal, seq)
    beta = ours["test"].map(normal[normal.direction == "loading"].set_index("test")["beta_n"])
    # beta_n printed to 3 decimals; Seq from two Sq printed in whole nm (+-0.0005 um each)
    seq_bound = 0.0005 * np.sqrt(2)
    ours["Seq_bound"] = seq_bound
    ours["beta_n_Seq_bound"] = 0.0005 * ours["Seq"] + beta * seq_bound
    problems = check("parameters", table, ours, read_published(table), ["test"],
                     ["Seq", "beta_n_Seq"])
    assert not problems, "\n".join(problems)


def test_listed_differences_are_real(normal) -> None:
    """Direct evidence for the listed Table 2.1/2.7 cells."""
    su1 = normal[(normal.test == "SU1") & (normal.direction == "unloading")].iloc[0]
    assert su1.beta_n * (4.0 - su1.alpha_n) / 20 * 1000 == pytest.approx(su1.Kn_An, abs=0.1)
    assert su1.beta_n * (4.0 - su1.P0) / 20 * 1000 == pytest.approx(85.28, abs=0.01)
    kn, dkn = kn_margin(su1.beta_n, su1.beta_n_moe, su1.P0, su1.P0_moe, 4.0)
    assert dkn / kn * su1.Kn_An == pytest.approx(su1.Kn_An_moe, rel=2e-3)
    ru1 = normal[normal.test == "RU1"].set_index("direction")
    total = np.hypot(ru1.at["loading", "beta_n_moe"], ru1.at["unloading", "beta_n_moe"])
    assert round(total, 3) == ru1.at["mean", "beta_n_moe"]
    s1 = normal[normal.test == "S1"].set_index("direction")
    mean_moe = np.hypot(s1.at["loading", "Kn_An_moe"], s1.at["unloading", "Kn_An_moe"]) / 2
    assert abs(mean_moe - s1.at["mean", "Kn_An_moe"]) > 0.005
    # RU1 unloading: |Pn| implied by the printed Kn, beta_n and P0
    load = ru1.at["unloading", "Kn_An"] * 20 / 1000 / ru1.at["unloading", "beta_n"] \
        + ru1.at["unloading", "P0"]
    assert 3.99 < load < 3.9995
