"""Snakemake command lines for the tests, each in a fork of one process that has it loaded.

``python tests/snakemake_forks.py`` reads requests from stdin, one JSON line each:
``{"cwd": folder, "env": {...}, "commands": [[arg, ...], ...], "parallel": n}``, and
answers each with one JSON line: a list of ``{"returncode", "stdout", "stderr"}`` in the
order of the commands. Snakemake and the modules the Snakefile imports load once; each
command runs in a child forked from this process (``parallel`` at a time) with the
request's folder and environment, so it costs its own parse, DAG and jobs (a dry run of
the end-to-end study ~0.3 s) instead of a fresh interpreter's ~1.6 s. Two things differ
from a fresh ``snakemake`` and change no answer: the loaded modules' objects are kept out of
the children's garbage collections (:func:`gc.freeze`; a full collection walked them all,
~13 % of a dry run), and YAML is parsed by libyaml (:func:`_yaml_in_c`). The tests start one
such process per pytest worker (``tests/conftest.py``).
"""

from __future__ import annotations

import gc
import json
import os
import sys
import tempfile
from typing import IO

from fork_child import become, exit_status


def _child(argv: list[str], cwd: str, env: dict[str, str], out: IO[bytes],
           err: IO[bytes]) -> None:
    """Run ``snakemake argv`` in ``cwd`` with ``env``, output to ``out``/``err``; never return."""
    code = 1
    try:
        # no standard input: the jobs must not read the server's requests
        become(cwd, env, ["snakemake", *argv],
               [os.open(os.devnull, os.O_RDONLY), out.fileno(), err.fileno()])
        sys.stdout = sys.__stdout__  # the server sends its own output to stderr
        from snakemake.cli import main

        main(argv)
        code = 0
    except SystemExit as exc:
        code = exit_status(exc)
    except BaseException:  # reported like the command line reports it
        import traceback

        traceback.print_exc()
    finally:
        import logging

        logging.shutdown()  # Snakemake's log file under .snakemake/log/
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)


def run(cwd: str, env: dict[str, str], commands: list[list[str]], parallel: int = 1
        ) -> list[dict[str, object]]:
    """Every command in a fork, ``parallel`` at a time; their return codes and outputs."""
    results: list[dict[str, object]] = [{} for _ in commands]
    running: dict[int, tuple[int, IO[bytes], IO[bytes]]] = {}
    pending = list(enumerate(commands))
    while pending or running:
        while pending and len(running) < max(parallel, 1):
            index, argv = pending.pop(0)
            out, err = tempfile.TemporaryFile(), tempfile.TemporaryFile()
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:
                _child(argv, cwd, env, out, err)
            running[pid] = (index, out, err)
        pid, status = os.wait()
        index, out, err = running.pop(pid)
        texts = []
        for stream in (out, err):
            stream.seek(0)
            texts.append(stream.read().decode("utf-8", "replace"))
            stream.close()
        results[index] = {"returncode": os.waitstatus_to_exitcode(status),
                          "stdout": texts[0], "stderr": texts[1]}
    return results


def _yaml_in_c() -> None:
    """Snakemake reads config files and the schema with PyYAML's pure-Python FullLoader
    (through yte): ~0.1 s of every parse here, most of it the 33 kB schema. Give it
    libyaml's parser with the same constructor and resolver (``CFullLoader``, the same
    documents; PyYAML ships both) when PyYAML was built with it."""
    import yaml

    if yaml.__with_libyaml__:
        yaml.FullLoader = yaml.CFullLoader


def serve() -> None:
    """Answer requests from stdin until it closes."""
    import jsonschema  # noqa: F401 - what the config check imports
    import smart_open  # noqa: F401 - what Snakemake imports when it opens the Snakefile
    import snakemake.cli

    snakemake.cli.get_argument_parser()  # collects the plugins: registries are singletons

    # what workflow/rules/common.smk imports
    import contactlab.config_check
    import contactlab.rulehelpers
    import contactlab.study
    import contactlab.testsheet  # noqa: F401

    _yaml_in_c()
    gc.freeze()  # loaded once, alive as long as the server: out of the children's collections

    answers = sys.stdout
    sys.stdout = sys.stderr  # nothing but answers on the answer stream
    for line in sys.stdin:
        request = json.loads(line)
        answer = run(request["cwd"], request["env"], request["commands"],
                     request.get("parallel", 1))
        answers.write(json.dumps(answer) + "\n")
        answers.flush()


if __name__ == "__main__":
    serve()
