"""Grade a class's exercise notebooks with the course's own checks.

    python exercises/grade.py SUBMISSIONS [--out grades.csv] [--html grades.html] [--jobs 2]
                              [--cell-timeout 60] [--notebook-timeout 600]

SUBMISSIONS holds one folder per student (with that student's ``.ipynb`` files, at any depth)
or one ``.ipynb`` per student (the student is the file's name). Each notebook is matched to the
course's exercise notebook (``exercises/*.ipynb``) by its file name, else by its content.

A *task* is a solution cell of the course's notebook (one with ``### BEGIN SOLUTION``) and the
check cells that follow it (cells that call ``check_...``). For each submission the grader

1. starts a fresh kernel (over IPC sockets, in an empty temporary folder) and captures the genuine
   ``rsgeo.exercises`` checks before any student code runs;
2. runs the student's code cells in order, each with a time limit (``--cell-timeout``) inside a
   time limit for the whole notebook (``--notebook-timeout``); an error does not stop the run, a
   cell that runs too long is interrupted. The student's own check cells (those identical to the
   course's) are skipped;
3. runs the *course's* check source of each task, with the genuine checks, as soon as the
   student's cells for that task have run (before the next cell the course has after the task's
   checks). A student who deletes, edits or redefines a check cannot change the grade.

Each task gets one verdict: ``Correct``, ``Not yet`` (with the check's message and hint),
``not attempted`` (the answer is still ``...``), ``error: <exception>`` or ``timed out``. The
grader writes a CSV (student, notebook, task, verdict, message) and an HTML summary (one table
per notebook: students by tasks, coloured), never stops on a bad submission (a file that is not a
notebook is one row with an ``error: ...`` verdict), and prints a progress bar on standard error.

Security: the grader stops honest mistakes and casual tampering (a redefined check), not a student
determined to attack the machine that grades; run untrusted submissions in a container.
"""

import argparse
import asyncio
import concurrent.futures
import csv
import difflib
import html
import json
import re
import secrets
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import nbformat
from nbclient import NotebookClient

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT / "book" / "_ext"))
from make_student_edition import BEGIN, strip_solutions  # noqa: E402

from offline_book import IPCKernelManager  # noqa: E402

COURSE = HERE
VERDICTS = ("Correct", "Not yet", "not attempted", "error", "timed out")
CHECK_CALL = re.compile(r"^\s*check_\w+\(", flags=re.M)
EXERCISE_TITLE = re.compile(r":::\{exercise\}\s*(\S+)")
FIELDS = ("student", "notebook", "task", "verdict", "message")


# -- The course's tasks ------------------------------------------------------

@dataclass
class Task:
    """One task of a course notebook: its solution cell and the check cells after it."""

    name: str
    solution: int                      # index of the solution cell among the code cells
    checks: list = field(default_factory=list)      # indices of its check cells
    check_source: str = ""


@dataclass
class Course:
    """A course exercise notebook: the keys its code cells are matched by, and its tasks."""

    path: Path
    keys: list
    tasks: list


def _normal(source):
    """A cell's source without trailing spaces and blank lines: what matching compares."""
    return "\n".join(line.rstrip() for line in source.strip().splitlines())


def read_course(path):
    """The tasks of one course notebook.

    Parameters
    ----------
    path : path-like
        An exercise notebook with worked solutions (``### BEGIN SOLUTION`` blocks).

    Returns
    -------
    Course
        ``keys``: each code cell's source as a student receives it (solutions stripped);
        ``tasks``: one :class:`Task` per solution cell, named after the ``{exercise}`` directive
        before it ("1.2"), else "task N".

    Raises
    ------
    ValueError
        If the notebook has no solution cell, or a task has no check cell after it.
    """
    notebook = nbformat.read(path, as_version=4)
    keys, tasks, title = [], [], None
    for cell in notebook.cells:
        if cell.cell_type == "markdown":
            found = EXERCISE_TITLE.search(cell.source)
            title = found.group(1) if found else title
            continue
        if cell.cell_type != "code":
            continue
        index = len(keys)
        if BEGIN in cell.source:
            keys.append(_normal(strip_solutions(cell.source)))
            tasks.append(Task(title or f"task {len(tasks) + 1}", index))
            title = None
        else:
            keys.append(_normal(cell.source))
            if tasks and CHECK_CALL.search(cell.source) and all(
                    index > task.solution for task in tasks):
                last = tasks[-1]
                if not last.checks or last.checks[-1] == index - 1:
                    last.checks.append(index)
                    last.check_source += cell.source.strip() + "\n"
    if not tasks:
        raise ValueError(f"{path} has no {BEGIN} cell: it is not a course exercise notebook")
    for task in tasks:
        if not task.checks:
            raise ValueError(f"{path}: task {task.name} has no check cell after its solution")
    return Course(Path(path), keys, tasks)


def course_notebooks(folder=COURSE):
    """Every exercise notebook of the course in ``folder``, read with :func:`read_course`."""
    return [read_course(path) for path in sorted(Path(folder).glob("*.ipynb"))]


def match_course(path, sources, courses):
    """The course notebook a submission answers: by file name, else by the content of its cells.

    Returns None when no course notebook shares enough cells with it.
    """
    stem = Path(path).stem.lower()
    named = [course for course in courses if stem.startswith(course.path.stem.lower())]
    if named:
        return max(named, key=lambda course: len(course.path.stem))
    scores = [(difflib.SequenceMatcher(None, course.keys, sources, autojunk=False).ratio(), i)
              for i, course in enumerate(courses)]
    score, best = max(scores, default=(0.0, None))
    return courses[best] if score >= 0.3 else None


def plan(course, sources):
    """What to run: the student's cells in order, with each task's check after its cells.

    Student cells are aligned with the course's code cells (``difflib`` on their sources): cells
    equal to a course check cell are skipped. Each task's course check runs where the student's
    copy of its (last) check cell is; if that was deleted or edited, before the first student
    cell aligned with a course cell after it, or at the end.

    Returns
    -------
    list of (kind, value)
        ``("cell", student index)`` or ``("check", Task)``.
    """
    matcher = difflib.SequenceMatcher(None, course.keys, sources, autojunk=False)
    aligned = {}
    for block in matcher.get_matching_blocks():
        for offset in range(block.size):
            aligned[block.b + offset] = block.a + offset
    check_keys = {course.keys[index] for task in course.tasks for index in task.checks}
    steps, pending = [], list(course.tasks)
    for index, source in enumerate(sources):
        position = aligned.get(index)
        if position is not None:
            while pending and position > pending[0].checks[-1]:
                steps.append(("check", pending.pop(0)))
        if source and source not in check_keys:
            steps.append(("cell", index))
        if pending and position == pending[0].checks[-1]:     # the student's copy of the check
            steps.append(("check", pending.pop(0)))
    steps += [("check", task) for task in pending]
    return steps


# -- Running a submission ------------------------------------------------------

PREAMBLE = '''
def {name}():
    import ast, json
    import rsgeo.exercises as exercises
    checks = {{name: getattr(exercises, name) for name in exercises.__all__}}
    verdict_type, not_solved = exercises.Verdict, exercises.ExerciseNotSolved

    def grade(source, namespace):
        tree = ast.parse(source)
        last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
        scope = dict(namespace)
        scope.update(checks)
        try:
            exec(compile(tree, "<course check>", "exec"), scope)
            value = None if last is None else eval(
                compile(ast.Expression(last.value), "<course check>", "eval"), scope)
            if isinstance(value, verdict_type):
                result = ["Correct" if value.ok else "Not yet", value.message,
                          "" if value.ok else value.hint]
            else:
                result = ["error: the check gave no verdict", repr(value)[:200], ""]
        except not_solved as error:
            result = ["not attempted", str(error), ""]
        except Exception as error:
            result = [f"error: {{type(error).__name__}}", str(error)[:500], ""]
        print("{token}" + json.dumps(result))
    return grade
{name} = {name}()
'''


@dataclass
class Row:
    """One line of the grades: a task's verdict for one student's notebook."""

    student: str
    notebook: str
    task: str
    verdict: str
    message: str = ""


def _error_text(reply_content):
    return f"{reply_content.get('ename', 'Error')}: {reply_content.get('evalue', '')}"[:500]


async def _run(notebook, course, cell_timeout, notebook_timeout, student, name):
    token = "RSGEO-GRADE-" + secrets.token_hex(8) + "="
    grader = "_rsgeo_grader_" + secrets.token_hex(6)
    sources = [_normal(cell.source) for cell in notebook.cells if cell.cell_type == "code"]
    code_cells = [cell for cell in notebook.cells if cell.cell_type == "code"]
    steps = plan(course, sources)
    folder = tempfile.mkdtemp(prefix="rsgeo-grade-")
    runner = nbformat.v4.new_notebook()
    client = NotebookClient(runner, km=IPCKernelManager(kernel_name="python3"),
                            kernel_name="python3", timeout=cell_timeout, allow_errors=True,
                            interrupt_on_timeout=True, error_on_timeout={
                                "ename": "TimedOut", "evalue": "the cell ran too long"},
                            resources={"metadata": {"path": folder}})
    errors = []
    client.on_cell_error = lambda cell, cell_index, execute_reply: errors.append(
        execute_reply["content"])
    rows, deadline = [], time.monotonic() + notebook_timeout
    cell_errors = {}                 # task name -> the first error or timeout in its cells
    try:
        async with client.async_setup_kernel():
            async def execute(source):
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return {"ename": "TimedOut", "evalue": "the notebook's time is up"}, ""
                client.timeout = max(1, int(min(cell_timeout, remaining)))
                cell = nbformat.v4.new_code_cell(source)
                runner.cells.append(cell)
                errors.clear()
                await client.async_execute_cell(cell, len(runner.cells) - 1)
                stdout = "".join(output.get("text", "") for output in cell.outputs
                                 if output.get("name") == "stdout")
                return (errors[0] if errors else None), stdout

            await execute(PREAMBLE.format(name=grader, token=token))
            task = course.tasks[0]             # the task whose cells are running
            for kind, value in steps:
                if kind == "cell":
                    failed, _ = await execute(code_cells[value].source)
                    if failed and task is not None:
                        cell_errors.setdefault(task.name, failed)
                    continue
                failed = cell_errors.get(value.name, {})
                if failed.get("ename") == "TimedOut":
                    rows.append(Row(student, name, value.name, "timed out", failed["evalue"]))
                else:
                    result = await execute(f"{grader}({value.check_source!r}, globals())")
                    row = _verdict_row(result, token, student, name, value.name)
                    if failed and row.verdict == "not attempted":   # the answer's cell raised
                        row.verdict, row.message = f"error: {failed.get('ename')}", _error_text(
                            failed)
                    rows.append(row)
                following = course.tasks.index(value) + 1
                task = course.tasks[following] if following < len(course.tasks) else None
    except Exception as error:                             # noqa: BLE001 - a dead kernel, etc.
        done = {row.task for row in rows}
        rows += [Row(student, name, task.name, f"error: {type(error).__name__}", str(error)[:500])
                 for task in course.tasks if task.name not in done]
    finally:
        if client.km is not None and await client.km.is_alive():
            await client.km.shutdown_kernel(now=True)
        shutil.rmtree(folder, ignore_errors=True)
    return rows


def _verdict_row(result, token, student, name, task):
    failed, stdout = result
    if failed:
        if failed.get("ename") == "TimedOut":
            return Row(student, name, task, "timed out", failed.get("evalue", ""))
        return Row(student, name, task, "error: the check did not run", _error_text(failed))
    lines = [line for line in stdout.splitlines() if line.startswith(token)]
    if not lines:
        return Row(student, name, task, "error: the check gave no verdict", "")
    verdict, message, hint = json.loads(lines[-1][len(token):])
    return Row(student, name, task, verdict, message + (f" Hint: {hint}" if hint else ""))


def grade_notebook(path, student, courses, cell_timeout=60, notebook_timeout=600):
    """Grade one submitted notebook; never raises for a bad submission.

    Parameters
    ----------
    path : path-like
        The submitted file.
    student : str
        The student's name, as it appears in the grades.
    courses : list of Course
        The course's exercise notebooks (:func:`course_notebooks`).
    cell_timeout, notebook_timeout : float
        Seconds one cell, and the whole notebook, may run.

    Returns
    -------
    list of Row
        One row per task of the matched course notebook, or one ``error: ...`` row (task "")
        for a file that is not a notebook or answers none of the course's.

    Raises
    ------
    ValueError
        If a time limit is not positive.
    """
    if not (cell_timeout > 0 and notebook_timeout > 0):
        raise ValueError(f"time limits must be positive seconds, got cell {cell_timeout}, "
                         f"notebook {notebook_timeout}")
    name = Path(path).name
    try:
        notebook = nbformat.read(path, as_version=4)
        sources = [_normal(cell.source) for cell in notebook.cells if cell.cell_type == "code"]
    except Exception as error:                             # noqa: BLE001 - any unreadable file
        return [Row(student, name, "", "error: not a notebook",
                    f"{type(error).__name__}: {str(error)[:300]}")]
    course = match_course(path, sources, courses)
    if course is None:
        return [Row(student, name, "", "error: not a course exercise notebook",
                    "its cells match none of the course's exercise notebooks")]
    name = course.path.name
    try:
        return asyncio.run(_run(notebook, course, cell_timeout, notebook_timeout, student, name))
    except Exception as error:                             # noqa: BLE001 - never stop the class
        return [Row(student, name, task.name, f"error: {type(error).__name__}", str(error)[:500])
                for task in course.tasks]


def submissions(folder):
    """(student, path) for every submission under ``folder``, sorted.

    A sub-folder is a student (all its ``.ipynb`` files, at any depth, checkpoints excluded;
    an empty one gives a "no notebook" row); a file at the top is a student named after its
    stem. Hidden files are skipped.

    Raises
    ------
    ValueError
        If ``folder`` is not a folder.
    """
    folder = Path(folder)
    if not folder.is_dir():
        raise ValueError(f"{folder} is not a folder: SUBMISSIONS must be a folder holding one "
                         "folder or one .ipynb per student")
    found = []
    for entry in sorted(folder.iterdir()):
        if entry.name.startswith("."):
            continue
        if entry.is_dir():
            notebooks = sorted(path for path in entry.rglob("*.ipynb")
                               if ".ipynb_checkpoints" not in path.parts)
            found += [(entry.name, path) for path in notebooks] or [(entry.name, None)]
        else:
            found.append((entry.stem, entry))
    return found


def _grade_one(job):
    student, path, cell_timeout, notebook_timeout, course_folder = job
    if path is None:
        return [Row(student, "", "", "error: no notebook", "the folder holds no .ipynb file")]
    return grade_notebook(path, student, course_notebooks(course_folder), cell_timeout,
                          notebook_timeout)


def progress(done, total, label, stream=sys.stderr, width=30):
    """Draw a plain-text progress bar on ``stream`` (standard error)."""
    filled = int(width * done / total) if total else width
    stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {label[:40]:<40}")
    if done == total:
        stream.write("\n")
    stream.flush()


def grade(folder, jobs=1, cell_timeout=60, notebook_timeout=600, course_folder=COURSE,
          show_progress=True):
    """Grade every submission under ``folder``.

    Parameters
    ----------
    folder : path-like
        SUBMISSIONS: one folder or one ``.ipynb`` per student.
    jobs : int
        Notebooks graded at once (each in its own process and kernel).
    cell_timeout, notebook_timeout : float
        Seconds one cell, and one whole notebook, may run.
    course_folder : path-like
        The course's exercise notebooks, with solutions (default: this folder).
    show_progress : bool
        Draw a progress bar on standard error.

    Returns
    -------
    list of Row

    Raises
    ------
    ValueError
        If ``folder`` is not a folder, ``jobs`` is not a positive integer, or the course folder
        holds no exercise notebook.
    """
    if int(jobs) != jobs or jobs < 1:
        raise ValueError(f"jobs must be a positive integer, got {jobs!r}")
    if not course_notebooks(course_folder):
        raise ValueError(f"{course_folder} holds no course exercise notebook")
    work = [(student, path, cell_timeout, notebook_timeout, str(course_folder))
            for student, path in submissions(folder)]
    rows, total = [], len(work)
    if show_progress:
        progress(0, total, "starting")
    with concurrent.futures.ProcessPoolExecutor(max_workers=int(jobs)) as pool:
        futures = {pool.submit(_grade_one, job): job for job in work}
        for done, future in enumerate(concurrent.futures.as_completed(futures), start=1):
            student, path = futures[future][:2]
            try:
                rows += future.result()
            except Exception as error:                     # noqa: BLE001 - a crashed worker
                rows.append(Row(student, Path(path).name if path else "", "",
                                f"error: {type(error).__name__}", str(error)[:500]))
            if show_progress:
                progress(done, total, f"{student}/{Path(path).name if path else ''}")
    return sorted(rows, key=lambda row: (row.student, row.notebook))     # tasks stay in order


def write_csv(rows, path):
    """Write the grades as CSV with the columns student, notebook, task, verdict, message."""
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow(FIELDS)
        for row in rows:
            writer.writerow([getattr(row, name) for name in FIELDS])


COLOURS = {"Correct": "#c9f0d1", "Not yet": "#ffe3b3", "not attempted": "#e6e6e6",
           "timed out": "#f5c6c6", "error": "#f5c6c6"}


def write_html(rows, path):
    """Write an HTML summary: per notebook, a table of students by tasks, coloured by verdict."""
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Grades</title><style>"
             "body{font-family:sans-serif}td,th{border:1px solid #999;padding:3px 8px}"
             "table{border-collapse:collapse;margin-bottom:2em}</style></head><body>",
             "<h1>Grades</h1><p>Hover a cell for the check's message.</p>"]
    problems = [row for row in rows if not row.task]
    if problems:
        parts.append("<h2>Submissions that could not be graded</h2><table><tr><th>student</th>"
                     "<th>file</th><th>verdict</th><th>message</th></tr>")
        parts += [f"<tr><td>{html.escape(row.student)}</td><td>{html.escape(row.notebook)}</td>"
                  f"<td style='background:{COLOURS['error']}'>{html.escape(row.verdict)}</td>"
                  f"<td>{html.escape(row.message)}</td></tr>" for row in problems]
        parts.append("</table>")
    graded = [row for row in rows if row.task]
    for notebook in sorted({row.notebook for row in graded}):
        these = [row for row in graded if row.notebook == notebook]
        tasks = list(dict.fromkeys(row.task for row in these))
        parts.append(f"<h2>{html.escape(notebook or '(no notebook)')}</h2><table><tr>"
                     "<th>student</th>" + "".join(f"<th>{html.escape(task or '-')}</th>"
                                                  for task in tasks) + "<th>correct</th></tr>")
        for student in sorted({row.student for row in these}):
            cells = {row.task: row for row in these if row.student == student}
            correct = sum(row.verdict == "Correct" for row in cells.values())
            parts.append(f"<tr><td>{html.escape(student)}</td>")
            for task in tasks:
                row = cells.get(task)
                if row is None:
                    parts.append("<td></td>")
                    continue
                colour = COLOURS.get(row.verdict.split(":")[0], "#ffffff")
                parts.append(f"<td style='background:{colour}' title='{html.escape(row.message)}'>"
                             f"{html.escape(row.verdict)}</td>")
            parts.append(f"<td>{correct}/{len(tasks)}</td></tr>")
        parts.append("</table>")
    parts.append("</body></html>")
    Path(path).write_text("\n".join(parts), encoding="utf-8")


def main(argv=None):
    """The command line; returns the exit status (0 even when students' answers are wrong)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("submissions", help="a folder: one folder or one .ipynb per student")
    parser.add_argument("--out", default="grades.csv", help="the CSV to write (grades.csv)")
    parser.add_argument("--html", help="the HTML summary (default: --out with .html)")
    parser.add_argument("--jobs", type=int, default=1, help="notebooks graded at once (1)")
    parser.add_argument("--cell-timeout", type=float, default=60, help="seconds per cell (60)")
    parser.add_argument("--notebook-timeout", type=float, default=600,
                        help="seconds per notebook (600)")
    parser.add_argument("--course", default=str(COURSE),
                        help="the course's exercise notebooks, with solutions (this folder)")
    options = parser.parse_args(argv)
    try:
        rows = grade(options.submissions, options.jobs, options.cell_timeout,
                     options.notebook_timeout, options.course)
    except ValueError as error:
        parser.error(str(error))
    write_csv(rows, options.out)
    summary = options.html or str(Path(options.out).with_suffix(".html"))
    write_html(rows, summary)
    counts = {verdict: sum(row.verdict.startswith(verdict) for row in rows)
              for verdict in VERDICTS}
    print(f"{len(rows)} verdicts ({', '.join(f'{n} {v}' for v, n in counts.items())}) "
          f"in {options.out} and {summary}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
