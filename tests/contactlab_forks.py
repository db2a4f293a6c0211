"""The rules' ``contactlab`` commands, each in a fork of one process that has it loaded.

A workflow test runs tens of jobs that each compute for a fraction of a second but spend
0.5-1.5 s starting Python and importing numpy, scipy, xarray, lmfit and matplotlib. For
the tests only, ``python tests/contactlab_forks.py SOCKET`` (:func:`serve`) imports the
package's modules once and answers at SOCKET; :func:`write_launcher` writes the
``contactlab`` launcher to put first on PATH (tests/conftest.py starts one server per
pytest worker and one for the end-to-end run). The launcher (standard library
only, ~20 ms) hands its command line, folder, environment and standard streams (as file
descriptors) to the server over a Unix socket; the server forks, the child runs
:func:`contactlab.cli.main` with them and exits as an interpreter exits, and the server
sends its exit status, which the launcher exits with. Nothing differs from a fresh process
but the start: the same code, the job's own folder, environment, streams and log files.
Without the server (its socket gone, or ``CONTACTLAB_TEST_FORKS`` unset) the launcher runs
the installed ``contactlab``.

BLAS reads its thread count once, at import: the server loads it with one thread, as the
solver rules ask (``OPENBLAS_NUM_THREADS=1``) and as :mod:`contactlab.blas` limits the
solvers anyway.

The loaded modules' objects are moved out of the garbage collector's reach
(:func:`gc.freeze`) before the first fork: they live as long as the server, and a child's
full collections would otherwise walk them all (and copy the pages they sit on) at every
job. The objects a job makes are collected as in a fresh process.
"""

from __future__ import annotations

import atexit
import contextlib
import gc
import json
import os
import selectors
import socket
import struct
import sys
import threading
from pathlib import Path

from fork_child import become, exit_status

#: the environment variable that names the server's socket
SOCKET_VARIABLE = "CONTACTLAB_TEST_FORKS"

LAUNCHER = '''#!{python} -IS
"""contactlab for the tests: run by the server at ${variable} (tests/contactlab_forks.py)."""
import json, os, socket, struct, sys
path = os.environ.get("{variable}", "")
try:
    client = socket.socket(socket.AF_UNIX)
    client.connect(path)
except OSError:
    os.execv("{real}", ["{real}", *sys.argv[1:]])
payload = json.dumps({{"argv": sys.argv[1:], "cwd": os.getcwd(),
                       "env": dict(os.environ)}}).encode()
socket.send_fds(client, [struct.pack("!Q", len(payload))], [0, 1, 2])
client.sendall(payload)
answer = b""
while len(answer) < 4:
    chunk = client.recv(4 - len(answer))
    if not chunk:
        sys.exit("contactlab: the test server ended before the command")
    answer += chunk
sys.exit(struct.unpack("!i", answer)[0])
'''


def _receive(connection: socket.socket) -> tuple[dict, list[int]]:
    """One request: the header with the three stream descriptors, then the JSON body."""
    header, fds, _, _ = socket.recv_fds(connection, 8, 3)
    size = struct.unpack("!Q", header)[0]
    body = bytearray()
    while len(body) < size:
        chunk = connection.recv(size - len(body))
        if not chunk:
            raise ConnectionError("the launcher closed its request early")
        body += chunk
    return json.loads(body), fds


def _child(request: dict, fds: list[int]) -> None:
    """Run the request's command as ``contactlab`` would and exit as its interpreter would
    (threads joined, a process pool's workers stopped, exit handlers run). Never returns."""
    code = 1
    try:
        become(request["cwd"], request["env"], ["contactlab", *request["argv"]], fds)
        from contactlab.cli import main

        code = main(request["argv"])
    except SystemExit as exc:
        code = exit_status(exc)
    except BaseException:
        import traceback

        traceback.print_exc()
    try:  # the interpreter's exit up to its module teardown (0.35 s with every module
        # loaded; a real process tears down only its own imports, and nothing observable)
        threading._shutdown()  # joins threads, stops process pools' workers
        atexit._run_exitfuncs()  # the exit handlers, logging's flush among them
        sys.stdout.flush()
        sys.stderr.flush()
    finally:
        os._exit(code)


def _preload() -> None:
    """Import every module of the package (and so the science it imports) once."""
    import importlib
    import pkgutil

    import matplotlib

    matplotlib.use("Agg")
    import contactlab

    for module in pkgutil.walk_packages(contactlab.__path__, "contactlab."):
        if not module.name.endswith(".__main__"):
            importlib.import_module(module.name)


def serve(path: str) -> None:
    """Accept launchers at ``path`` until standard input closes (the process that started
    the server has ended); fork one child per command and, once the child has exited, send
    its exit status (128 + signal if a signal ended it) to its launcher. Each command line
    is logged to ``<path>.log``."""
    _preload()
    gc.freeze()  # see the module's docstring
    listener = socket.socket(socket.AF_UNIX)
    listener.bind(path)
    listener.listen(16)
    served = open(f"{path}.log", "a", encoding="utf-8")  # open while the server runs
    waiting = selectors.DefaultSelector()
    waiting.register(listener, selectors.EVENT_READ)
    waiting.register(sys.stdin, selectors.EVENT_READ)
    print("ready", flush=True)
    while True:
        for key, _ in waiting.select():
            if key.fileobj is sys.stdin:
                return
            if key.fileobj is listener:
                connection, _ = listener.accept()
                try:
                    request, fds = _receive(connection)
                except (OSError, ValueError):
                    connection.close()
                    continue
                served.write(json.dumps(request["argv"]) + "\n")
                served.flush()
                pid = os.fork()
                if pid == 0:
                    waiting.close()
                    served.close()
                    listener.close()
                    connection.close()
                    _child(request, fds)
                for fd in fds:
                    os.close(fd)
                waiting.register(os.pidfd_open(pid), selectors.EVENT_READ, (pid, connection))
            else:  # a child has exited
                pid, connection = key.data
                waiting.unregister(key.fileobj)
                os.close(key.fileobj)
                code = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
                with contextlib.suppress(OSError):  # a launcher that is gone
                    connection.sendall(struct.pack("!i", code if code >= 0 else 128 - code))
                connection.close()


def write_launcher(folder: Path, real: str) -> Path:
    """The ``contactlab`` launcher in ``folder``, falling back to ``real``."""
    launcher = folder / "contactlab"
    launcher.write_text(LAUNCHER.format(python=sys.executable, variable=SOCKET_VARIABLE,
                                        real=real), encoding="utf-8")
    launcher.chmod(0o755)
    return launcher


if __name__ == "__main__":
    os.environ.update({"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"})
    serve(sys.argv[1])
