"""Helpers shared by tests: the CLI as a user runs it (``run_cli``, a child process) or in this process (``call_cli``)."""

import contextlib
import io
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run_cli(*args: str, cwd: Path | None = None, timeout: float = 60) -> subprocess.CompletedProcess:
    """Run the ethimon CLI in a subprocess (for what only a process shows: signals, pipes, hangs, imports)."""
    env = dict(os.environ)
    env.setdefault("PYTHONHASHSEED", "0")
    return subprocess.run([sys.executable, "-m", "ethimon.cli", *args], cwd=cwd or ROOT, env=env,
                          capture_output=True, text=True, timeout=timeout)


def call_cli(*args: str, cwd: Path | None = None, timeout: float | None = None) -> subprocess.CompletedProcess:
    """``ethimon.cli.main(args)`` in this process, read as :func:`run_cli` reads a child: exit code, stdout, stderr.

    ``cwd`` (default: the checkout) is the working directory for the call; ``timeout`` is accepted for
    the same signature as :func:`run_cli` and not enforced (use ``run_cli`` where a hang is the question)."""
    from ethimon.cli import main
    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    os.chdir(cwd or ROOT)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = main([str(a) for a in args])
    finally:
        os.chdir(here)
    return subprocess.CompletedProcess(["ethimon", *args], rc, out.getvalue(), err.getvalue())
