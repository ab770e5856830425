"""Machine facts recorded with every benchmark result."""

from __future__ import annotations

import os
import platform
import sys


def machine_facts() -> dict:
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
    return facts
