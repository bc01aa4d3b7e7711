"""The grader (exercises/grade.py) on planted submissions made from the course's own notebook:
each kind of submission an instructor meets gets the verdict it deserves, and none stops \
the run."""

import csv
import subprocess
import sys

import nbformat
import pytest

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "exercises"))
import grade  # noqa: E402
from make_student_edition import BEGIN, strip_solutions  # noqa: E402

EXERCISE = ROOT / "exercises" / "ex01_distortions.ipynb"     # the quickest to run
TASKS = ["1.1", "1.2", "1.3"]


def _solution_cells(notebook):
    return [cell for cell in notebook.cells if cell.cell_type == "code" and BEGIN in cell.source]


def _check_cells(notebook):
    return [cell for cell in notebook.cells
            if cell.cell_type == "code" and grade.CHECK_CALL.search(cell.source)]


def _write(notebook, path):
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(notebook, path)


def plant(folder):
    """One submission of each kind, from the course's notebook; returns the folder."""
    def course():
        return nbformat.read(EXERCISE, as_version=4)

    _write(course(), folder / "right" / EXERCISE.name)                 # the worked solutions

    wrong = course()                                                   # in metres, then None
    first, second, third = _solution_cells(wrong)
    first.source += "\nskew_km = 1000 * skew_km"
    second.source = "growth_percent = None"
    _write(wrong, folder / "wrong" / EXERCISE.name)

    untouched = course()                                               # the student edition
    for cell in _solution_cells(untouched):
        cell.source = strip_solutions(cell.source)
    _write(untouched, folder / "untouched" / "ex01_distortions (1).ipynb")

    looping = course()                                                 # 1.2 never ends
    _solution_cells(looping)[1].source += "\nwhile True:\n    pass"
    _write(looping, folder / "looping" / EXERCISE.name)

    raising = course()                                                 # fails before the imports
    first_code = next(cell for cell in raising.cells
                      if cell.cell_type == "code" and "from rsgeo" in cell.source)
    first_code.source = "raise RuntimeError('broken at the top')\n" + first_code.source
    _write(raising, folder / "raising" / EXERCISE.name)

    deleted = course()                                                 # 1.1 wrong, its check gone
    _solution_cells(deleted)[0].source += "\nskew_km = -skew_km"
    deleted.cells = [cell for cell in deleted.cells if cell is not _check_cells(deleted)[0]]
    _write(deleted, folder / "deleted" / EXERCISE.name)

    cheat = course()                                                   # every check "Correct"
    for cell in _solution_cells(cheat):
        cell.source += "\nskew_km = growth_percent = swath_km = 1.0"
    imports = next(index for index, cell in enumerate(cheat.cells) if "from rsgeo" in cell.source)
    cheat.cells.insert(imports + 1, nbformat.v4.new_code_cell(
        "import rsgeo.exercises\n"
        "def always(*args, **kwargs):\n"
        "    return rsgeo.exercises.Verdict(True, 'Correct')\n"
        "check_skew = check_pixel_growth = check_swath = always\n"
        "rsgeo.exercises.check_skew = rsgeo.exercises.check_swath = always"))
    _write(cheat, folder / "cheat" / EXERCISE.name)

    (folder / "text").mkdir()                                          # not a notebook
    (folder / "text" / EXERCISE.name).write_text("my answers: 7 km, 2 %, 2330 km\n")
    (folder / "photo.jpg").write_bytes(b"\xff\xd8\xff\xe0 not a notebook either")
    _write(course(), folder / "single.ipynb")                          # one .ipynb, no folder
    return folder


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = plant(tmp_path_factory.mktemp("submissions"))
    out = folder.parent / "grades.csv"
    run = subprocess.run([sys.executable, str(ROOT / "exercises" / "grade.py"), str(folder),
                          "--out", str(out), "--jobs", "2", "--cell-timeout", "8"],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    with open(out, newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    verdicts = {}
    for row in rows:
        verdicts.setdefault(row["student"], {})[row["task"]] = (row["verdict"], row["message"])
    return verdicts, run, out


def test_the_csv_has_the_columns_the_issue_names(graded):
    verdicts, run, out = graded
    assert out.read_text().splitlines()[0] == "student,notebook,task,verdict,message"
    assert out.with_suffix(".html").exists()


@pytest.mark.parametrize("student", ["right", "single"])
def test_right_answers_are_correct(graded, student):
    verdicts = graded[0][student]
    assert [verdicts[task][0] for task in TASKS] == ["Correct"] * 3


def test_wrong_answers_get_not_yet_with_the_hint(graded):
    verdicts = graded[0]["wrong"]
    assert verdicts["1.1"][0] == "Not yet" and "metres" in verdicts["1.1"][1]
    assert verdicts["1.2"][0] == "Not yet" and "None" in verdicts["1.2"][1]
    assert verdicts["1.3"][0] == "Correct"


def test_the_student_edition_untouched_is_not_attempted(graded):
    verdicts = graded[0]["untouched"]
    assert [verdicts[task][0] for task in TASKS] == ["not attempted"] * 3


def test_an_infinite_loop_times_out_and_the_rest_is_graded(graded):
    verdicts = graded[0]["looping"]
    assert [verdicts[task][0] for task in TASKS] == ["Correct", "timed out", "Correct"]


def test_a_notebook_that_raises_at_the_top_gets_errors(graded):
    verdicts = graded[0]["raising"]
    assert verdicts["1.1"] == ("error: RuntimeError", "RuntimeError: broken at the top")
    assert all(verdicts[task][0] == "error: NameError" for task in TASKS[1:]), verdicts


def test_a_deleted_check_still_runs_from_the_course(graded):
    verdicts = graded[0]["deleted"]
    assert verdicts["1.1"][0] == "Not yet" and "positive" in verdicts["1.1"][1]
    assert [verdicts[task][0] for task in TASKS[1:]] == ["Correct"] * 2


def test_a_redefined_check_does_not_change_the_grade(graded):
    verdicts = graded[0]["cheat"]
    assert [verdicts[task][0] for task in TASKS] == ["Not yet"] * 3


def test_files_that_are_not_notebooks_are_one_error_row_each(graded):
    verdicts = graded[0]
    assert verdicts["text"] == {"": verdicts["text"][""]}
    assert verdicts["text"][""][0] == "error: not a notebook"
    assert verdicts["photo"][""][0] == "error: not a notebook"


def test_progress_goes_to_standard_error(graded):
    run = graded[1]
    assert "[" + "#" * 30 + "] 10/10" in run.stderr
    assert "verdicts" in run.stdout


def test_the_html_summary_colours_each_verdict(graded):
    page = graded[2].with_suffix(".html").read_text()
    assert page.count("<table>") == 2                       # ex01 and the not-a-notebook rows
    for colour in (grade.COLOURS["Correct"], grade.COLOURS["Not yet"],
                   grade.COLOURS["not attempted"], grade.COLOURS["timed out"]):
        assert colour in page


def test_a_task_is_a_solution_and_its_checks():
    course = grade.read_course(EXERCISE)
    assert [task.name for task in course.tasks] == TASKS
    assert all(task.check_source.startswith("check_") for task in course.tasks)
    for path in sorted((ROOT / "exercises").glob("*.ipynb")):      # every course notebook reads
        assert grade.read_course(path).tasks


def test_bad_arguments_are_refused(tmp_path):
    with pytest.raises(ValueError, match="not a folder"):
        grade.submissions(tmp_path / "missing")
    with pytest.raises(ValueError, match="positive integer"):
        grade.grade(tmp_path, jobs=0)
    with pytest.raises(ValueError, match="positive"):
        grade.grade_notebook(EXERCISE, "x", [], cell_timeout=0)


def test_the_mistakes_listed_are_the_hints_the_checks_give():
    from rsgeo import distortion, exercises

    checks = [name for name in exercises.__all__ if name.startswith("check_")]
    for name in checks:
        assert exercises.recognised_mistakes(name), f"{name}: no hint found in its source"
    listed = [hint for _kind, hint in exercises.recognised_mistakes(exercises.check_skew)]
    skew = abs(distortion.earth_rotation_skew(-23.5, 113.0, 778.0, 98.5))
    for answer in (1000 * skew, -skew, 3.0 * skew):          # metres, a sign, no known mistake
        verdict = exercises.check_skew(answer, -23.5, 113.0, 778.0, 98.5)
        assert not verdict.ok and verdict.hint in listed, verdict.hint
    fitness = " ".join(hint for _kind, hint in exercises.recognised_mistakes("check_fitness"))
    assert "{" not in fitness                                # module constants are filled in
    with pytest.raises(ValueError, match="not a check"):
        exercises.recognised_mistakes("print")
