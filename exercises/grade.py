"""Grade a class's exercise notebooks with the course's own checks, out of the students' reach.

    python exercises/grade.py SUBMISSIONS [--out grades.csv] [--html grades.html] [--jobs 2]
                              [--cell-timeout 60] [--notebook-timeout 600] [--memory-mb 3072]
                              [--unsafe]

SUBMISSIONS holds one folder per student (with that student's ``.ipynb`` files, at any depth)
or one ``.ipynb`` per student (the student is the file's name). Each notebook is matched to the
course's exercise notebook (``exercises/*.ipynb``) by its content (its cells), else by its file
name; a notebook saved under another exercise's name is graded as the exercise it holds and
flagged in the ``note`` column ("saved as ex04_resampling.ipynb, graded as ex02b_datums"). A
symbolic link is refused (it could point at the solutions).

A *task* is a solution cell of the course's notebook (one with ``### BEGIN SOLUTION``), its
answers (the names the student edition sets to ``...``) and the check cells that follow it
(cells that call ``check_...``). For each submission the grader

1. starts a fresh kernel in bubblewrap (sandbox.py): its own process tree (PID namespace, gone
   with the kernel), no network, the whole system read-only except its own scratch folder, the
   course's repository, the submissions, ``/tmp``, ``/run`` and the home folder hidden except
   what the kernel needs (Python, rsgeo and rsgeo_course read-only, the notebook itself), and a
   memory limit (``--memory-mb``). Without ``bwrap`` it refuses to grade, unless told
   ``--unsafe``: then an audit hook stands in, which is no security boundary, and every row's
   ``note`` says so. Before the first submission it starts one such kernel to check the sandbox
   works, and stops with exit status 3 and the reason (bubblewrap's own message) if it does not;
2. runs the student's code cells in order, each with a time limit (``--cell-timeout``) inside a
   time limit for the whole notebook (``--notebook-timeout``); an error does not stop the run, a
   cell that runs too long is interrupted. A kernel that dies, or a cell that does not stop when
   interrupted, costs only its task: a fresh kernel runs the cells before it again (not it) and
   the next tasks are graded. The student's own check cells are skipped;
3. after each task's cells, reads the task's answers out of the kernel as JSON (numbers, text,
   small arrays) through a reader installed before any student code (judge.py: its result comes
   back in the execute reply, which no print or hook reaches, and a variable named ``list`` or
   ``type`` does not disturb it), and judges them *in the grader's process*: the course's check
   cell runs there with the genuine checks and the course's own inputs (the course notebook run
   with its worked solutions). Nothing a student's code does in its kernel reaches a verdict.

Each task gets one verdict: ``Correct``, ``Not yet`` (with the check's message and hint),
``not attempted`` (the answer is still ``...``), ``error: <exception>`` (the student's own cell's
error, e.g. ``error: SyntaxError``, not what follows from it; ``error: DeadKernelError`` when
the kernel died in the task) or ``timed out``. A numeric answer
is judged by one tolerance rule (judge.py): the check's, with a float32 read as the decimal it
prints as, or the right answer rounded to 2 decimals in the task's unit (within 1 %).

The grader writes a CSV (student, notebook, task, verdict, message, file, note), a row per task
as soon as each notebook is graded (flushed; the file is rewritten sorted at the end), then an
HTML summary (one table per notebook: students by tasks, coloured). ``file`` is the submitted
file's path under SUBMISSIONS as the student named it (bytes that are not UTF-8 written as
``\\xe9``). It never stops on a bad submission (a file that is not a notebook is one row with an
``error: ...`` verdict), and prints a progress bar on standard error.
"""

import argparse
import asyncio
import concurrent.futures
import csv
import difflib
import html
import os
import re
import shutil
import site
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
import judge  # noqa: E402
import sandbox  # noqa: E402
from make_student_edition import BEGIN, strip_solutions  # noqa: E402

COURSE = HERE
VERDICTS = ("Correct", "Not yet", "not attempted", "error", "timed out")
CHECK_CALL = re.compile(r"^\s*check_\w+\(", flags=re.M)
EXERCISE_TITLE = re.compile(r":::\{exercise\}\s*(\S+)")
FIELDS = ("student", "notebook", "task", "verdict", "message", "file", "note")
CONTENT_MATCH = 0.3          # the share of a course notebook's cells a submission must share
MAX_RESTARTS = 3             # fresh kernels a notebook may need after one died or hung
KERNEL_FAILED = "error: the grader could not start a kernel"
NO_BWRAP = ("bubblewrap (bwrap) is not installed, and the grader runs no student's code without "
            "its sandbox: install it (Debian and Ubuntu: apt install bubblewrap), or pass "
            "--unsafe to grade anyway (every row's note will say so)")
UNSAFE_NOTE = ("UNSAFE: graded without bubblewrap (--unsafe): the notebook's code could read "
               "the solutions and the other submissions, write into the course and outlive its "
               "kernel; a memory limit, a scratch folder and an audit hook were all that stood "
               "in its way")
DEAD = {"dead": "the kernel died while running this cell (os._exit, a crash or the memory "
                "limit); a fresh kernel ran the cells before it again, without it",
        "hung": "the cell ran too long and did not stop when interrupted (or its reply was "
                "over 64 MiB); a fresh kernel ran the cells before it again, without it",
        "timeout": "the cell ran too long and was interrupted"}


def printable(text):
    """``text`` with what cannot be written as UTF-8 escaped readably.

    A folder name from a zip made on another system is Latin-1 bytes, which Python on Linux
    decodes with surrogate escapes (``os.fsdecode``); written as ``\\xe9`` it stays readable and
    never stops a CSV or an HTML page.

    >>> printable("Jos\\udce9_Silva")
    'Jos\\\\xe9_Silva'
    """
    return str(text).encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")


# -- The course's tasks ------------------------------------------------------

@dataclass
class Task:
    """One task of a course notebook: its solution cell, its answers and its check cells."""

    name: str
    solution: int                      # index of the solution cell among the code cells
    answers: list = field(default_factory=list)     # the names the student edition sets to ...
    checks: list = field(default_factory=list)      # indices of its check cells
    check_source: str = ""


@dataclass
class Course:
    """A course exercise notebook: its code cells (with solutions), the keys its cells are
    matched by (as students receive them), and its tasks."""

    path: Path
    keys: list
    tasks: list
    cells: list = field(default_factory=list)


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
        ``cells``: the code cells' sources with solutions (what the judge runs);
        ``tasks``: one :class:`Task` per solution cell, named after the ``{exercise}`` directive
        before it ("1.2"), else "task N".

    Raises
    ------
    ValueError
        If the notebook has no solution cell, or a task has no check cell after it.
    """
    notebook = nbformat.read(path, as_version=4)
    keys, cells, tasks, title = [], [], [], None
    for cell in notebook.cells:
        if cell.cell_type == "markdown":
            found = EXERCISE_TITLE.search(cell.source)
            title = found.group(1) if found else title
            continue
        if cell.cell_type != "code":
            continue
        index = len(keys)
        cells.append(cell.source)
        if BEGIN in cell.source:
            student = strip_solutions(cell.source)
            keys.append(_normal(student))
            tasks.append(Task(title or f"task {len(tasks) + 1}", index,
                              judge.answer_names(student)))
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
        if not task.answers:
            raise ValueError(f"{path}: task {task.name} sets no answer to ... for students")
    return Course(Path(path), keys, tasks, cells)


def course_notebooks(folder=COURSE):
    """Every exercise notebook of the course in ``folder``, read with :func:`read_course`."""
    return [read_course(path) for path in sorted(Path(folder).glob("*.ipynb"))]


def match_course(path, sources, courses):
    """The course notebook a submission answers: by its content first, else by its file name.

    Returns
    -------
    (Course or None, str)
        The course notebook (None when neither content nor name matches one) and a note for the
        grades when the file's name names another exercise ("saved as ex04_resampling.ipynb,
        graded as ex02b_datums"), else "".
    """
    name = Path(path).name
    stem = name.lower()
    named = [course for course in courses if stem.startswith(course.path.stem.lower())]
    by_name = max(named, key=lambda course: len(course.path.stem)) if named else None
    scores = [(difflib.SequenceMatcher(None, course.keys, sources, autojunk=False).ratio(), i)
              for i, course in enumerate(courses)]
    score, best = max(scores, default=(0.0, None))
    by_content = courses[best] if score >= CONTENT_MATCH else None
    if by_content is None:
        return by_name, ""
    if by_name is not None and by_name is not by_content:
        return by_content, (f"saved as {printable(name)}, graded as {by_content.path.stem}: "
                            "its cells are that exercise's")
    return by_content, ""


def plan(course, sources):
    """What to run: the student's cells in order, with each task's check after its cells.

    Student cells are aligned with the course's code cells (``difflib`` on their sources): cells
    equal to a course check cell are skipped. Each task is judged where the student's copy of
    its (last) check cell is; if that was deleted or edited, before the first student cell
    aligned with a course cell after it, or at the end.

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


# The exercise checks must compute the right answer to give feedback in the student's own
# kernel, so the student edition holds them: a task's cells that reach into a check's internals
# (its declaration, the task object and its ``right`` answer, the check modules themselves, a
# check function's closure or globals) are not the student's computation. A screen of the
# source, not a proof: code that builds these names from pieces gets past it.
CHECKER_INTERNALS = re.compile(
    r"\.task\s*\(|\bdeclarations?\s*\(|\.declaration\b|\brecognised_mistakes\b"
    r"|\bDeclaration\b|\bMistake\s*\(|rsgeo_course\.exercises\.(?:engine|ex\d)"
    r"|\bfrom\s+\.?engine\s+import|__(?:globals|closure|wrapped|code|defaults)__")

USES_INTERNALS = ("this task's cells reach into the exercise check's internals ({found}): the "
                  "grade needs your own computation, with the chapter's method")


def internals_used(steps, sources):
    """{task name: the first checker internal its cells use}, from :func:`plan`'s steps.

    A task's cells are the student's cells run after the previous task's check and up to its
    own.
    """
    found, cells = {}, []
    for kind, value in steps:
        if kind == "cell":
            cells.append(sources[value])
            continue
        for source in cells:
            match = CHECKER_INTERNALS.search(source)
            if match:
                found[value.name] = match.group(0).strip()
                break
        cells = []
    return found


def refuse_internals(rows, internals):
    """``rows`` with every judged task in ``internals`` (:func:`internals_used`) "Not yet"."""
    for row in rows:
        if row.task in internals and row.verdict in ("Correct", "Not yet"):
            row.verdict = "Not yet"
            row.message = USES_INTERNALS.format(found=internals[row.task])
    return rows


# -- Running a submission ------------------------------------------------------

@dataclass
class Row:
    """One line of the grades: a task's verdict for one student's notebook."""

    student: str
    notebook: str
    task: str
    verdict: str
    message: str = ""
    file: str = ""              # the submitted file, as the student named it (escaped)
    note: str = ""              # a misfiled notebook, a missing sandbox


Fence = sandbox.Fence


def make_fence(folder, course_folder=COURSE, outputs=(), memory=sandbox.DEFAULT_MEMORY,
               unsafe=False, private=""):
    """What the kernels grading the class in ``folder`` may see, change and take.

    Parameters
    ----------
    folder : path-like
        SUBMISSIONS (kept secret: a kernel sees only the notebook it grades).
    course_folder : path-like
        The course's exercise notebooks, with solutions (secret).
    outputs : iterable of path-like
        The grader's output files (shown empty; their folders hidden).
    memory : int
        Bytes of address space per kernel.
    unsafe : bool
        Allow grading without bubblewrap (an audit hook instead) where it is not installed.
    private : str
        The grader's folder for the kernels' scratch folders.

    Returns
    -------
    sandbox.Fence
    """
    outputs = [Path(out).resolve() for out in outputs]
    secret = [Path(course_folder).resolve(), HERE, ROOT / "_build", ROOT / ".git",
              Path(folder).resolve()]
    hidden = [ROOT, *sandbox.private_places(), *(out.parent for out in outputs)]
    protected = [ROOT, sys.prefix, sys.base_prefix, *site.getsitepackages(),
                 *(out.parent for out in outputs)]
    return sandbox.Fence(memory=int(memory), hidden=sorted({str(path) for path in hidden}),
                         secret=sorted({str(path) for path in secret}),
                         readable=sandbox.needed_paths(),
                         blanked=[str(out) for out in outputs], folder=str(private),
                         unsafe=bool(unsafe) and sandbox.bwrap_path() is None,
                         protected=sorted({str(path) for path in protected}))


def _error_text(reply_content):
    return f"{reply_content.get('ename', 'Error')}: {reply_content.get('evalue', '')}"[:500]


def _task_row(task, found, failed, scope):
    """[verdict, message] for one task from the answers read out of the kernel.

    ``found``: name -> encoded answer (None when they could not be read); ``failed``: the first
    error of the task's own cells (a reply's content), reported instead of what follows from it.
    """
    if failed and failed.get("ename") == "TimedOut":
        return ["timed out", failed.get("evalue", "")]
    if found is None:
        if failed:
            return [f"error: {failed.get('ename')}", _error_text(failed)]
        return ["error: the answers could not be read", "the kernel's reader gave none"]
    answers, missing = {}, []
    for name in task.answers:
        try:
            answers[name] = judge.decode(found.get(name, {"t": "missing"}))
        except KeyError:
            missing.append(name)
        except (ValueError, TypeError, IndexError):      # a malformed (tampered) report
            return ["error: the answers could not be read", f"`{name}` came back malformed"]
    if missing:
        if failed:
            return [f"error: {failed.get('ename')}", _error_text(failed)]
        return ["error: NameError", f"`{missing[0]}` is not defined: the cell that sets it is "
                "missing or was not run"]
    if scope is None:
        return ["error: the course notebook did not run", "see the grader's note"]
    verdict, message, hint = judge.judge(task, scope, answers)
    if failed and verdict in ("not attempted", "Not yet") or (
            failed and verdict.startswith("error")):
        if verdict == "Not yet":
            return [verdict, f"{message} (your cell raised {_error_text(failed)})"
                    + (f" Hint: {hint}" if hint else "")]
        return [f"error: {failed.get('ename')}", _error_text(failed)]
    return [verdict, message + (f" Hint: {hint}" if hint else "")]


class _KernelLost(Exception):
    """The notebook's kernels died or hung more often than :data:`MAX_RESTARTS`."""


def _failure(reply):
    """What a cell's :class:`sandbox.Reply` says went wrong (None when it ran), as an error
    reply's content: ``ename`` and ``evalue``."""
    if reply.status == "ok":
        return None
    if reply.status == "error" or reply.content.get("ename") == "TimedOut":
        return reply.content
    return {"ename": "DeadKernelError" if reply.status == "dead" else "TimedOut",
            "evalue": DEAD[reply.status]}


async def _run(notebook, course, cell_timeout, notebook_timeout, student, name, fence,
               path=None):
    code_cells = [cell.source for cell in notebook.cells if cell.cell_type == "code"]
    steps = plan(course, [_normal(source) for source in code_cells])
    try:
        scopes, course_failure = judge.course_scopes(course), None
    except Exception as error:                             # noqa: BLE001 - the course is broken
        scopes, course_failure = {}, f"{type(error).__name__}: {str(error)[:300]}"
    reader = judge.reader_name()
    kernel = sandbox.StudentKernel(fence, notebook=str(path) if path else None,
                                   exec_lines=[judge.reader_install(reader)])
    deadline = time.monotonic() + notebook_timeout
    rows, cell_errors, ran, restarts = [], {}, [], 0

    async def execute(source, **options):
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            return sandbox.Reply("timeout", {"ename": "TimedOut",
                                             "evalue": "the notebook's time is up"})
        return await kernel.execute(source, min(cell_timeout, remaining), **options)

    async def recover():
        """A fresh kernel, in which the cells that ran so far run again (not those that
        killed or hung a kernel, nor those interrupted)."""
        nonlocal restarts
        while True:
            restarts += 1
            if restarts > MAX_RESTARTS:
                raise _KernelLost(f"its kernel died or hung {restarts - 1} times: the tasks "
                                  "after that were not graded")
            await kernel.start()
            for index in list(ran):
                reply = await execute(code_cells[index])
                if reply.status in ("dead", "hung"):
                    ran.remove(index)
                    break
            else:
                return

    try:
        await kernel.start()
        task = course.tasks[0]             # the task whose cells are running
        for kind, value in steps:
            if kind == "cell":
                reply = await execute(code_cells[value])
                failed = _failure(reply)
                if failed and task is not None:
                    cell_errors.setdefault(task.name, failed)
                if reply.status in ("ok", "error"):
                    ran.append(value)
                elif reply.status in ("dead", "hung"):
                    await recover()
                continue
            failed = cell_errors.get(value.name)
            found = None
            if not (failed and failed.get("ename") == "TimedOut"):
                reply = await execute("", silent=True, user_expressions={
                    "answers": judge.reader_expression(reader, value.answers)})
                if reply.status == "ok":
                    found = judge.read_reply(reply.content.get("user_expressions", {})
                                             .get("answers"))
                elif reply.status in ("dead", "hung"):
                    failed = failed or _failure(reply)
                    await recover()
            verdict, message = _task_row(value, found, failed, scopes.get(value.name))
            if course_failure:
                message = f"{message} (the course notebook failed: {course_failure})"
            rows.append(Row(student, name, value.name, verdict, message))
            following = course.tasks.index(value) + 1
            task = course.tasks[following] if following < len(course.tasks) else None
    except (_KernelLost, sandbox.SandboxError) as error:
        if not rows and isinstance(error, sandbox.SandboxError):
            raise                              # not one kernel: the grader's trouble
        verdict = KERNEL_FAILED if isinstance(error, sandbox.SandboxError) else (
            "error: DeadKernelError")
        done = {row.task for row in rows}
        rows += [Row(student, name, task.name, verdict, str(error)[:1500])
                 for task in course.tasks if task.name not in done]
    finally:
        await kernel.stop()
    return rows


def grade_notebook(path, student, courses, cell_timeout=60, notebook_timeout=600, fence=None,
                   shown_as=None, within=None):
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
    fence : sandbox.Fence, optional
        What the kernels may see, change and take (default: :func:`make_fence` for the
        notebook's folder).
    shown_as : str, optional
        The ``file`` column (default: the file's name).
    within : path-like, optional
        SUBMISSIONS: a file that is a symbolic link, or is not really inside it, is refused.

    Returns
    -------
    list of Row
        One row per task of the matched course notebook, or one ``error: ...`` row (task "")
        for a file that is not a notebook or answers none of the course's. When no kernel
        could be started (never the notebook's doing), every task's verdict is
        :data:`KERNEL_FAILED`.

    Raises
    ------
    ValueError
        If a time limit is not positive.
    """
    if not (cell_timeout > 0 and notebook_timeout > 0):
        raise ValueError(f"time limits must be positive seconds, got cell {cell_timeout}, "
                         f"notebook {notebook_timeout}")
    fence = fence or make_fence(Path(path).parent)
    name = printable(Path(path).name)
    shown_as = printable(shown_as or Path(path).name)
    note = UNSAFE_NOTE if fence.unsafe else ""
    real, base = os.path.realpath(path), os.path.realpath(within or Path(path).parent)
    if os.path.islink(path) or not real.startswith(base.rstrip(os.sep) + os.sep):
        return [Row(student, name, "", "error: not a notebook",
                    "a symbolic link, not a notebook: hand in the notebook itself", shown_as)]
    try:
        notebook = nbformat.read(path, as_version=4)
        sources = [_normal(cell.source) for cell in notebook.cells if cell.cell_type == "code"]
    except Exception as error:                             # noqa: BLE001 - any unreadable file
        return [Row(student, name, "", "error: not a notebook",
                    f"{type(error).__name__}: {printable(str(error))[:300]}", shown_as)]
    course, misfiled = match_course(path, sources, courses)
    if course is None:
        return [Row(student, name, "", "error: not a course exercise notebook",
                    "its cells match none of the course's exercise notebooks", shown_as)]
    name = course.path.name
    try:
        rows = asyncio.run(_run(notebook, course, cell_timeout, notebook_timeout, student, name,
                                fence, path))
    except sandbox.SandboxError as error:                  # the grader's trouble, not theirs
        rows = [Row(student, name, task.name, KERNEL_FAILED, str(error)[:1500])
                for task in course.tasks]
    except Exception as error:                             # noqa: BLE001 - never stop the class
        rows = [Row(student, name, task.name, f"error: {type(error).__name__}", str(error)[:500])
                for task in course.tasks]
    internals = internals_used(plan(course, sources), [cell.source for cell in notebook.cells
                                                         if cell.cell_type == "code"])
    for row in rows:
        row.file, row.note = shown_as, "; ".join(part for part in (misfiled, note) if part)
    return refuse_internals(rows, internals)


def submissions(folder):
    """(student, path) for every submission under ``folder``, sorted.

    A sub-folder is a student (all its ``.ipynb`` files, at any depth, checkpoints excluded;
    an empty one gives a "no notebook" row); a file at the top is a student named after its
    stem. Hidden files are skipped. Names are kept as the file system gives them (a Latin-1
    name carries surrogate escapes; :func:`printable` writes it).

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
    student, path, shown_as, cell_timeout, notebook_timeout, courses, fence, within = job
    if path is None:
        return [Row(student, "", "", "error: no notebook", "the folder holds no .ipynb file",
                    shown_as)]
    return grade_notebook(path, student, courses, cell_timeout, notebook_timeout, fence,
                          shown_as, within)


def progress(done, total, label, stream=sys.stderr, width=30):
    """Draw a plain-text progress bar on ``stream`` (standard error)."""
    filled = int(width * done / total) if total else width
    stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {label[:40]:<40}")
    if done == total:
        stream.write("\n")
    stream.flush()


def grade(folder, jobs=1, cell_timeout=60, notebook_timeout=600, course_folder=COURSE,
          show_progress=True, on_rows=None, memory=sandbox.DEFAULT_MEMORY, outputs=(),
          unsafe=False, on_start=None):
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
        The course's exercise notebooks, with solutions (default: this folder). They are read
        once, before any submission runs.
    show_progress : bool
        Draw a progress bar on standard error.
    on_rows : callable, optional
        Called with each notebook's rows as soon as it is graded (the CSV written row by row).
    memory : int
        Bytes of memory (address space) each student kernel may take.
    outputs : iterable of path-like
        The grader's output files: shown empty to the kernels, their folders hidden.
    unsafe : bool
        Grade even where bubblewrap is not installed (every row's note says so).
    on_start : callable, optional
        Called once the sandbox has been tried, before the first submission runs.

    Returns
    -------
    list of Row

    Raises
    ------
    ValueError
        If ``folder`` is not a folder, ``jobs`` is not a positive integer, or the course folder
        holds no exercise notebook.
    sandbox.SandboxError
        If bubblewrap is not installed and ``unsafe`` is False, or a kernel cannot be started
        as the students' will be (a test kernel is started first, with bubblewrap's message).
    """
    if int(jobs) != jobs or jobs < 1:
        raise ValueError(f"jobs must be a positive integer, got {jobs!r}")
    courses = course_notebooks(course_folder)
    if not courses:
        raise ValueError(f"{course_folder} holds no course exercise notebook")
    found = submissions(folder)
    if sandbox.bwrap_path() is None and not unsafe:
        raise sandbox.SandboxError(NO_BWRAP)
    private = tempfile.mkdtemp(prefix="rsgeo-grading-")
    try:
        fence = make_fence(folder, course_folder, outputs, memory, unsafe, private)
        if show_progress:
            progress(0, len(found) or 1, "trying the sandbox")
        _preflight(fence, course_folder)
        if on_start is not None:
            on_start()
        base = Path(folder)
        work = [(printable(student), path,
                 printable(path.relative_to(base)) if path else printable(student),
                 cell_timeout, notebook_timeout, courses, fence, str(base))
                for student, path in found]
        rows, total = [], len(work)
        if show_progress:
            progress(0, total, "starting")
        with concurrent.futures.ProcessPoolExecutor(max_workers=int(jobs)) as pool:
            futures = {pool.submit(_grade_one, job): job for job in work}
            for done, future in enumerate(concurrent.futures.as_completed(futures), start=1):
                student, path, shown_as = futures[future][:3]
                try:
                    these = future.result()
                except Exception as error:                 # noqa: BLE001 - a crashed worker
                    these = [Row(student, printable(Path(path).name) if path else "", "",
                                 f"error: {type(error).__name__}", str(error)[:500], shown_as)]
                rows += these
                if on_rows is not None:
                    on_rows(these)
                if show_progress:
                    progress(done, total, shown_as)
    finally:
        shutil.rmtree(private, ignore_errors=True)
    return sorted(rows, key=lambda row: (row.student, row.file, row.notebook))  # tasks in order


def _preflight(fence, course_folder):
    """Start one kernel as the students' will be; check that it reads answers and, in
    bubblewrap, that it cannot see the course's notebooks (:func:`sandbox.preflight`)."""
    reader = judge.reader_name()
    code = "import rsgeo, rsgeo_course.exercises\nx = 1.5"
    if not fence.unsafe:
        code += (f"\nimport os\nassert not os.path.exists({str(course_folder)!r}) or not "
                 f"os.listdir({str(course_folder)!r}), 'the course is visible in the sandbox'")
    reply = sandbox.preflight(fence, [judge.reader_install(reader)], {
        "code": code, "expressions": {"answers": judge.reader_expression(reader, ["x"])}})
    found = judge.read_reply(reply.content.get("user_expressions", {}).get("answers"))
    if found != {"x": {"t": "float", "v": "1.5"}}:
        raise sandbox.SandboxError(f"a test kernel started, but its answers could not be "
                                   f"read: {reply.content.get('user_expressions')}")


class CsvRows:
    """The grades' CSV, written as the rows come (each notebook's flushed at once); the file is
    created by :meth:`open` or the first rows, not before (a refused run leaves it alone)."""

    def __init__(self, path):
        self.path, self.file, self.writer = path, None, None

    def open(self):
        if self.file is None:
            Path(self.path).parent.mkdir(parents=True, exist_ok=True)
            self.file = open(self.path, "w", newline="", encoding="utf-8")    # noqa: SIM115
            self.writer = csv.writer(self.file)
            self.writer.writerow(FIELDS)
            self.file.flush()

    def __call__(self, rows):
        self.open()
        for row in rows:
            self.writer.writerow([printable(getattr(row, name)) for name in FIELDS])
        self.file.flush()

    def close(self):
        if self.file is not None:
            self.file.close()


def write_csv(rows, path):
    """Write the grades as CSV (the columns of :data:`FIELDS`), whatever the names contain."""
    writer = CsvRows(path)
    try:
        writer(rows)
    finally:
        writer.close()


COLOURS = {"Correct": "#c9f0d1", "Not yet": "#ffe3b3", "not attempted": "#e6e6e6",
           "timed out": "#f5c6c6", "error": "#f5c6c6"}


def _text(value):
    return html.escape(printable(value))


def write_html(rows, path):
    """Write an HTML summary: per notebook, a table of students by tasks, coloured by verdict."""
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Grades</title><style>"
             "body{font-family:sans-serif}td,th{border:1px solid #999;padding:3px 8px}"
             "table{border-collapse:collapse;margin-bottom:2em}</style></head><body>",
             "<h1>Grades</h1><p>Hover a cell for the check's message.</p>"]
    notes = sorted({row.note for row in rows if row.note})
    if notes:
        parts.append("<ul>" + "".join(f"<li>{_text(note)}</li>" for note in notes) + "</ul>")
    problems = [row for row in rows if not row.task]
    if problems:
        parts.append("<h2>Submissions that could not be graded</h2><table><tr><th>student</th>"
                     "<th>file</th><th>verdict</th><th>message</th></tr>")
        parts += [f"<tr><td>{_text(row.student)}</td><td>{_text(row.file or row.notebook)}</td>"
                  f"<td style='background:{COLOURS['error']}'>{_text(row.verdict)}</td>"
                  f"<td>{_text(row.message)}</td></tr>" for row in problems]
        parts.append("</table>")
    graded = [row for row in rows if row.task]
    for notebook in sorted({row.notebook for row in graded}):
        these = [row for row in graded if row.notebook == notebook]
        tasks = list(dict.fromkeys(row.task for row in these))
        parts.append(f"<h2>{_text(notebook or '(no notebook)')}</h2><table><tr>"
                     "<th>student</th><th>file</th>" + "".join(
                         f"<th>{_text(task or '-')}</th>" for task in tasks)
                     + "<th>correct</th></tr>")
        for student, shown_as in sorted({(row.student, row.file) for row in these}):
            cells = {row.task: row for row in these
                     if row.student == student and row.file == shown_as}
            correct = sum(row.verdict == "Correct" for row in cells.values())
            parts.append(f"<tr><td>{_text(student)}</td><td>{_text(shown_as)}</td>")
            for task in tasks:
                row = cells.get(task)
                if row is None:
                    parts.append("<td></td>")
                    continue
                colour = COLOURS.get(row.verdict.split(":")[0], "#ffffff")
                parts.append(f"<td style='background:{colour}' title='{_text(row.message)}'>"
                             f"{_text(row.verdict)}</td>")
            parts.append(f"<td>{correct}/{len(tasks)}</td></tr>")
        parts.append("</table>")
    parts.append("</body></html>")
    Path(path).write_text("\n".join(parts), encoding="utf-8")


def main(argv=None):
    """The command line; returns the exit status: 0 when every notebook was graded (whatever
    the verdicts), 2 for bad arguments or when bubblewrap is missing without ``--unsafe``, 3
    when a student kernel could not be started."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("submissions", help="a folder: one folder or one .ipynb per student")
    parser.add_argument("--out", default="grades.csv", help="the CSV to write (grades.csv)")
    parser.add_argument("--html", help="the HTML summary (default: --out with .html)")
    parser.add_argument("--jobs", type=int, default=1, help="notebooks graded at once (1)")
    parser.add_argument("--cell-timeout", type=float, default=60, help="seconds per cell (60)")
    parser.add_argument("--notebook-timeout", type=float, default=600,
                        help="seconds per notebook (600)")
    parser.add_argument("--memory-mb", type=int, default=sandbox.DEFAULT_MEMORY // 2 ** 20,
                        help="memory (address space) per student kernel, MiB (3072)")
    parser.add_argument("--course", default=str(COURSE),
                        help="the course's exercise notebooks, with solutions (this folder)")
    parser.add_argument("--unsafe", action="store_true",
                        help="grade even without bubblewrap: the notebooks' code can then read "
                        "the solutions and write into the course (every row's note says so)")
    options = parser.parse_args(argv)
    summary = options.html or str(Path(options.out).with_suffix(".html"))
    if options.memory_mb < 256:
        parser.error(f"--memory-mb must be at least 256, got {options.memory_mb}")
    if options.unsafe and sandbox.bwrap_path() is None:
        print(f"grade.py: warning: {UNSAFE_NOTE}", file=sys.stderr)
    streamed = CsvRows(options.out)
    try:
        rows = grade(options.submissions, options.jobs, options.cell_timeout,
                     options.notebook_timeout, options.course, on_rows=streamed,
                     memory=options.memory_mb * 2 ** 20, outputs=(options.out, summary),
                     unsafe=options.unsafe, on_start=streamed.open)
    except ValueError as error:
        parser.error(str(error))
    except sandbox.SandboxError as error:
        missing = sandbox.bwrap_path() is None and not options.unsafe
        print(f"grade.py: nothing graded: {error}" if missing else
              f"grade.py: nothing graded: a student kernel cannot start in the sandbox: {error}",
              file=sys.stderr)
        return 2 if missing else 3
    finally:
        streamed.close()
    write_csv(rows, options.out)              # from the grader's memory, sorted, last
    write_html(rows, summary)
    counts = {verdict: sum(row.verdict.startswith(verdict) for row in rows)
              for verdict in VERDICTS}
    print(f"{len(rows)} verdicts ({', '.join(f'{n} {v}' for v, n in counts.items())}) "
          f"in {printable(options.out)} and {printable(summary)}")
    failed = [row for row in rows if row.verdict == KERNEL_FAILED]
    if failed:
        print(f"grade.py: {len(failed)} tasks not graded: the grader could not start their "
              f"kernel: {failed[0].message}", file=sys.stderr)
        return 3
    if any(row.note.startswith(UNSAFE_NOTE) or UNSAFE_NOTE in row.note for row in rows):
        print(f"grade.py: warning: {UNSAFE_NOTE}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
