"""What a benchmark's numbers depend on, written above every saved table as '# key: value' lines.

Used by the scripts beside it (``python benchmarks/NAME.py`` puts this folder on ``sys.path``).
"""

import csv
import datetime
import os
import platform
import subprocess
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


def git(*args):
    """Output of a git command in the repository (the commit measured), or "?" without git."""
    try:
        return subprocess.run(["git", *args], cwd=Path(__file__).resolve().parents[1],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def table_value(value):
    """A number as the saved tables write it: 4 significant digits below 1, else 4 decimals;
    NaN as an empty field."""
    if isinstance(value, float):
        return "" if np.isnan(value) else f"{value:.4g}" if abs(value) < 1 else f"{value:.4f}"
    return value


def save_table(file, header, names, rows):
    """Write ``rows`` (dicts) as CSV with the columns ``names``, below ``# key: value`` lines
    (:func:`header_lines`) of ``header``; return the file's path."""
    file = Path(file)
    file.parent.mkdir(parents=True, exist_ok=True)
    with open(file, "w", newline="") as handle:
        handle.write(header_lines(header))
        writer = csv.DictWriter(handle, names, restval="")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: table_value(value) for key, value in row.items()})
    return file
