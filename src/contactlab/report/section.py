"""One report section: an HTML fragment plus its tables (CSV, Markdown) and figures (PNG, PDF).

The report toolkit (this module and :mod:`contactlab.report.index`) knows no science: each
branch's own report builder (``contactlab.<branch>.report``) fills a :class:`ReportSection`
and writes it to ``results/report/sections/`` as a page of its own (the report's styles,
links relative to the section's folder, so it opens alone); :mod:`contactlab.report.index`
stitches the sections into ``index.html``. A :class:`ReportSection` takes its title, prose,
captions and file names from the section's declaration (:mod:`contactlab.report.declaration`)
and writes each figure's and table's caption beside it for Snakemake's report;
:class:`Section` is the page underneath, built from text the caller gives (the comparison
pages of studies use it directly). Tables are written by :func:`contactlab.io.write_table`.
While a section is built, its links are relative to ``report_dir``; :meth:`Section.write`
rebases them to the folder it writes to.
"""

from __future__ import annotations

import html
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

from contactlab.atomic import atomic_path
from contactlab.display import shown, with_units
from contactlab.io import write_table, write_text
from contactlab.report.declaration import Declaration, caption_file, load
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


def dodge(drawn: Any, points: float) -> Any:
    """Move what was just drawn (the return of ``ax.plot``, ``ax.errorbar``, ``ax.vlines``)
    ``points`` to the right and return it: series at the same x (a step, a test) side by
    side without changing their numbers; the axes keep the limits of the numbers."""
    import matplotlib.transforms as transforms
    from matplotlib.artist import Artist
    from matplotlib.container import Container

    if isinstance(drawn, Container):
        artists = drawn.get_children()
    elif isinstance(drawn, Artist):
        artists = [drawn]
    else:
        artists = list(drawn)
    for artist in artists:
        artist.set_transform(transforms.offset_copy(
            artist.axes.transData, fig=artist.figure, x=points, y=0.0, units="points"))
    return drawn


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
        self, table: pd.DataFrame, caption: str, csv_path: str | os.PathLike[str],
        digits: int = 4, units: Mapping[str, str] | str | None = None,
        margins: Mapping[str, str] | None = None,
    ) -> None:
        """Write ``table`` to CSV/Markdown and show it with a caption and a download link:
        each column of numbers headed with its unit (``units``, else
        ``table.attrs["units"]``), each number with the digits its margin justifies
        (:mod:`contactlab.display`; ``margins`` names margin columns the ``_moe`` suffix does
        not, ``digits`` the significant digits of the others)."""
        write_table(table, csv_path, digits, units=units, margins=margins)
        text = shown(table, digits, margins)
        text.columns = with_units(table, units).columns
        body = text.to_html(index=False, border=0)
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

    def figure_row(self, figures: list[tuple[plt.Figure, str, str | os.PathLike[str]]]
                   ) -> None:
        """Save each (figure, caption, PNG path) as :meth:`figure` does and show them side
        by side (a row that wraps on a narrow page)."""
        start = len(self.blocks)
        for fig, caption, png_path in figures:
            self.figure(fig, caption, png_path)
        row = "".join(self.blocks[start:])
        del self.blocks[start:]
        self.blocks.append(f"<div class='figure-row'>{row}</div>")

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

    def links(self, items: list[tuple[str, str]], cls: str = "links") -> None:
        """Add a list of links: (text, target) pairs, each target a page of the report
        relative to ``report_dir`` (``tests/RU1.html``, ``index.html#stiffness-tests``),
        rebased with the page's other links."""
        entries = "".join(f"<li><a href='{html.escape(target)}'>{html.escape(text)}</a></li>"
                          for text, target in items)
        self.blocks.append(f"<ul class='{html.escape(cls)}'>{entries}</ul>")

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


#: Characters that start inline markup in reStructuredText or a tag in Jinja (``{%``).
_RST_MARKUP = frozenset("\\`*_|[]<>{}%#")


def rst_text(text: str) -> str:
    """A paragraph of plain ``text`` as reStructuredText that reads as the text itself:
    every character that starts inline markup or a Jinja tag escaped (Snakemake renders a
    caption file through Jinja, then docutils), and the first one, so that the paragraph
    cannot start a list, a comment or a directive."""
    escaped = "".join(f"\\{c}" if c in _RST_MARKUP else c for c in text[1:])
    return (f"\\{text[0]}" if text else "") + escaped


class ReportSection:
    """A report section built from its declaration (:mod:`contactlab.report.declaration`).

    Text, captions and file names come from ``contactlab/report/sections/<name>.yaml``: the
    builder names each figure and table by its declared stem and each paragraph or note by
    its key, and gives the values of their ``{fields}``. :meth:`write` writes the page and,
    beside each figure and table written, its caption for Snakemake's report
    (``<stem>.rst``: the caption, the section's title and its caveats).
    """

    def __init__(self, name: str, report_dir: str | os.PathLike[str], *,
                 title: str | None = None, anchor: str | None = None) -> None:
        """The section ``name``; ``title`` and ``anchor`` replace the declared ones for a
        page of its own the section builds (one per test)."""
        self.declaration: Declaration = load(name)
        self.report_dir = Path(report_dir)
        self.page = Section(title or self.declaration.title, anchor or self.declaration.anchor,
                            self.report_dir)
        self.captions: dict[Path, str] = {}
        self.caveats: list[str] = []

    def say(self, key: str, /, **values: Any) -> str:
        """The declared text ``key`` with its fields filled (to compose a paragraph)."""
        return self.declaration.say(key, **values)

    def paragraph(self, key: str, /, **values: Any) -> None:
        """Add the declared text ``key`` as a paragraph."""
        self.page.paragraph(self.say(key, **values))

    def paragraph_text(self, text: str) -> None:
        """Add a paragraph composed of declared texts (:meth:`say`)."""
        self.page.paragraph(text)

    def note(self, key: str, /, **values: Any) -> None:
        """Add the declared text ``key`` as a highlighted note."""
        self.page.note(self.say(key, **values))

    def note_text(self, text: str) -> None:
        """Add a note composed of declared texts (:meth:`say`)."""
        self.page.note(text)

    def caveat(self, key: str, /, **values: Any) -> None:
        """Add a note on what the data are (e.g. RECONSTRUCTED, SYNTHETIC), repeated in the
        caption of every figure and table of the section in Snakemake's report."""
        text = self.say(key, **values)
        self.page.note(text)
        self.caveats.append(text)

    def heading(self, key: str, /, **values: Any) -> None:
        """Start a sub-section headed by the declared text ``key``."""
        self.page.heading(self.say(key, **values))

    def links(self, items: list[tuple[str, str]]) -> None:
        """Add a list of links to pages of the report (:meth:`Section.links`)."""
        self.page.links(items)

    def keys(self, prefix: str) -> list[str]:
        """The declared text keys ``<prefix><n>``, in the order declared."""
        return [key for key in self.declaration.text if key.startswith(prefix)
                and key[len(prefix):].isdigit()]

    def _file(self, kind: str, stem: str, values: dict[str, Any]) -> tuple[Path, str]:
        """The file and caption of a figure or table written; its caption file is written
        with the page."""
        path = self.declaration.file(kind, stem, self.report_dir, values)
        caption = self.declaration.caption(kind, stem, values)
        self.captions[path] = caption
        return path, caption

    def figure_path(self, stem: str, /, **values: Any) -> Path:
        """The PNG of the declared figure ``stem`` (for a figure drawn and saved elsewhere,
        :func:`save_figure`; show it with :meth:`image`)."""
        return self.declaration.file("figure", stem, self.report_dir, values)

    def figure(self, fig: plt.Figure, stem: str, /, **values: Any) -> None:
        """Save ``fig`` as the declared figure ``stem`` (PNG and PDF) and show it with its
        caption."""
        path, caption = self._file("figure", stem, values)
        self.page.figure(fig, caption, path)

    def image(self, stem: str, /, **values: Any) -> None:
        """Show the declared figure ``stem``, already saved, with its caption."""
        path, caption = self._file("figure", stem, values)
        self.page.image(path, caption)

    def image_of(self, section: str, stem: str, /, **values: Any) -> None:
        """Show a figure another section declares and saves (``section``'s figure ``stem``
        with its caption there), e.g. a test's fits on the test's own page."""
        other = load(section)
        self.page.image(other.file("figure", stem, self.report_dir, values),
                        other.caption("figure", stem, values))

    def table(self, table: pd.DataFrame, stem: str, /, digits: int = 4,
              units: Mapping[str, str] | str | None = None,
              margins: Mapping[str, str] | None = None, **values: Any) -> None:
        """Write ``table`` as the declared table ``stem`` (CSV, Markdown) and show it with
        its caption (units and digits: :meth:`Section.table`)."""
        path, caption = self._file("table", stem, values)
        self.page.table(table, caption, path, digits, units, margins)

    def table_file(self, table: pd.DataFrame, stem: str, /, digits: int = 4,
                   units: Mapping[str, str] | str | None = None,
                   margins: Mapping[str, str] | None = None, **values: Any) -> None:
        """Write ``table`` as the declared table ``stem`` (CSV, Markdown) without showing
        it on the page; its caption goes to Snakemake's report only."""
        path, _ = self._file("table", stem, values)
        write_table(table, path, digits, units=units, margins=margins)

    def caption_text(self, caption: str) -> str:
        """The caption file of a figure or table: its caption, the section it belongs to
        and the section's caveats, as reStructuredText (:func:`rst_text`)."""
        parts = [caption, f"Report section: {self.declaration.title}.", *self.caveats]
        return "\n\n".join(rst_text(part) for part in parts) + "\n"

    def write(self, path: str | os.PathLike[str]) -> None:
        """Write the section page to ``path`` and the caption file of every figure and
        table written (:func:`contactlab.report.declaration.caption_file`)."""
        for file, caption in self.captions.items():
            write_text(self.caption_text(caption), caption_file(file))
        self.page.write(path)
