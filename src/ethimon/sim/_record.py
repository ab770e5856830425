"""``--record DIR``: PNG frames (TinyRenderer, headless), a trace, and a plot."""

from __future__ import annotations

import csv
import json
import math
import os
import time
from typing import Any

__all__ = ["Recorder", "plot_trace"]

_SIGNALS = ("human_distance", "ee_speed", "contact_force", "joint_speed_max", "hazard_distance")


def _clean(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


class Recorder:
    """Collects frames during a run and writes the trace and plot at the end."""

    def __init__(self, directory: str, sim: Any) -> None:
        self.dir = directory
        self.sim = sim
        os.makedirs(directory, exist_ok=True)
        self.files: list[str] = []
        self.seconds = 0.0  # time spent rendering frames (kept out of the realtime factor)

    def frame(self, moment: str, cycle: int | None = None) -> str:
        """Render the current scene to ``frame_<cycle>_<moment>.png``."""
        from matplotlib import image as mpimg

        t0 = time.perf_counter()
        c = self.sim.cycle if cycle is None else cycle
        path = os.path.join(self.dir, f"frame_{c:05d}_{moment}.png")
        mpimg.imsave(path, self.sim.render())
        self.files.append(path)
        self.seconds += time.perf_counter() - t0
        return path

    def finish(self, result: Any) -> list[str]:
        """Write ``trace.jsonl``, ``trace.csv``, ``summary.json`` and ``plot.png``."""
        jl = os.path.join(self.dir, "trace.jsonl")
        with open(jl, "w", encoding="utf-8") as fh:
            for r in result.trace:
                row = {
                    "cycle": r.cycle, "t_s": round(r.t_s, 6),
                    "signals": {k: _clean(v) for k, v in r.signals.items()},
                    "override": r.override, "response": r.response,
                    "violations": list(r.violations), "risk": _clean(r.risk),
                    "faults": list(r.faults), "latched": r.latched, "controller": r.controller,
                    "task_step": r.task_step, "joint_speed_max_rad_s": r.joint_speed_max_rad_s,
                    "safe_pose_error_rad": r.safe_pose_error_rad,
                }
                fh.write(json.dumps(row) + "\n")
        cs = os.path.join(self.dir, "trace.csv")
        with open(cs, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["cycle", "t_s", *_SIGNALS, "risk", "override", "response", "controller",
                        "violations", "faults", "safe_pose_error_rad"])
            for r in result.trace:
                w.writerow([r.cycle, f"{r.t_s:.6f}", *(r.signals.get(s, "") for s in _SIGNALS),
                            "" if r.risk is None else r.risk, int(r.override), r.response,
                            r.controller, ";".join(r.violations), ";".join(r.faults),
                            f"{r.safe_pose_error_rad:.5f}"])
        sj = os.path.join(self.dir, "summary.json")
        pl = os.path.join(self.dir, "plot.png")
        self.files += [jl, cs, sj, pl]  # summary.json lists every file of the recording, itself included
        with open(sj, "w", encoding="utf-8") as fh:
            summ = result.summary()
            summ["files"] = list(self.files)
            json.dump({k: _clean(v) for k, v in summ.items()}, fh, indent=2)
        plot_trace(result.trace, pl)
        return list(self.files)


def plot_trace(trace, path: str, title: str | None = None) -> str:
    """Plot risk, human distance, speeds and override over time to ``path`` (Agg backend)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    t = [r.t_s for r in trace]
    fig = Figure(figsize=(9, 7.5))
    axes = fig.subplots(4, 1, sharex=True)
    axes[0].plot(t, [math.nan if r.risk is None else r.risk for r in trace], color="tab:purple")
    axes[0].set_ylabel("risk R_e")
    axes[1].plot(t, [r.signals.get("human_distance", math.nan) for r in trace], label="monitor input")
    axes[1].plot(t, [r.human_distance_true_m for r in trace], "--", alpha=0.6, label="simulated")
    axes[1].set_ylabel("human dist. (m)")
    axes[1].legend(loc="upper right", fontsize=7)
    axes[2].plot(t, [r.signals.get("ee_speed", math.nan) for r in trace], label="ee speed (m/s)")
    axes[2].plot(t, [r.joint_speed_max_rad_s for r in trace], label="max joint speed (rad/s)")
    axes[2].set_ylabel("speed")
    axes[2].legend(loc="upper right", fontsize=7)
    axes[3].step(t, [int(r.override) for r in trace], where="post", color="tab:red", label="override")
    axes[3].step(t, [0.5 if r.faults else 0 for r in trace], where="post", color="tab:orange",
                 label="fault")
    axes[3].set_ylabel("override")
    axes[3].set_yticks([0, 1])
    axes[3].set_xlabel("simulated time (s)")
    axes[3].legend(loc="upper right", fontsize=7)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    return path
