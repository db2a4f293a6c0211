"""One report section: an HTML fragment plus its tables (CSV, Markdown) and figures (PNG, PDF).

The report toolkit (this module and :mod:`contactlab.report.index`) knows no science: each
branch's own report builder (``contactlab.<branch>.report``) fills a :class:`Section` and
writes it to ``results/report/sections/`` as a page of its own (the report's styles, links
relative to the section's folder, so it opens alone); :mod:`contactlab.report.index`
stitches the sections into ``index.html``. Tables are written by
:func:`contactlab.io.write_table`. While a section is built, its links are relative to
``report_dir``; :meth:`Section.write` rebases them to the folder it writes to.
"""

from __future__ import annotations

import html
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

from contactlab.io import atomic_path, write_table, write_text
from contactlab.report.style import STYLE, rebase_links

#: Metadata in saved figures is fixed so the same data give the same files.
_PNG_METADATA = {"Software": None}
_PDF_METADATA = {"Creator": None, "Producer": None, "CreationDate": None}


def save_figure(fig: plt.Figure, png_path: str | os.PathLike[str]) -> None:
    """Save ``fig`` as PNG at ``png_path`` and as PDF beside it, then close it."""
    png_path = Path(png_path)
    with atomic_path(png_path) as tmp:
        fig.savefig(tmp, dpi=150, bbox_inches="tight", metadata=_PNG_METADATA, format="png")
    with atomic_path(png_path.with_suffix(".pdf")) as tmp:
        fig.savefig(tmp, bbox_inches="tight", metadata=_PDF_METADATA, format="pdf")
    plt.close(fig)


@dataclass
class Section:
    """An HTML fragment built block by block; ``report_dir`` anchors relative links."""

    title: str
    anchor: str
    report_dir: Path
    blocks: list[str] = field(default_factory=list)

    def _relative(self, path: str | os.PathLike[str]) -> str:
        return Path(os.path.relpath(Path(path), self.report_dir)).as_posix()

    def paragraph(self, text: str) -> None:
        """Add a paragraph of plain text (escaped)."""
        self.blocks.append(f"<p>{html.escape(text)}</p>")

    def note(self, text: str) -> None:
        """Add a highlighted note, e.g. that data are reconstructed or a case did not converge."""
        self.blocks.append(f'<p class="note">{html.escape(text)}</p>')

    def table(
        self, table: pd.DataFrame, caption: str, csv_path: str | os.PathLike[str], digits: int = 3
    ) -> None:
        """Write ``table`` to CSV/Markdown and show it with a caption and a download link."""
        write_table(table, csv_path, digits)
        body = table.to_html(
            index=False, float_format=lambda v: f"{v:.{digits}f}", na_rep="–", border=0
        )
        link = self._relative(csv_path)
        self.blocks.append(
            f"<figure class='table' id='tab-{Path(csv_path).stem}'>"
            f"<div class='table-scroll'>{body}</div>"
            f"<figcaption>{html.escape(caption)} "
            f"(<a href='{link}'>CSV</a>)</figcaption></figure>"
        )

    def figure(self, fig: plt.Figure, caption: str, png_path: str | os.PathLike[str]) -> None:
        """Save ``fig`` as PNG and PDF and show it with a caption."""
        save_figure(fig, png_path)
        self.image(png_path, caption)

    def image(self, png_path: str | os.PathLike[str], caption: str) -> None:
        """Show a figure already saved by :func:`save_figure` (PNG, PDF beside) with a
        caption; its id (``fig-<file name>``) lets the page's contents link it."""
        png = self._relative(png_path)
        pdf = self._relative(Path(png_path).with_suffix(".pdf"))
        self.blocks.append(
            f"<figure id='fig-{Path(png_path).stem}'><img src='{png}' "
            f"alt='{html.escape(caption)}'><figcaption>{html.escape(caption)} "
            f"(<a href='{pdf}'>PDF</a>)</figcaption></figure>"
        )

    def heading(self, text: str) -> None:
        """Start a sub-section (``<h3>``, listed in the page's contents)."""
        slug = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
        self.blocks.append(f"<h3 id='{self.anchor}-{slug}'>{html.escape(text)}</h3>")

    def render(self) -> str:
        """The fragment: a ``<section>`` with a heading and the blocks in order, its links
        relative to ``report_dir``."""
        inner = "\n".join(self.blocks)
        return (
            f"<section id='{self.anchor}'>\n<h2>{html.escape(self.title)}</h2>\n{inner}\n"
            "</section>\n"
        )

    def page(self, folder: str | os.PathLike[str]) -> str:
        """The section as an HTML page of its own for a file in ``folder``: the report's
        styles and the fragment with its links relative to ``folder``."""
        return (
            "<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
            f"<title>{html.escape(self.title)}</title>\n<style>{STYLE}</style>\n</head>\n"
            "<body>\n<main class='alone'>\n"
            + rebase_links(self.render(), self.report_dir, folder)
            + "</main>\n</body>\n</html>\n"
        )

    def write(self, path: str | os.PathLike[str]) -> None:
        """Write the section page to ``path`` (atomically): it opens on its own, and
        :func:`contactlab.report.index.build_index` stitches its ``<section>``."""
        write_text(self.page(Path(path).parent), path)
