"""The student edition: the full course with only the exercises' solutions removed.

Its chapters are executed when it is built (every figure there), its exercise notebooks stop at
their first task, and its own build command, from the README, succeeds.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest
from nbclient.exceptions import CellExecutionError

from notebook_runner import ROOT, execute_notebook

sys.path.insert(0, str(ROOT / "exercises"))
from make_student_edition import BEGIN, make_student_edition, strip_solutions  # noqa: E402

CHAPTERS = sorted(path.relative_to(ROOT) for path in (ROOT / "book").glob("*.ipynb"))


@pytest.fixture(scope="module")
def edition(tmp_path_factory):
    folder = tmp_path_factory.mktemp("student") / "student_edition"
    assert make_student_edition(folder) >= 16
    return folder


def test_solutions_are_gone_and_checks_stay(edition):
    for path in sorted((edition / "exercises").glob("*.ipynb")):
        sources = [cell.source for cell in nbformat.read(path, as_version=4).cells
                   if cell.cell_type == "code"]
        assert not any(BEGIN in source for source in sources)
        assert any("check_" in source for source in sources)


def test_chapters_are_the_instructors_chapters(edition):
    for chapter in CHAPTERS:
        assert (edition / chapter).read_bytes() == (ROOT / chapter).read_bytes(), chapter
    config = (edition / "_config.yml").read_text()
    # chapters run, figures and all
    assert re.search(r"execute_notebooks:\s*(force|cache)", config)
    # exercises: students run them
    assert re.search(r"exclude_patterns:\n\s+- \"exercises/\*\"", config)


@pytest.mark.parametrize("name",
                         sorted(path.name for path in (ROOT / "exercises").glob("*.ipynb")))
def test_student_notebook_stops_at_its_first_task(edition, name):
    path = edition / "exercises" / name
    with pytest.raises(CellExecutionError) as failure:
        execute_notebook(path)
    assert failure.value.ename == "ExerciseNotSolved"
    assert "this task is yours" in str(failure.value)
    # it stopped at the first check, not earlier
    cells = nbformat.read(path, as_version=4).cells
    first_check = next(cell for cell in cells
                       if cell.cell_type == "code" and cell.source.startswith("check_"))
    assert first_check.source in str(failure.value)


def test_the_edition_builds_with_every_chapter_executed(edition):
    # The README's command (`jupyter-book build student_edition`), warnings as errors here.
    jupyter_book = Path(sys.executable).parent / "jupyter-book"
    build = subprocess.run([str(jupyter_book), "build", str(edition), "-W", "-n", "--keep-going"],
                           capture_output=True, text=True, timeout=1500)
    assert build.returncode == 0, (build.stdout + build.stderr)[-4000:]
    if os.environ.get("CI"):            # CI built the course just before: no chapter runs twice
        executed = re.findall(r"(\S+\.ipynb): Executing notebook", build.stdout + build.stderr)
        assert not executed, f"the edition executed again: {executed}"
    html = edition / "_build" / "html"
    for chapter in CHAPTERS:
        page = (html / chapter.with_suffix(".html")).read_text()
        assert "cell_output" in page, f"{chapter}: no outputs: the chapter was not executed"
        # built alone, the edition has no Portuguese book beside it to switch to
        assert "rsgeo-language-switch" not in page, f"{chapter} links to a missing Portuguese book"
        if chapter.name.startswith("0") and "_widget" not in chapter.name:
            assert re.search(r"<img[^>]+(_images/|data:image/png)", page), (
                f"{chapter} has no figure")
    for exercise in sorted((edition / "exercises").glob("*.ipynb")):
        page = (html / "exercises" / exercise.with_suffix(".html").name).read_text()
        assert BEGIN not in page and "check_" in page


def test_unbalanced_markers_are_refused():
    with pytest.raises(ValueError, match="without"):
        strip_solutions("x = ...\n### BEGIN SOLUTION\nx = 1\n")
