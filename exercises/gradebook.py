"""Turn the grader's verdicts into marks: a gradebook an LMS imports, and feedback per student.

    python exercises/gradebook.py grades.csv [--scheme scheme.toml | --correct 1 --not-yet 0
                                  --weight ex04_resampling=2 --out-of 10] [--roster roster.csv]
                                  [--moodle moodle.csv] [--canvas canvas.csv] [--feedback DIR]
                                  [--marks marks.csv] [--language pt_BR]

``grades.csv`` is what ``exercises/grade.py`` writes: a row per task (student, notebook, task,
verdict, message, file, note), with the verdict ``Correct``, ``Not yet``, ``not attempted``,
``error: ...`` or ``timed out``.

**The marking scheme is the instructor's.** By default a task earns 1 mark when it is
``Correct`` and nothing otherwise: "Not yet" is feedback (the check's message says what is still
wrong), not marks. A notebook's mark is its tasks' marks out of its number of tasks (the tasks
of the course's exercise notebook, ``--course``, so a notebook handed in half or not at all
counts what is missing as nothing); the total is the notebooks' marks as fractions, weighted
(default: each notebook the same), scaled to ``out_of`` (default 10). Notebooks not named in
the scheme count when they are in ``grades.csv`` for some student. A scheme that does give
"Not yet" something (``--not-yet 0.5``) still gives a placeholder nothing: a "Not yet" earns
its mark only when the same notebook has at least one task ``Correct`` and its message is not
the check refusing a placeholder (zero, None, NaN or infinity), so that a notebook answering 0,
or 1, everywhere earns nothing under any scheme.

The scheme file (TOML; every key optional)::

    out_of = 10                    # the total's scale
    [marks]                        # the mark of each verdict (others earn 0)
    correct = 1
    not_yet = 0
    [notebooks.ex04_resampling]    # a notebook (its file name without .ipynb)
    weight = 2                     # its weight in the total (default 1)
    canvas_id = 12345              # its Canvas assignment's id (see below)
    title = "Exercises 4"          # its column's name in the LMS (default: its title)

Naming notebooks in ``[notebooks]`` also limits the total (and the LMS columns) to them.

**Exports** (each optional; the formats as the LMSs document their CSV gradebook import):

- ``--moodle``: Moodle's *Import grades from CSV file* ("Grade import", MoodleDocs,
  docs.moodle.org/311/en/Grade_import): a header row, then a row per student; the first column
  identifies the user (``Email address``, ``ID number`` or ``Username``, which Moodle's import
  maps with "Identify user by": useremail, useridnumber or username), then one column per
  grade item (a notebook, then ``Total``), which the import's "Grade item mappings" map to the
  course's grade items. Decimal points, UTF-8.
- ``--canvas``: Canvas's gradebook import, as The Ohio State University's CarmenCanvas guide
  "Import a CSV file to Carmen Grades" (teaching.resources.osu.edu) documents it: the student
  (name, or ID, or SIS User ID), SIS Login ID, Section, then the assignments, a new assignment
  column creating an assignment, in the layout of Canvas's own gradebook export, which that
  guide starts from: the columns ``Student``, ``ID``, ``SIS User ID``, ``SIS Login ID``,
  ``Section``, then one per assignment named ``Name (id)`` when the scheme gives the
  assignment's ``canvas_id`` (an existing assignment), else ``Name`` (Canvas then creates the
  assignment); the second row is the export's ``Points Possible``.
- ``--feedback DIR``: one Markdown file per student: each notebook's mark, and each task's
  verdict with the check's message (what is wrong, which way, the hint); never a right answer
  (the checks never print the expected value, and a ``Correct`` task's message, which quotes
  the student's own value, is left out).
- ``--marks``: a plain table (student, a column per notebook, total), for a spreadsheet.

**The roster** (``--roster roster.csv``, optional) maps the grader's student names (the
submission folders' names) to the LMS's identities: a CSV with the column ``student`` and any
of ``name`` (the name Canvas shows, "Last, First"), ``email``, ``idnumber``, ``username``
(Moodle), ``canvas_id``, ``sis_user_id``, ``sis_login_id``, ``section`` (Canvas). Without one,
the grader's names are the usernames. A student of ``grades.csv`` missing from the roster
stops the export with their names (students of the roster without a row get no marks: an
empty row, or 0 with ``--absent-zero``).

A malformed ``grades.csv`` (missing columns, an unknown verdict, a row of the wrong length, not
UTF-8), scheme or roster stops the command with a message naming the file and the line, and
exit status 2.
"""

import argparse
import csv
import math
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import nbformat
import tomllib

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
FIELDS = ("student", "notebook", "task", "verdict", "message", "file", "note")
REQUIRED = ("student", "notebook", "task", "verdict", "message")
#: the verdict classes a scheme gives marks to, and how grade.py writes each
KINDS = {"correct": "Correct", "not_yet": "Not yet", "not_attempted": "not attempted",
         "error": "error: ...", "timed_out": "timed out"}
BEGIN = "### BEGIN SOLUTION"
EXERCISE_TITLE = re.compile(r":::\{exercise\}\s*(\S+)")
ROSTER_FIELDS = ("student", "name", "email", "idnumber", "username", "canvas_id",
                 "sis_user_id", "sis_login_id", "section")
MOODLE_IDS = {"email": "Email address", "idnumber": "ID number", "username": "Username"}
CANVAS_COLUMNS = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
# A check refusing a placeholder: "`x` is zero, and it should not be.", "`x` is None: ...",
# "`x` is nan, not a finite number." (rsgeo_course.exercises.engine), in English and in the
# course's Portuguese (rsgeo_course.po), whichever language the grader ran in
PLACEHOLDER_MESSAGES = (
    r"is zero, and it should not be", r"é igual a zero, e não deveria",
    r"is None: did your function return", r"é None: a sua função devolveu",
    r"not a finite number", r"não um número finito")
PLACEHOLDER = re.compile("|".join(PLACEHOLDER_MESSAGES))
TEXTS = {
    "en": {"title": "Feedback on your exercises", "student": "Student", "total": "Total",
           "of": "of", "task": "Task", "verdict": "Verdict", "message": "What the check says",
           "absent": "not handed in", "notes": "Notes", "scheme": "Marking",
           "scheme_text": "a task earns {correct:g} when it is Correct{not_yet}; the total is "
                          "out of {out_of:g}.",
           "not_yet_text": ", {not_yet:g} when it is Not yet after a real attempt",
           "Correct": "Correct", "Not yet": "Not yet", "not attempted": "not attempted",
           "timed out": "timed out", "error": "error"},
    "pt_BR": {"title": "Retorno sobre os seus exercícios", "student": "Estudante",
              "total": "Total", "of": "de", "task": "Tarefa", "verdict": "Veredito",
              "message": "O que a verificação diz", "absent": "não entregue",
              "notes": "Observações", "scheme": "Notas",
              "scheme_text": "uma tarefa vale {correct:g} quando o veredito é Correto{not_yet}; o "
                             "total é sobre {out_of:g}.",
              "not_yet_text": ", {not_yet:g} quando é Ainda não depois de uma tentativa real",
              "Correct": "Correto", "Not yet": "Ainda não", "not attempted": "não tentada",
              "timed out": "tempo esgotado", "error": "erro"},
}


class GradebookError(ValueError):
    """A malformed input (grades, scheme, roster): the message names the file and the line."""


# -- Reading -------------------------------------------------------------------------------------

@dataclass
class Row:
    """One row of grades.csv."""

    student: str
    notebook: str
    task: str
    verdict: str
    message: str = ""
    file: str = ""
    note: str = ""
    line: int = 0


def verdict_kind(verdict):
    """The scheme's name for a verdict ("correct", "not_yet", ...), or None if unknown."""
    if verdict.startswith("error"):
        return "error"
    return {text: kind for kind, text in KINDS.items()}.get(verdict)


def read_grades(path):
    """The rows of a grades.csv that grade.py wrote.

    Parameters
    ----------
    path : path-like
        The CSV: a header with at least student, notebook, task, verdict and message.

    Returns
    -------
    list of Row

    Raises
    ------
    GradebookError
        When the file is missing, not UTF-8, empty, lacks a column, has a row of another length
        than its header, or a verdict that grade.py does not write.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise GradebookError(f"{path}: no such file (the CSV that exercises/grade.py "
                             "writes, e.g. grades.csv)") from None
    except UnicodeDecodeError as error:
        raise GradebookError(f"{path}: not UTF-8 text (byte {error.start}): is it the CSV "
                             "that exercises/grade.py writes?") from None
    reader = csv.reader(text.splitlines())
    try:
        header = next(reader)
    except StopIteration:
        raise GradebookError(f"{path} is empty: it needs a header ({', '.join(FIELDS)}) "
                             "and a row per task") from None
    header = [name.strip() for name in header]
    missing = [name for name in REQUIRED if name not in header]
    if missing:
        raise GradebookError(f"{path}, line 1: no column {', '.join(missing)} (the header is "
                             f"{', '.join(header)!r}; grade.py writes {', '.join(FIELDS)})")
    rows = []
    for line, values in enumerate(reader, start=2):
        if not values or not "".join(values).strip():
            continue
        if len(values) != len(header):
            raise GradebookError(f"{path}, line {line}: {len(values)} fields, the header has "
                                 f"{len(header)}")
        record = dict(zip(header, values))
        row = Row(**{name: record.get(name, "") for name in FIELDS}, line=line)
        if not row.student.strip():
            raise GradebookError(f"{path}, line {line}: no student")
        if verdict_kind(row.verdict) is None:
            raise GradebookError(f"{path}, line {line}: the verdict {row.verdict!r} is not one "
                                 f"grade.py writes ({', '.join(KINDS.values())})")
        rows.append(row)
    if not rows:
        raise GradebookError(f"{path} has a header but no rows: nothing was graded")
    return rows


def course_tasks(folder=HERE):
    """{notebook: (title, [task names])} of the course's exercise notebooks in ``folder``.

    A task is a solution cell (``### BEGIN SOLUTION``), named as grade.py names it: after the
    ``{exercise}`` directive before it ("2b.1"), else "task N".
    """
    found = {}
    for path in sorted(Path(folder).glob("*.ipynb")):
        notebook = nbformat.read(path, as_version=4)
        title, tasks, name = path.stem, [], None
        for cell in notebook.cells:
            if cell.cell_type == "markdown":
                heading = re.search(r"^# (.+)$", cell.source, flags=re.M)
                if heading and title == path.stem:
                    title = heading.group(1).strip()
                directive = EXERCISE_TITLE.search(cell.source)
                name = directive.group(1) if directive else name
            elif cell.cell_type == "code" and BEGIN in cell.source:
                tasks.append(name or f"task {len(tasks) + 1}")
                name = None
        if tasks:
            found[path.stem] = (title, tasks)
    return found


# -- The scheme ---------------------------------------------------------------------------------

@dataclass
class Scheme:
    """How verdicts become marks (see the module's docstring)."""

    marks: dict = field(default_factory=lambda: {"correct": 1.0})
    out_of: float = 10.0
    weights: dict = field(default_factory=dict)        # notebook -> weight
    canvas_ids: dict = field(default_factory=dict)     # notebook -> Canvas assignment id
    titles: dict = field(default_factory=dict)         # notebook -> the LMS column's name
    notebooks: list = None                             # the notebooks that count, if named

    def mark(self, kind):
        return float(self.marks.get(kind, 0.0))


def _number(value, what, where, positive=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
            value) or value < 0 or (positive and value == 0):
        need = "a positive number" if positive else "a number, 0 or more"
        raise GradebookError(f"{where}: {what} must be {need}, got {value!r}")
    return float(value)


def read_scheme(path=None, overrides=None):
    """The marking scheme: defaults, then ``path`` (TOML), then ``overrides`` (the options).

    Parameters
    ----------
    path : path-like, optional
        A scheme file (see the module's docstring).
    overrides : dict, optional
        ``marks`` (kind -> mark), ``weights`` (notebook -> weight), ``out_of``.

    Returns
    -------
    Scheme

    Raises
    ------
    GradebookError
        For a file that is not TOML, an unknown key or verdict, or a mark or weight that is
        not a number of 0 or more.
    """
    scheme = Scheme()
    if path is not None:
        where = str(path)
        try:
            data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise GradebookError(f"{where}: no such scheme file") from None
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
            raise GradebookError(f"{where}: not a TOML scheme ({error})") from None
        unknown = sorted(set(data) - {"out_of", "marks", "notebooks"})
        if unknown:
            raise GradebookError(f"{where}: unknown setting {', '.join(unknown)} (a scheme has "
                                 "out_of, [marks] and [notebooks.NAME])")
        if "out_of" in data:
            scheme.out_of = _number(data["out_of"], "out_of", where, positive=True)
        for kind, value in data.get("marks", {}).items():
            if kind not in KINDS:
                raise GradebookError(f"{where}: [marks] has {kind!r}; the verdicts are "
                                     f"{', '.join(KINDS)}")
            scheme.marks[kind] = _number(value, f"[marks] {kind}", where)
        notebooks = data.get("notebooks", {})
        if notebooks:
            scheme.notebooks = list(notebooks)
        for name, settings in notebooks.items():
            unknown = sorted(set(settings) - {"weight", "canvas_id", "title"})
            if unknown:
                raise GradebookError(f"{where}: [notebooks.{name}] has unknown "
                                     f"{', '.join(unknown)} (weight, canvas_id, title)")
            if "weight" in settings:
                scheme.weights[name] = _number(settings["weight"], f"{name}'s weight", where)
            if "canvas_id" in settings:
                scheme.canvas_ids[name] = str(settings["canvas_id"])
            if "title" in settings:
                scheme.titles[name] = str(settings["title"])
    overrides = overrides or {}
    for kind, value in (overrides.get("marks") or {}).items():
        if value is not None:
            scheme.marks[kind] = _number(value, f"the mark of {KINDS[kind]!r}", "options")
    for name, value in (overrides.get("weights") or {}).items():
        scheme.weights[name] = _number(value, f"{name}'s weight", "--weight")
    if overrides.get("out_of") is not None:
        scheme.out_of = _number(overrides["out_of"], "--out-of", "options", positive=True)
    if scheme.notebooks is not None and not sum(
            scheme.weights.get(name, 1.0) for name in scheme.notebooks):
        raise GradebookError("every notebook of the scheme weighs 0: nothing would count")
    return scheme


def parse_weight(text):
    """``NOTEBOOK=WEIGHT`` (an option's value) as (notebook, float)."""
    name, sign, value = text.partition("=")
    try:
        return name.strip(), float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not NOTEBOOK=WEIGHT, e.g. "
                                          "ex04_resampling=2") from None


# -- Marks --------------------------------------------------------------------------------------

@dataclass
class NotebookMark:
    """One student's marks on one notebook."""

    notebook: str
    title: str
    tasks: list                    # [(task, verdict, message, mark)]
    points: float                  # the tasks' marks added
    possible: float                # its tasks' number times the mark of Correct
    handed_in: bool = True
    notes: list = field(default_factory=list)

    @property
    def fraction(self):
        return self.points / self.possible if self.possible else 0.0


def task_marks(rows, scheme):
    """[(row, mark)] for one submission's rows, by the scheme, placeholders earning nothing."""
    any_correct = any(verdict_kind(row.verdict) == "correct" for row in rows)
    marked = []
    for row in rows:
        kind = verdict_kind(row.verdict)
        mark = scheme.mark(kind)
        if kind == "not_yet" and (not any_correct or PLACEHOLDER.search(row.message)):
            mark = 0.0                     # a placeholder, or no real work in the notebook
        marked.append((row, mark))
    return marked


def compute_marks(rows, scheme, course=None):
    """Every student's marks.

    Parameters
    ----------
    rows : list of Row
    scheme : Scheme
    course : dict, optional
        :func:`course_tasks`' answer (default: the course's exercise notebooks).

    Returns
    -------
    notebooks : list of str
        The notebooks that count, in order.
    marks : dict
        student -> {"notebooks": {notebook: NotebookMark}, "total": float, "other": [Row]}
        (``other``: rows of no notebook that counts, e.g. a file that was not a notebook).
    """
    course = course_tasks() if course is None else course
    seen = list(dict.fromkeys(row.notebook for row in rows if row.notebook and row.task))
    notebooks = scheme.notebooks if scheme.notebooks is not None else sorted(
        seen, key=lambda name: (name not in course, name))
    tasks_of = {}
    for name in notebooks:
        tasks = list(course.get(name, (name, []))[1])
        tasks += [row.task for row in rows if row.notebook == name and row.task
                  and row.task not in tasks]
        tasks_of[name] = list(dict.fromkeys(tasks))
    by_student = {}
    for row in rows:
        by_student.setdefault(row.student, []).append(row)
    marks = {}
    for student, own in sorted(by_student.items()):
        result = {}
        for name in notebooks:
            title = scheme.titles.get(name) or course.get(name, (name, []))[0]
            possible = len(tasks_of[name]) * scheme.mark("correct")
            submissions = {}
            for row in own:
                if row.notebook == name and row.task:
                    submissions.setdefault(row.file, []).append(row)
            best = None
            for _file, these in sorted(submissions.items()):
                marked = task_marks(these, scheme)
                by_task = {row.task: (row, mark) for row, mark in marked}
                listed = [(task, *(
                    (by_task[task][0].verdict, by_task[task][0].message, by_task[task][1])
                    if task in by_task else ("not attempted", "", 0.0)))
                    for task in tasks_of[name]]
                notes = sorted({row.note for row in these if row.note})
                candidate = NotebookMark(name, title, listed,
                                         sum(mark for *_, mark in listed), possible,
                                         notes=notes)
                if best is None or candidate.points > best.points:
                    best = candidate
            if len(submissions) > 1:
                best.notes.append(f"{len(submissions)} submissions of this notebook were "
                                  "graded; the best one counts")
            result[name] = best or NotebookMark(
                name, title, [(task, "not attempted", "", 0.0) for task in tasks_of[name]],
                0.0, possible, handed_in=False)
        weights = {name: scheme.weights.get(name, 1.0) for name in notebooks}
        weight = sum(weights.values())
        total = (scheme.out_of * sum(result[name].fraction * weights[name]
                                     for name in notebooks) / weight) if weight else 0.0
        other = [row for row in own if row.notebook not in notebooks or not row.task]
        marks[student] = {"notebooks": result, "total": total, "other": other}
    return notebooks, marks


# -- The roster and the exports -----------------------------------------------------------------

def read_roster(path):
    """{grader's student name: {field: value}} from a roster CSV (see the docstring).

    Raises
    ------
    GradebookError
        For a missing file, no ``student`` column, an unknown column, or a student twice.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise GradebookError(f"{path}: no such roster file") from None
    except UnicodeDecodeError:
        raise GradebookError(f"{path}: the roster is not UTF-8 text") from None
    reader = csv.DictReader(text.splitlines())
    header = [name.strip() for name in reader.fieldnames or []]
    if "student" not in header:
        raise GradebookError(f"{path}, line 1: the roster needs a column 'student' (the names "
                             f"grades.csv uses); it has {', '.join(header) or 'no header'}")
    unknown = [name for name in header if name not in ROSTER_FIELDS]
    if unknown:
        raise GradebookError(f"{path}, line 1: unknown column {', '.join(unknown)} (a roster "
                             f"has {', '.join(ROSTER_FIELDS)})")
    roster = {}
    for line, record in enumerate(reader, start=2):
        record = {key.strip(): (value or "").strip() for key, value in record.items() if key}
        student = record.get("student", "")
        if not student:
            raise GradebookError(f"{path}, line {line}: no student")
        if student in roster:
            raise GradebookError(f"{path}, line {line}: {student!r} is listed twice")
        roster[student] = record
    return roster


def check_roster(students, roster):
    """Raise GradebookError naming the graded students the roster does not list."""
    missing = sorted(set(students) - set(roster))
    if missing:
        raise GradebookError(f"the roster does not list {len(missing)} graded student(s): "
                             f"{', '.join(missing[:10])}; add them (column 'student')")


def _number_text(value):
    return f"{value:.2f}".rstrip("0").rstrip(".")


def item_name(notebook, scheme, course):
    """The LMS column's name of a notebook."""
    return scheme.titles.get(notebook) or course.get(notebook, (notebook, []))[0]


def everyone(marks, roster):
    """The students to export: the graded ones, then the roster's others (in its order)."""
    return sorted(marks) + [name for name in (roster or {}) if name not in marks]


def write_moodle(path, notebooks, marks, scheme, course, roster=None, identify=None,
                 absent_zero=False):
    """Moodle's grade import CSV: the user's identifier, a column per notebook, the total."""
    roster = roster or {}
    if identify is None:
        identify = next((key for key in ("email", "idnumber", "username")
                         if roster and all(entry.get(key) for entry in roster.values())),
                        "username")
    header = [MOODLE_IDS[identify]] + [item_name(name, scheme, course) for name in notebooks]
    header.append("Total")
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for student in everyone(marks, roster):
            entry = roster.get(student, {})
            ident = entry.get(identify) or (student if identify == "username" else "")
            if not ident:
                raise GradebookError(f"the roster gives {student!r} no {identify}: Moodle "
                                     f"identifies users by it (--moodle-id)")
            if student in marks:
                own = marks[student]
                values = [_number_text(own["notebooks"][name].points) for name in notebooks]
                values.append(_number_text(own["total"]))
            else:
                values = ["0" if absent_zero else ""] * (len(notebooks) + 1)
            writer.writerow([ident, *values])


def write_canvas(path, notebooks, marks, scheme, course, roster=None, absent_zero=False):
    """Canvas's gradebook import CSV (see the module's docstring)."""
    roster = roster or {}
    names = []
    for name in notebooks:
        title = item_name(name, scheme, course)
        ident = scheme.canvas_ids.get(name)
        names.append(f"{title} ({ident})" if ident else title)
    possible = [_number_text(len(course.get(name, (name, []))[1]) * scheme.mark("correct"))
                if name in course else "" for name in notebooks]
    if any(not value for value in possible):            # from the graded tasks instead
        sample = next(iter(marks.values()), None)
        possible = [value or (_number_text(sample["notebooks"][name].possible) if sample
                              else "") for name, value in zip(notebooks, possible)]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow([*CANVAS_COLUMNS, *names])
        writer.writerow(["    Points Possible", "", "", "", "", *possible])
        for student in everyone(marks, roster):
            entry = roster.get(student, {})
            identity = [entry.get("name") or student, entry.get("canvas_id", ""),
                        entry.get("sis_user_id", ""), entry.get("sis_login_id", ""),
                        entry.get("section", "")]
            if student in marks:
                values = [_number_text(marks[student]["notebooks"][name].points)
                          for name in notebooks]
            else:
                values = ["0" if absent_zero else ""] * len(notebooks)
            writer.writerow([*identity, *values])


def write_marks(path, notebooks, marks, scheme, course):
    """A plain table: student, each notebook's points, the total."""
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["student", *notebooks, f"total (of {_number_text(scheme.out_of)})"])
        for student, own in sorted(marks.items()):
            writer.writerow([student, *(_number_text(own["notebooks"][name].points)
                                        for name in notebooks), _number_text(own["total"])])


def safe_name(text):
    """A file name for a student (letters, digits, ., -, _)."""
    name = re.sub(r"[^\w.-]+", "_", text, flags=re.UNICODE).strip("._")
    return name or "student"


def _one_line(text):
    return " ".join(str(text).split()).replace("|", "\\|")


def feedback_markdown(student, own, scheme, language="en"):
    """One student's feedback (Markdown): marks, and each task's verdict and message."""
    words = TEXTS[language]
    not_yet = scheme.mark("not_yet")
    lines = [f"# {words['title']}", "", f"{words['student']}: {student}", "",
             f"**{words['total']}: {_number_text(own['total'])} {words['of']} "
             f"{_number_text(scheme.out_of)}**", "",
             f"{words['scheme']}: " + words["scheme_text"].format(
                 correct=scheme.mark("correct"), out_of=scheme.out_of,
                 not_yet=words["not_yet_text"].format(not_yet=not_yet) if not_yet else ""), ""]
    for mark in own["notebooks"].values():
        status = "" if mark.handed_in else f" ({words['absent']})"
        lines += [f"## {mark.title}{status}", "",
                  f"{_number_text(mark.points)} {words['of']} {_number_text(mark.possible)}",
                  ""]
        lines += [f"| {words['task']} | {words['verdict']} | {words['message']} |",
                  "|---|---|---|"]
        for task, verdict, message, _mark in mark.tasks:
            kind = verdict_kind(verdict)
            shown = words.get(verdict, verdict) if kind != "error" else (
                words["error"] + verdict[len("error"):])
            said = "" if kind == "correct" else _one_line(message)
            lines.append(f"| {_one_line(task)} | {_one_line(shown)} | {said} |")
        lines.append("")
        if mark.notes:
            lines += [f"{words['notes']}: " + "; ".join(_one_line(n) for n in mark.notes), ""]
    other = own["other"]
    if other:
        lines += [f"## {words['notes']}", ""]
        lines += [f"- {_one_line(row.file or row.notebook)}: {_one_line(row.verdict)} "
                  f"{_one_line(row.message)}" for row in other]
        lines.append("")
    return "\n".join(lines)


def write_feedback(folder, marks, scheme, language="en"):
    """One Markdown file per student in ``folder``; returns {student: path}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written, used = {}, set()
    for student, own in sorted(marks.items()):
        name = safe_name(student)
        stem, number = name, 2
        while name.lower() in used:
            name, number = f"{stem}-{number}", number + 1
        used.add(name.lower())
        path = folder / f"{name}.md"
        path.write_text(feedback_markdown(student, own, scheme, language) + "\n",
                        encoding="utf-8")
        written[student] = path
    return written


# -- The command --------------------------------------------------------------------------------

def main(argv=None):
    """The command line; returns the exit status (2 on a malformed input)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("grades", help="grades.csv, as exercises/grade.py writes it")
    parser.add_argument("--scheme", help="a marking scheme (TOML; see --help's first lines)")
    for kind, text in KINDS.items():
        parser.add_argument(f"--{kind.replace('_', '-')}", type=float, metavar="MARK",
                            help=f"the mark of a task {text!r} (default "
                                 f"{'1' if kind == 'correct' else '0'})")
    parser.add_argument("--weight", action="append", type=parse_weight, default=[],
                        metavar="NOTEBOOK=W", help="a notebook's weight in the total (1)")
    parser.add_argument("--out-of", type=float, help="the total's scale (10)")
    parser.add_argument("--course", default=str(HERE),
                        help="the course's exercise notebooks (their tasks; this folder)")
    parser.add_argument("--roster", help="CSV: student, and name/email/idnumber/username/"
                        "canvas_id/sis_user_id/sis_login_id/section")
    parser.add_argument("--moodle", help="write Moodle's grade import CSV here")
    parser.add_argument("--moodle-id", choices=sorted(MOODLE_IDS),
                        help="Moodle's user identifier (default: email, idnumber or username, "
                             "the first the roster gives everyone)")
    parser.add_argument("--canvas", help="write Canvas's gradebook import CSV here")
    parser.add_argument("--feedback", help="a folder: one Markdown file per student")
    parser.add_argument("--marks", help="a plain CSV of marks (student, notebooks, total)")
    parser.add_argument("--absent-zero", action="store_true",
                        help="roster students without a submission get 0, not an empty cell")
    parser.add_argument("--language", choices=sorted(TEXTS), default="en",
                        help="the feedback files' language (en)")
    options = parser.parse_args(argv)
    try:
        rows = read_grades(options.grades)
        scheme = read_scheme(options.scheme, {
            "marks": {kind: getattr(options, kind) for kind in KINDS},
            "weights": dict(options.weight), "out_of": options.out_of})
        course = course_tasks(options.course)
        roster = read_roster(options.roster) if options.roster else None
        notebooks, marks = compute_marks(rows, scheme, course)
        unknown = [name for name in scheme.weights if name not in notebooks]
        if unknown:
            raise GradebookError(f"--weight/scheme names {', '.join(unknown)}, which is not a "
                                 f"notebook that counts ({', '.join(notebooks)})")
        if roster is not None:
            check_roster(marks, roster)
        if options.moodle:
            write_moodle(options.moodle, notebooks, marks, scheme, course, roster,
                         options.moodle_id, options.absent_zero)
        if options.canvas:
            write_canvas(options.canvas, notebooks, marks, scheme, course, roster,
                         options.absent_zero)
        if options.marks:
            write_marks(options.marks, notebooks, marks, scheme, course)
        if options.feedback:
            write_feedback(options.feedback, marks, scheme, options.language)
    except GradebookError as error:
        parser.exit(2, f"gradebook.py: error: {error}\n")
    width = max(len(student) for student in marks)
    print(f"{'student':<{width}}  total (of {_number_text(scheme.out_of)})")
    for student, own in sorted(marks.items()):
        print(f"{student:<{width}}  {_number_text(own['total'])}")
    written = [name for name in (options.moodle, options.canvas, options.marks,
                                 options.feedback) if name]
    if written:
        print("written: " + ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
