"""Each report section is declared once (contactlab/report/sections/<name>.yaml): its
builder shows what it declares and nothing else, its rule declares the same files
(tests/test_rulehelpers.py; the end-to-end run builds them, tests/test_workflow.py), and
Snakemake's report gets each caption from the file the builder writes."""

from __future__ import annotations

import ast
import html
import re
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd
import pytest
from docutils.core import publish_parts
from jinja2 import Environment

from contactlab.report.declaration import DeclarationError, fields, load, names, parse
from contactlab.report.section import ReportSection, rst_text

SRC = Path(__file__).resolve().parents[1] / "src" / "contactlab"
#: Every report builder: a branch's report module (or report_<part>).
BUILDERS = sorted(p for p in SRC.glob("*/**/report*.py") if p.parent.name != "report")
#: The ReportSection methods that take a declared key, and the position of the key.
KEY_ARGUMENT = {"say": 0, "paragraph": 0, "note": 0, "caveat": 0, "heading": 0,
                "figure_path": 0, "image": 0, "figure": 1, "table": 1, "table_file": 1}


def test_every_section_is_declared_once_with_files_of_its_own() -> None:
    declarations = [load(name) for name in names()]
    assert len(declarations) == 15
    assert len({d.anchor for d in declarations}) == len({d.title for d in declarations}) == 15
    stems: dict[tuple[str, str], str] = {}
    for declaration in declarations:
        assert re.match(r"^\d\d_[a-z0-9_]+$", declaration.name)
        for (kind, stem) in declaration.items:
            assert (kind, stem) not in stems, f"{stem} in {stems.get((kind, stem))} and " \
                                              f"{declaration.name}"
            stems[(kind, stem)] = declaration.name


def _literals(node: ast.AST) -> set[str]:
    """The string literals an argument can take (through ``a if c else b``), not the
    pieces of an f-string."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return {node.value}
    if isinstance(node, ast.IfExp):
        return _literals(node.body) | _literals(node.orelse)
    return set()


def _keys_in(path: Path) -> tuple[set[str], set[str], set[str], list[str]]:
    """Of a builder: its string constants, the heads of its f-strings and ``keys(...)``
    prefixes, the keys it passes to ReportSection methods, and the sections it builds."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    constants, prefixes, used = set(), set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            constants.add(node.value)
        elif isinstance(node, ast.JoinedStr) and node.values \
                and isinstance(node.values[0], ast.Constant):
            prefixes.add(node.values[0].value)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and isinstance(node.func.value, ast.Name) \
                and node.func.value.id in ("section", "sec"):
            method = node.func.attr
            if method == "keys":
                prefixes.add(node.args[0].value)
            elif method in KEY_ARGUMENT and len(node.args) > KEY_ARGUMENT[method]:
                used |= _literals(node.args[KEY_ARGUMENT[method]])
    built = {node.args[0].value for node in ast.walk(tree) if isinstance(node, ast.Call)
             and getattr(node.func, "id", getattr(node.func, "attr", "")) == "ReportSection"
             and node.args and isinstance(node.args[0], ast.Constant)}
    # the sections it builds: those it makes a ReportSection of (it may show another's
    # figures by name), else every section it names
    return constants, prefixes, used, [n for n in names() if n in (built or constants)]


@pytest.mark.parametrize("builder", BUILDERS, ids=lambda p: str(p.relative_to(SRC)))
def test_a_builder_shows_what_its_declaration_lists_and_nothing_else(builder: Path) -> None:
    """Every text, figure and table of the builder's declaration(s) is named in the builder
    (a key, or a prefix it completes such as ``flag_<name>``), and every key the builder
    passes to its section is declared."""
    constants, prefixes, used, sections = _keys_in(builder)
    assert sections, f"{builder.name} builds no declared section"
    declared = set()
    for name in sections:
        declaration = load(name)
        declared |= set(declaration.text) | {stem for _, stem in declaration.items}
    unused = {key for key in declared if key not in constants
              and not any(key.startswith(p) for p in prefixes if p.endswith("_"))}
    assert not unused, f"declared but not written by {builder.name}: {sorted(unused)}"
    assert not used - declared, f"written but not declared: {sorted(used - declared)}"


def _plain(rst: str) -> str:
    """A caption file as Snakemake shows it: Jinja, then docutils, as text."""
    body = publish_parts(Environment().from_string(rst).render(), writer="html")["body"]
    return html.unescape(re.sub(r"<[^>]+>", "", body)).strip()


@pytest.mark.parametrize("name", names())
def test_every_caption_reaches_snakemakes_report_as_written(name: str) -> None:
    """Each caption of the section, its fields filled, survives Jinja and reStructuredText
    unchanged: no character of it starts markup, a list or a template tag."""
    declaration = load(name)
    for item in declaration.items.values():
        caption = item.caption.format(**dict.fromkeys(fields(item.caption), 1))
        assert _plain(rst_text(caption)) == caption
    for tricky in ("1. a_b |x| *y* `z` [1]_ w_ {{ v }} {% t %} {# c #} 95% \\ end",
                   "- item", ".. note:: n", "(a) list", "----", "Term: with colon"):
        assert _plain(rst_text(tricky)) == tricky


def test_a_section_writes_declared_files_with_their_captions(tmp_path: Path) -> None:
    section = ReportSection("50_receding_gap", tmp_path)
    section.paragraph("problem")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    section.figure(fig, "receding_gap_zones", f_fixed=0.5, w_fixed=2.5)
    section.table(pd.DataFrame({"w/c": [1.0]}), "receding_gap_thresholds")
    section.table_file(pd.DataFrame({"N": [1]}), "receding_gap_summary")
    section.write(tmp_path / "sections" / "50_receding_gap.html")
    page = (tmp_path / "sections" / "50_receding_gap.html").read_text()
    assert "Transition points: against w/c at f = 0.5 (top), against f at w/c = 2.5" in page
    assert "receding_gap_summary" not in page  # written, not shown
    caption = (tmp_path / "figures" / "receding_gap_zones.rst").read_text()
    assert _plain(caption).startswith("Transition points: against w/c at f = 0.5 (top)")
    assert "Report section: Receding contact: layer with a gap" in _plain(caption)
    for stem in ("receding_gap_thresholds", "receding_gap_summary"):
        assert (tmp_path / "tables" / f"{stem}.rst").is_file()
        assert (tmp_path / "tables" / f"{stem}.md").is_file()


def test_a_builder_cannot_show_what_is_not_declared(tmp_path: Path) -> None:
    section = ReportSection("50_receding_gap", tmp_path)
    with pytest.raises(DeclarationError, match=r"50_receding_gap.yaml: no figure 'gap_map' "
                                               r"in figures: declare it there"):
        section.figure_path("gap_map")
    with pytest.raises(DeclarationError, match=r"50_receding_gap.yaml: no text 'intro'"):
        section.paragraph("intro")
    with pytest.raises(DeclarationError, match=r"figure 'receding_gap_zones': caption needs "
                                               r"the value 'w_fixed'"):
        section.image("receding_gap_zones", f_fixed=0.5)


def test_caveats_reach_every_caption_of_the_section(tmp_path: Path) -> None:
    section = ReportSection("22_dic", tmp_path)
    section.caveat("reconstructed", tests="RU1i")
    section.table(pd.DataFrame({"test": ["RU1i"]}), "dic_quality")
    section.write(tmp_path / "sections" / "22_dic.html")
    caption = _plain((tmp_path / "tables" / "dic_quality.rst").read_text())
    assert "The frames of RU1i are RECONSTRUCTED" in caption
    assert "The frames of RU1i are RECONSTRUCTED" in \
        (tmp_path / "sections" / "22_dic.html").read_text()


@pytest.mark.parametrize(("data", "message"), [
    ([], "expected a mapping"),
    ({"title": "T", "anchor": "t", "category": "C", "figure": {}}, r"unknown key\(s\) figure"),
    ({"title": "T", "anchor": "t"}, "missing category"),
    ({"title": "T", "anchor": "t", "category": "C", "figures": {"a": {"when": "x"}}},
     "figures: a: give a caption"),
    ({"title": "T", "anchor": "t", "category": "C", "tables": {"a b": "c"}},
     "tables: 'a b' is not a file stem"),
    ({"title": "T", "anchor": "t", "category": "C", "tables": {"a": "c {x"}},
     "tables: a: caption: .*write a brace as"),
    ({"title": "T", "anchor": "t", "category": "C",
      "tables": {"a": {"caption": "c", "when": "fe.enabled"}}}, "when must name a condition"),
    ({"title": "T", "anchor": "t", "category": "C",
      "tables": {"a": {"caption": "c", "where": "x"}}}, r"unknown key\(s\) where"),
    ({"title": "T", "anchor": "t", "category": "C", "text": {"p": 3}}, "text: p: expected a"),
    ({"title": "T", "anchor": "t", "category": "C",
      "figures": {"a_{x}": {"caption": "c", "subcategory": "{y}"}}}, "subcategory must be"),
])
def test_a_malformed_declaration_is_named_with_its_field(data: object, message: str) -> None:
    with pytest.raises(DeclarationError, match=r"sections/99_x.yaml: .*" + message):
        parse("99_x", data)
