"""The grader (exercises/grade.py, judge.py, sandbox.py) on a synthetic class: each
kind of submission an instructor meets gets the verdict it deserves, no cheat changes a verdict,
and nothing, whatever a file is named, loses the class's rows."""

import csv
import os
import subprocess
import sys
from types import SimpleNamespace

import nbformat
import numpy as np
import pytest
from grade_class_fixtures import (
    EXERCISE,
    EXPECTED,
    LATIN1_STUDENT,
    NOT_A_NOTEBOOK,
    PLANTED,
    TASKS,
    plant,
    slice_course,
)

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "exercises"))
import grade  # noqa: E402
import judge  # noqa: E402
import sandbox  # noqa: E402

from rsgeo_course.exercises import engine  # noqa: E402


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = plant(tmp_path_factory.mktemp("submissions"))
    course = slice_course(tmp_path_factory.mktemp("course"))
    out = folder.parent / "grades" / "grades.csv"
    # the grader's limit on a cell is wall-clock time (a sleeping student uses no CPU): 30 s
    # stops the looping and the sleeping students, and no honest cell comes near it on a
    # loaded machine (4 s did: an honest cell timed out beside a busy CI)
    run = subprocess.run([sys.executable, str(ROOT / "exercises" / "grade.py"), str(folder),
                          "--out", str(out), "--jobs", "2", "--cell-timeout", "30",
                          "--memory-mb", "3072", "--course", str(course)],
                         capture_output=True, text=True, timeout=600)
    planted = [path for path in PLANTED if path.exists()]
    for path in planted:                                 # never leave a planted file behind
        path.unlink()
    assert run.returncode == 0, run.stderr[-3000:]
    with open(out, newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    verdicts = {}
    for row in rows:
        verdicts.setdefault(row["student"], {})[row["task"]] = row
    return SimpleNamespace(verdicts=verdicts, rows=rows, run=run, out=out, planted=planted)


def test_every_row_of_the_class_is_the_verdict_it_deserves(graded):
    got = {student: [graded.verdicts.get(student, {}).get(task, {}).get("verdict", "(no row)")
                     for task in TASKS] for student in EXPECTED}
    assert got == EXPECTED
    for student, verdict in NOT_A_NOTEBOOK.items():
        assert graded.verdicts[student][""]["verdict"] == verdict
    assert len(graded.rows) == len(TASKS) * len(EXPECTED) + len(NOT_A_NOTEBOOK)


def test_the_csv_has_the_file_and_a_note_and_the_html_is_written(graded):
    assert graded.out.read_text().splitlines()[0] == ",".join(grade.FIELDS)
    page = graded.out.with_suffix(".html").read_text(encoding="utf-8")
    assert "Jos\\xe9_Silva" in page and page.count("<table>") == 2


def test_a_latin1_folder_keeps_its_name_escaped(graded):
    rows = graded.verdicts["Jos\\xe9_Silva"]
    assert rows["2b.1"]["file"] == "Jos\\xe9_Silva/ex02b_datums.ipynb"


def test_a_misfiled_notebook_is_graded_as_its_content_and_flagged(graded):
    row = graded.verdicts["misfiled"]["2b.1"]
    assert row["notebook"] == "ex02b_datums.ipynb"
    assert "saved as ex04_resampling.ipynb, graded as ex02b_datums" in row["note"]
    renamed = graded.verdicts["renamed"]["2b.1"]
    assert renamed["file"] == "renamed/my homework (final).ipynb"
    assert "saved as" not in renamed["note"]


def test_a_cells_own_error_is_reported_and_the_students_variable_named(graded):
    assert "SyntaxError" in graded.verdicts["syntax_error"]["2b.1"]["message"]
    assert "`hrc_shift_px`" in graded.verdicts["wrong"]["2b.2"]["message"]
    assert "metres" in graded.verdicts["wrong"]["2b.1"]["message"]


def test_no_submission_wrote_outside_its_folder(graded):
    assert graded.planted == []
    if sandbox.bwrap_path() is None:
        assert "bwrap not installed" in graded.verdicts["right"]["2b.1"]["note"]


def test_progress_goes_to_standard_error(graded):
    total = len(EXPECTED) + len(NOT_A_NOTEBOOK)
    assert f"[{'#' * 30}] {total}/{total}" in graded.run.stderr
    assert "verdicts" in graded.run.stdout


# -- Pieces, without a kernel ---------------------------------------------------------------

def test_names_that_are_not_utf8_are_written(tmp_path):
    student = os.fsdecode(LATIN1_STUDENT)
    out = tmp_path / "grades.csv"
    grade.write_csv([grade.Row(student, "x.ipynb", "1", "Correct", "ok", student + "/x")], out)
    grade.write_html([grade.Row(student, "x.ipynb", "1", "Correct", "ok", student)],
                     tmp_path / "grades.html")
    assert "Jos\\xe9_Silva,x.ipynb" in out.read_text(encoding="utf-8")


def _task(check_source, answers):
    return SimpleNamespace(check_source=check_source, answers=answers)


def test_one_tolerance_rule_accepts_float32_and_two_decimals():
    window = np.full((2, 2), 28.6)
    scope = {"window": window, "dx": 0.3, "dy": 0.6}
    bilinear = _task("check_bilinear(value, window, dx, dy)", ["value"])   # rtol 1e-9
    assert judge.judge(bilinear, scope, {"value": np.float32(28.6)})[0] == "Correct"
    encoded = {"t": "npscalar", "dtype": "float32", "v": str(np.float32(28.6))}
    assert judge.judge(bilinear, scope, {"value": judge.decode(encoded)})[0] == "Correct"
    predicted = np.array([[0.0, 0.0], [0.0, 0.0]])
    observed = np.array([[22.5137, 0.0], [0.0, 22.5137]])
    rms = _task("check_rms(rms, predicted, observed)", ["rms"])            # rtol 1e-6
    scope = {"predicted": predicted, "observed": observed}
    assert judge.judge(rms, scope, {"rms": 22.51})[0] == "Correct"
    assert judge.judge(rms, scope, {"rms": 22.52})[0] == "Not yet"
    assert engine.accepts_rounded(0.0, 0.003) is False


def test_the_judge_uses_the_courses_inputs_and_names_the_students_variable():
    window = np.array([[10.0, 20.0], [30.0, 60.0]])
    bilinear = _task("check_bilinear(value, window, dx, dy)", ["value"])
    cheat = judge.judge(bilinear, {"window": window, "dx": 0.3, "dy": 0.6}, {"value": 10.0})
    assert cheat[0] == "Not yet"                  # dx, dy = 0, 0 in the kernel change nothing
    pixels = _task("check_datum_shift_pixels(hrc_shift_px, xy, 29191, 31981, pixel_size=2.5)",
                   ["hrc_shift_px"])
    verdict = judge.judge(pixels, {"xy": [[775445.0, 7369105.0]]}, {"hrc_shift_px": 0.0})
    assert verdict[0] == "Not yet" and "`hrc_shift_px`" in verdict[1]
    assert judge.answer_names("gain, offset = ..., ...\nx = 1") == ["gain", "offset"]


def test_a_misfiled_notebook_matches_by_content(tmp_path):
    courses = grade.course_notebooks()
    notebook = nbformat.read(EXERCISE, as_version=4)
    sources = [grade._normal(cell.source) for cell in notebook.cells if cell.cell_type == "code"]
    course, note = grade.match_course(tmp_path / "ex04_resampling.ipynb", sources, courses)
    assert course.path.name == EXERCISE.name and "graded as ex02b_datums" in note
    course, note = grade.match_course(tmp_path / "ex04_resampling.ipynb", [], courses)
    assert course.path.name == "ex04_resampling.ipynb" and note == ""


@pytest.mark.skipif(sandbox.bwrap_path() is None, reason="bubblewrap (bwrap) is not installed")
def test_bwrap_hides_the_course_and_the_network(tmp_path):
    command = sandbox.bwrap_command(
        [sys.executable, "-c", "import os, socket, sys; print(os.listdir(sys.argv[1]));"
         "socket.create_connection(('1.1.1.1', 53), timeout=2)", str(ROOT / "exercises")],
        str(tmp_path), str(tmp_path), [str(ROOT / "exercises")])
    run = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert run.stdout.strip() == "[]" and run.returncode != 0


def test_a_task_is_a_solution_its_answers_and_its_checks():
    course = grade.read_course(EXERCISE)
    assert [task.name for task in course.tasks] == ["2b.1", "2b.2", "2b.3"]
    assert [task.answers for task in course.tasks] == [["shift_px"], ["hrc_shift_px"],
                                                       ["gap_px"]]
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
    from rsgeo import distortion
    from rsgeo_course import exercises

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
