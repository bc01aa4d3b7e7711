"""A small synthetic class for tests/test_grade.py: one submission of each kind an instructor
meets, all made from a two-task slice of the course's shortest exercise notebook
(ex02b: 2b.1 and 2b.2, without the nat1 scene that 2b.3 loads), so that the class grades in
seconds.

:func:`slice_course` writes the course folder the grader uses (the slice, and ex04_resampling
for a misfiled notebook to be named after); :data:`EXPECTED` is the verdict each submission
deserves, task by task; :func:`plant` writes the class into a folder.
"""

import os

import nbformat

from notebook_runner import ROOT

EXERCISE = ROOT / "exercises" / "ex02b_datums.ipynb"
OTHER = ROOT / "exercises" / "ex04_resampling.ipynb"
TASKS = ["2b.1", "2b.2"]
LATIN1_STUDENT = b"Jos\xe9_Silva"          # a folder name from a zip made on another system
PLANTED = [ROOT / "exercises" / "zz_planted.ipynb", ROOT / "grades_planted.csv"]

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
    "cheat_grader": ["error: the answers could not be read"] * 2,
    "cheat_solutions": ["error: PermissionError", U],
    "cheat_inputs": [N, N],
    "cheat_writes": [C, C],
    "misfiled": [C, C],
    "renamed": [C, C],
    "Jos\\xe9_Silva": [C, C],
    "float32_rounded": [C, C],
    "memory_hog": ["error: MemoryError", "error: NameError"],
}
NOT_A_NOTEBOOK = {"empty": "error: not a notebook"}


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


def plant(folder):
    """Write the class into ``folder`` (one sub-folder per student); returns ``folder``."""
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
    return folder
