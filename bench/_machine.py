"""Machine facts recorded with every benchmark result (``"machine"`` in each JSON)."""

from __future__ import annotations

import datetime as _dt
import os
import platform
import sys


def loadavg() -> list[float] | None:
    """1/5/15-minute load averages now (None where the OS has none): the machine may be shared."""
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:
        return None


def machine_facts(**extra) -> dict:
    """CPU, cores, Python, platform, numpy/ethimon versions, UTC time and the load average now.

    ``extra`` (e.g. ``torch=torch.__version__, threads=2``) is added as given. Call it when the
    measurement ends, so ``loadavg`` is the load it ran under; scripts that also record the load
    at the start add ``loadavg_start``.
    """
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    facts = {"cpu": cpu, "cores": os.cpu_count(), "python": sys.version.split()[0],
             "implementation": platform.python_implementation(), "platform": platform.platform()}
    try:
        import numpy
        facts["numpy"] = numpy.__version__
    except ImportError:
        pass
    try:
        import ethimon
        facts["ethimon"] = ethimon.__version__
    except ImportError:
        pass
    if "torch" in sys.modules:  # only when the script already imported it (never imported here)
        facts["torch"] = sys.modules["torch"].__version__
    facts["date_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    facts["loadavg"] = loadavg()
    facts.update(extra)
    return facts
