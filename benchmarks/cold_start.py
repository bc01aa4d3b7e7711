"""What a cold Numba cache costs: each chapter's first run against its second, in CPU-seconds.

    python benchmarks/cold_start.py [NOTEBOOK ...]      # default: every chapter of the book
    python benchmarks/cold_start.py --suite             # the fast test run instead

Each notebook runs twice in a fresh process (``jupyter nbconvert --execute``, in its own
folder, as the book's build runs it): first with Numba's cache in an empty folder of its
own (``NUMBA_CACHE_DIR``, which Numba uses before any other place), so that every kernel
the chapter calls is compiled, then again with the cache that run filled. The CPU time of
the whole run (nbconvert, the kernel and what they start) is read from the operating
system (``RUSAGE_CHILDREN``), so a machine busy with other work stretches the wall time but
hardly the CPU time. ``--suite`` does the same for the README's fast test run. The table
lands in ``benchmarks/results/cold_start.csv``: cold and warm CPU-seconds, their ratio,
and the wall times beside them.
"""

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from machine import describe, git, save_table

ROOT = Path(__file__).resolve().parent.parent
FAST_SUITE = [sys.executable, "-m", "pytest", "-n", "2", "-q", "-p", "no:cacheprovider",
              "-m", "not notebooks and not browser and not slow"]


def children_cpu():
    """CPU-seconds (user + system) of every finished child process so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def measure(command, cache, cwd):
    """(CPU-seconds, wall seconds) of ``command`` run with Numba's cache in ``cache``."""
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    before, start = children_cpu(), time.perf_counter()
    run = subprocess.run(command, cwd=cwd, env=environment, capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed:\n{run.stdout[-3000:]}{run.stderr[-2000:]}")
    return children_cpu() - before, time.perf_counter() - start


def notebook_command(path, output):
    return [sys.executable, "-m", "jupyter", "nbconvert", "--to", "notebook", "--execute",
            "--ExecutePreprocessor.timeout=3600", "--output", str(output), str(path)]


def cold_and_warm(name, command, cwd):
    """The row of one command: its cold run, then its warm run on the cache the first filled."""
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
        cold_cpu, cold_wall = measure(command, cache, cwd)
        warm_cpu, warm_wall = measure(command, cache, cwd)
    row = {"run": name, "cold_cpu_s": cold_cpu, "warm_cpu_s": warm_cpu,
           "cold_over_warm": cold_cpu / warm_cpu, "cold_wall_s": cold_wall,
           "warm_wall_s": warm_wall}
    print(f"{name:40s} {cold_cpu:8.1f} {warm_cpu:8.1f} {cold_cpu / warm_cpu:6.2f} "
          f"{cold_wall:8.1f} {warm_wall:8.1f}", flush=True)
    return row


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path)
    parser.add_argument("--suite", action="store_true", help="the fast test run instead")
    parser.add_argument("--output", type=Path,
                        default=ROOT / "benchmarks" / "results" / "cold_start.csv")
    options = parser.parse_args(argv)
    print(f"{'run':40s} {'cold CPU':>8s} {'warm CPU':>8s} {'ratio':>6s} {'cold s':>8s} "
          f"{'warm s':>8s}")
    rows = []
    if options.suite:
        rows.append(cold_and_warm("fast test run (README)", FAST_SUITE, ROOT))
    else:
        paths = options.notebooks or sorted((ROOT / "book").glob("*.ipynb"))
        with tempfile.TemporaryDirectory(prefix="executed-") as folder:
            for path in paths:
                path = path.resolve()
                command = notebook_command(path, Path(folder) / path.name)
                rows.append(cold_and_warm(path.relative_to(ROOT).as_posix(), command,
                                          path.parent))
    names = ["run", "cold_cpu_s", "warm_cpu_s", "cold_over_warm", "cold_wall_s", "warm_wall_s"]
    header = describe(commit=git("rev-parse", "--short", "HEAD"),
                      command="python benchmarks/cold_start.py"
                      + (" --suite" if options.suite else ""))
    output = options.output
    if options.suite:
        output = output.with_name(output.stem + "_suite.csv")
    print("saved", save_table(output, header, names, rows))


if __name__ == "__main__":
    main()
