"""The student edition: solutions removed, checks kept, and each notebook stops at its first task."""

import sys

import nbformat
import pytest
from nbclient.exceptions import CellExecutionError

from conftest import ROOT, execute_notebook

sys.path.insert(0, str(ROOT / "exercises"))
from make_student_edition import BEGIN, make_student_edition, strip_solutions  # noqa: E402


@pytest.fixture(scope="module")
def edition(tmp_path_factory):
    folder = tmp_path_factory.mktemp("student")
    assert make_student_edition(folder) >= 16
    return folder


def test_solutions_are_gone_and_checks_stay(edition):
    for path in sorted((edition / "exercises").glob("*.ipynb")):
        sources = [cell.source for cell in nbformat.read(path, as_version=4).cells if cell.cell_type == "code"]
        assert not any(BEGIN in source for source in sources)
        assert any("check_" in source for source in sources)
    assert 'execute_notebooks: "off"' in (edition / "_config.yml").read_text()


@pytest.mark.parametrize("name", sorted(path.name for path in (ROOT / "exercises").glob("*.ipynb")))
def test_student_notebook_stops_at_its_first_task(edition, name):
    path = edition / "exercises" / name
    with pytest.raises(CellExecutionError) as failure:
        execute_notebook(path)
    assert failure.value.ename == "ExerciseNotSolved"
    assert "this task is yours" in str(failure.value)
    # it stopped at the first check, not earlier
    cells = nbformat.read(path, as_version=4).cells
    first_check = next(cell for cell in cells if cell.cell_type == "code" and cell.source.startswith("check_"))
    assert first_check.source in str(failure.value)


def test_unbalanced_markers_are_refused():
    with pytest.raises(ValueError, match="without"):
        strip_solutions("x = ...\n### BEGIN SOLUTION\nx = 1\n")
