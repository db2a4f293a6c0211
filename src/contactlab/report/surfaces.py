"""Report section for the surfaces branch: Seq next to the published Tables 2.3 and 2.10."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import xarray as xr

from contactlab.published import read_published
from contactlab.report.section import Section

#: Thesis tables that print Seq per test (ground and structured tests).
SEQ_TABLES = ("2.3", "2.10")


def published_seq(directory: Path | None = None) -> pd.Series:
    """Published Seq (um) per test from Tables 2.3 and 2.10."""
    frames = [read_published(table, directory) for table in SEQ_TABLES]
    return pd.concat(frames).set_index("test")["Seq"]


def seq_comparison(seq: xr.Dataset, published: pd.Series) -> pd.DataFrame:
    """Ours beside published Seq, with the difference, one row per test."""
    table = seq[["Sq_specimen", "Sq_pad", "Seq"]].to_dataframe().reset_index()
    table["Seq_published"] = table["test"].map(published)
    table["difference"] = table["Seq"] - table["Seq_published"]
    return table


def build_section(seq_path: Path, report_dir: Path, published_dir: Path | None,
                  out: Path) -> None:
    """Write the surfaces section with its table and figure."""
    with xr.open_dataset(seq_path) as seq:
        table = seq_comparison(seq.load(), published_seq(published_dir))
    section = Section("Surfaces: equivalent roughness Seq", "surfaces", report_dir)
    section.paragraph(
        "Seq = sqrt(Sq_specimen^2 + Sq_pad^2) (eq. 2.1) of the imaged interface of each test "
        "(specimen and pad sides named in the test sheet), from the published areal Sq of "
        "Tables A.1 and A.27, beside the Seq printed in Tables 2.3 and 2.10. Units: um."
    )
    section.table(table, "Seq per test: ours and published (um)",
                  report_dir / "tables" / "seq.csv")
    fig, ax = plt.subplots(figsize=(6, 3.2))
    x = np.arange(len(table))
    ax.bar(x - 0.2, table["Seq"], 0.4, label="contactlab (eq. 2.1)")
    ax.bar(x + 0.2, table["Seq_published"], 0.4, label="published (Tables 2.3, 2.10)")
    ax.set_xticks(x, table["test"])
    ax.set_ylabel("Seq (um)")
    ax.legend(frameon=False)
    section.figure(fig, "Equivalent roughness of each test interface",
                   report_dir / "figures" / "seq.png")
    section.write(out)
