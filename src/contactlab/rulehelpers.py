"""Helpers of the rule files (``workflow/rules/*.smk``): the one home of the workflow's logic.

The rule files stay declarative (inputs, outputs, params, one shell command); what needs
a loop or a decision lives here, as plain functions of config sections, the test sheet
and wildcard values, so it is tested (tests/test_rulehelpers.py) and ``snakemake --lint``
stays clean. Command-line options are returned as lists of words, which a rule passes as
one quoted argument each (``{params.x:q}``); ``results`` is the study's results folder
(``results/`` or ``results/studies/<name>/``). Nothing here imports Snakemake or reads
files other than the package's own report declarations.

Sections: the arguments of a declared command (:func:`command_args`); the report files a
rule declares (:func:`section_files`, from the section's declaration); contact stiffness
(which tests have raw data, their files); receding contacts (sweep values, chunks, profile
names); finite elements (the values of a run that are not config values, file lists).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from contactlab.cli import command
from contactlab.published import PUBLISHED_TESTS


def command_args(path: str, config: Mapping[str, Any], **values: Any) -> list[str]:
    """The arguments a rule passes to ``contactlab <path>``: ``values`` and every option the
    command takes from the config, read from the effective ``config`` (see
    :meth:`contactlab.command.Command.words`)."""
    return command(path).words(config, **values)

# --------------------------------------------------------------------------- report files


def table_files(*csv: str) -> list[str]:
    """Each report table with the Markdown copy :func:`contactlab.io.write_table` writes."""
    return [path for name in csv for path in (name, str(Path(name).with_suffix(".md")))]


@dataclass(frozen=True)
class ReportFile:
    """A figure (PNG) or table (CSV) of a report section: its path, its caption file for
    Snakemake's report, its stem and its sub-category there (None: none)."""

    path: str
    caption: str
    stem: str
    subcategory: str | None


@dataclass(frozen=True)
class SectionFiles:
    """Every file a report section's builder writes, as its declaration lists them."""

    section: str
    category: str
    figures: list[ReportFile]
    tables: list[ReportFile]

    @property
    def pdfs(self) -> list[str]:
        """The PDF copy :func:`contactlab.report.section.save_figure` writes of each figure."""
        return [str(Path(f.path).with_suffix(".pdf")) for f in self.figures]

    @property
    def markdown(self) -> list[str]:
        """The Markdown copy :func:`contactlab.io.write_table` writes of each table."""
        return [str(Path(t.path).with_suffix(".md")) for t in self.tables]

    @property
    def captions(self) -> list[str]:
        """The caption file of every figure and table."""
        return [f.caption for f in (*self.figures, *self.tables)]


def section_page(name: str, results: str = "results/") -> str:
    """The page of report section ``name``: ``<results>report/sections/<name>.html``."""
    return f"{results}report/sections/{name}.html"


def section_files(name: str, results: str = "results/", **values: Any) -> SectionFiles:
    """The files of report section ``name`` from its declaration
    (``contactlab/report/sections/<name>.yaml``, :mod:`contactlab.report.declaration`).

    ``values`` give what the rule knows: for each field of a stem the list of its values
    (``problem=["line", "uniform"]``: one figure per value), for each ``when`` condition
    whether it holds (``fe=True``). ValueError naming the declaration if a field or a
    condition has no value, or a value is given that the declaration does not use.
    """
    from itertools import product

    from contactlab.report.declaration import FOLDERS, caption_file, load

    declaration = load(name)
    report_dir = f"{results}report"
    used: set[str] = set()
    files: dict[str, list[ReportFile]] = {"figure": [], "table": []}
    for item in declaration.items.values():
        needed = ([item.when] if item.when else []) + item.fields
        missing = [key for key in needed if key not in values]
        if missing:
            raise ValueError(f"{declaration.path}: {FOLDERS[item.kind]}: {item.stem} needs "
                             f"{', '.join(missing)} from the rule")
        used.update(needed)
        if item.when and not values[item.when]:
            continue
        for combination in product(*(values[field] for field in item.fields)):
            filled = dict(zip(item.fields, combination, strict=True))
            path = declaration.file(item.kind, item.stem, report_dir, filled)
            files[item.kind].append(ReportFile(
                str(path), str(caption_file(path)), path.stem,
                item.subcategory.format(**filled) if item.subcategory else None))
    unused = sorted(set(values) - used)
    if unused:
        raise ValueError(f"{declaration.path}: no figure or table uses {', '.join(unused)}")
    return SectionFiles(section_page(name, results), declaration.category,
                        files["figure"], files["table"])


# --------------------------------------------------------------------------- stiffness


def demo_data_files(directory: str = "results/demo") -> list[str]:
    """The raw-data paths the demo rules write (accepted as missing at start-up): each
    thesis test's load log and fields, and its image folder (:func:`demo_image_folder`)."""
    return [*(f"{directory}/{test}/{name}" for test in PUBLISHED_TESTS
              for name in ("load_log.csv", "fields.nc")),
            *(demo_image_folder(test, directory) for test in PUBLISHED_TESTS)]


def demo_image_folders(sheet: pd.DataFrame) -> list[str]:
    """The image demo folders the test sheet's ``images`` column names (inputs all studies
    share, built before a run plans them: :mod:`contactlab.studies.shared`)."""
    demos = set(demo_data_files())
    column = sheet["images"] if "images" in sheet else []
    return sorted({str(cell).strip() for cell in column
                   if isinstance(cell, str) and cell.strip() in demos})


def demo_image_folder(test: str, directory: str = "results/demo") -> str:
    """The folder of the RECONSTRUCTED image demo of thesis test ``test`` (rule
    ``dic_demo``), which a test-sheet row may name in its ``images`` column."""
    return f"{directory}/{test}_images"


def has_path(sheet: pd.DataFrame, test: str, column: str) -> bool:
    """True if the test-sheet cell ``column`` of ``test`` holds a path."""
    value = sheet.loc[test].get(column)
    return value is not None and not pd.isna(value) and str(value).strip() != ""


def raw_tests(sheet: pd.DataFrame) -> list[str]:
    """Tests with a load log and fields, images or a contact-displacement file, in sheet
    order."""
    return [str(t) for t in sheet.index
            if has_path(sheet, t, "load_log")
            and any(has_path(sheet, t, c) for c in ("fields", "images", "contact_displacement"))]


def image_tests(sheet: pd.DataFrame) -> list[str]:
    """Tests whose displacements are correlated from their camera frames (``images``)."""
    return [t for t in raw_tests(sheet) if has_path(sheet, t, "images")]


def image_fields(test: str, results: str = "results/") -> str:
    """The DIC fields correlated from the frames of image test ``test`` (rule
    ``dic_fields``)."""
    return f"{results}dic/{test}/fields.nc"


def raw_inputs(sheet: pd.DataFrame, results: str = "results/"
               ) -> Callable[[Any], dict[str, str]]:
    """Input function: the test's load log and fields (correlated from its images, see
    :func:`image_fields`) or contact displacement paths."""

    def inputs(wildcards: Any) -> dict[str, str]:
        row = sheet.loc[wildcards.test]
        files = {"load_log": str(row["load_log"])}
        if has_path(sheet, wildcards.test, "fields"):
            files["fields"] = str(row["fields"])
        elif has_path(sheet, wildcards.test, "images"):
            files["fields"] = image_fields(wildcards.test, results)
        else:
            files["contact_displacement"] = str(row["contact_displacement"])
        return files

    return inputs


def image_inputs(sheet: pd.DataFrame) -> Callable[[Any], dict[str, str]]:
    """Input function of ``dic_fields``: the test's image folder and load log."""

    def inputs(wildcards: Any) -> dict[str, str]:
        row = sheet.loc[wildcards.test]
        return {"images": str(row["images"]).strip(), "load_log": str(row["load_log"]).strip()}

    return inputs


def demo_reference_results(sheet: pd.DataFrame, results: str = "results/") -> list[str]:
    """The stiffness results the image report compares the image demo with: those of the
    thesis tests whose demo image folder (:func:`demo_image_folder`) an image test names,
    where the sheet has that test with raw data."""
    folders = {demo_image_folder(t): t for t in PUBLISHED_TESTS}
    raw = set(raw_tests(sheet))
    named = {folders.get(Path(str(sheet.loc[t, "images"]).strip()).as_posix())
             for t in image_tests(sheet)}
    return [f"{results}stiffness/{t}.nc" for t in sheet.index if t in named and t in raw]


def raw_data_option(wildcards: Any, input: Mapping[str, Any]) -> list[str]:
    """The ``--fields`` or ``--contact-displacement`` option of ``stiffness process``.

    Returned as separate words, so the rule quotes the path as one argument (``:q``).
    """
    if "fields" in input.keys():
        return ["--fields", str(input["fields"])]
    return ["--contact-displacement", str(input["contact_displacement"])]


# --------------------------------------------------------------------------- receding


def sweep_values(spec: Mapping[str, float] | Sequence[float]) -> list[float]:
    """Values from a {start, stop, step} range (stop included) or an explicit list."""
    if isinstance(spec, Mapping):
        count = round((spec["stop"] - spec["start"]) / spec["step"]) + 1
        if count < 1:
            raise ValueError(f"empty sweep range {dict(spec)}")
        return [round(spec["start"] + i * spec["step"], 10) for i in range(count)]
    return [float(v) for v in spec]


def chunk_values(values: Sequence[float], chunk: int, chunks: int) -> list[str]:
    """The values of one chunk, interleaved (balances cheap and dear points), as CLI words."""
    return [str(v) for v in values[int(chunk) :: chunks]]


def sweep_chunks(section: Mapping[str, Any], key: str) -> list[int]:
    """The chunks of a sweep over ``section[key]`` (at most ``section["chunks"]``, one value
    each at least)."""
    return list(range(min(section["chunks"], len(sweep_values(section[key])))))


def sweep_chunk(section: Mapping[str, Any], key: str, chunk: int | str) -> list[str]:
    """The values of ``section[key]`` in one chunk of its sweep (:func:`chunk_values`)."""
    return chunk_values(sweep_values(section[key]), int(chunk), len(sweep_chunks(section, key)))


def gap_compare_n(gap: Mapping[str, Any]) -> list[int]:
    """The comparison N of the gap problem (Fig. 5.5): ``compare_n`` without the main N."""
    return [n for n in gap["compare_n"] if n != gap["n"]]


def number_name(value: float) -> str:
    """A number in a file name: as ``:g`` writes it where that reads back as the same
    number (``2.5``, ``1``), else its exact shortest form (``1.23456789``)."""
    text = f"{float(value):g}"
    return text if float(text) == float(value) else repr(float(value))


def gap_profile_name(point: Mapping[str, float]) -> str:
    """File stem of a profile point, e.g. ``w2.5_f0.5``."""
    return f"w{number_name(point['w'])}_f{number_name(point['f'])}"


def gap_profile_point(name: str) -> dict[str, float]:
    """The profile point of a file stem (:func:`gap_profile_name`), read from the name
    alone, so that each profile job depends on its own point only."""
    match = re.fullmatch(r"w(?P<w>[^_]+)_f(?P<f>[^_]+)", name)
    if match is None:
        raise ValueError(f"{name!r} is not a gap profile name w<w>_f<f>")
    return {"w": float(match["w"]), "f": float(match["f"])}


#: The file stems of pressure patches (rule wildcard ``law``): a named law of
#: ``receding.patches.laws`` or a user's shape ``table_<name>`` (the schema's name pattern).
#: Written out rather than read from the config, so that a patch's jobs depend on their own
#: law only.
PATCH_LAW_PATTERN = "uniform|hertz|punch|table_[A-Za-z][A-Za-z0-9_]*"


def patch_names(patches: Mapping[str, Any]) -> list[str]:
    """The pressure patches of ``receding.patches``: the named laws and the user's shapes
    (``table_<name>``, results/receding/table_<name>.nc), one rule for both."""
    return [*patches["laws"], *(f"table_{name}" for name in patches["tables"])]


def patch_shape(law: str, tables: Mapping[str, Mapping[str, Sequence[float]]]
                ) -> dict[str, Any]:
    """``problem`` (and the table's ``table_x``, ``table_p``) of ``receding patch-sweep``
    for a patch law or a user's shape ``table_<name>`` of ``receding.patches.tables``."""
    if law.startswith("table_"):
        table = tables[law.removeprefix("table_")]
        return {"problem": "table", "table_x": table["x"], "table_p": table["p"]}
    return {"problem": law}


def liftoff_profile_name(point: Mapping[str, float] | float, law: str = "line") -> str:
    """File stem of a line/patch profile: ``line_f0.5`` or ``patch_uniform_w1_f0.3``."""
    if isinstance(point, Mapping):
        return f"patch_{point['law']}_w{number_name(point['w'])}_f{number_name(point['f'])}"
    return f"{law}_f{number_name(point)}"


def liftoff_profile_point(name: str) -> dict[str, Any]:
    """The patch profile point of a file stem (:func:`liftoff_profile_name`), from the name
    alone."""
    match = re.fullmatch(r"patch_(?P<law>[a-z]+)_w(?P<w>[^_]+)_f(?P<f>[^_]+)", name)
    if match is None:
        raise ValueError(f"{name!r} is not a patch profile name patch_<law>_w<w>_f<f>")
    return {"law": match["law"], "w": float(match["w"]), "f": float(match["f"])}


def rough_ct_ratio(rough: Mapping[str, Any]) -> float:
    """C_T / C of a rough-interface run that takes one ratio (profiles, FE runs): the first
    of ``receding.rough.ct_ratios``, or 1/m with Mindlin's m at ``receding.rough.nu``."""
    from contactlab.receding.core.interface import mindlin_ratio

    ratios = rough["ct_ratios"]
    return float(ratios[0]) if ratios else 1.0 / mindlin_ratio(float(rough["nu"]))


def rough_problems_pattern() -> str:
    """The wildcard pattern of a rough-interface sweep's problem (``receding.problems``:
    the line load and the named pressure laws)."""
    from contactlab.receding.problems import named_liftoff

    return "|".join(named_liftoff())


def _widths(problem: str) -> bool:
    """Whether a receding problem has a half-width w/c (``receding.problems``)."""
    from contactlab.receding.problems import problem as receding_problem

    return receding_problem(problem).widths


def rough_profile_name(point: Mapping[str, Any]) -> str:
    """File stem of a rough-interface profile: ``line_f0.5_C1`` or ``uniform_w1_f0.3_C1``.

    A problem with a half-width needs ``w``: ValueError naming the entry if it has none."""
    widths = _widths(point["problem"])
    if widths and "w" not in point:
        raise ValueError(f"receding.rough.profiles entry {dict(point)}: a "
                         f"{point['problem']} patch needs w")
    where = f"_w{number_name(point['w'])}" if widths else ""
    return f"{point['problem']}{where}_f{number_name(point['f'])}_C{number_name(point['C'])}"


def rough_profile_point(name: str) -> dict[str, Any]:
    """The options of ``receding rough-profile`` for the profile named ``name``
    (:func:`rough_profile_name`), from the name alone."""
    match = re.fullmatch(r"(?P<problem>[a-z]+)(_w(?P<w>[^_]+))?_f(?P<f>[^_]+)_C(?P<C>[^_]+)",
                         name)
    if match is None:
        raise ValueError(f"{name!r} is not a rough profile name <problem>[_w<w>]_f<f>_C<C>")
    values: dict[str, Any] = {"problem": match["problem"], "f": float(match["f"]),
                              "C": float(match["C"])}
    if match["w"] is not None:
        values["w_hat"] = float(match["w"])
    return values


def rough_pairs_summary(pairs: Mapping[str, Any], results: str = "results/") -> list[str]:
    """The stiffness summary ``receding rough-pairs`` reads, when one of the tested ``pairs``
    (name -> law, ``receding.rough.pairs.tests``) is ``from_test``."""
    return [f"{results}stiffness/summary.nc"] if any("from_test" in t
                                                     for t in pairs.values()) else []


def rough_fe_runs(config: Mapping[str, Any], results: str = "results/") -> list[str]:
    """<results>fe/rough/<problem>_C<C>_h<h>.nc: the FE runs of the rough-interface
    comparison (``receding.rough.fe``; none unless ``fe.enabled``)."""
    spec = config["receding"]["rough"]["fe"]
    if not config["fe"]["enabled"]:
        return []
    return [f"{results}fe/rough/{problem}_C{C:g}_h{h:g}.nc" for problem in spec["problems"]
            for C in spec["C"] for h in spec["h"]]


def rough_fe_run(config: Mapping[str, Any], problem: str, C: str, h: str) -> dict[str, Any]:
    """The values of one ``fe rough`` run that are not config values: the problem, C, C_T
    (:func:`rough_ct_ratio` times C, passed explicitly so the DDT side reads the same from
    the run), h/c and the level name ``h<h>``."""
    rough = config["receding"]["rough"]
    spec = rough["fe"]
    cs = {f"{float(v):g}": float(v) for v in spec["C"]}
    hs = {f"{float(v):g}": float(v) for v in spec["h"]}
    if problem not in spec["problems"] or C not in cs or h not in hs:
        raise ValueError(f"fe rough run {problem}_C{C}_h{h} is not in receding.rough.fe "
                         f"(problems {spec['problems']}, C {sorted(cs)}, h {sorted(hs)})")
    compliance = cs[C]
    return {"problem": problem, "compliance": compliance,
            "compliance_t": compliance * rough_ct_ratio(rough), "h": hs[h], "level": f"h{h}"}


# --------------------------------------------------------------------------- finite elements


def fe_problems(fe: Mapping[str, Any]) -> list[str]:
    """The receding problems the FE branch checks (none when it is off)."""
    return list(fe["problems"]) if fe["enabled"] else []


def comparison_run(fe: dict, problem: str, results: str = "results/") -> str:
    """The FE run compared with the DDT solution: the problem's ``level``."""
    return f"{results}fe/runs/{problem}_{fe['problems'][problem]['level']}.nc"


def ddt_file(fe: dict, problem: str) -> str | None:
    """The receding results file ``fe compare`` reads when the solve fails
    (``fe.problems.<problem>.ddt_file``), or None (the option is left out)."""
    return fe["problems"][problem].get("ddt_file") or None


def ddt_inputs(fe: dict, problem: str, targets: list[str]) -> list[str]:
    """The receding results file as an input only when some rule makes it."""
    path = fe["problems"][problem].get("ddt_file", "")
    return [path] if path and path in targets else []


#: The module of the receding solver each FE problem is checked against (the functions
#: are ``contactlab.fe.receding.ddt.SOLVERS``; named here so the DAG does not import the solvers).
DDT_SOLVER_MODULES = {
    "gap": "contactlab.receding.gap.solver",
    "line": "contactlab.receding.liftoff.line",
    "uniform": "contactlab.receding.liftoff.patch",
}


def ddt_sources(problem: str, root: str = ".") -> list[str]:
    """The source file of the receding solver the comparison calls.

    As an input of ``fe_compare`` it makes the comparison rerun when the solver changes.
    Relative to ``root`` (the working directory) when the package lives below it.
    """
    from importlib.util import find_spec

    spec = find_spec(DDT_SOLVER_MODULES[problem])
    path = Path(spec.origin if spec and spec.origin else "").resolve()
    try:
        return [path.relative_to(Path(root).resolve()).as_posix()]
    except ValueError:
        return [str(path)]


def convergence_runs(fe: dict, problem: str, results: str = "results/") -> list[str]:
    """The FE runs of a problem's mesh convergence study (sec. 8.3)."""
    levels = fe["problems"][problem].get("convergence", [])
    return [f"{results}fe/runs/{problem}_{level}.nc" for level in levels]


def convergence_files(fe: dict, results: str = "results/") -> list[str]:
    """<results>fe/convergence_<problem>.nc of every problem with a convergence study."""
    if not fe.get("enabled", False):
        return []
    return [f"{results}fe/convergence_{p}.nc" for p, spec in fe.get("problems", {}).items()
            if spec.get("convergence")]


def study_edges(fe: dict, problem: str) -> list[str]:
    """Block edges of a problem in the FE study: the gap problem keeps its own (Fig. 8.1)."""
    if problem == "gap":
        return [fe["problems"]["gap"]["edges"]]
    return list(fe["study"]["edges"])


def study_runs(fe: dict, problem: str, results: str = "results/") -> list[str]:
    """The FE runs of one problem's h and L study: every h of ``fe.study.h`` on the configured
    domain (scale 1), every scale of ``fe.study.scale`` at ``h_ref``, for each block edge."""
    study = fe["study"]
    points = [(h, 1.0) for h in study["h"]] + [(study["h_ref"], s) for s in study["scale"]]
    unique = list(dict.fromkeys((float(h), float(s)) for h, s in points))
    return [f"{results}fe/study/{problem}_{edges}_h{h:g}_s{s:g}.nc"
            for edges in study_edges(fe, problem) for h, s in unique]


def study_files(fe: dict, results: str = "results/") -> list[str]:
    """<results>fe/study_<problem>.nc of every studied problem (empty when the study is off)."""
    study = fe.get("study", {})
    if not (fe.get("enabled", False) and study.get("enabled", False)):
        return []
    return [f"{results}fe/study_{p}.nc" for p in study["problems"]]


def study_run(fe: dict, problem: str, edges: str, h: str, scale: str) -> dict[str, Any]:
    """The values of one run of the study that ``contactlab fe receding`` does not take from
    the config: the problem, its block ``edges``, h/c = ``h``, strip length and block depth
    of ``fe.problems.<problem>`` times ``scale``, and the level name ``h<h>_s<scale>``."""
    study = fe["study"]
    hs = {f"{float(v):g}": float(v) for v in [*study["h"], study["h_ref"]]}
    scales = {f"{float(v):g}": float(v) for v in study["scale"]}
    if h not in hs or scale not in scales or edges not in study_edges(fe, problem):
        raise ValueError(f"fe study run {problem}_{edges}_h{h}_s{scale} is not in fe.study "
                         f"(h {sorted(hs)}, scale {sorted(scales)}, edges "
                         f"{study_edges(fe, problem)})")
    spec = fe["problems"][problem]
    length = spec["length"] * scales[scale]
    if not spec["x_fine"] < length:
        raise ValueError(f"fe.study.scale {scale} makes the {problem} strip ({length:g} c) "
                         f"shorter than fe.problems.{problem}.x_fine ({spec['x_fine']:g} c)")
    return {"problem": problem, "h": hs[h], "length": f"{length:g}",
            "depth": f"{spec['depth'] * scales[scale]:g}", "edges": edges,
            "level": f"h{h}_s{scale}"}


def materials_fe_runs(fe: dict, results: str = "results/") -> list[str]:
    """<results>fe/materials/<pair>_h<h>.nc: the line-load runs of each pair of materials on
    each mesh of ``fe.materials`` (none unless ``fe.enabled`` and ``fe.materials.enabled``)."""
    spec = fe.get("materials", {})
    if not (fe.get("enabled", False) and spec.get("enabled", False)):
        return []
    return [f"{results}fe/materials/{pair}_h{float(h):g}.nc" for pair in spec["pairs"]
            for h in spec["h"]]


def materials_fe_run(fe: dict, pair: str, h: str) -> dict[str, Any]:
    """The values of one pair's run that ``contactlab fe receding`` does not take from the
    config: the line load, f, h/c, the domain, the strip's and the block's E and nu and the
    level name ``<pair>_h<h>``."""
    spec = fe["materials"]
    hs = {f"{float(v):g}": float(v) for v in spec["h"]}
    if pair not in spec["pairs"] or h not in hs:
        raise ValueError(f"fe materials run {pair}_h{h} is not in fe.materials (pairs "
                         f"{sorted(spec['pairs'])}, h {sorted(hs)})")
    body = spec["pairs"][pair]
    return {"problem": "line", "f": spec["f"], "h": hs[h], "length": spec["length"],
            "depth": spec["depth"], "young": body["young_layer"], "poisson": body["nu_layer"],
            "young_half_plane": body["young_half_plane"],
            "poisson_half_plane": body["nu_half_plane"], "level": f"{pair}_h{h}"}


def asperity_runs(fe: dict, results: str = "results/") -> list[str]:
    """<results>fe/asperity/sy<sigma_y>.nc: the elastic model (sy0) and each yield stress."""
    spec = fe.get("asperity", {})
    if not (fe.get("enabled", False) and spec.get("enabled", False)):
        return []
    return [f"{results}fe/asperity/sy{sy:g}.nc" for sy in [0, *spec["yield_stress"]]]
