"""Checks of the hand transcriptions of the thesis tables in ``resources/published``.

Every derived column is recomputed from the other printed cells and compared within the
printed rounding: half a unit of the last printed decimal of the derived cell, widened by the
range the derived value takes when every input cell varies over its own rounding interval
(evaluated at all corners of that box, the functions being monotone in each input there).
Cells that disagree beyond that are genuine thesis typos/inconsistencies; they are listed
explicitly below with the evidence, and the tests require them to keep disagreeing.
"""

from __future__ import annotations

import io
import itertools
import math
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import pandas as pd
import pytest

from contactlab import published as pub
from contactlab.published import (
    MEAN_ROW_TABLES,
    NOMINAL_AREA_MM2,
    NORMAL_LOAD_KN,
    PER_STEP_FIT_TABLES,
    TANGENTIAL_TABLES,
    mean_row_stiffness,
    per_step_fits,
    read_published,
)

AN = NOMINAL_AREA_MM2  # mm^2
CHAPTER2 = [f"2.{i}" for i in range(1, 12)]
APPENDIX = [f"A.{i}" for i in range(1, 40)]
ALL_TABLES = CHAPTER2 + APPENDIX
GROUND = ["RU1", "RU2", "RU3", "SU1", "SU2", "SU3"]
STRUCTURED = ["S1", "S2", "S3"]
DIMENSIONLESS = {"gof", "f", "f_moe", "Str", "fractal_dimension", "Cc", "Cc_moe", "beta_n_Seq",
                 "step"}
STEPS = {(t, d): 5 for t in GROUND + STRUCTURED for d in ("loading", "unloading")}
STEPS[("SU1", "loading")] = 2  # sec. 2.6.2: SU1 gave only two loading steps
STEPS[("SU1", "unloading")] = 3  # ... and three unloading steps

Key = tuple[str, ...]
Cell = str | tuple[float, float]  # a printed cell, or (value, half-width) for a non-printed input
Case = tuple[Key, str, Callable[..., float], Sequence[Cell]]

# Kn/An of Tables 2.1/2.7 is evaluated at the measured maximum normal load, which the thesis
# reports only by its nominal value (4, 8, 12 kN). The loads implied by the printed cells all lie
# within 0.1% of nominal (largest: RU1 unloading, 0.10% low), far inside the 1% load-control
# band of sec. 2.5.2, so the nominal load is given a +/-0.1% interval in that check.
PN_REL_TOL = 1e-3


# --------------------------------------------------------------------------- helpers
def raw(table: str) -> pd.DataFrame:
    """The printed cells of a table as strings (column names without units)."""
    names = list(read_published(table).columns)
    path = pub.PUBLISHED_DIR / f"table_{table}.csv"
    body = [ln for ln in path.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    df = pd.read_csv(io.StringIO("\n".join(body)), dtype=str, keep_default_na=False)
    df.columns = names
    return df


def half_unit(cell: str) -> float:
    """Half a unit of the last printed digit of ``cell`` (handles ``1.93E+04``)."""
    mantissa, _, exponent = cell.upper().partition("E")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** ((int(exponent) if exponent else 0) - decimals)


def _interval(cell: Cell) -> tuple[float, float]:
    value, half = (float(cell), half_unit(cell)) if isinstance(cell, str) else cell
    return value - half, value + half


def bounds(func: Callable[..., float], cells: Sequence[Cell]) -> tuple[float, float]:
    """Range of ``func`` over the rounding box of the printed input ``cells``."""
    ranges = [_interval(c) for c in cells]
    values = [func(*corner) for corner in itertools.product(*ranges)]
    return min(values), max(values)


def agrees(printed: str, func: Callable[..., float], cells: Sequence[Cell]) -> bool:
    """Whether the printed cell equals ``func(cells)`` to the printed rounding."""
    lo, hi = bounds(func, cells)
    value, tol = float(printed), half_unit(printed) + 1e-9 * max(1.0, abs(float(printed)))
    return lo - tol <= value <= hi + tol


def failures(cases: Iterable[Case]) -> set[Key]:
    """Keys of the cases whose printed cell disagrees with its recomputation."""
    return {key for key, printed, func, cells in cases if not agrees(printed, func, cells)}


def mean(*xs: float) -> float:
    return sum(xs) / len(xs)


def mean_abs(*xs: float) -> float:
    return sum(abs(x) for x in xs) / len(xs)


def mean_moe(*ms: float) -> float:
    """Margin of a mean by the addition rule (sec. 2.5.1/2.5.3): sqrt(sum m^2) / n."""
    return math.sqrt(sum(m * m for m in ms)) / len(ms)


def steps_of(cell: str) -> list[int]:
    return [int(s) for s in cell.split(";")] if cell else []


def fit_rows(test: str, direction: str) -> pd.DataFrame:
    table = next(t for t in PER_STEP_FIT_TABLES if TANGENTIAL_TABLES[t][:2] == (test, direction))
    return raw(table).set_index("step")


# --------------------------------------------------------------------------- thesis typos
# Every cell below disagrees with its recomputation from other printed cells.
KNOWN_TYPOS: dict[Key, str] = {
    ("2.1", "SU1", "unloading", "Kn_An"): (
        "Kn/An = 200.040 needs -Pn - P0 = 2.880 kN; with the printed P0 = 2.772 eq. (2.4) gives "
        "85.285. The printed alpha_n (1.120) and P0 (2.772) look swapped: with P0 = 1.120 eq. "
        "(2.4) gives 200.02, and alpha_n ~ Pnmax - P0 as in every other unloading row"),
    ("2.7", "S1", "mean", "Kn_An_moe"): (
        "printed 5.161; the addition rule on the printed loading/unloading margins (7.579, 6.986) "
        "gives 5.154, the rule that reproduces every other mean row of Tables 2.1 and 2.7"),
    ("2.11", "S1", "Sq_before"): (
        "1057 nm is the pad B Sq of S3 in Table A.27 (S1 pad B: 1016); S1/S3 swapped"),
    ("2.11", "S3", "Sq_before"): (
        "1016 nm is the pad B Sq of S1 in Table A.27 (S3 pad B: 1057); S1/S3 swapped"),
}


def known(prefix: str) -> set[Key]:
    return {k for k in KNOWN_TYPOS if k[0] == prefix}


# --------------------------------------------------------------------------- files and loader
@pytest.mark.parametrize("table", ALL_TABLES)
def test_every_table_parses_with_units_and_provenance(table: str) -> None:
    df = read_published(table)
    assert len(df) > 0
    assert df.attrs["source"].startswith(f"Thesis Table {table}: ")
    lines = (pub.PUBLISHED_DIR / f"table_{table}.csv").read_text(encoding="utf-8").splitlines()
    assert lines[1].startswith("# Source: ../shared/seed, thesis ")
    assert "text line numbers" in lines[1]
    units = df.attrs["units"]
    assert set(units) == set(df.columns)
    for col in df.columns:
        if pd.api.types.is_numeric_dtype(df[col]) and not df[col].isna().all():
            assert units[col] != "1" or col in DIMENSIONLESS, (table, col)
        if col.endswith("_moe"):
            assert units[col] == units[col[: -len("_moe")]], (table, col)
            assert (df[col].dropna() >= 0).all(), (table, col)


def test_readme_lists_every_file() -> None:
    text = (pub.PUBLISHED_DIR / "README.md").read_text(encoding="utf-8")
    for table in ALL_TABLES:
        assert f"table_{table}.csv" in text, table
    assert {p.name for p in pub.PUBLISHED_DIR.glob("*.csv")} == {
        f"table_{t}.csv" for t in ALL_TABLES}


def test_read_published_errors(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"table_9\.99\.csv"):
        read_published("9.99", tmp_path)
    (tmp_path / "table_X.1.csv").write_text("# Thesis Table X.1: x\nok,bad name [kN\n1,2\n")
    with pytest.raises(ValueError, match=r"table_X\.1\.csv"):
        read_published("X.1", tmp_path)
    (tmp_path / "table_X.2.csv").write_text("a [kN],a\n1,2\n")
    with pytest.raises(ValueError, match=r"table_X\.2\.csv"):
        read_published("X.2", tmp_path)
    (tmp_path / "table_X.3.csv").write_text("# Thesis Table X.3: y\na [kN],b\n1,2\n")
    df = read_published("X.3", tmp_path)
    assert list(df.columns) == ["a", "b"]
    assert df.attrs == {"units": {"a": "kN", "b": "1"}, "source": "Thesis Table X.3: y"}


def test_tangential_table_index() -> None:
    assert len(PER_STEP_FIT_TABLES) == len(MEAN_ROW_TABLES) == 18
    assert set(PER_STEP_FIT_TABLES) | set(MEAN_ROW_TABLES) == {
        f"A.{i}" for i in [*range(2, 26), *range(28, 40)]}
    pairs = {TANGENTIAL_TABLES[t][:2] for t in PER_STEP_FIT_TABLES}
    assert pairs == {TANGENTIAL_TABLES[t][:2] for t in MEAN_ROW_TABLES} == set(STEPS)


@pytest.mark.parametrize("loader", [per_step_fits, mean_row_stiffness])
def test_concatenated_tables_row_counts(loader: Callable[..., pd.DataFrame]) -> None:
    df = loader()
    counts = df.groupby(["test", "direction"]).size().to_dict()
    assert counts == STEPS
    assert len(df) == 85
    for (test, direction), group in df.groupby(["test", "direction"]):
        assert list(group["step"]) == list(range(1, STEPS[(test, direction)] + 1))
        assert group["table"].nunique() == 1
        assert TANGENTIAL_TABLES[group["table"].iloc[0]][:2] == (test, direction)
    assert df.attrs["units"]["Kt0_An" if loader is per_step_fits else "Kt0_An_mean_row"] == (
        "kN/mm3")


def test_normal_loads_match_thesis() -> None:
    """-Pn of each test: Table A.1 group labels, and -Pn/An printed in Tables 2.1 and 2.2."""
    a1 = read_published("A.1").dropna(subset=["Pn_max"])
    for _, row in a1.iterrows():
        assert row["Pn_max"] == NORMAL_LOAD_KN[row["test"]]
    for table in ("2.1", "2.2", "2.7", "2.8"):
        for _, row in read_published(table).iterrows():
            assert row["Pn_An"] * AN == pytest.approx(NORMAL_LOAD_KN[row["test"]])


# --------------------------------------------------------------------------- per-step fits
def _per_step_cases() -> Iterable[Case]:
    for table in PER_STEP_FIT_TABLES:
        test, _, _ = TANGENTIAL_TABLES[table]
        pn = NORMAL_LOAD_KN[test]
        for _, r in raw(table).iterrows():
            key = (table, r["step"])
            # f = |Qs / Pn| (sec. 2.5.3)
            yield (*key, "f"), r["f"], lambda q, pn=pn: abs(q) / pn, [r["Qs"]]
            # Kt0 = |beta_t Qs| (eq. 2.5 at Qt = 0); kN/um -> kN/mm, per An
            yield ((*key, "Kt0_An"), r["Kt0_An"], lambda b, q: abs(b * q) * 1000 / AN,
                   [r["beta_t"], r["Qs"]])
            # eq. (2.9): dKt0/Kt0 = sqrt((dbeta/beta)^2 + (dQs/Qs)^2)
            yield ((*key, "Kt0_An_moe"), r["Kt0_An_moe"],
                   lambda b, bm, q, qm: abs(b * q) * 1000 / AN * math.hypot(bm / b, qm / q),
                   [r["beta_t"], r["beta_t_moe"], r["Qs"], r["Qs_moe"]])


def test_per_step_fits_recompute() -> None:
    assert failures(_per_step_cases()) == known("A.")


def test_per_step_friction_margin_lower_bound() -> None:
    """Eq. (2.10): df/f = sqrt((dQs/Qs)^2 + (dPn/Pn)^2) >= dQs/|Qs|.

    The dPn term cannot be recomputed exactly (the normal-load error of sec. 2.5.2 does not
    reproduce the printed margins), so only the lower bound is checked.
    """
    for table in PER_STEP_FIT_TABLES:
        for _, r in raw(table).iterrows():
            _, f_hi = bounds(lambda fm, f: fm / f, [r["f_moe"], r["f"]])
            q_lo, _ = bounds(lambda qm, q: qm / abs(q), [r["Qs_moe"], r["Qs"]])
            assert f_hi >= q_lo, (table, r["step"])


def test_per_step_signs_and_gof() -> None:
    """Loading steps: beta_t < 0, Qs > 0 (Qs = f(-Pn)); unloading: beta_t > 0, Qs < 0."""
    df = per_step_fits()
    sign = df["direction"].map({"loading": 1, "unloading": -1})
    assert ((df["Qs"] * sign) > 0).all()
    assert ((df["beta_t"] * sign) < 0).all()
    assert ((df["alpha_t"] * sign) < 0).all()
    assert df["gof"].between(0, 1).all()


def test_mean_row_tables_consistent() -> None:
    df = mean_row_stiffness()
    assert (df["Kt0_An_row_min"] <= df["Kt0_An_mean_row"]).all()
    assert (df["Kt0_An_mean_row"] <= df["Kt0_An_row_max"]).all()
    assert (df["Kt0_An_mean_row_moe"] > 0).all()
    spread = df["Kt0_An_row_max"] - df["Kt0_An_row_min"]
    assert (df["Kt0_An_mean_row_moe"] < spread).all()
    joined = df.merge(per_step_fits(), on=["test", "direction", "step"], validate="1:1")
    assert len(joined) == len(df)
    # Sec. 2.6.3: mean-row values are "similar" to the mean-field fits; within a factor 1.5.
    ratio = joined["Kt0_An_mean_row"] / joined["Kt0_An"]
    assert ratio.between(1 / 1.5, 1.5).all()


# --------------------------------------------------------------------------- tables 2.2 / 2.8
@pytest.mark.parametrize("table", ["2.2", "2.8"])
def test_tangential_means_recompute(table: str) -> None:
    """Means over the steps whose Kt0 margin is below 50% (sec. 2.7), addition rule margins."""
    df = raw(table).set_index(["test", "direction"])
    cases: list[Case] = []
    for test in df.index.get_level_values("test").unique():
        used: dict[str, pd.DataFrame] = {}
        for direction in ("loading", "unloading"):
            r = df.loc[(test, direction)]
            fits = fit_rows(test, direction)
            qualifying = [int(s) for s, row in fits.iterrows()
                          if float(row["Kt0_An_moe"]) < 0.5 * float(row["Kt0_An"])]
            assert steps_of(r["steps_used"]) == qualifying, (table, test, direction)
            used[direction] = fits.loc[[str(s) for s in qualifying]]
            if not qualifying:
                assert all(r[c] == "" for c in r.index if c not in ("Pn_An", "texture_wavelength"))
        both = pd.concat(list(used.values()))
        for direction, rows in (*used.items(), ("combined", both)):
            if rows.empty:
                continue
            r = df.loc[(test, direction)]
            beta = mean_abs if direction == "combined" else mean
            for col, func in (("Kt0_An", mean), ("beta_t", beta), ("f", mean)):
                key = (table, test, direction)
                cases.append(((*key, col), r[col], func, list(rows[col])))
                cases.append(((*key, f"{col}_moe"), r[f"{col}_moe"], mean_moe,
                              list(rows[f"{col}_moe"])))
    assert failures(cases) == known(table)


# --------------------------------------------------------------------------- tables 2.1 / 2.7
@pytest.mark.parametrize("table", ["2.1", "2.7"])
def test_normal_stiffness_at_max_load(table: str) -> None:
    """Eq. (2.4): Kn = beta_n (-Pn - P0) at -Pn = max normal load; Kn/An in kN/mm^3."""
    cases: list[Case] = []
    for _, r in raw(table).iterrows():
        if r["direction"] == "mean":
            continue
        pn = (NORMAL_LOAD_KN[r["test"]], PN_REL_TOL * NORMAL_LOAD_KN[r["test"]])
        cases.append(((table, r["test"], r["direction"], "Kn_An"), r["Kn_An"],
                      lambda b, p0, pn: b * (pn - p0) * 1000 / AN, [r["beta_n"], r["P0"], pn]))
        # eq. (2.8) lower bound: dKn/Kn >= dbeta/beta (the dPn term is not reproducible)
        _, k_hi = bounds(lambda km, k: km / k, [r["Kn_An_moe"], r["Kn_An"]])
        b_lo, _ = bounds(lambda bm, b: bm / b, [r["beta_n_moe"], r["beta_n"]])
        assert k_hi >= b_lo, (table, r["test"], r["direction"])
        assert 0 < float(r["gof"]) <= 1
    assert failures(cases) == {k for k in known(table) if k[2] != "mean"}


def test_table_2_1_su1_unloading_swap_evidence() -> None:
    """With alpha_n and P0 swapped, SU1 unloading satisfies eq. (2.4) like the other rows."""
    r = raw("2.1").set_index(["test", "direction"]).loc[("SU1", "unloading")]
    assert agrees(r["Kn_An"], lambda b, p0: b * (4.0 - p0) * 1000 / AN,
                  [r["beta_n"], r["alpha_n"]])


# Mean-row beta_n margins: Table 2.7 uses the addition rule for a mean (sqrt(a^2+b^2)/2) as
# for Kn; Table 2.1 prints sqrt(a^2+b^2) (twice as large) for every test. Consistent within
# each table, so this is encoded as a per-table factor rather than listed as typos.
BETA_MEAN_MOE_FACTOR = {"2.1": 2.0, "2.7": 1.0}


@pytest.mark.parametrize("table", ["2.1", "2.7"])
def test_normal_mean_rows(table: str) -> None:
    df = raw(table).set_index(["test", "direction"])
    factor = BETA_MEAN_MOE_FACTOR[table]
    cases: list[Case] = []
    for test in df.index.get_level_values("test").unique():
        lo, un, me = (df.loc[(test, d)] for d in ("loading", "unloading", "mean"))
        key = (table, test, "mean")
        cases += [
            ((*key, "Kn_An"), me["Kn_An"], mean, [lo["Kn_An"], un["Kn_An"]]),
            ((*key, "Kn_An_moe"), me["Kn_An_moe"], mean_moe, [lo["Kn_An_moe"], un["Kn_An_moe"]]),
            ((*key, "beta_n"), me["beta_n"], mean, [lo["beta_n"], un["beta_n"]]),
            ((*key, "beta_n_moe"), me["beta_n_moe"], lambda a, b: factor * mean_moe(a, b),
             [lo["beta_n_moe"], un["beta_n_moe"]]),
        ]
        assert me["gof"] == me["alpha_n"] == me["P0"] == ""
    assert failures(cases) == {k for k in known(table) if k[2] == "mean"}


# --------------------------------------------------------------------------- 2.3 / 2.10
def _roughness_sq(table: str) -> dict[str, str]:
    return dict(zip(raw(table)["surface"], raw(table)["Sq"], strict=True))


@pytest.mark.parametrize("table", ["2.3", "2.10"])
def test_equivalent_roughness(table: str) -> None:
    """Eq. (2.1): Seq = sqrt(Sq_specimen^2 + Sq_padB^2) (imaged interface), and beta_n*Seq."""
    normal = raw("2.1" if table == "2.3" else "2.7").set_index(["test", "direction"])
    cases: list[Case] = []
    for _, r in raw(table).iterrows():
        test = r["test"]
        if table == "2.3":
            sq = _roughness_sq("A.1")
            specimen = ("rough" if test.startswith("R") else "smooth") + "_specimen_B"
        else:
            sq = _roughness_sq("A.27")
            specimen = f"{test}_specimen"
        cases.append(((table, test, "Seq"), r["Seq"], lambda a, b: math.hypot(a, b) / 1000,
                      [sq[specimen], sq[f"{test}_pad_B"]]))
        cases.append(((table, test, "beta_n_Seq"), r["beta_n_Seq"], lambda b, s: b * s,
                      [normal.loc[(test, "loading"), "beta_n"], r["Seq"]]))
    assert failures(cases) == known(table)


# --------------------------------------------------------------------------- 2.4 / 2.9
@pytest.mark.parametrize(("table", "tangential", "normal"),
                         [("2.4", "2.2", "2.1"), ("2.9", "2.8", "2.7")])
def test_coupling_ratio(table: str, tangential: str, normal: str) -> None:
    """Cc = Kt0 / Kn (sec. 2.5.3): combined Kt0/An over Kn/An of the basis; division rule."""
    kt = raw(tangential).set_index(["test", "direction"])
    kn = raw(normal).set_index(["test", "direction"])
    cases: list[Case] = []
    for _, r in raw(table).iterrows():
        t, n = kt.loc[(r["test"], "combined")], kn.loc[(r["test"], r["basis"])]
        cells = [t["Kt0_An"], t["Kt0_An_moe"], n["Kn_An"], n["Kn_An_moe"]]
        key = (table, r["test"], r["basis"])
        cases.append(((*key, "Cc"), r["Cc"], lambda a, am, b, bm: a / b, cells))
        cases.append(((*key, "Cc_moe"), r["Cc_moe"],
                      lambda a, am, b, bm: a / b * math.hypot(am / a, bm / b), cells))
    assert failures(cases) == known(table)
    bases = raw(table).groupby("test")["basis"].apply(list).to_dict()
    expected = ["mean", "loading", "unloading"] if table == "2.4" else ["mean"]
    assert all(b == expected for b in bases.values())


# --------------------------------------------------------------------------- 2.5 / 2.11
@pytest.mark.parametrize(("table", "roughness"), [("2.5", "A.1"), ("2.11", "A.27")])
def test_pad_roughness_reduction(table: str, roughness: str) -> None:
    sq = _roughness_sq(roughness)
    cases: list[Case] = []
    for _, r in raw(table).iterrows():
        cases.append(((table, r["test"], "reduction"), r["reduction"],
                      lambda b, a: (b - a) / b * 100, [r["Sq_before"], r["Sq_after"]]))
        if r["Sq_before"] != sq[f"{r['test']}_pad_B"]:  # 'before' = pad B Sq of Table A.1/A.27
            cases.append(((table, r["test"], "Sq_before"), "0", lambda: 1.0, []))
    assert failures(cases) == known(table)


def test_table_2_11_swap_evidence() -> None:
    r = raw("2.11").set_index("test")["Sq_before"]
    sq = _roughness_sq("A.27")
    assert (r["S1"], r["S3"]) == (sq["S3_pad_B"], sq["S1_pad_B"])


# --------------------------------------------------------------------------- roughness
@pytest.mark.parametrize("table", ["A.1", "A.26", "A.27", "2.6"])
def test_roughness_sanity(table: str) -> None:
    df = read_published(table)
    if "Ra" in df:
        assert (df["Rq"] >= df["Ra"]).all()
    if "Sa" in df:
        assert (df["Sq"] >= df["Sa"]).all()
        assert df["Str"].between(0, 1).all()
        assert df["fractal_dimension"].between(2, 3).all()
        assert (df["sample_area"] == 2).all()  # sec. 2.3.4: 2 mm^2 sample areas
    lambdas = [c for c in df.columns if c.startswith("lambda_c")]
    if table == "2.6":  # cut-off slightly above the texture wavelength (sec. 2.8)
        assert (df["lambda_c"] > df["structure_wavelength"]).all()
        assert (df["lambda_c"] <= 2.5 * df["structure_wavelength"]).all()
        assert (df["profile_length"] == 1).all()
    else:  # sec. 2.3.4: lambda_c = 800 um for every 20X measurement
        assert lambdas and all((df[c] == 800).all() for c in lambdas)
        assert set(df["kind"]) == {"specimen", "pad"}
        pads = df[df["kind"] == "pad"]
        assert set(pads["side"]) == {"A", "B"}
        if "profile_length" in df:  # sec. 2.3.4: 4 mm pad profiles, 5 mm specimen profiles
            assert (pads["profile_length"] == 4).all()
            specimen_lengths = set(df.loc[df["kind"] == "specimen", "profile_length"])
            assert specimen_lengths <= {5, 4.98}  # S1 normal-to-pattern printed as 4.98


def test_roughness_surfaces_and_text_values() -> None:
    a1 = read_published("A.1").set_index("surface")
    assert len(a1) == 16
    assert set(a1.index) == {f"{s}_specimen_{x}" for s in ("rough", "smooth") for x in "AB"} | {
        f"{t}_pad_{x}" for t in GROUND for x in "AB"}
    # Sec. 2.6: 'rough specimen' Sq 1.422 um, 'smooth specimen' Sq 0.687 um (side B, imaged)
    assert a1.loc["rough_specimen_B", "Sq"] == 1422
    assert a1.loc["smooth_specimen_B", "Sq"] == 687
    assert a1.loc["rough_specimen_A", "test"] == "RU1;RU2;RU3"
    a27 = read_published("A.27").set_index("surface")
    # Sec. 2.9: specimen Sq 0.752 (S3), 0.761 (S1), 0.432 (S2)
    assert [a27.loc[f"{t}_specimen", "Sq"] for t in ("S3", "S1", "S2")] == [752, 761, 432]
    # Sec. 2.9 says the pad Sq values lie "between 1.016 and 1.057 um"; the pad B values of
    # Table A.27 (and Sq_before of Table 2.11) are 1016, 1003 and 1057 nm, so the S2 pad
    # (1003 nm) is below the stated range: a small inconsistency of the text, kept visible here.
    pad_b = a27.loc[[f"{t}_pad_B" for t in STRUCTURED], "Sq"]
    assert (pad_b.min(), pad_b.max()) == (1003, 1057)
    assert a27.loc["S2_pad_B", "Sq"] < 1016
    a26 = read_published("A.26")
    assert len(a26) == len(a27) + 3
    assert set(a26["profile_direction"].dropna()) == {"normal_to_pattern", "parallel_to_pattern"}
    wavelengths = read_published("2.6").set_index("test")["structure_wavelength"].to_dict()
    assert wavelengths == {"S1": 10, "S2": 5, "S3": 2}
