"""The surfaces report section from processed demo scans: tables, pictures, labels."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from contactlab.cli import main
from contactlab.io import read_table, stamp, write_netcdf
from contactlab.surfaces.roughness import published_roughness
from contactlab.surfaces.seq import add_beta_n, add_scan_seq, seq_dataset
from contactlab.testsheet import read_test_sheet


@pytest.mark.slow
def test_section_has_every_table_and_picture(processed: pd.DataFrame, repo: Path,
                                              tmp_path: Path) -> None:
    work = processed.attrs["work"]
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    seq = add_beta_n(add_scan_seq(seq_dataset(sheet, published_roughness()), sheet,
                                  processed["Sq"]))
    write_netcdf(stamp(seq, title="t", source="s", history="h"), tmp_path / "seq.nc")
    report = tmp_path / "report"
    out = report / "sections" / "10_surfaces.html"
    status = main(["surfaces", "report", "--seq", str(tmp_path / "seq.nc"),
                   "--texture", str(work / "texture.nc"), "--surface-dir", str(work),
                   "--report-dir", str(report), "--out", str(out)])
    assert status == 0
    page = out.read_text()
    assert "SYNTHETIC" in page and "34 surfaces" in page
    for name in ("surfaces_maps", "surfaces_profiles", "surfaces_spectra", "seq"):
        assert (report / "figures" / f"{name}.png").stat().st_size > 10_000
        assert f"figures/{name}.png" in page
    areal = read_table(report / "tables" / "surfaces_areal.csv")
    assert len(areal) == 25
    assert (areal["Sq_difference"].abs() < 1.0).all()
    profile = read_table(report / "tables" / "surfaces_profile.csv")
    assert len(profile) == 28 and (profile["Rq_difference"].abs() < 1.0).all()
    structured = read_table(report / "tables" / "surfaces_100x.csv")
    assert list(structured["test"]) == ["S3", "S2", "S1"]
    assert (structured["sampling_length"] == 160.0).all()
    assert structured.attrs["units"]["sampling_length"] == "um"
    assert areal.attrs["units"]["Sa"] == areal.attrs["units"]["Sa_published"] == "nm"
    undefined = read_table(report / "tables" / "surfaces_undefined.csv")
    assert list(zip(undefined["surface"], undefined["parameter"], strict=True)) == [
        ("S1_specimen", "Str")]
    assert "stays above s = 0.2" in undefined["reason"].iloc[0]
    assert "stays above s = 0.2" in page and "No scan had undefined points" in page
    assert len(read_table(report / "tables" / "surfaces_filled.csv")) == 0
    assert len(read_table(report / "tables" / "surfaces_other.csv")) == 0
    table = read_table(report / "tables" / "seq.csv")
    assert table["difference_scan"].abs().max() < 0.01
    assert {"beta_n_Seq", "beta_n_Seq_scan", "beta_n_Seq_published"} <= set(table.columns)


def test_report_without_texture_keeps_the_published_seq_section(repo: Path,
                                                                  tmp_path: Path) -> None:
    """Without scan results the section still shows Seq from the published Sq."""
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    seq = stamp(seq_dataset(sheet, published_roughness()), title="t", source="s", history="h")
    write_netcdf(seq, tmp_path / "seq.nc")
    out = tmp_path / "report" / "s.html"
    assert main(["surfaces", "report", "--seq", str(tmp_path / "seq.nc"),
                 "--report-dir", str(tmp_path / "report"), "--out", str(out)]) == 0
    table = read_table(tmp_path / "report" / "tables" / "seq.csv")
    assert table["Seq"].iloc[0] == pytest.approx(2.038, abs=5e-4)


def test_section_lists_refused_scans_and_still_shows_the_others(repo: Path,
                                                                 tmp_path: Path) -> None:
    """A texture summary with a refused scan: the section names it with its
    reason in a table of its own and keeps the evaluated surface in the other tables."""
    from contactlab.surfaces.sheet import SurfaceSpec
    from contactlab.surfaces.texture import summary_dataset, surface_dataset, surface_texture

    data = repo / "tests" / "data" / "scans"
    specs = [SurfaceSpec("alicona", "other", data / "al3d-1.al3d", None, "x", None, None, 25.0),
             SurfaceSpec("wyko", "other", data / "opd-1-crop.opd", None, "x", None, None, 8.0)]
    datasets = [surface_dataset(surface_texture(spec, 20, 0.001, record_refused=True))
                for spec in specs]
    for ds in datasets:
        write_netcdf(stamp(ds, title="t", source="s", history="h"),
                     tmp_path / f"{ds.attrs['surface']}.nc")
    write_netcdf(stamp(summary_dataset(datasets), title="t", source="s", history="h"),
                 tmp_path / "texture.nc")
    sheet = read_test_sheet(repo / "config" / "tests.csv")
    write_netcdf(stamp(seq_dataset(sheet, published_roughness()), title="t", source="s",
                       history="h"), tmp_path / "seq.nc")
    report = tmp_path / "report"
    out = report / "sections" / "10_surfaces.html"
    assert main(["surfaces", "report", "--seq", str(tmp_path / "seq.nc"),
                 "--texture", str(tmp_path / "texture.nc"), "--surface-dir", str(tmp_path),
                 "--report-dir", str(report), "--out", str(out)]) == 0
    page = out.read_text()
    assert "1 scan(s) were refused" in page and "opd-1-crop.opd: 95 of 49152 points" in page
    refused = read_table(report / "tables" / "surfaces_refused.csv")
    assert list(zip(refused["surface"], refused["scan"], strict=True)) == [("wyko", "areal")]
    other = read_table(report / "tables" / "surfaces_other.csv").set_index("surface")
    assert other.loc["alicona", "Sq"] > 0 and np.isnan(other.loc["wyko", "Sq"])
