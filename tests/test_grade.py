"""The grader (exercises/grade.py, judge.py, sandbox.py) on a synthetic class, graded for real
(real kernels in bubblewrap): each kind of submission an instructor meets gets the verdict it
deserves, no cheat changes a verdict or writes outside its scratch folder or outlives its
kernel, and nothing, whatever a file is named, loses the class's rows. Without bubblewrap the
grader refuses (unless told ``--unsafe``); a kernel that cannot start stops it loudly."""

import csv
import os
import shutil
import stat
import subprocess
import sys
import textwrap
import time
from types import SimpleNamespace

import nbformat
import numpy as np
import pytest
from grade_class_fixtures import (
    BUILT,
    CHEATS,
    ENGINE,
    EXERCISE,
    EXPECTED,
    FORGED,
    LATIN1_STUDENT,
    NOT_A_NOTEBOOK,
    SITE_PACKAGES,
    STEAL,
    SURVIVOR,
    TASKS,
    plant,
    planted_paths,
    slice_course,
    steals,
)

from notebook_runner import ROOT

sys.path.insert(0, str(ROOT / "exercises"))
import grade  # noqa: E402
import judge  # noqa: E402
import sandbox  # noqa: E402

from rsgeo_course.exercises import engine  # noqa: E402

GRADER = [sys.executable, str(ROOT / "exercises" / "grade.py")]
needs_bwrap = pytest.mark.skipif(sandbox.bwrap_path() is None,
                                 reason="bubblewrap (bwrap) is not installed")


def _files(folder):
    """{path: (size, mtime)} of everything under ``folder`` (links not followed)."""
    found = {}
    for root, folders, files in os.walk(folder):
        for name in folders + files:
            path = os.path.join(root, name)
            info = os.lstat(path)
            found[path] = (info.st_size if stat.S_ISREG(info.st_mode) else 0, info.st_mtime_ns)
    return found


def _names(folder):
    return sorted(os.listdir(folder))


def _processes(text):
    """The processes whose command line holds ``text``: [(pid, command line)]."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as file:
                command = file.read().replace(b"\0", b" ").decode("utf-8", "replace")
        except OSError:
            continue
        if text in command and int(pid) != os.getpid():
            found.append((int(pid), command))
    return found


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    if sandbox.bwrap_path() is None:
        pytest.skip("bubblewrap (bwrap) is not installed: the grader refuses to grade without it")
    base = tmp_path_factory.mktemp("grading")
    course = slice_course(base / "course")
    out = base / "grades" / "grades.csv"
    folder = plant(base / "submissions", course, out)
    planted = planted_paths(folder, course)
    there_before = {path for path in planted if os.path.lexists(path)}
    watched = [ROOT, ROOT / "exercises", ROOT / "rsgeo", ENGINE.parent, SITE_PACKAGES]
    names = {str(path): _names(path) for path in watched}
    files = {**_files(folder), **_files(course)}
    code, engine_mtime = ENGINE.read_bytes(), ENGINE.stat().st_mtime_ns
    kernels_before = {pid for pid, _ in _processes("rsgeo-grading-")}
    # the grader's limit on a cell is wall-clock time (a sleeping student uses no CPU): 20 s
    # stops the looping, sleeping and hanging students, and no honest cell of this slice comes
    # near it on a loaded machine (4 s did: an honest cell timed out beside a busy CI)
    start = time.monotonic()
    run = subprocess.run([*GRADER, str(folder), "--out", str(out), "--jobs", "2",
                          "--cell-timeout", "20", "--memory-mb", "3072", "--course", str(course)],
                         capture_output=True, text=True, timeout=900)
    seconds = time.monotonic() - start
    grades = out.read_bytes() if out.exists() else b""
    time.sleep(4)            # a process left behind would rewrite the grades by now (every 0.5 s)
    grades_later = out.read_bytes() if out.exists() else b""
    survivors = _processes(SURVIVOR)
    kernels = [process for process in _processes("rsgeo-grading-")
               if process[0] not in kernels_before]
    for pid, _ in survivors + kernels:                   # never leave a process behind
        os.kill(pid, 9)
    left = [path for path in planted if os.path.lexists(path) and path not in there_before]
    for path in left:                                    # never leave a planted file behind
        shutil.rmtree(path) if os.path.isdir(path) else os.unlink(path)
    engine_changed = ENGINE.read_bytes() != code
    if engine_changed:
        ENGINE.write_bytes(code)
    assert run.returncode == 0, run.stderr[-3000:]
    with open(out, newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    verdicts = {}
    for row in rows:
        verdicts.setdefault(row["student"], {})[row["task"]] = row
    return SimpleNamespace(
        verdicts=verdicts, rows=rows, run=run, out=out, left=left, seconds=seconds,
        engine_changed=engine_changed or ENGINE.stat().st_mtime_ns != engine_mtime,
        names_before=names, names_after={str(path): _names(path) for path in watched},
        files_before=files, files_after={**_files(folder), **_files(course)},
        grades=grades, grades_later=grades_later, survivors=survivors, kernels=kernels)


def test_every_row_of_the_class_is_the_verdict_it_deserves(graded):
    got = {student: [graded.verdicts.get(student, {}).get(task, {}).get("verdict", "(no row)")
                     for task in TASKS] for student in EXPECTED}
    assert got == EXPECTED
    for student, verdict in NOT_A_NOTEBOOK.items():
        assert graded.verdicts[student][""]["verdict"] == verdict
    assert len(graded.rows) == len(TASKS) * len(EXPECTED) + len(NOT_A_NOTEBOOK)
    assert "symbolic link" in graded.verdicts["symlinked"][""]["message"]
    assert "died" in graded.verdicts["dies"]["2b.1"]["message"]
    assert "did not stop when interrupted" in graded.verdicts["hangs"]["2b.1"]["message"]


def test_no_cheat_wrote_outside_its_scratch_folder(graded):
    assert graded.left == []                     # the course, rsgeo, site-packages, the class
    assert not graded.engine_changed
    assert graded.names_after == graded.names_before
    assert graded.files_after == graded.files_before       # the class and the course, untouched


def test_nothing_a_kernel_started_outlives_the_grader(graded):
    assert graded.survivors == [] and graded.kernels == []
    assert graded.grades_later == graded.grades and FORGED.encode() not in graded.grades


def test_the_sandboxed_run_says_nothing_is_unsafe_and_stays_quick(graded):
    assert not any(row["note"] for row in graded.rows if row["student"] == "right")
    assert "UNSAFE" not in graded.run.stderr
    # about a minute and a half on two cores beside other work; the time limits alone (the
    # looping, sleeping and hanging students) take a minute of one worker
    assert graded.seconds < 300, graded.seconds


def test_the_cheats_that_read_would_have_won_without_the_sandbox(graded, tmp_path):
    """The control: run outside any sandbox, each cheat that reads gets the solutions (so its
    "Not yet" in the class is the sandbox's doing)."""
    base = graded.out.parent.parent
    cheats = steals(base / "submissions", base / "course")
    if not BUILT.exists():                         # the book was not built on this machine
        cheats.pop("cheat_build")
    setup = [cell.source for cell in nbformat.read(EXERCISE, as_version=4).cells
             if cell.cell_type == "code" and "from rsgeo" in cell.source][0]
    script = setup + "\nresults = {}\n"
    for student, (read, paths) in cheats.items():
        script += read + STEAL.format(paths=paths) + f"results[{student!r}] = won\n"
    script += "print(results)\n"
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=300, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip().splitlines()[-1] == str({student: True for student in cheats})
    assert set(CHEATS) >= set(cheats)


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


def test_progress_goes_to_standard_error(graded):
    total = len(EXPECTED) + len(NOT_A_NOTEBOOK)
    assert f"[{'#' * 30}] {total}/{total}" in graded.run.stderr
    assert "verdicts" in graded.run.stdout


# -- Without bubblewrap, or when it cannot run ------------------------------------------------

def _small_class(tmp_path):
    folder = tmp_path / "class"
    (folder / "right").mkdir(parents=True)
    shutil.copy(slice_course(tmp_path / "course") / EXERCISE.name, folder / "right")
    return folder


def _without_bwrap(tmp_path, fake=None):
    """An environment whose PATH has no bwrap (or ``fake``'s script as bwrap)."""
    bin_folder = tmp_path / "bin"
    bin_folder.mkdir()
    if fake is not None:
        (bin_folder / "bwrap").write_text("#!/bin/sh\n" + fake)
        (bin_folder / "bwrap").chmod(0o755)
    return {**os.environ, "PATH": str(bin_folder)}


def test_without_bwrap_the_grader_refuses_and_writes_nothing(tmp_path):
    out = tmp_path / "grades.csv"
    run = subprocess.run([*GRADER, str(_small_class(tmp_path)), "--out", str(out), "--course",
                          str(tmp_path / "course")], capture_output=True, text=True,
                         timeout=300, env=_without_bwrap(tmp_path))
    assert run.returncode == 2
    assert "bubblewrap (bwrap) is not installed" in run.stderr and "--unsafe" in run.stderr
    assert not out.exists()


def test_with_unsafe_it_grades_and_every_row_says_so(tmp_path):
    folder = _small_class(tmp_path)
    (folder / "empty").mkdir()
    (folder / "empty" / EXERCISE.name).write_bytes(b"")
    out = tmp_path / "grades.csv"
    run = subprocess.run([*GRADER, str(folder), "--out", str(out), "--course",
                          str(tmp_path / "course"), "--unsafe", "--cell-timeout", "60"],
                         capture_output=True, text=True, timeout=300,
                         env=_without_bwrap(tmp_path))
    assert run.returncode == 0, run.stderr[-3000:]
    with open(out, newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    assert [row["verdict"] for row in rows if row["student"] == "right"] == ["Correct"] * 2
    assert all(row["note"].startswith("UNSAFE: graded without bubblewrap") for row in rows
               if row["task"])
    assert "UNSAFE" in run.stderr


def test_a_kernel_that_cannot_start_stops_the_grader_loudly(tmp_path):
    message = ("bwrap: No permissions to creating new namespace, likely because the kernel does "
               "not allow non-privileged user namespaces.")
    out = tmp_path / "grades.csv"
    run = subprocess.run([*GRADER, str(_small_class(tmp_path)), "--out", str(out), "--course",
                          str(tmp_path / "course")], capture_output=True, text=True,
                         timeout=300, env=_without_bwrap(tmp_path, f"echo '{message}' >&2\n"
                                                                   "exit 1\n"))
    assert run.returncode == 3, run.stderr[-3000:]
    assert "cannot start in the sandbox" in run.stderr and message in run.stderr
    assert not out.exists()


# -- The sandbox itself ----------------------------------------------------------------------

@needs_bwrap
def test_bwrap_hides_the_course_and_keeps_a_venv_that_lives_under_tmp(tmp_path):
    """A venv under /tmp (hidden in the sandbox) still runs; the course, the class and the
    network are out of reach; only the scratch folder is writable; the processes die with it."""
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=120)
    secret, work = tmp_path / "secret", tmp_path / "work"
    for path in (secret, work):
        path.mkdir()
    (secret / "solutions.ipynb").write_text("{}")
    fence = sandbox.Fence(hidden=[*sandbox.private_places(), str(ROOT)],
                          secret=[str(secret), str(ROOT / "exercises")],
                          readable=[*sandbox.needed_paths(), str(venv)])
    probe = textwrap.dedent(f"""\
        import os, socket, sys
        print(sys.prefix)
        print(os.listdir({str(secret)!r}), os.listdir({str(ROOT / "exercises")!r}))
        open("written", "w").write("scratch is writable")
        for target in ({str(tmp_path / "x")!r}, {str(ROOT / "rsgeo" / "x")!r}):
            try:
                open(target, "w")
                print("wrote", target)
            except OSError as error:
                print(error.strerror)
        try:
            socket.create_connection(("1.1.1.1", 53), timeout=2)
        except OSError as error:
            print(error.strerror)
        """)
    command = sandbox.bwrap_command([str(venv / "bin" / "python"), "-c", probe], str(work),
                                    str(work), fence)
    run = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == [str(venv), "[] []", "Read-only file system",
                                       "Read-only file system", "Network is unreachable"]
    assert (work / "written").read_text() == "scratch is writable"
    assert not (tmp_path / "x").exists()
    fence.readable.remove(str(venv))              # the control: hidden, the venv is gone
    command = sandbox.bwrap_command([str(venv / "bin" / "python"), "-c", "1"], str(work),
                                    str(work), fence)
    assert subprocess.run(command, capture_output=True, timeout=60).returncode != 0


@needs_bwrap
def test_every_process_dies_with_the_sandbox(tmp_path):
    fence = sandbox.Fence(hidden=sandbox.private_places(), readable=sandbox.needed_paths())
    marker = f"zz-rsgeo-orphan-{os.getpid()}"
    orphan = (f"import subprocess, sys; subprocess.Popen([sys.executable, '-c', "
              f"'import time; time.sleep(600)', {marker!r}], start_new_session=True)")
    command = sandbox.bwrap_command([sys.executable, "-c", orphan], str(tmp_path),
                                    str(tmp_path), fence)
    run = subprocess.run(command, capture_output=True, timeout=60)
    assert run.returncode == 0, run.stderr
    time.sleep(0.5)
    assert [line for _, line in _processes(marker) if "Popen" not in line] == []


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


def test_the_reader_uses_the_real_builtins_and_its_reply_only():
    """The reader installed in a namespace whose builtins a student shadowed (and rebound)
    still encodes; a malformed or failed reply is no answer."""
    import builtins

    class Shell:
        user_ns = {"list": [1], "type": "t", "json": None, "__import__": None,
                   "answer": np.array([1.5, 2.5], dtype=np.float32), "name": "text"}

    private = {"__builtins__": dict(vars(builtins)), "dumps": __import__("json").dumps,
               "shell": Shell(), "MAX_ITEMS": judge.MAX_ITEMS}
    exec(judge.READER, private)
    text = private["answers"](["answer", "name", "list", "missing"])
    reply = {"status": "ok", "data": {"text/plain": repr(text)}}
    found = judge.read_reply(reply)
    assert judge.decode(found["answer"]).tolist() == [1.5, 2.5]
    assert judge.decode(found["name"]) == "text" and judge.decode(found["list"]) == [1]
    assert found["missing"] == {"t": "missing"}
    assert judge.read_reply({"status": "error", "ename": "NameError"}) is None
    assert judge.read_reply({"status": "ok", "data": {"text/plain": "'not json'"}}) is None
    assert judge.reader_expression("_r", ["a"]) == "_r(['a'])"
    assert "_r" in judge.reader_install("_r")


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


def test_the_fence_keeps_the_solutions_secret_and_the_outputs_blank(tmp_path):
    out = tmp_path / "out" / "grades.csv"
    fence = grade.make_fence(tmp_path / "class", grade.COURSE, [out])
    assert {str(grade.COURSE), str(ROOT / "_build"), str(ROOT / ".git"),
            str((tmp_path / "class").resolve())} <= set(fence.secret)
    assert {str(ROOT), str(out.parent.resolve())} <= set(fence.hidden)
    assert fence.blanked == [str(out.resolve())]
    command = sandbox.bwrap_command(["true"], str(tmp_path), str(tmp_path), fence)
    bound = {command[i + 1] for i, item in enumerate(command) if item == "--ro-bind"}
    assert not any(path.startswith(str(grade.COURSE)) for path in bound)
    for flag in ("--unshare-pid", "--die-with-parent", "--unshare-net", "--new-session"):
        assert flag in command


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


def test_a_task_that_calls_the_checks_internals_is_not_its_own_computation():
    """The answer key travels with the checks (local feedback needs it): a task whose cells
    reach into a check's declaration, task object or module is refused; the course's own
    notebooks and honest uses of the same words (a raster's ``bounds.right``) are not."""
    path = ROOT / "exercises" / "ex01_distortions.ipynb"
    course = grade.read_course(path)
    notebook = nbformat.read(path, as_version=4)
    sources = [cell.source for cell in notebook.cells if cell.cell_type == "code"]
    steps = grade.plan(course, [grade._normal(source) for source in sources])
    assert grade.internals_used(steps, sources) == {}
    first, second = (task.solution for task in course.tasks[:2])
    cheats = [
        "from rsgeo_course.exercises.ex01_distortions import SKEW\n"
        "skew_km = SKEW.task(latitude_deg=-30.0, frame_length_km=113.0, altitude_km=778.0,\n"
        "                    inclination_deg=98.5).right",
        "from rsgeo_course import exercises\n"
        "skew_km = exercises.declaration(exercises.check_skew).task(-30.0, 113, 778, 98.5).right",
        "skew_km = check_skew.__globals__['SKEW'].task(-30.0, 113.0, 778.0, 98.5).right",
    ]
    for cheat in cheats:
        changed = list(sources)
        changed[first] = cheat
        # an honest cell of the next task that says "right" (a raster's bounds)
        changed[second] = "west, right = 0.0, 10.0\ngrowth_percent = right - west"
        steps = grade.plan(course, [grade._normal(source) for source in changed])
        found = grade.internals_used(steps, changed)
        assert list(found) == [course.tasks[0].name], (cheat, found)
    rows = [grade.Row("ana", path.name, task.name, "Correct", "") for task in course.tasks]
    rows[-1].verdict = "error: NameError"
    grade.refuse_internals(rows, {course.tasks[0].name: ".task(",
                                  course.tasks[-1].name: ".task("})
    assert [row.verdict for row in rows] == ["Not yet", "Correct", "error: NameError"]
    assert "internals (.task()" in rows[0].message
