"""Helpers of workflow/rules/fe.smk: command-line arguments and file lists from the config.

Kept out of the rule file so that it holds rules only (``snakemake --lint``). Functions of
the ``fe:`` config section (a dict) and wildcard values; no Snakemake objects. Arguments are
lists of words, so the rules pass each as one quoted argument (``:q``); ``results`` is the
study's results folder (``results/`` or ``results/studies/<name>/``).
"""

from __future__ import annotations


def receding_args(fe: dict, problem: str, level: str) -> list[str]:
    """Arguments of ``contactlab fe receding`` for one problem on one mesh level."""
    spec = fe["problems"][problem]
    options = {
        "problem": problem,
        "f": spec["f"],
        "w-hat": spec.get("w_hat", 0.0),
        "h": fe["levels"][level],
        "length": spec["length"],
        "depth": spec["depth"],
        "x-fine": spec["x_fine"],
        "edges": spec["edges"],
        "young": spec["young"],
        "increments": fe["increments"],
        "level": level,
    }
    return [word for key, value in options.items() for word in (f"--{key}", str(value))]


def comparison_run(fe: dict, problem: str, results: str = "results/") -> str:
    """The FE run compared with the DDT solution: the problem's ``level``."""
    return f"{results}fe/runs/{problem}_{fe['problems'][problem]['level']}.nc"


def ddt_file_arg(fe: dict, problem: str) -> list[str]:
    path = fe["problems"][problem].get("ddt_file", "")
    return ["--ddt-file", path] if path else []


def ddt_inputs(fe: dict, problem: str, targets: list[str]) -> list[str]:
    """The receding results file as an input only when some rule makes it."""
    path = fe["problems"][problem].get("ddt_file", "")
    return [path] if path and path in targets else []


def ddt_sources(problem: str, src: str = "src") -> list[str]:
    """Source files of the receding solvers the comparison calls (those that exist).

    As inputs of ``fe_compare`` they make the comparison rerun when a solver appears or
    changes, so the *_ddt values fill in by themselves.
    """
    from pathlib import Path

    from contactlab.fe.ddt import API_CANDIDATES

    files = []
    for module, _ in API_CANDIDATES[problem]:
        path = Path(src, *module.split(".")).with_suffix(".py")
        if path.exists() and str(path) not in files:
            files.append(str(path))
    return files


def convergence_runs(fe: dict, problem: str, results: str = "results/") -> list[str]:
    levels = fe["problems"][problem].get("convergence", [])
    return [f"{results}fe/runs/{problem}_{level}.nc" for level in levels]


def convergence_files(fe: dict, results: str = "results/") -> list[str]:
    if not fe.get("enabled", False):
        return []
    return [f"{results}fe/convergence_{p}.nc" for p, spec in fe.get("problems", {}).items()
            if spec.get("convergence")]


def asperity_runs(fe: dict, results: str = "results/") -> list[str]:
    """<results>fe/asperity/sy<sigma_y>.nc: the elastic model (sy0) and each yield stress."""
    spec = fe.get("asperity", {})
    if not (fe.get("enabled", False) and spec.get("enabled", False)):
        return []
    return [f"{results}fe/asperity/sy{sy:g}.nc" for sy in [0, *spec["yield_stress"]]]


def asperity_args(fe: dict) -> list[str]:
    """Mesh, material and loading arguments of ``contactlab fe asperity``."""
    return [word for key, value in fe["asperity"].items()
            if key not in ("enabled", "yield_stress")
            for word in (f"--{key.replace('_', '-')}", str(value))]
