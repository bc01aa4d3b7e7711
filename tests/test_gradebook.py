"""exercises/gradebook.py: the grader's verdicts become the marks of the instructor's scheme
(Correct earns, "Not yet" is feedback unless the scheme says otherwise, and a placeholder never
earns), exported as Moodle's and Canvas's gradebook import CSVs, with a feedback file per
student that holds no right answer; a malformed grades.csv stops it with a clear message.

The grades are a small synthetic grades.csv in grade.py's columns, for the course's real
exercise notebooks 1 (tasks 1.1 to 1.3) and 2b (2b.1 to 2b.3).
"""

import csv
import sys

import pytest

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "exercises"))
import gradebook  # noqa: E402

HEADER = ["student", "notebook", "task", "verdict", "message", "file", "note"]
ZERO = "`{}` is zero, and it should not be. Hint: divide by the pixel size."
SMALL = "`{}` is too small by more than half. Hint: use radians."
RIGHT = "`{}` = 28.6 km."              # a Correct message quotes the (right) value
ANSWERS = {"1.1": "skew_km", "1.2": "swath_km", "1.3": "growth"}


def rows_for(student, verdicts, notebook="ex01_distortions", tasks=("1.1", "1.2", "1.3")):
    rows = []
    for task, verdict in zip(tasks, verdicts):
        name = ANSWERS.get(task, "shift_px")
        message = {"Correct": RIGHT, "zero": ZERO, "Not yet": SMALL}.get(verdict, "")
        shown = "Not yet" if verdict == "zero" else verdict
        if verdict.startswith("error"):
            message = "NameError: name 'np' is not defined"
        rows.append([student, notebook, task, shown, message.format(name),
                     f"{student}/{notebook}.ipynb", ""])
    return rows


CLASS = (rows_for("ana", ["Correct"] * 3)
         + rows_for("bruno", ["Correct", "Not yet", "not attempted"])
         + rows_for("zeros", ["zero"] * 3)                 # 0 everywhere
         + rows_for("ones", ["Not yet"] * 3)               # 1 everywhere: never Correct
         + rows_for("carla", ["Correct", "zero", "error: NameError"])
         + rows_for("ana", ["Correct", "Not yet", "timed out"], "ex02b_datums",
                    ("2b.1", "2b.2", "2b.3")))


def write(path, rows, header=HEADER):
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows(rows)
    return path


@pytest.fixture
def grades(tmp_path):
    return write(tmp_path / "grades.csv", CLASS)


def read(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.reader(handle))


def totals(path, scheme=None):
    rows = gradebook.read_grades(path)
    notebooks, marks = gradebook.compute_marks(rows, scheme or gradebook.read_scheme())
    return notebooks, {student: round(own["total"], 3) for student, own in marks.items()}


def test_by_default_only_correct_earns_and_a_placeholder_earns_nothing(grades):
    notebooks, total = totals(grades)
    assert notebooks == ["ex01_distortions", "ex02b_datums"]
    # ex01 3/3 and ex02b 1/3, each notebook weighing the same, out of 10
    assert total["ana"] == pytest.approx(10 * (1 + 1 / 3) / 2, abs=1e-3)
    # one Correct of three in ex01, and no ex02b handed in: it counts as nothing
    assert total["bruno"] == pytest.approx(10 * (1 / 3) / 2, abs=1e-3)
    assert total["zeros"] == 0 and total["ones"] == 0


def test_half_marks_for_not_yet_only_after_a_real_attempt(grades):
    scheme = gradebook.read_scheme(overrides={"marks": {"not_yet": 0.5}})
    _, total = totals(grades, scheme)
    assert total["bruno"] == pytest.approx(10 * (1.5 / 3) / 2, abs=1e-3)
    # 0 everywhere, 1 everywhere: no Correct in the notebook, so "Not yet" earns nothing
    assert total["zeros"] == 0 and total["ones"] == 0
    # a Correct task does not make the zero placeholder beside it worth anything
    assert total["carla"] == pytest.approx(10 * (1 / 3) / 2, abs=1e-3)


def test_the_scheme_file_sets_marks_weights_and_the_scale(grades, tmp_path):
    scheme_file = tmp_path / "scheme.toml"
    scheme_file.write_text("out_of = 20\n[marks]\ncorrect = 2\n"
                           "[notebooks.ex01_distortions]\nweight = 3\ncanvas_id = 4711\n"
                           "[notebooks.ex02b_datums]\nweight = 1\ntitle = \"Datums\"\n")
    scheme = gradebook.read_scheme(scheme_file)
    notebooks, total = totals(grades, scheme)
    assert notebooks == ["ex01_distortions", "ex02b_datums"]
    assert total["ana"] == pytest.approx(20 * (3 * 1 + 1 * 1 / 3) / 4, abs=1e-3)
    assert total["bruno"] == pytest.approx(20 * (3 * 1 / 3) / 4, abs=1e-3)
    # a scheme naming only one notebook counts only that one
    scheme_file.write_text("[notebooks.ex02b_datums]\n")
    notebooks, total = totals(grades, gradebook.read_scheme(scheme_file))
    assert notebooks == ["ex02b_datums"] and total["bruno"] == 0
    assert total["ana"] == pytest.approx(10 / 3, abs=1e-3)


@pytest.mark.parametrize("text, complaint", [
    ("[marks]\nnot_yet = -1\n", "must be a number, 0 or more"),
    ("[marks]\nmaybe = 1\n", "'maybe'; the verdicts are"),
    ("out_of = 0\n", "must be a positive number"),
    ("passmark = 5\n", "unknown setting passmark"),
    ("[notebooks.ex01_distortions]\nweigth = 2\n", "unknown weigth"),
    ("out_of = \n", "not a TOML scheme"),
])
def test_a_malformed_scheme_is_refused(tmp_path, text, complaint):
    path = tmp_path / "scheme.toml"
    path.write_text(text)
    with pytest.raises(gradebook.GradebookError, match=complaint):
        gradebook.read_scheme(path)


def test_moodle_and_canvas_files_in_their_import_formats(grades, tmp_path):
    roster = tmp_path / "roster.csv"
    write(roster, [["ana", "Souza, Ana", "ana@uni.br", "2026001", "8101", "S1", "Turma A"],
                   ["bruno", "Lima, Bruno", "bruno@uni.br", "2026002", "8102", "S2", "Turma A"],
                   ["zeros", "Zero, Zé", "ze@uni.br", "2026003", "8103", "S3", "Turma B"],
                   ["ones", "Um, Ivo", "ivo@uni.br", "2026004", "8104", "S4", "Turma B"],
                   ["carla", "Dias, Carla", "carla@uni.br", "2026005", "8105", "S5", "Turma B"],
                   ["dora", "Reis, Dora", "dora@uni.br", "2026006", "8106", "S6", "Turma B"]],
          header=["student", "name", "email", "idnumber", "canvas_id", "sis_user_id",
                  "section"])
    scheme = tmp_path / "scheme.toml"
    scheme.write_text("[notebooks.ex01_distortions]\ncanvas_id = 4711\n"
                      "[notebooks.ex02b_datums]\n")
    moodle, canvas = tmp_path / "moodle.csv", tmp_path / "canvas.csv"
    assert gradebook.main([str(grades), "--scheme", str(scheme), "--roster", str(roster),
                           "--moodle", str(moodle), "--canvas", str(canvas)]) == 0
    # Moodle: the user's identifier (mapped to useremail), then a column per grade item
    table = read(moodle)
    assert table[0] == ["Email address", "Exercises 1: systematic distortions",
                        "Exercises 2b: datums", "Total"]
    by_user = {row[0]: row[1:] for row in table[1:]}
    assert by_user["ana@uni.br"] == ["3", "1", "6.67"]
    assert by_user["ze@uni.br"] == ["0", "0", "0"]
    assert by_user["dora@uni.br"] == ["", "", ""]          # on the roster, nothing handed in
    # Canvas: Student, ID, SIS User ID, SIS Login ID, Section, then "Name (id)" columns
    table = read(canvas)
    assert table[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section",
                        "Exercises 1: systematic distortions (4711)", "Exercises 2b: datums"]
    assert table[1][0].strip() == "Points Possible" and table[1][5:] == ["3", "3"]
    by_name = {row[0]: row[1:] for row in table[2:]}
    assert by_name["Souza, Ana"] == ["8101", "S1", "", "Turma A", "3", "1"]
    assert by_name["Lima, Bruno"][4:] == ["1", "0"]
    # every identifier, every student of the roster, once
    assert len(by_name) == 6


def test_the_moodle_identifier_defaults_to_the_grader_names_without_a_roster(grades, tmp_path):
    moodle = tmp_path / "moodle.csv"
    gradebook.main([str(grades), "--moodle", str(moodle), "--moodle-id", "username"])
    table = read(moodle)
    assert table[0][0] == "Username" and {row[0] for row in table[1:]} == {
        "ana", "bruno", "zeros", "ones", "carla"}


def test_a_student_missing_from_the_roster_stops_the_export(grades, tmp_path, capsys):
    roster = write(tmp_path / "roster.csv", [["ana", "ana@uni.br"]],
                   header=["student", "email"])
    with pytest.raises(SystemExit) as stop:
        gradebook.main([str(grades), "--roster", str(roster), "--moodle",
                        str(tmp_path / "m.csv")])
    assert stop.value.code == 2
    assert "does not list 4 graded student(s): bruno, carla, ones, zeros" in (
        capsys.readouterr().err)


def test_feedback_files_give_verdicts_and_messages_but_no_right_answer(grades, tmp_path):
    folder = tmp_path / "feedback"
    assert gradebook.main([str(grades), "--feedback", str(folder)]) == 0
    files = sorted(path.name for path in folder.iterdir())
    assert files == ["ana.md", "bruno.md", "carla.md", "ones.md", "zeros.md"]
    bruno = (folder / "bruno.md").read_text()
    assert "| 1.2 | Not yet | `swath_km` is too small by more than half. Hint: use radians. |" \
        in bruno
    assert "| 1.1 | Correct |  |" in bruno and "| 1.3 | not attempted |" in bruno
    assert "Exercises 2b: datums (not handed in)" in bruno
    assert "Total: 1.67 of 10" in bruno
    for path in folder.iterdir():
        assert "28.6" not in path.read_text(), path.name       # a Correct message's value
    carla = (folder / "carla.md").read_text()
    assert "| 1.3 | error: NameError | NameError: name 'np' is not defined |" in carla
    portuguese = tmp_path / "retorno"
    gradebook.main([str(grades), "--feedback", str(portuguese), "--language", "pt_BR"])
    assert "| 1.1 | Correto |  |" in (portuguese / "bruno.md").read_text()


def test_the_marks_table(grades, tmp_path):
    marks = tmp_path / "marks.csv"
    gradebook.main([str(grades), "--marks", str(marks), "--weight", "ex02b_datums=0"])
    table = read(marks)
    assert table[0] == ["student", "ex01_distortions", "ex02b_datums", "total (of 10)"]
    assert ["ana", "3", "1", "10"] in table and ["zeros", "0", "0", "0"] in table


def test_the_best_of_two_submissions_counts_and_is_noted(tmp_path):
    rows = (rows_for("ana", ["Not yet"] * 3)
            + [row[:5] + ["ana/copy.ipynb", ""] for row in rows_for("ana", ["Correct"] * 3)])
    path = write(tmp_path / "grades.csv", rows)
    _, marks = gradebook.compute_marks(gradebook.read_grades(path), gradebook.read_scheme())
    mark = marks["ana"]["notebooks"]["ex01_distortions"]
    assert mark.points == 3 and "2 submissions" in mark.notes[0]


@pytest.mark.parametrize("content, complaint", [
    (b"", "is empty: it needs a header"),
    (b"student,notebook,task,verdict\nana,ex01_distortions,1.1,Correct\n",
     "line 1: no column message"),
    (b"student,notebook,task,verdict,message,file,note\n"
     b"ana,ex01_distortions,1.1,Maybe,,,\n", "line 2: the verdict 'Maybe' is not one"),
    (b"student,notebook,task,verdict,message,file,note\n"
     b"ana,ex01_distortions,1.1,Correct,,\n", "line 2: 6 fields, the header has 7"),
    (b"student,notebook,task,verdict,message,file,note\n"
     b",ex01_distortions,1.1,Correct,,,\n", "line 2: no student"),
    (b"student,notebook,task,verdict,message,file,note\n", "no rows: nothing was graded"),
    (b"student,notebook,task,verdict,message,file,note\nJos\xe9,ex01,1.1,Correct,,,\n",
     "not UTF-8 text"),
])
def test_a_malformed_grades_csv_stops_with_a_clear_message(tmp_path, capsys, content, complaint):
    path = tmp_path / "grades.csv"
    path.write_bytes(content)
    with pytest.raises(SystemExit) as stop:
        gradebook.main([str(path), "--moodle", str(tmp_path / "moodle.csv")])
    assert stop.value.code == 2
    error = capsys.readouterr().err
    assert error.startswith("gradebook.py: error: ") and complaint in error, error
    assert not (tmp_path / "moodle.csv").exists()


def test_a_missing_grades_file_and_a_bad_weight(tmp_path, capsys, grades):
    with pytest.raises(SystemExit) as stop:
        gradebook.main([str(tmp_path / "nowhere.csv")])
    assert stop.value.code == 2 and "no such file" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        gradebook.main([str(grades), "--weight", "ex09_nothing=2"])
    assert stop.value.code == 2 and "ex09_nothing" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        gradebook.main([str(grades), "--weight", "ex01_distortions"])
    assert stop.value.code == 2 and "NOTEBOOK=WEIGHT" in capsys.readouterr().err


def test_task_names_are_the_graders():
    # grade.py names a task after the {exercise} directive before its solution cell
    tasks = gradebook.course_tasks()
    assert tasks["ex02b_datums"] == ("Exercises 2b: datums", ["2b.1", "2b.2", "2b.3"])
    assert set(tasks) == {path.stem for path in (ROOT / "exercises").glob("ex*.ipynb")}
