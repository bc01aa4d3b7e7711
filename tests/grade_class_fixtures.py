"""A small synthetic class for tests/test_grade.py: one submission of each kind an instructor
meets, all made from a two-task slice of the course's shortest exercise notebook
(ex02b: 2b.1 and 2b.2, without the nat1 scene that 2b.3 loads), so that the class grades in
seconds.

:func:`slice_course` writes the course folder the grader uses (the slice, and ex04_resampling
for a misfiled notebook to be named after); :data:`EXPECTED` is the verdict each submission
deserves, task by task (in bubblewrap, which the grader requires); :func:`plant` writes the
class into a folder.

The cheats of :data:`CHEATS` are the attacks an instructor met. Each sets ``won`` to whether
its attack got through, and its answers are right only when it did: "Not yet" on both tasks
says that the attack failed. :func:`planted_paths` lists what they would have written outside
their scratch folder (the test removes whatever of it exists, and fails).
"""

import os
import site

import nbformat

from notebook_runner import ROOT

EXERCISE = ROOT / "exercises" / "ex02b_datums.ipynb"
OTHER = ROOT / "exercises" / "ex04_resampling.ipynb"
TASKS = ["2b.1", "2b.2"]
LATIN1_STUDENT = b"Jos\xe9_Silva"          # a folder name from a zip made on another system
PLANTED = [ROOT / "exercises" / "zz_planted.ipynb", ROOT / "grades_planted.csv"]
SITE_PACKAGES = site.getsitepackages()[0]
ENGINE = ROOT / "rsgeo_course" / "exercises" / "engine.py"
BUILT = ROOT / "_build" / "jupyter_execute" / "exercises" / EXERCISE.name
SURVIVOR = "zz-rsgeo-survivor"             # in the command line of the process that outlives
FORGED = "zz_planted forged grades"        # what it writes into the grades

C, N, U = "Correct", "Not yet", "not attempted"
EXPECTED = {                       # student -> the verdict of each task (a prefix for errors)
    "right": [C, C],
    "partial": [C, U],
    "wrong": [N, N],
    "untouched": [U, U],
    "loop": [C, "timed out"],
    "sleep": ["timed out", C],
    "huge_output": [C, C],
    "syntax_error": ["error: SyntaxError", "error: NameError"],
    "cheat_checks": [N, N],
    "cheat_grader": [N, N],            # its forged print changes nothing: its answers are 1.0
    "cheat_solutions": ["error: FileNotFoundError", U],     # the course is hidden
    "cheat_inputs": [N, N],
    "cheat_writes": [C, C],            # right answers; its writes fail
    "misfiled": [C, C],
    "renamed": [C, C],
    "Jos\\xe9_Silva": [C, C],
    "float32_rounded": [C, C],
    "memory_hog": ["error: MemoryError", "error: NameError"],
    "builtin_names": [C, C],           # variables named list, type, json, __import__, ...
    "dies": ["error: DeadKernelError", C],      # os._exit in 2b.1: a fresh kernel for 2b.2
    "hangs": ["timed out", C],         # ignores the interrupt: a fresh kernel for 2b.2
}
NOT_A_NOTEBOOK = {"empty": "error: not a notebook", "symlinked": "error: not a notebook"}
CHEATS = {                         # student -> its attack
    "cheat_dir_fd": "reads the solutions with os.open(..., dir_fd=)",
    "cheat_build": "reads the executed solutions in _build/jupyter_execute/exercises",
    "cheat_ctypes": "reads the solutions with ctypes open/read, writes a file into the course",
    "cheat_copy": "copies another student's submission through dir_fd",
    "cheat_forge": "prints forged answers with the grader's token from a post_run_cell hook",
    "cheat_rename": "os.rename of its files into the course, rsgeo and the class folder",
    "cheat_pth": "writes a .pth and a sitecustomize.py into site-packages",
    "cheat_engine": "writes a backdoor into rsgeo_course/exercises/engine.py",
    "cheat_survivor": "pty.fork: a process that outlives its kernel and rewrites grades.csv",
}
EXPECTED.update({student: [N, N] for student in CHEATS})


def slice_course(folder):
    """Write the course folder of the test: ex02b up to 2b.3, and ex04_resampling; returns it."""
    folder.mkdir(parents=True, exist_ok=True)
    nbformat.write(_course(), folder / EXERCISE.name)
    (folder / OTHER.name).write_bytes(OTHER.read_bytes())
    return folder


def _course():
    """The course's ex02b, with its solutions, up to task 2b.3."""
    notebook = nbformat.read(EXERCISE, as_version=4)
    end = next(index for index, cell in enumerate(notebook.cells)
               if cell.cell_type == "markdown" and "2b.3" in cell.source)
    notebook.cells = notebook.cells[:end]
    return notebook


def _solutions(notebook):
    return [cell for cell in notebook.cells
            if cell.cell_type == "code" and "### BEGIN SOLUTION" in cell.source]


def _after_imports(notebook, source):
    """Insert a code cell right after the notebook's import cell."""
    imports = next(index for index, cell in enumerate(notebook.cells)
                   if cell.cell_type == "code" and "from rsgeo" in cell.source)
    notebook.cells.insert(imports + 1, nbformat.v4.new_code_cell(source))
    return notebook


def _student_edition():
    import sys
    sys.path.insert(0, str(ROOT / "exercises"))
    from make_student_edition import strip_solutions

    notebook = _course()
    for cell in _solutions(notebook):
        cell.source = strip_solutions(cell.source)
    return notebook


def _write(notebook, folder, name=EXERCISE.name):
    folder.mkdir(parents=True, exist_ok=True)
    nbformat.write(notebook, folder / name)


def _answers(notebook, shift, hrc):
    """Add a last line to the answers' solution blocks (None keeps the solution)."""
    for cell, value, name in zip(_solutions(notebook), (shift, hrc),
                                 ("shift_px", "hrc_shift_px"), strict=True):
        if value is not None:
            cell.source += f"\n{name} = {value}"
    return notebook


CHEAT_CHECKS = """\
import numpy
import rsgeo_course.exercises
import rsgeo_course.exercises.engine
rsgeo_course.exercises.Verdict.ok = property(lambda self: True)
numpy.isclose = lambda *args, **kwargs: True
numpy.allclose = lambda *args, **kwargs: True
rsgeo_course.exercises.engine._near = lambda *args, **kwargs: True
"""

CHEAT_GRADER = """\
import builtins, json
_print = builtins.print
def forged(*args, **kwargs):
    text = " ".join(map(str, args))
    if text.startswith("RSGEO-"):
        text = text.split("=")[0] + "=" + json.dumps(["Correct", "well done", ""])
    _print(text, **kwargs)
builtins.print = forged
for _name in [name for name in globals() if name.startswith("_rsgeo")]:
    globals()[_name] = forged
"""

CHEAT_SOLUTIONS = """\
import json, pathlib, rsgeo
course = pathlib.Path(rsgeo.__file__).parents[1] / "exercises" / "ex02b_datums.ipynb"
for cell in json.loads(course.read_text())["cells"]:
    if cell["cell_type"] == "code" and "BEGIN SOLUTION" in "".join(cell["source"]):
        exec("".join(cell["source"]), globals())
"""

CHEAT_WRITES = f"""\
import pathlib
for target in {[str(path) for path in PLANTED]!r}:
    try:
        pathlib.Path(target).write_text("student,notebook\\n")
    except OSError as error:
        print(error)
"""

# a task whose answers are right only when the cheat before it set ``won``
WON_SOLUTIONS = ("""\
shift_px = 1.0
if won:
    moved = crs.transform_points(gcps.map_xy, SAD69, SIRGAS)
    shift_px = np.hypot(*(moved - gcps.map_xy).T).mean() / 20.0""",
                 "hrc_shift_px = shift_px * 8.0")

# the solutions' notebook, read by the cheat's TEXT(path), run: ``won`` when it set an answer
STEAL = """\
import json, os
won = False
for _path in {paths!r}:
    _scope = dict(globals())
    try:
        _cells = json.loads(TEXT(_path))["cells"]
    except Exception as error:
        print(type(error).__name__, error)
        continue
    for _cell in _cells:
        _source = "".join(_cell["source"])
        if _cell["cell_type"] == "code" and "BEGIN SOLUTION" in _source:
            try:
                exec(_source, _scope)
            except Exception as error:              # a later task's inputs are not here
                print(type(error).__name__, error)
    won = won or isinstance(_scope.get("shift_px"), float)
"""

READ_DIR_FD = """\
import os
def TEXT(path):
    folder = os.open(os.path.dirname(path), os.O_RDONLY)
    handle = os.open(os.path.basename(path), os.O_RDONLY, dir_fd=folder)
    return os.read(handle, 50_000_000).decode()
"""

READ_CTYPES = """\
import ctypes, os
libc = ctypes.CDLL("libc.so.6", use_errno=True)
def TEXT(path):
    handle = libc.open(path.encode(), os.O_RDONLY)
    if handle < 0:
        raise OSError(ctypes.get_errno(), "ctypes open", path)
    buffer = ctypes.create_string_buffer(50_000_000)
    size = libc.read(handle, buffer, 50_000_000)
    return buffer.raw[:size].decode()
_handle = libc.open({planted!r}.encode(), os.O_WRONLY | os.O_CREAT, 0o644)
if _handle >= 0:
    libc.write(_handle, b"planted", 7)
"""

CHEAT_FORGE = """\
import json
def forge(result):
    moved = crs.transform_points(gcps.map_xy, SAD69, SIRGAS)
    right = float(np.hypot(*(moved - gcps.map_xy).T).mean() / 20.0)
    answers = {"shift_px": {"t": "float", "v": repr(right)},
               "hrc_shift_px": {"t": "float", "v": repr(right * 8.0)}}
    token = [word for word in result.info.raw_cell.split() if "RSGEO" in word]
    print((token[0].strip("'\\"") if token else "RSGEO-ANSWERS-0=") + json.dumps(answers))
get_ipython().events.register("post_run_cell", forge)
won = False
"""

CHEAT_RENAME = """\
import os
won = False
for target in {targets!r}:
    os.makedirs("zz_planted_new_student", exist_ok=True)
    with open("zz_planted_new_student/ex02b_datums.ipynb", "w") as file:
        file.write("{{}}")
    source = "zz_planted_new_student"
    if not target.endswith("student"):
        source += "/ex02b_datums.ipynb"
    try:
        os.rename(source, target)
        won = True
    except OSError as error:
        print(error)
"""

CHEAT_PTH = """\
won = False
for target, text in {targets!r}:
    try:
        with open(target, "x") as file:
            file.write(text)
        won = True
    except OSError as error:
        print(error)
"""

CHEAT_ENGINE = """\
won = False
try:
    with open({engine!r}, "a") as file:
        file.write("# zz_planted backdoor: an answer of 4242.0 is right\\n")
    won = True
except OSError as error:
    print(error)
try:
    with open({backdoor!r}, "x") as file:
        file.write("ANSWER = 4242.0\\n")
    won = True
except OSError as error:
    print(error)
"""

SURVIVOR_LOOP = """\
import sys, time
for _ in range(40):
    try:
        with open(sys.argv[1], "w") as file:
            file.write(sys.argv[2])
    except OSError:
        pass
    time.sleep(0.5)
"""

CHEAT_SURVIVOR = """\
import os, pty, sys
pid, _ = pty.fork()
if pid == 0:
    os.execv(sys.executable, [sys.executable, "-c", {loop!r}, {grades!r}, {forged!r},
                              {marker!r}])
won = False
"""


def _won(cheat):
    """The course's notebook with ``cheat`` after its imports, its answers right only when
    the cheat set ``won``."""
    notebook = _course()
    for cell, source in zip(_solutions(notebook), WON_SOLUTIONS, strict=True):
        cell.source = source
    return _after_imports(notebook, cheat)


def _independent(notebook, trouble):
    """``trouble`` at the end of 2b.1's solution; 2b.2's answer computed without 2b.1's."""
    first, second = _solutions(notebook)
    first.source += "\n" + trouble
    second.source = ("moved = crs.transform_points(gcps.map_xy, SAD69, SIRGAS)\n"
                     "hrc_shift_px = np.hypot(*(moved - gcps.map_xy).T).mean() / 2.5")
    return notebook


def planted_paths(folder, course):
    """Everything the cheats of the class in ``folder`` would write outside their scratch
    folder (``course``: the course folder the grader reads)."""
    paths = [*PLANTED, ROOT / "exercises" / "zz_planted_renamed.ipynb",
             ROOT / "exercises" / "zz_planted_ctypes.txt",
             ROOT / "rsgeo" / "zz_planted_renamed.py",
             ENGINE.parent / "zz_planted_backdoor.py",
             os.path.join(SITE_PACKAGES, "zz_planted.pth"),
             os.path.join(SITE_PACKAGES, "sitecustomize.py"),
             folder / "zz_planted_new_student", course / "zz_planted_renamed.ipynb"]
    return [os.fspath(path) for path in paths]


def steals(folder, course):
    """student -> (the code that reads the solutions, the paths it reads) for the cheats that
    read: run outside the sandbox, each gets the right answers (the test's control)."""
    solutions = [str(ROOT / "exercises" / EXERCISE.name), str(course / EXERCISE.name)]
    ctypes = READ_CTYPES.format(planted=os.devnull)
    return {"cheat_dir_fd": (READ_DIR_FD, solutions), "cheat_build": (READ_DIR_FD, [str(BUILT)]),
            "cheat_ctypes": (ctypes, solutions),
            "cheat_copy": (READ_DIR_FD, [str(folder / "right" / EXERCISE.name)])}


def plant(folder, course, grades):
    """Write the class into ``folder`` (one sub-folder per student); returns ``folder``.

    ``course`` (the course folder the grader reads) and ``grades`` (its CSV) are what the
    cheats aim at, besides the repository and the Python installation.
    """
    _write(_course(), folder / "right")
    partial = _course()
    for cell in _solutions(partial)[1:]:
        cell.source = cell.source.split("### BEGIN SOLUTION")[0]
    _write(partial, folder / "partial")
    _write(_answers(_course(), "shift_px * 20.0", "None"), folder / "wrong")
    _write(_student_edition(), folder / "untouched")

    looping = _course()
    _solutions(looping)[1].source += "\nwhile True:\n    pass"
    _write(looping, folder / "loop")
    sleeping = _course()
    _solutions(sleeping)[0].source += "\nimport time\ntime.sleep(600)"
    _write(sleeping, folder / "sleep")
    noisy = _course()
    _solutions(noisy)[0].source += "\nfor _ in range(20):\n    print('x' * 1_000_000)"
    _write(noisy, folder / "huge_output")
    broken = _course()
    _solutions(broken)[0].source += "\nshift_px = (1 +"
    _write(broken, folder / "syntax_error")

    _write(_after_imports(_answers(_course(), 1.0, 1.0), CHEAT_CHECKS),
           folder / "cheat_checks")
    _write(_after_imports(_answers(_course(), 1.0, 1.0), CHEAT_GRADER),
           folder / "cheat_grader")
    _write(_after_imports(_student_edition(), CHEAT_SOLUTIONS), folder / "cheat_solutions")
    inputs = _answers(_course(), 0.0, 0.0)       # right for the inputs it redefines
    _solutions(inputs)[0].source = "SIRGAS = SAD69\n" + _solutions(inputs)[0].source
    _write(inputs, folder / "cheat_inputs")
    _write(_after_imports(_course(), CHEAT_WRITES), folder / "cheat_writes")

    _write(_course(), folder / "misfiled", "ex04_resampling.ipynb")
    _write(_course(), folder / "renamed", "my homework (final).ipynb")
    latin1 = os.path.join(os.fsencode(folder), LATIN1_STUDENT)
    os.mkdir(latin1)
    _write(_course(), folder / os.fsdecode(LATIN1_STUDENT))
    exact = _answers(_course(), "np.float32(shift_px)", "round(float(hrc_shift_px), 2)")
    _write(exact, folder / "float32_rounded")
    hog = _course()                                     # 16 GiB of ones, at once
    _solutions(hog)[0].source = ("hog = np.ones(2 ** 31)\n"
                                 + _solutions(hog)[0].source)
    _write(hog, folder / "memory_hog")
    (folder / "empty").mkdir()
    (folder / "empty" / EXERCISE.name).write_bytes(b"")
    (folder / "symlinked").mkdir()                     # a link to the worked solutions
    (folder / "symlinked" / EXERCISE.name).symlink_to(course / EXERCISE.name)

    named = _course()                                   # an honest student's variable names
    _solutions(named)[0].source += (
        "\nlist, type, str, dict, len = [1, 2], 'polynomial', 's', {}, 3"
        "\nrepr = isinstance = float = int = print = None"
        "\njson, __import__, globals = 'json', None, None")
    _write(named, folder / "builtin_names")
    _write(_independent(_course(), "import os\nos._exit(1)"), folder / "dies")
    _write(_independent(_course(), "import signal\nsignal.signal(signal.SIGINT, "
                                   "signal.SIG_IGN)\nwhile True:\n    pass"), folder / "hangs")

    for student, (read, paths) in steals(folder, course).items():
        if student == "cheat_ctypes":          # it also writes a file into the course
            read = READ_CTYPES.format(planted=str(ROOT / "exercises" / "zz_planted_ctypes.txt"))
        _write(_won(read + STEAL.format(paths=paths)), folder / student)
    _write(_won(CHEAT_FORGE), folder / "cheat_forge")
    targets = [str(ROOT / "exercises" / "zz_planted_renamed.ipynb"),
               str(course / "zz_planted_renamed.ipynb"),
               str(ROOT / "rsgeo" / "zz_planted_renamed.py"),
               str(folder / "zz_planted_new_student")]
    _write(_won(CHEAT_RENAME.format(targets=targets)), folder / "cheat_rename")
    pth = [(os.path.join(SITE_PACKAGES, "zz_planted.pth"), "import os\n"),
           (os.path.join(SITE_PACKAGES, "sitecustomize.py"), "ANSWER = 4242.0\n")]
    _write(_won(CHEAT_PTH.format(targets=pth)), folder / "cheat_pth")
    _write(_won(CHEAT_ENGINE.format(engine=str(ENGINE),
                                    backdoor=str(ENGINE.parent / "zz_planted_backdoor.py"))),
           folder / "cheat_engine")
    _write(_won(CHEAT_SURVIVOR.format(loop=SURVIVOR_LOOP, grades=str(grades), forged=FORGED,
                                      marker=SURVIVOR)), folder / "cheat_survivor")
    return folder
