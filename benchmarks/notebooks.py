"""How long each notebook takes to run top to bottom, and what its figures lack.

    python benchmarks/notebooks.py [NOTEBOOK ...]     # default: every chapter and exercise

Executes each notebook as the tests do (a fresh kernel, in its own folder, auditing
its figures as the book's build does: book/_ext/figure_audit.py), prints its wall
time, and lists the problems the audit finds in its figures. The course's goal:
every notebook in 30 s or less on a 2-core machine.
"""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from notebook_runner import execute_notebook  # noqa: E402

if __name__ == "__main__":
    paths = [Path(p) for p in sys.argv[1:]] or (sorted((ROOT / "book").glob("*.ipynb"))
                                                 + sorted((ROOT / "exercises").glob("*.ipynb")))
    print(f"{'notebook':40s} {'seconds':>8s}  figure problems")
    for path in paths:
        notebook = execute_notebook(path, audit_figures=True)
        problems = notebook.metadata["figure_problems"]
        print(f"{path.name:40s} {notebook.metadata['seconds']:8.1f}  {len(problems)}")
        for problem in problems:
            print(f"    {problem}")
