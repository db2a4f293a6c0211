"""A comparison page of several studies: their parameters and headline results overlaid.

A compare file (``config/compare/<name>.yaml``, schema ``contactlab/schemas/compare.schema.yaml``)
names the studies and the headline quantities (:mod:`contactlab.studies.headline`)::

    title: Friction and the lifting-off layer
    studies: [default, fine_friction, line_lambda]   # the first is the reference
    quantities: [gap.f_stick, gap.f_sep, line.a, line.b, line.K_T]

:func:`build_compare_page` writes ``results/compare/<name>/index.html``: the studies (state
and provenance from :mod:`contactlab.studies.catalog`), the parameters that differ, the
headline results that differ (:mod:`contactlab.studies.diff`), and one figure per quantity
with every study's curve in its own colour, the legend naming the study and the keys it
changes against the default study, beside a figure of each study's change from the
reference (relative where that helps); links to each study's report; which study lacks which
points of the others'. Figures and tables are written with
:mod:`contactlab.report.section` (PNG and PDF, CSV and Markdown) beside the page.
A family's page (``results/studies/<family>/compare/index.html``) is the same page over the
family's variants.
"""

from __future__ import annotations

import html
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from contactlab.config_check import ConfigError, load_yaml_file
from contactlab.schema import schema_file

#: The compare files' folder and schema, relative to the repository root.
COMPARE_DIR = "config/compare"
#: Panels of a two-dimensional quantity (one per value of its second coordinate) at most.
MAX_PANELS = 4
#: Marker shapes of the studies in a figure, in order.
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "h")


def read_compare_file(path: str | os.PathLike[str]) -> dict[str, Any]:
    """A compare file, checked against the schema, its quantities against the known ones;
    ConfigError naming the file and the field otherwise."""
    from jsonschema import Draft202012Validator

    from contactlab.studies.headline import BY_ID

    spec = load_yaml_file(path)
    schema = load_yaml_file(schema_file("compare"))
    errors = sorted(Draft202012Validator(schema).iter_errors(spec), key=lambda e: list(e.path))
    if errors:
        raise ConfigError("\n".join(
            f"{path}: {'.'.join(map(str, e.path)) or '(top level)'}: {e.message}"
            for e in errors))
    for i, name in enumerate(spec["quantities"]):
        if name not in BY_ID:
            raise ConfigError(f"{path}: quantities[{i}]: unknown quantity {name!r}; known: "
                              f"{', '.join(BY_ID)}")
    return spec


def compare_files(root: str | os.PathLike[str] = ".") -> dict[str, Path]:
    """The compare files of the repository at ``root`` by name (file stem)."""
    return {p.stem: p for p in sorted((Path(root) / COMPARE_DIR).glob("*.yaml"))}


def read_compare_files(root: str | os.PathLike[str] = "."
                       ) -> tuple[dict[str, dict[str, Any]], dict[str, str]]:
    """Every compare file read (:func:`read_compare_file`) by name, and why each file that
    cannot be read cannot: only a run that asks for its page fails on it."""
    specs, problems = {}, {}
    for name, path in compare_files(root).items():
        try:
            specs[name] = read_compare_file(path)
        except ConfigError as exc:
            problems[name] = str(exc)
    return specs, problems


def index_links(report_dir: str | os.PathLike[str] = "results/report",
                root: str | os.PathLike[str] = ".") -> list[tuple[str, str]]:
    """The comparison pages of the compare files that have been built, as (title, link
    relative to the report folder ``report_dir``), for the report page's list
    (:func:`contactlab.report.index.build_index`, ``comparisons``); a page not built yet is
    not linked (the report rule lists them again when one is)."""
    links = []
    for name, path in compare_files(root).items():
        page = Path("results/compare") / name / "index.html"
        if not (Path(root) / page).is_file():
            continue
        try:
            title = load_yaml_file(path).get("title") or name
        except ConfigError:
            title = name
        links.append((str(title), os.path.relpath(page, report_dir)))
    return links


def study_results(name: str) -> str:
    """The results folder of the study ``name`` (``default``: ``results/``)."""
    from contactlab.provenance import results_dir

    return results_dir(None if name == "default" else name)


def page_inputs(studies: Sequence[str], quantities: Sequence[str]) -> list[str]:
    """The result files the page of ``studies`` and ``quantities`` reads."""
    from contactlab.studies.headline import BY_ID

    files = {BY_ID[q].file for q in quantities}
    return [f"{study_results(s)}{f}" for s in studies for f in sorted(files)]


class StudiesNotBuilt(FileNotFoundError):
    """A comparison page asked for studies whose results are not there yet."""


def unknown_studies(studies: Sequence[str], run_studies: Sequence[str] = (),
                    root: str | os.PathLike[str] = ".") -> list[str]:
    """The names of ``studies`` that are no study of the repository (:func:`contactlab.
    studies.catalog.discover`) nor of this run."""
    from contactlab.studies.catalog import discover

    known = {*discover(root), *run_studies}
    return [name for name in studies if name not in known]


def compare_page_inputs(compares: Mapping[str, Mapping[str, Any]], run_studies: Sequence[str],
                        problems: Mapping[str, str] | None = None):
    """Input function of the ``compare_page`` rule: the result files the page of the
    ``{name}`` wildcard reads -- all of them for the studies this run builds
    (``run_studies``), those that exist for the others (the page notes what a study lacks).
    ConfigError for a compare file that cannot be read (``problems``) or names a study that
    does not exist; StudiesNotBuilt, naming them and how to build them, for studies that
    have no result."""
    problems = problems or {}

    def inputs(wildcards: Any) -> list[str]:
        if wildcards.name in problems:
            raise ConfigError(problems[wildcards.name])
        spec = compares[wildcards.name]
        unknown = unknown_studies(spec["studies"], run_studies)
        if unknown:
            raise ConfigError(f"config/compare/{wildcards.name}.yaml: studies: no study "
                              f"{', '.join(map(repr, unknown))}: name the default study, a "
                              "study file's study or a family's <family>/<variant> "
                              "(contactlab studies list)")
        files, absent = [], []
        for study in spec["studies"]:
            wanted = page_inputs([study], spec["quantities"])
            have = wanted if study in run_studies else [f for f in wanted if Path(f).exists()]
            files += have
            if not have:
                absent.append(study)
        if absent:
            raise StudiesNotBuilt(
                f"config/compare/{wildcards.name}.yaml compares studies with none of the "
                f"results it shows: {', '.join(absent)}. Build each first (snakemake -j2 all "
                "--configfile config/studies/<file>.yaml; the default study: snakemake -j2 "
                "all), or just the files the page reads: "
                f"{', '.join(page_inputs(absent, spec['quantities']))}")
        return files

    return inputs


def legend_label(name: str, changes: Mapping[str, Sequence[Any]], limit: int = 3) -> str:
    """A study's legend entry: its name and the keys it changes against the default study
    with their values (``fine_friction: receding.gap.chunks=8, ...``), at most ``limit``."""
    from contactlab.studies.diff import format_value

    items = [f"{key}={format_value(value[1])}" for key, value in changes.items()]
    if not items:
        return f"{name} (no changes)" if name != "default" else name
    more = f", +{len(items) - limit} more" if len(items) > limit else ""
    return f"{name}: {', '.join(items[:limit])}{more}"


def overlay_figure(q, data: Sequence[Any], labels: Sequence[str], ylabel: str | None = None,
                   title: str | None = None, first_style: int = 0):
    """One quantity of several studies in one figure: a line per study along its first
    coordinate (a panel per value of a second coordinate common to all, at most
    :data:`MAX_PANELS`), a marker per study for a single number. ``ylabel`` and ``title``
    replace the quantity's (its name, or ratio in units of c, with its unit; its label);
    ``first_style``: the style of the first study drawn (a difference figure starts at the
    second study's)."""
    import matplotlib.pyplot as plt
    import numpy as np

    from contactlab.display import axis_label, symbol

    colours = plt.get_cmap("tab10")
    # hollow markers of their own shape, larger for the earlier studies: curves that
    # coincide stay visible one inside the other
    style = [{"color": colours(i % 10), "marker": MARKERS[i % len(MARKERS)],
              "mfc": "none", "ms": 4 + 2.5 * (len(data) + first_style - 1 - i), "lw": 1.0}
             for i in range(first_style, first_style + len(data))]
    present = [(d, lab, st) for d, lab, st in zip(data, labels, style, strict=True)
               if d is not None]
    first = present[0][0]
    ylabel = ylabel or axis_label(symbol(q.variable, first.attrs.get("long_name")),
                                  first.attrs.get("units"))
    legend_height = 0.17 * len(present) + 0.15
    if first.ndim == 0:
        fig, ax = plt.subplots(figsize=(6.5, 3.2 + legend_height))
        for i, (d, lab, st) in enumerate(present):
            ax.plot([i], [float(d.values)], ls="none", label=lab, **st)
        ax.set_xticks(range(len(present)), [lab.split(":")[0] for _, lab, _ in present])
        ax.set_ylabel(ylabel)
    else:
        dim = first.dims[0]
        if first.ndim == 1:
            panels = [None]
        else:
            other = first.dims[1]
            common = set(np.asarray(first[other].values).tolist())
            for d, _, _ in present[1:]:
                common &= set(np.asarray(d[other].values).tolist())
            values = [v for v in np.asarray(first[other].values).tolist() if v in common]
            step = max(1, -(-len(values) // MAX_PANELS))
            panels = [(other, v) for v in values[::step][:MAX_PANELS]]
        fig, axes = plt.subplots(1, len(panels), squeeze=False, sharey=True,
                                 figsize=(max(6.5, 3.4 * len(panels)), 3.4 + legend_height))
        for ax, panel in zip(axes[0], panels, strict=True):
            for d, lab, st in present:
                line = d if panel is None else d.sel({panel[0]: panel[1]})
                x = line[dim].values if dim in line.coords else np.arange(line.size)
                numeric = np.asarray(x).dtype.kind in "fiu"
                ax.plot(x if numeric else np.arange(len(x)), line.values, label=lab, **st)
                if not numeric:
                    ax.set_xticks(np.arange(len(x)), [str(v) for v in x], rotation=45,
                                  ha="right")
            coordinate = first[dim].attrs if dim in first.coords else {}
            ax.set_xlabel(axis_label(symbol(dim, coordinate.get("long_name")),
                                     coordinate.get("units")))
            if panel is not None:
                ax.set_title(f"{panel[0]} = {panel[1]:g}" if isinstance(panel[1], float)
                             else f"{panel[0]} = {panel[1]}", fontsize=9)
        axes[0][0].set_ylabel(ylabel)
    handles, names = fig.axes[0].get_legend_handles_labels()
    fig.suptitle(title or q.label, fontsize=9)
    fig.legend(handles, names, fontsize=7, loc="lower center", frameon=False, ncols=1)
    fig.tight_layout(rect=(0, legend_height / fig.get_figheight(), 1, 1))
    return fig


def difference_figure(q, data: Sequence[Any], labels: Sequence[str], reference: str):
    """The differences of each study from the reference (the first of ``data``) along the
    quantity's coordinates (:func:`contactlab.studies.diff.difference`), relative in
    percent where that helps (:func:`contactlab.studies.diff.helps_relative`); None when
    the reference or every other study lacks the quantity."""
    from contactlab.display import axis_label, symbol
    from contactlab.studies.diff import difference, helps_relative

    if data[0] is None or all(d is None for d in data[1:]):
        return None
    relative = helps_relative(data[0].values)
    changes = [None if d is None else difference(data[0], d, relative) for d in data[1:]]
    name = symbol(q.variable, data[0].attrs.get("long_name"))
    ylabel = axis_label(f"{name} - {name} of {reference}", data[0].attrs.get("units")) \
        if not relative else f"({name} - {name} of {reference}) / |{name} of {reference}| (%)"
    fig = overlay_figure(q, changes, labels[1:], ylabel=ylabel,
                         title=f"{q.label}: change from {reference}", first_style=1)
    for ax in fig.axes:
        ax.axhline(0.0, color="0.4", lw=0.6)
    return fig


def study_report(study: str, root: str | os.PathLike[str] = ".") -> Path | None:
    """The report page of ``study`` if it has been built."""
    page = Path(root) / study_results(study) / "report" / "index.html"
    return page if page.is_file() else None


def build_compare_page(name: str, title: str, studies: Sequence[str],
                       quantities: Sequence[str], out: str | os.PathLike[str],
                       root: str | os.PathLike[str] = ".", description: str = "",
                       units: Mapping[str, str] | None = None) -> Path:
    """Write the comparison page of ``studies`` (names; the first is the reference) over
    ``quantities`` (headline ids) to ``out`` (its figures and tables beside it).

    Parameters
    ----------
    name : the comparison's name (its folder; the page's anchor).
    title, description : the page's heading and introductory paragraph.
    studies, quantities : what to compare.
    out : the page, ``results/compare/<name>/index.html`` by convention.
    root : the repository root (where config/ and results/ are).
    units : the unit of each config key (the command options' declarations).
    """
    import pandas as pd

    from contactlab.io import write_text
    from contactlab.report.index import build_date
    from contactlab.report.section import Section
    from contactlab.studies.catalog import discover, study_status
    from contactlab.studies.diff import (
        diff_studies,
        format_percent,
        format_value,
        points_not_compared,
    )
    from contactlab.studies.effective import load_schema
    from contactlab.studies.headline import quantity, read_quantity
    from contactlab.studies.manifest import netcdf_provenance

    root, out = Path(root), Path(out)
    folder = out.parent
    known = discover(root)
    schema = load_schema()
    statuses = {s: study_status(known[s], root, schema) if s in known else None
                for s in studies}
    chosen = [quantity(q) for q in quantities]
    diff = diff_studies(studies, root, chosen, units=units)
    section = Section(title, f"compare-{name}", folder)
    if description:
        section.paragraph(description)
    rows = []
    for s in studies:
        st = statuses[s]
        made = {}
        for q in chosen:  # what the compared files were made with
            path = root / study_results(s) / q.file
            if path.exists():
                made = netcdf_provenance(path)
                break
        rows.append({"study": s, "results": study_results(s),
                     "config (SHA-256)": made.get("config_sha256", "-"),
                     "git commit": made.get("git_commit", "-"),
                     "changes against the default study": "; ".join(
                         f"{k} = {format_value(v[1])}"
                         for k, v in (st.changes if st else {}).items()) or "-"})
    section.heading("Studies")
    section.table(pd.DataFrame(rows), f"The studies compared (the first, {studies[0]}, is the "
                  "reference of every change below), the config hash and commit their "
                  "compared result files record, and what each changes against the default "
                  "study (contactlab studies list tells which are complete or stale).",
                  folder / "tables" / "studies.csv")
    reports = {s: study_report(s, root) for s in studies}
    section.links([(f"Report of {s}", os.path.relpath(page, folder))
                   for s, page in reports.items() if page is not None])
    unbuilt = [s for s, page in reports.items() if page is None]
    if unbuilt:
        section.paragraph(f"No report built yet for {', '.join(unbuilt)} (snakemake -j2 "
                          "all with the study's config builds it).")
    section.heading("Parameters")
    if diff.parameters:
        table = pd.DataFrame([{"key": r.key, "units": r.units or "-",
                               **{s: format_value(v) for s, v in
                                  zip(studies, r.values, strict=True)}}
                              for r in diff.parameters])
        section.table(table, "Config keys whose values differ between the studies.",
                      folder / "tables" / "parameters.csv")
    else:
        section.paragraph("The studies' effective configs are the same.")
    section.heading("Headline results")
    if diff.results:
        table = pd.DataFrame([{"quantity": r.key, "at": r.at or "-", "units": r.units,
                               studies[0]: format_value(r.values[0]),
                               **{f"{s} (Δ%)": f"{format_value(v)} ({format_percent(rel)})"
                                  for s, v, rel in zip(studies[1:], r.values[1:],
                                                       r.rel_change, strict=True)}}
                              for r in diff.results])
        section.table(table, f"Headline results that differ ({len(diff.results)} of "
                      f"{diff.results_compared} compared at the points every study has; "
                      f"{diff.results_equal} equal); the relative change is against "
                      f"{studies[0]}.", folder / "tables" / "results.csv")
    else:
        section.paragraph(f"All {diff.results_compared} headline values compared are equal.")
    for line in points_not_compared(diff):
        section.note(line)
    section.paragraph("Each quantity: every study's values overlaid (left) and each study's "
                      f"change from {studies[0]} at the points both have (right; relative, "
                      "in percent, where no reference value is near zero). Lengths of the "
                      "receding contacts are in units of the layer thickness c (a/c, b/c, "
                      "w/c).")
    for q in chosen:
        data = [read_quantity(root / study_results(s), q) for s in studies]
        if all(d is None for d in data):
            section.note(f"{q.id}: no study has {q.file}.")
            continue
        labels = [legend_label(s, statuses[s].changes if statuses[s] else {}) for s in studies]
        missing = [s for s, d in zip(studies, data, strict=True) if d is None]
        caption = (f"{q.label}: {', '.join(s for s in studies if s not in missing)} "
                   f"({q.file}, variable {q.variable}); the legend names each study's "
                   "changed keys.")
        if missing:
            caption += f" Not in {', '.join(missing)}."
        stem = q.id.replace(".", "_")
        figures = [(overlay_figure(q, data, labels), caption, folder / "figures" / f"{stem}.png")]
        change = difference_figure(q, data, labels, studies[0])
        if change is not None:
            figures.append((change, f"{q.label}: each study minus {studies[0]} at the points "
                            "both have.", folder / "figures" / f"{stem}_change.png"))
        section.figure_row(figures)
    page = (
        "<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<p class='built'>Built {html.escape(build_date())} from the studies' result "
        "files by contactlab.studies.compare.</p>\n"
        + section.render() + "</body>\n</html>\n")
    return write_text(page, out)


_STYLE = """
body { font-family: sans-serif; margin: 1em auto; max-width: 90em; padding: 0 1.5em; color: #222; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { padding: 0.2em 0.6em; border-bottom: 1px solid #ccc; text-align: left; }
figure { margin: 1.5em 0; overflow-x: auto; } figure img { max-width: 100%; }
figcaption { font-size: 0.9em; color: #333; margin-top: 0.4em; }
.figure-row { display: flex; flex-wrap: wrap; gap: 1.5em; align-items: flex-start; }
.figure-row figure { flex: 1 1 32em; margin: 1em 0; }
.note { background: #fff4d6; padding: 0.5em; border-left: 4px solid #e0a800; }
p.built { font-size: 0.85em; color: #555; }
"""


def compare_page_from_file(path: str | os.PathLike[str], out: str | os.PathLike[str],
                           root: str | os.PathLike[str] = ".",
                           units: Mapping[str, str] | None = None) -> Path:
    """The page of one compare file (:func:`read_compare_file`) written to ``out``."""
    spec = read_compare_file(path)
    return build_compare_page(Path(path).stem, spec.get("title", Path(path).stem),
                              spec["studies"], spec["quantities"], out, root,
                              spec.get("description", ""), units)


def family_page(family: str, grid: Mapping[str, Any], studies: Sequence[str],
                quantities: Sequence[str], out: str | os.PathLike[str],
                root: str | os.PathLike[str] = ".",
                units: Mapping[str, str] | None = None) -> Path:
    """The comparison page of a family's variants (``studies``, the first the reference)
    over ``quantities``, written to ``out``; ``grid`` is the family file's grid."""
    values = ", ".join(f"{key}: {value}" for key, value in grid.items())
    return build_compare_page(family, f"Family {family}: {len(studies)} variants", studies,
                              quantities, out, root,
                              f"Every variant of the family's grid ({values}), against the "
                              "first.", units)
