"""How long the grader takes for a class: STUDENTS students x the course's exercise notebooks.

    python benchmarks/grading.py [--students 40] [--notebooks 9] [--jobs 2]

Each student hands in the course's own notebooks (worked solutions: every task runs in full, the
slowest case); the grader (exercises/grade.py) grades them with its defaults. Prints the wall
time, the time per notebook, and the verdict counts. Not a test: it takes minutes.
"""

import argparse
import shutil
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "exercises"))
import grade  # noqa: E402


def main(argv=None):
    """Build the class in a temporary folder, grade it, print the timing."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--students", type=int, default=40)
    parser.add_argument("--notebooks", type=int, default=9, help="the first N notebooks")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--unsafe", action="store_true",
                        help="grade without bubblewrap, as grade.py --unsafe (timing only)")
    options = parser.parse_args(argv)
    notebooks = sorted((ROOT / "exercises").glob("*.ipynb"))[:options.notebooks]
    with tempfile.TemporaryDirectory(prefix="rsgeo-class-") as folder:
        for number in range(options.students):
            student = Path(folder) / f"student{number:02d}"
            student.mkdir()
            for notebook in notebooks:
                shutil.copy(notebook, student / notebook.name)
        start = time.perf_counter()
        rows = grade.grade(folder, jobs=options.jobs, show_progress=True,
                           unsafe=options.unsafe)
        seconds = time.perf_counter() - start
    count = options.students * len(notebooks)
    print(f"{options.students} students x {len(notebooks)} notebooks ({count}), "
          f"--jobs {options.jobs}: {seconds:.0f} s, {seconds / count:.1f} s per notebook")
    print(dict(Counter(row.verdict for row in rows)))


if __name__ == "__main__":
    main()
