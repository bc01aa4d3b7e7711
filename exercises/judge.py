"""The grader's judge: the course's genuine checks, run on a student's answers outside the
student's kernel.

The student's kernel only *produces* answers: after each task the grader reads the task's
answer variables (the names the student edition sets to ``...``) out of the kernel as JSON
(:data:`READER`, :func:`read_reply`, :func:`decode`). This module, in the grader's own
process where no student code ever runs, executes the course's notebook with its worked
solutions (once per process, :func:`course_scopes`) and evaluates each task's check cell
there, with the course's own inputs and the student's answers put in place of the course's.
Nothing a student does in the kernel (replace ``Verdict.ok``, ``numpy.isclose``, a helper of
``rsgeo_course.exercises``, the grader's code, redefine an input such as
``dx, dy = 0.0, 0.0``, print or hook what looks like answers) reaches the check.

One tolerance rule for every numeric check
------------------------------------------
The checks themselves apply it (``rsgeo_course.exercises.engine.accepts_rounded``), so a
student sees in the notebook the verdict the grader gives: an answer is right within the
check's own tolerance, read as the decimal it prints as (a float32 ``28.6`` is judged as
28.6, not 28.600000381), or when it is the right answer rounded to the decimals it is
written with (2 or more), within 1 % of it, and no mistake the check recognises rounds to it too.
"""

import ast
import contextlib
import inspect
import json
import os
import tempfile

import numpy as np

MAX_ITEMS = 100_000           # an answer larger than this is sent as its type and repr only

# The answers' reader: installed in the student's kernel at its start, before any student code
# (IPython exec_lines, :func:`reader_install`), as a function of ``builtins`` under a name drawn
# at random for that kernel. Its globals are its own: the real builtins as they were at the
# kernel's start, ``json.dumps`` and the IPython shell, so a student's variable named ``list``,
# ``type``, ``json`` or ``__import__`` (or a rebound ``builtins.print``) changes nothing. The
# grader calls it through ``user_expressions`` (:func:`reader_expression`): its result comes
# back in the execute reply, a channel no print, hook or other output reaches
# (:func:`read_reply`). A student who tampers with the kernel itself can only misreport their
# own answers, never a verdict (the verdicts are made here, from the course's inputs).
READER = '''
def encode(value, depth=0):
    if value is Ellipsis:
        return {"t": "ellipsis"}
    if value is None or isinstance(value, (bool, str)):
        return {"t": "plain", "v": value}
    if isinstance(value, int):
        return {"t": "int", "v": str(int(value))}
    if isinstance(value, float):
        return {"t": "float", "v": repr(float(value))}
    if isinstance(value, complex):
        return {"t": "complex", "v": [repr(value.real), repr(value.imag)]}
    kind = type(value).__module__.split(".")[0]
    if kind == "numpy" and hasattr(value, "dtype") and getattr(value, "ndim", 1) == 0:
        return {"t": "npscalar", "dtype": str(value.dtype), "v": str(value)}
    if (kind == "numpy" and hasattr(value, "tolist") and value.dtype.kind in "biuf"
            and value.size <= MAX_ITEMS):
        return {"t": "array", "dtype": str(value.dtype), "shape": list(value.shape),
                "v": [str(item) for item in value.ravel().tolist()]}
    if isinstance(value, (list, tuple)) and len(value) <= MAX_ITEMS and depth < 4:
        return {"t": "tuple" if isinstance(value, tuple) else "list",
                "v": [encode(item, depth + 1) for item in value]}
    return {"t": "object", "type": type(value).__name__, "repr": repr(value)[:300]}


def answers(names):
    namespace = shell.user_ns
    found = {}
    for name in names:
        try:
            found[name] = encode(namespace[name]) if name in namespace else {"t": "missing"}
        except Exception as error:
            found[name] = {"t": "object", "type": type(error).__name__, "repr": ""}
    return dumps(found)
'''

INSTALL = '''
def _rsgeo_install(name, source, max_items):
    import builtins, json
    from IPython import get_ipython
    private = {{"__builtins__": dict(vars(builtins)), "dumps": json.dumps,
                "shell": get_ipython(), "MAX_ITEMS": max_items}}
    exec(source, private)
    setattr(builtins, name, private["answers"])
_rsgeo_install({name!r}, {source!r}, {max_items!r})
del _rsgeo_install
'''


def reader_name():
    """A fresh, unguessable name for one kernel's answers' reader."""
    import secrets

    return "_rsgeo_answers_" + secrets.token_hex(8)


def reader_install(name):
    """The code (an IPython ``exec_lines`` entry) that installs :data:`READER` as ``name``."""
    return INSTALL.format(name=name, source=READER, max_items=MAX_ITEMS)


def reader_expression(name, names):
    """The user expression that asks the reader ``name`` for the answers ``names``."""
    return f"{name}({list(names)!r})"


def read_reply(result):
    """The answers in one user expression's result: name -> encoded value, or None.

    ``result`` is ``content["user_expressions"][key]`` of an execute reply: ``{"status": "ok",
    "data": {"text/plain": repr of the JSON text}}``, or ``{"status": "error", ...}`` when the
    reader could not run (then None).
    """
    if not isinstance(result, dict) or result.get("status") != "ok":
        return None
    try:
        text = ast.literal_eval(result["data"]["text/plain"])
        found = json.loads(text)
    except (KeyError, TypeError, ValueError, SyntaxError, MemoryError, RecursionError):
        return None
    return found if isinstance(found, dict) else None


class _Opaque:
    """Stands for a student's answer that is no number, text or array (a function, a module):
    the check sees an object of the same type name and says it is the wrong form."""

    def __init__(self, text):
        self._text = text

    def __repr__(self):
        return self._text


def _opaque(type_name, text):
    return type(type_name, (_Opaque,), {})(text)


def _scalar(dtype, text):
    """A numpy scalar from the kernel; a float32 becomes the Python float it prints as."""
    dtype = np.dtype(dtype)
    if dtype.kind == "f":
        value = float(text)
        return value if dtype.itemsize < 8 else dtype.type(value)
    if dtype.kind == "b":
        return np.bool_(text == "True")
    if dtype.kind in "iu":
        return dtype.type(int(text))
    return dtype.type(text)


def decode(encoded):
    """A student's answer back from the JSON :data:`READER` returns (see there for the form).

    Returns
    -------
    object
        The answer; a float32 array comes back as float64 of the decimals it prints as.

    Raises
    ------
    KeyError
        For an answer the kernel did not have (``{"t": "missing"}``).
    """
    kind = encoded["t"]
    if kind == "missing":
        raise KeyError("missing")
    if kind == "ellipsis":
        return Ellipsis
    if kind == "plain":
        return encoded["v"]
    if kind == "int":
        return int(encoded["v"])
    if kind == "float":
        return float(encoded["v"])
    if kind == "complex":
        return complex(float(encoded["v"][0]), float(encoded["v"][1]))
    if kind == "npscalar":
        return _scalar(encoded["dtype"], encoded["v"])
    if kind == "array":
        dtype = np.dtype(encoded["dtype"])
        if dtype.kind == "f":
            items = [float(item) for item in encoded["v"]]
            dtype = np.float64
        elif dtype.kind == "b":
            items = [item == "True" for item in encoded["v"]]
        else:
            items = [int(item) for item in encoded["v"]]
        return np.array(items, dtype=dtype).reshape(encoded["shape"])
    if kind in ("list", "tuple"):
        items = [decode(item) for item in encoded["v"]]
        return tuple(items) if kind == "tuple" else items
    return _opaque(encoded.get("type", "object"), encoded.get("repr", ""))


def answer_names(solution_source):
    """The names a task's student edition sets to ``...``: the answers the grader reads.

    ``rms = ...`` gives ``["rms"]``, ``gain, offset = ..., ...`` gives ``["gain", "offset"]``.
    """
    names = []
    for node in ast.walk(ast.parse(solution_source)):
        if not isinstance(node, ast.Assign):
            continue
        values = node.value.elts if isinstance(node.value, ast.Tuple) else [node.value]
        if not all(isinstance(value, ast.Constant) and value.value is Ellipsis
                   for value in values):
            continue
        for target in node.targets:
            for item in target.elts if isinstance(target, ast.Tuple) else [target]:
                if isinstance(item, ast.Name) and item.id not in names:
                    names.append(item.id)
    return names


# -- The course's inputs --------------------------------------------------------------------

_SCOPES = {}


def course_scopes(course):
    """The course notebook's namespace at each task's check, run with its worked solutions.

    Runs in the grader's process (never the student's kernel), in a temporary folder, once per
    course notebook and process. ``course`` is a ``grade.Course`` (``cells``: the code cells'
    sources with solutions; ``tasks``: with ``checks``, the indices of their check cells).

    Returns
    -------
    dict
        Task name -> a shallow copy of the namespace just before its first check cell.

    Raises
    ------
    Exception
        Whatever a course cell raises: the course notebook itself is broken.
    """
    key = (str(course.path), hash(tuple(course.cells)))
    if key in _SCOPES:
        return _SCOPES[key]
    os.environ.setdefault("MPLBACKEND", "Agg")
    starts = {task.checks[0]: task.name for task in course.tasks}
    check_cells = {index for task in course.tasks for index in task.checks}
    namespace = {"__name__": "__course__", "display": lambda *args, **kwargs: None}
    scopes, here = {}, os.getcwd()
    with tempfile.TemporaryDirectory(prefix="rsgeo-judge-") as folder:
        os.chdir(folder)
        try:
            for index, source in enumerate(course.cells):
                if index in starts:
                    scopes[starts[index]] = dict(namespace)
                if index in check_cells or not source.strip():
                    continue
                with contextlib.redirect_stdout(open(os.devnull, "w")):   # noqa: SIM115
                    exec(compile(source, f"<{course.path.name} cell {index}>", "exec"),
                         namespace)
        finally:
            os.chdir(here)
            with contextlib.suppress(Exception):
                import matplotlib.pyplot as plt
                plt.close("all")
    _SCOPES[key] = scopes
    return scopes


# -- Judging ---------------------------------------------------------------------------------

def _one_verdict(call, scope, answers, checks):
    """The verdict of one check call: (ok, message, hint)."""
    function = scope.get(call.func.id) if isinstance(call.func, ast.Name) else None
    if function is None or getattr(checks, call.func.id, None) is not function:
        function = getattr(checks, getattr(call.func, "id", ""), None)
    if function is None:
        raise ValueError(f"the course's check cell calls {ast.unparse(call.func)}, "
                         "not a check of rsgeo_course.exercises")
    args = [eval(compile(ast.Expression(arg), "<check>", "eval"), scope) for arg in call.args]
    kwargs = {keyword.arg: eval(compile(ast.Expression(keyword.value), "<check>", "eval"), scope)
              for keyword in call.keywords}
    signature = inspect.signature(function)
    signature.bind(*args, **kwargs)             # the course's call fits the check
    quoted = [arg.id for arg in call.args if isinstance(arg, ast.Name) and arg.id in answers]
    if quoted and "name" in signature.parameters and "name" not in kwargs and len(quoted) == 1:
        kwargs["name"] = quoted[0]            # the verdict names the student's variable
    verdict = function(*args, **kwargs)
    message, hint = verdict.message, verdict.hint
    declared = getattr(function, "declaration", None)
    if declared is not None and len(quoted) == 1 and declared.answer != quoted[0]:
        message = message.replace(f"`{declared.answer}`", f"`{quoted[0]}`")
        hint = hint.replace(f"`{declared.answer}`", f"`{quoted[0]}`")
    return bool(verdict.ok), message, hint


def judge(task, scope, answers):
    """The verdict on one task: the course's check cell, with the student's answers.

    Parameters
    ----------
    task : grade.Task
        ``check_source``: the course's check cell(s); ``answers``: the answer names.
    scope : dict
        The course's namespace at the task's check (:func:`course_scopes`).
    answers : dict
        The student's answers, by name (decoded with :func:`decode`).

    Returns
    -------
    list of str
        ``[verdict, message, hint]``: "Correct", "Not yet", "not attempted" or "error: ...".
    """
    from rsgeo_course import exercises

    scope = dict(scope)
    scope.update(answers)
    try:
        results = []
        for statement in ast.parse(task.check_source).body:
            calls = [node for node in ast.walk(statement) if isinstance(node, ast.Call)
                     and isinstance(node.func, ast.Name) and node.func.id.startswith("check_")]
            if isinstance(statement, ast.Expr) and calls and statement.value is calls[0]:
                results.append(_one_verdict(calls[0], scope, answers, exercises))
            else:
                exec(compile(ast.Module([statement], []), "<course check>", "exec"), scope)
    except exercises.ExerciseNotSolved as error:
        return ["not attempted", str(error), ""]
    except Exception as error:                          # noqa: BLE001 - any failure is a row
        return [f"error: {type(error).__name__}", str(error)[:500], ""]
    if not results:
        return ["error: the check gave no verdict", "", ""]
    failed = [result for result in results if not result[0]]
    ok, message, hint = failed[0] if failed else results[-1]
    return ["Correct" if ok else "Not yet", message, "" if ok else hint]
