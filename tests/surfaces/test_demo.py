"""The SYNTHETIC demo scans, processed like real ones, against the published tables.

Stated tolerances (also in the report): Sq 1 %, Sa 3 %, Sp 2 %,
Str +-(0.1 Str + 0.02), Rq 1 %, Ra 3 %, Rz 30 % (20x) and 10 % (100x, Table 2.6),
fractal dimension +-0.08 (absolute). The 100x profiles are evaluated on sampling
lengths of 160 um (five per evaluation length, the surface sheet's
``sampling_length_um``): on sampling lengths = lambda_c no profile with S3's Ra/Rq
reaches its Rz (see test_published_100x_rz_needs_the_160um_sampling_length).
The generator scales with its own periodic spectral filter, the analysis uses the
non-periodic end-corrected filter, plane/line removal and the X3P round trip, so the
agreement checks the analysis chain.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from contactlab.published import read_published
from contactlab.surfaces.demo import (
    LABEL,
    PIXEL_UM,
    _line_parameters,
    power_for_ratio,
    published_targets,
    seed_for,
)
from contactlab.surfaces.parameters import profile_parameters
from contactlab.surfaces.roughness import published_roughness
from contactlab.surfaces.scans import read_scan
from contactlab.surfaces.seq import add_beta_n, add_scan_seq, seq_dataset
from contactlab.surfaces.sheet import read_surface_sheet
from contactlab.testsheet import read_test_sheet


def test_scans_are_labelled_synthetic(processed: pd.DataFrame) -> None:
    scan = read_scan(processed.attrs["work"] / "results/surfaces/demo_scans/RU1_pad_B_areal.x3p",
                     0.0)
    assert scan.synthetic and "SYNTHETIC" in LABEL
    assert scan.dx == pytest.approx(2.01)
    assert scan.size_um[0] * scan.size_um[1] == pytest.approx(2e6, rel=0.01)  # 2 mm^2
    assert processed["synthetic"].all()


def test_seeded_generation_is_reproducible() -> None:
    a = seed_for("RU1_pad_B:areal", 1).standard_normal(3)
    b = seed_for("RU1_pad_B:areal", 1).standard_normal(3)
    c = seed_for("RU1_pad_B:areal", 2).standard_normal(3)
    np.testing.assert_array_equal(a, b)
    assert not np.allclose(a, c)


def test_power_transform_hits_the_height_ratio() -> None:
    """mean|g|^p / rms of sign(g)|g|^p for Gaussian g; p = 1 gives sqrt(2/pi)."""
    assert power_for_ratio(np.sqrt(2 / np.pi)) == pytest.approx(1.0, abs=1e-6)
    g = np.random.default_rng(0).standard_normal(400_000)
    for ratio in (0.66, 0.75, 0.85):
        h = np.sign(g) * np.abs(g) ** power_for_ratio(ratio)
        assert np.mean(np.abs(h)) / np.sqrt(np.mean(h**2)) == pytest.approx(ratio, abs=3e-3)


def _areal_published() -> pd.DataFrame:
    return pd.concat([read_published("A.1"), read_published("A.27")]).set_index("surface")


def test_areal_parameters_match_tables_a1_a27(processed: pd.DataFrame) -> None:
    published = _areal_published()
    assert len(published) == 25
    for surface, p in published.iterrows():
        o = processed.loc[surface]
        assert 1000 * o["Sq"] == pytest.approx(p["Sq"], rel=0.01), surface
        assert 1000 * o["Sa"] == pytest.approx(p["Sa"], rel=0.03), surface
        assert o["Sp"] == pytest.approx(p["Sp"], rel=0.02), surface
        if surface == "S1_specimen":  # grooves: the ACF does not decay along them
            continue
        assert abs(o["Str"] - p["Str"]) <= 0.1 * p["Str"] + 0.02, surface
        # The thesis does not state its method; ours (cube counting) and the published are
        # both just above 2 for these surfaces, so only an absolute 0.08 is asserted
        # (observed worst 0.067).
        assert 2.0 < o["fractal_dimension"] < 2.1, surface
        assert abs(o["fractal_dimension"] - p["fractal_dimension"]) <= 0.08, surface


def test_profile_parameters_match_tables_a1_a26(processed: pd.DataFrame) -> None:
    published = pd.concat([read_published("A.1"), read_published("A.26")])
    published = published.drop_duplicates("surface").set_index("surface")
    assert len(published) == 28
    for surface, p in published.iterrows():
        o = processed.loc[surface]
        assert 1000 * o["Rq"] == pytest.approx(p["Rq"], rel=0.01), surface
        assert 1000 * o["Ra"] == pytest.approx(p["Ra"], rel=0.03), surface
        assert o["Rz"] == pytest.approx(p["Rz"], rel=0.30), surface


def test_structured_100x_profiles_match_table_2_6(processed: pd.DataFrame) -> None:
    """Rq 1 %, Ra 3 %, Rz 10 % for S1, S2 and S3, on five 160 um sampling lengths."""
    work = processed.attrs["work"]
    for row in read_published("2.6").itertuples():
        surface = f"{row.test}_specimen_100x"
        o = processed.loc[surface]
        assert o["lambda_c"] == row.lambda_c and o["sampling_length"] == 160.0
        with xr.open_dataset(work / f"{surface}.nc") as ds:
            assert int(ds["n_sampling_lengths"]) == 5 and float(ds["sampling_length"]) == 160.0
        scan = read_scan(work / f"results/surfaces/demo_scans/{surface}_profile.x3p", 0.0)
        assert scan.dx == pytest.approx(row.profile_width / 1000)  # 167 nm pixels
        assert 1000 * o["Rq"] == pytest.approx(row.Rq, rel=0.01), row.test
        assert 1000 * o["Ra"] == pytest.approx(row.Ra, rel=0.03), row.test
        assert o["Rz"] == pytest.approx(row.Rz, rel=0.10), row.test


def test_grooves_set_the_str_of_the_10um_specimen(processed: pd.DataFrame) -> None:
    """S1's 10 um grooves survive the 20x objective and make the texture directional: the ACF
    does not decay along them within the scan, so ISO leaves Str undefined; the bound the
    reason states is consistent with the published 0.002 (Table A.27)."""
    assert np.isnan(processed.loc["S1_specimen", "Str"])
    reason = processed.attrs["undefined"].loc["S1_specimen", "Str"]
    assert "stays above s = 0.2" in reason
    bound = float(re.search(r"Str < ([0-9.]+)", reason).group(1))
    assert 0.002 < bound < 0.02
    assert processed.loc["S2_specimen", "Str"] > 0.5
    # every other surface has all its parameters
    undefined = processed.attrs["undefined"]
    assert [(s, p) for s in undefined.index for p in undefined.columns
            if undefined.loc[s, p]] == [("S1_specimen", "Str")]


def test_seq_from_scans_beside_the_published(processed: pd.DataFrame, repo: Path) -> None:
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    ds = seq_dataset(sheet, published_roughness())
    ds = add_beta_n(add_scan_seq(ds, sheet, processed["Sq"]))
    np.testing.assert_allclose(ds["Seq_scan"], ds["Seq"], rtol=0.01)
    printed = pd.concat([read_published("2.3"), read_published("2.10")]).set_index("test")
    for test in printed.index:
        assert float(ds["Seq_scan"].sel(test=test)) == pytest.approx(
            printed.loc[test, "Seq"], rel=0.01)
        # beta_n * Seq from the published Sq against the printed two or three decimals
        assert float(ds["beta_n_Seq"].sel(test=test)) == pytest.approx(
            printed.loc[test, "beta_n_Seq"], abs=0.006), test
    # RU1i, RU1 from its camera frames, has RU1's pair but no published beta_n of its own
    assert set(ds["test"].values) - set(printed.index) == {"RU1i"}
    assert float(ds["Seq_scan"].sel(test="RU1i")) == float(ds["Seq_scan"].sel(test="RU1"))
    assert np.isnan(float(ds["beta_n_Seq"].sel(test="RU1i")))
    assert ds["beta_n_Seq_scan"].attrs["units"] == "1"


def test_surface_files_are_cf_and_hold_spectra(processed: pd.DataFrame) -> None:
    work = processed.attrs["work"]
    with xr.open_dataset(work / "rough_specimen_A.nc") as ds:
        assert ds["Sq"].attrs["units"] == "um"
        assert ds["psd_areal"].sizes["q_areal"] > 10 and ds["psd_profile"].sizes["q_profile"] > 10
        # histogram is a density: integrates to one
        widths = np.gradient(ds["roughness_height"].values)
        assert float(np.sum(ds["height_density"].values * widths)) == pytest.approx(1, abs=0.02)
        assert ds.attrs["profile_direction"] == "lengthwise"
        assert int(ds["n_profiles"]) == 5 and int(ds["n_sampling_lengths"]) == 5
        assert float(ds["sampling_length"]) == 800.0  # blank in the sheet: lambda_c
        assert ds["sampling_length"].attrs["units"] == "um"


def test_targets_cover_every_published_surface() -> None:
    targets = published_targets()
    assert len(targets["areal"]) == 25 and len(targets["profile"]) == 31


def max_rz_over_rq(n: int, ratio: float) -> float:
    """Largest Rz/Rq of sampling lengths of n points whose Ra/Rq is ``ratio``.

    Rz is the highest point minus the lowest; for a given sum of |z| (Ra) the other
    n - 2 points use least of the sum of squares (Rq) at equal magnitude c (Cauchy-
    Schwarz), so the extreme is two spikes +-s and n - 2 points at +-c with
    2 s + (n - 2) c = n ratio and 2 s^2 + (n - 2) c^2 = n (Rq = 1); it decreases and
    is concave in the ratio, so averaging over sampling lengths (ratios of means,
    sec. 2.3.4) cannot exceed it either.
    """
    a, b, c = 2 + 4 / (n - 2), -4 * n * ratio / (n - 2), (n * ratio) ** 2 / (n - 2) - n
    return float(2 * (-b + np.sqrt(b * b - 4 * a * c)) / (2 * a))


def test_published_100x_rz_needs_the_160um_sampling_length(repo: Path) -> None:
    """Why the sheet gives the 100x scans sampling lengths of 160 um, not lambda_c.

    Read as sec. 2.3.4 words it (sampling length = lambda_c), Rq and Rz would be means
    over sampling lengths of n = lambda_c / 167 nm = 30, 60, 120 points (the Alicona
    pixel, Table 2.6's profile width). Any profile has Rz/Rq <= sqrt(2 n) (7.75 for
    S3): all published ratios are within it. With the published Ra/Rq as well, S3
    allows at most 6.33 (published 6.89): no profile reproduces S3's Ra, Rq and Rz
    together on those sampling lengths. Five sampling lengths over the 0.8 mm
    evaluation length (ISO 4288's default, the sheet's 160 um: 958 points) allow far
    more, and the demo scans match all three (test above).
    """
    table = read_published("2.6").set_index("test")
    n = (table["lambda_c"] / PIXEL_UM["100x"]).round().astype(int)
    assert list(n) == [30, 60, 120]
    ratio = table["Rz"] / (table["Rq"] / 1000)
    assert (ratio < np.sqrt(2 * n)).all()
    ceiling = pd.Series({t: max_rz_over_rq(n[t], table.loc[t, "Ra"] / table.loc[t, "Rq"])
                         for t in table.index})
    assert ceiling["S3"] == pytest.approx(6.33, abs=0.01) and ratio["S3"] > ceiling["S3"]
    assert (ratio[["S2", "S1"]] < ceiling[["S2", "S1"]]).all()
    specs = [s for s in read_surface_sheet(repo / "config" / "surfaces.csv")
             if s.objective == "100x"]
    assert len(specs) == 3
    for spec in specs:
        test = spec.surface.split("_")[0]
        assert spec.sampling_length == pytest.approx(0.8 * spec.profile_length_um / 5)
        n_wide = round(spec.sampling_length / PIXEL_UM["100x"])
        wide = max_rz_over_rq(n_wide, table.loc[test, "Ra"] / table.loc[test, "Rq"])
        assert n_wide == 958 and wide > 28 > 4 * ratio[test]
    # the plain bound: two opposite spikes in an otherwise flat sampling length
    z = np.zeros(30)
    z[[2, 17]] = (1.0, -1.0)
    p = profile_parameters(z, PIXEL_UM["100x"], 5.0)
    assert p.Rz / p.Rq == pytest.approx(np.sqrt(60))
    # the bound with Ra/Rq: the extreme segment reaches it exactly
    r = 56 / 73
    s = max_rz_over_rq(30, r) / 2
    z = np.where(np.arange(30) % 2 == 0, 1.0, -1.0) * (30 * r - 2 * s) / 28
    z[[2, 17]] = (s, -s)
    p = profile_parameters(np.tile(z, 4), PIXEL_UM["100x"], 5.0)
    assert p.Ra / p.Rq == pytest.approx(r) and p.Rz / p.Rq == pytest.approx(2 * s)
    assert p.Rq == pytest.approx(1.0)


def test_calibration_statistics_are_profile_parameters() -> None:
    """The generator's all-lines-at-once Ra, Rq, Rz are profile_parameters' means."""
    lines = np.random.default_rng(3).standard_normal((5, 1003)) ** 3
    expected = [profile_parameters(line, 0.167, 5.0) for line in lines]
    got = _line_parameters(lines, 0.167, 5.0)
    for name, value in zip(("Ra", "Rq", "Rz"), got, strict=True):
        assert value == pytest.approx(np.mean([getattr(e, name) for e in expected]), rel=1e-12)
