"""What a benchmark's numbers depend on, written above every saved table as '# key: value' lines.

Used by the scripts beside it (``python benchmarks/NAME.py`` puts this folder on ``sys.path``).
"""

import datetime
import os
import platform
from pathlib import Path

import numpy as np


def processor_name():
    """The CPU's model name from /proc/cpuinfo, else what the platform module says."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def describe(**versions):
    """Date, CPU counts, processor, Python and NumPy, then ``versions`` (name: version text)."""
    import rsgeo

    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return {"date": datetime.date.today().isoformat(), "cpus": str(os.cpu_count()),
            "cpus usable": str(usable), "processor": processor_name(),
            "python": platform.python_version(), "numpy": np.__version__,
            "rsgeo": getattr(rsgeo, "__version__", "?"), **versions}


def header_lines(header):
    """``{key: value}`` as the '# key: value' lines that open a saved table."""
    return "".join(f"# {key}: {value}\n" for key, value in header.items())
