"""Assemble ``results/report/index.html`` from the section fragments.

The page opens with the run's metadata (date, study, config hash, contactlab version, git
commit, what a named study changes) and an introduction saying what it holds, then a table
of contents beside the sections: the parts of the thesis (from the sections' file-name
numbers, docs/CONVENTIONS.md), each part's sections, and each section's sub-sections,
figures and tables. A section file is a page of its own (:mod:`contactlab.report.section`);
its ``<section>`` is taken with its links rebased from the section's folder to the page's.
"""

from __future__ import annotations

import datetime as dt
import html
import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from contactlab import __version__
from contactlab.io import history_time, write_text
from contactlab.report.style import STYLE, rebase_links

#: The parts of the page by the tens of a section's file-name number (``NN_<name>.html``).
PARTS = {
    1: "Surfaces (ch. 2)",
    2: "Contact stiffness (ch. 2)",
    3: "Asperity models (ch. 3)",
    5: "Receding contacts (chs 5-7)",
    7: "Finite element cross-checks (ch. 8)",
}
OTHER_PART = "Other sections"

_SECTION = re.compile(r"<section id='([^']+)'>\s*<h2>(.*?)</h2>.*</section>", re.S)
_ITEM = re.compile(r"<h3 id='([^']+)'>(.*?)</h3>|<figure(?: class='([^']*)')? id='([^']+)'>"
                   r".*?<figcaption>(.*?)</figcaption>", re.S)
_TAGS = re.compile(r"<[^>]+>")


@dataclass
class Fragment:
    """One section fragment and what its contents list: sub-sections, figures, tables."""

    path: Path
    text: str
    anchor: str
    title: str
    part: str
    headings: list[tuple[str, str]] = field(default_factory=list)
    figures: list[tuple[str, str]] = field(default_factory=list)
    tables: list[tuple[str, str]] = field(default_factory=list)


def _caption(text: str, limit: int = 90) -> str:
    """A caption's text (markup and the PDF/CSV link dropped), shortened for the contents."""
    plain = " ".join(html.unescape(_TAGS.sub("", text)).split())
    plain = re.sub(r"\s*\((PDF|CSV)\)$", "", plain)
    return plain if len(plain) <= limit else plain[:limit - 1].rstrip() + "…"


def part_of(path: Path) -> str:
    """The part a section belongs to, from its file name's number (``25_x.html``: 2)."""
    match = re.match(r"(\d+)_", path.name)
    return PARTS.get(int(match.group(1)) // 10, OTHER_PART) if match else OTHER_PART


def read_fragment(path: str | os.PathLike[str]) -> Fragment:
    """Parse a section file (its ``<section>``, links relative to the file's folder);
    ValueError naming the file if it holds none."""
    path = Path(path)
    match = _SECTION.search(path.read_text(encoding="utf-8"))
    if match is None:
        raise ValueError(f"{path}: not a report section (no <section id=...><h2>)")
    text = match.group(0) + "\n"
    fragment = Fragment(path, text, match.group(1), match.group(2), part_of(path))
    for item in _ITEM.finditer(text):
        heading_id, heading, kind, item_id, caption = item.groups()
        if heading_id:
            fragment.headings.append((heading_id, _caption(heading)))
        elif kind == "table":
            fragment.tables.append((item_id, _caption(caption)))
        else:
            fragment.figures.append((item_id, _caption(caption)))
    return fragment


def build_date() -> str:
    """When the page is built: ``SOURCE_DATE_EPOCH`` if set (reproducible builds), else now."""
    return history_time() or dt.datetime.now(dt.UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def run_header(provenance: dict[str, str], changes: dict[str, list],
               date: str | None = None) -> str:
    """The page's run metadata: date, study, config hash, version, commit, and what a study
    changes."""
    rows = [("built (UTC)", date or build_date()),
            ("study", provenance.get("study", "default")),
            ("config (SHA-256, first 16 hex digits)", provenance.get("config_sha256", "-")),
            ("contactlab version", __version__), ("git commit", provenance.get("git_commit", "-"))]
    cells = "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
                    for k, v in rows)
    text = f"<table class='run'>{cells}</table>\n"
    if changes:
        items = "".join(f"<tr><td><code>{html.escape(key)}</code></td>"
                        f"<td>{html.escape(json.dumps(old))}</td>"
                        f"<td>{html.escape(json.dumps(new))}</td></tr>"
                        for key, (old, new) in sorted(changes.items()))
        text += ("<p>This study changes the default study (config/config.yaml) in:</p>\n"
                 "<table class='changes'><tr><th>key</th><th>default</th><th>this study</th>"
                 f"</tr>{items}</table>\n")
    else:
        text += "<p>The default study (config/config.yaml), no changes.</p>\n"
    return text


def introduction(fragments: list[Fragment], intro: str = "") -> str:
    """What the page holds: the user's ``intro`` (if any), then the counts of sections,
    figures and tables, where their files are and how to read the page."""
    parts = list(dict.fromkeys(f.part for f in fragments))
    figures = sum(len(f.figures) for f in fragments)
    tables = sum(len(f.tables) for f in fragments)
    text = f"<p>{html.escape(intro)}</p>\n" if intro else ""
    text += (
        "<p>The report of one run of the contactlab workflow, which reproduces the "
        "computations of the thesis from the data in <code>resources/</code> and "
        f"<code>config/</code>. It holds {len(fragments)} section(s) in {len(parts)} "
        f"part(s) ({html.escape(', '.join(parts))}) with {figures} figure(s) and {tables} "
        "table(s). Each section is built from the result files of this run "
        "(<code>results/&lt;branch&gt;/*.nc</code>) and, where the thesis publishes a table "
        "or figure, shows the computed values beside the published ones. Notes on a yellow "
        "ground flag reconstructed demo data and cases that did not converge.</p>\n"
        "<p>Every figure links its PDF and every table its CSV (Markdown copy beside it), "
        "in <code>figures/</code> and <code>tables/</code> next to this page; Snakemake's "
        "report (<code>make report</code>) packs the figures and tables with their captions "
        "and provenance. The contents list each part, its sections and, unfolded, their "
        "figures and tables.</p>\n")
    return text


def _links(items: list[tuple[str, str]]) -> str:
    return "".join(f"<li><a href='#{html.escape(i)}'>{html.escape(c)}</a></li>"
                   for i, c in items)


def contents(fragments: list[Fragment]) -> str:
    """The navigable table of contents: parts, sections, sub-sections, figures, tables."""
    out = ["<nav id='contents'>\n<h2>Contents</h2>\n<ul>"]
    for part in dict.fromkeys(f.part for f in fragments):
        out.append(f"<li class='part'>{html.escape(part)}<ul>")
        for f in (f for f in fragments if f.part == part):
            inner = _links(f.headings)
            for label, items in (("figures", f.figures), ("tables", f.tables)):
                if items:
                    inner += (f"<li><details><summary>{len(items)} {label}</summary><ul>"
                              f"{_links(items)}</ul></details></li>")
            out.append(f"<li><a href='#{f.anchor}'>{f.title}</a>"
                       + (f"<ul>{inner}</ul>" if inner else "") + "</li>")
        out.append("</ul></li>")
    out.append("</ul>\n</nav>\n")
    return "\n".join(out)


def comparison_links(comparisons: list[tuple[str, str]]) -> str:
    """The list of comparison pages of studies (title, link relative to the page), or
    nothing if there are none."""
    if not comparisons:
        return ""
    items = "".join(f"<li><a href='{html.escape(href)}'>{html.escape(title)}</a></li>"
                    for title, href in comparisons)
    return ("<p>Comparisons of studies side by side (config/compare/; each is built once "
            "its studies are, <code>snakemake -j1 compare</code>):</p>\n"
            f"<ul class='comparisons'>{items}</ul>\n")


def build_index(sections: list[str | os.PathLike[str]], out: str | os.PathLike[str],
                title: str, intro: str = "", provenance: dict[str, str] | None = None,
                changes: dict[str, list] | None = None, date: str | None = None,
                comparisons: list[tuple[str, str]] | None = None) -> Path:
    """Write the report page: run metadata, the comparison pages of studies
    (``comparisons``: title and link relative to the page), introduction, contents and the
    sections in the order given, grouped by part."""
    fragments = [read_fragment(p) for p in sections]
    body, part = [], None
    for f in fragments:
        if f.part != part:
            part = f.part
            body.append(f"<h2 class='part'>{html.escape(part)}</h2>")
        body.append(rebase_links(f.text, f.path.parent, Path(out).parent)
                    + "<p class='top'><a href='#contents'>back to the contents</a></p>")
    page = (
        "<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
        f"<title>{html.escape(title)}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
        f"<header>\n<h1>{html.escape(title)}</h1>\n"
        + run_header(provenance or {}, changes or {}, date)
        + comparison_links(comparisons or [])
        + introduction(fragments, intro)
        + "</header>\n<div class='layout'>\n"
        + contents(fragments)
        + "<main>\n" + "\n".join(body) + "\n</main>\n</div>\n"
        + f"<footer><p>Generated by contactlab {__version__}.</p></footer>\n</body>\n</html>\n"
    )
    return write_text(page, out)
