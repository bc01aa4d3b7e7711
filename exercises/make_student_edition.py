"""Make the student edition of the course: the book with the exercises' solutions removed.

    python exercises/make_student_edition.py [OUTPUT_FOLDER]     # default: student_edition

Copies the book's sources (``_config.yml``, ``_toc.yml``, ``references.bib``,
``book/``, ``exercises/`` and the saved benchmark tables ``benchmarks/results/``
that chapters show) to OUTPUT_FOLDER. In every exercise notebook, the lines of a
code cell between ``### BEGIN SOLUTION`` and ``### END SOLUTION`` (both
included) are removed, leaving the task's ``answer = ...`` placeholder and the
check that follows it; such cells are shown, not hidden behind a toggle.

The edition is the full course: its chapters are executed when it is built, with
every figure, exactly as in the instructors' book. Only the exercise notebooks are
not executed (they stop at the first unsolved task, by design: students run them).
Build it with

    jupyter-book build OUTPUT_FOLDER
"""

import re
import shutil
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "### BEGIN SOLUTION", "### END SOLUTION"
# chapter 6 imports its experiment harness, benchmarks/ga_experiments.py, beside the tables
SOURCES = ("_config.yml", "_toc.yml", "references.bib", "book", "exercises", "benchmarks/results",
           "benchmarks/ga_experiments.py")


def strip_solutions(source):
    """A code cell's source without its solution blocks; raises ValueError on unbalanced
    markers."""
    kept, inside = [], False
    for number, line in enumerate(source.splitlines(), start=1):
        marker = line.strip()
        if marker == BEGIN:
            if inside:
                raise ValueError(f"line {number}: {BEGIN} inside another solution block")
            inside = True
        elif marker == END:
            if not inside:
                raise ValueError(f"line {number}: {END} without {BEGIN}")
            inside = False
        elif not inside:
            kept.append(line)
    if inside:
        raise ValueError(f"{BEGIN} without {END}")
    return "\n".join(kept).rstrip()


def student_notebook(path):
    """Rewrite one notebook in place for students; return the number of solution cells stripped."""
    notebook = nbformat.read(path, as_version=4)
    stripped = 0
    for cell in notebook.cells:
        if cell.cell_type == "code" and BEGIN in cell.source:
            cell.source = strip_solutions(cell.source)
            tags = cell.metadata.get("tags", [])
            cell.metadata["tags"] = [tag for tag in tags if tag != "hide-input"]
            stripped += 1
    nbformat.write(notebook, path)
    return stripped


def make_student_edition(output):
    output = Path(output)
    if output.exists():
        shutil.rmtree(output)
    output.mkdir(parents=True)
    for name in SOURCES:
        source = ROOT / name
        if not source.exists():
            raise FileNotFoundError(f"{source} is missing: the student edition needs it")
        if source.is_dir():
            shutil.copytree(source, output / name, ignore=shutil.ignore_patterns(
                "_build", ".ipynb_checkpoints", "__pycache__", "make_student_edition.py"))
        else:
            shutil.copy2(source, output / name)
    config = (output / "_config.yml").read_text()
    # chapters run as in the instructors' book; exercises stop at their first task, so students
    # run them
    config, count = re.subn(r"^execute:\n",
                            "execute:\n  exclude_patterns:\n    - \"exercises/*\"\n",
                            config, count=1, flags=re.M)
    if count != 1:
        raise ValueError("_config.yml has no `execute:` section to exclude the exercises from")
    # its chapters are the instructors' chapters, code for code, and jupyter-cache matches a
    # notebook by its code: once the course's book is built, the edition reuses its executions
    # and runs no chapter again (a chapter changed since then runs, and joins that cache)
    cache = ROOT / "_build" / ".jupyter_cache"
    if cache.exists():
        config, count = re.subn(r"^(  execute_notebooks: cache.*\n)", rf"\1  cache: {cache}\n",
                                config, count=1, flags=re.M)
        if count != 1:
            raise ValueError("_config.yml does not execute into a cache "
                             "(execute_notebooks: cache)")
    config = re.sub(r"^title:\s*(.*)$", r"title: \1 (student edition)", config, count=1,
                    flags=re.M)
    # the edition is built alone: no Portuguese book beside it for the language switch to open
    config, count = re.subn(r"^(\s*i18n_other_book:).*$", r'\1 ""', config, count=1, flags=re.M)
    if count != 1:
        raise ValueError("_config.yml has no `i18n_other_book:` setting to switch off")
    (output / "_config.yml").write_text(config)
    total = sum(student_notebook(path) for path in sorted((output / "exercises").glob("*.ipynb")))
    return total


if __name__ == "__main__":
    folder = sys.argv[1] if len(sys.argv) > 1 else "student_edition"
    count = make_student_edition(folder)
    print(f"student edition in {folder}/: {count} solutions removed; build it with "
          f"`jupyter-book build {folder}`")
