"""The verdict engine of the exercise checks: the verdict, the answer's form, how far it is off.

A check (one module per chapter beside this one) is a :class:`Declaration` and a function:
the declaration names the task's inputs, computes the right answer from them and lists the
mistakes the check recognises, each a :class:`Mistake` (the wrong answer it produces, computed
from the same inputs, and its hint); the function judges a student's answer against it with the
helpers here.

A check judges an answer in this order:

1. the placeholder ``...`` (the student edition's) raises :class:`ExerciseNotSolved`, so that
   running the notebook stops at the first task still to do;
2. the answer's *form*: ``None`` (a function that returned nothing), a string, a tuple, an
   array where one number is needed, a GCP index where an id is needed, a method name or a
   degree outside the offered choices, NaN; each gets a message about the form;
3. its *value*: which way and roughly how far it is off (never the expected value itself),
   with the hint for each mistake whose wrong answer it matches; an answer that matches no
   known mistake gets the task's general hint.

Every message is translated before it is filled (:mod:`rsgeo._i18n`): ``_("`{name}` is
{value}").format(...)``; a hint is English text marked with ``N_()`` in a declaration and
translated when a verdict gives it.
"""

import html
from collections.abc import Callable
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from rsgeo.errors import RsgeoError

from .._i18n import N_, _, prose_number

__all__ = ["ExerciseNotSolved", "Verdict", "Mistake", "Declaration", "declare", "declaration",
           "declarations", "recognised_mistakes", "accepts_rounded", "decimals_written",
           "MIN_DECIMALS", "ROUNDED_RELATIVE",
           # the helpers every chapter's checks judge with
           "WrongForm", "require", "number", "integer", "listed", "one_of", "two_numbers",
           "near", "how_far", "position_verdict", "first_hint"]


class ExerciseNotSolved(Exception):
    """Raised by a check when the answer is still the ``...`` placeholder."""


@dataclass
class Verdict:
    """The outcome of a check: ``ok``, and a message with a hint when not ok.

    The message and the hint are in the language the check ran in (a check translates
    them before it fills in their values); the labels ("Correct", "Not yet", "Hint") are
    translated when the verdict is shown.

    Examples
    --------
    >>> Verdict(False, "`x` is too large by 10 to 50 %.", "Square, average, root.")
    Not yet: `x` is too large by 10 to 50 %.
    Hint: Square, average, root.
    """

    ok: bool
    message: str
    hint: str = ""

    def __bool__(self):
        return self.ok

    def __repr__(self):
        if self.ok:
            return _("Correct") + f": {self.message}"
        hint = "\n" + _("Hint") + f": {self.hint}" if self.hint else ""
        return _("Not yet") + f": {self.message}" + hint

    def _repr_html_(self):
        colour, title = ("#1a7f37", _("Correct")) if self.ok else ("#b35900", _("Not yet"))
        hint = ("<br><em>" + _("Hint") + f":</em> {html.escape(self.hint)}"
                if (self.hint and not self.ok) else "")
        return (f'<div class="rsgeo-verdict" style="border-left:4px solid {colour};'
                f'padding:4px 8px"><strong>{title}:</strong> {html.escape(self.message)}'
                f"{hint}</div>")


# -- What a check declares ----------------------------------------------------------------------

@dataclass(frozen=True)
class Mistake:
    """A mistake a check recognises, and the hint a student who made it gets.

    Attributes
    ----------
    hint : str
        English, marked with ``N_()``; may hold ``{fields}`` the check fills in.
    wrong : callable, optional
        ``wrong(task)``: the answer this mistake produces from the task's inputs (``task``,
        see :meth:`Declaration.task`), or None where the mistake cannot happen for these
        inputs; with ``many``, a list of such answers.
    recognise : callable, optional
        ``recognise(answer, task)``: True when ``answer`` shows the mistake (for a mistake seen
        in the answer's shape or layout rather than in one wrong value).
    many : bool
        ``wrong`` gives a list of answers, each showing the mistake.
    """

    hint: str
    wrong: Callable | None = None
    recognise: Callable | None = None
    many: bool = False

    def answers(self, task):
        """The answers this mistake produces for ``task`` (NaN where it makes no number).

        Parameters
        ----------
        task : types.SimpleNamespace
            The task, from :meth:`Declaration.task`.

        Returns
        -------
        list
            Its wrong answers; empty where the mistake cannot happen for these inputs or is
            recognised by ``recognise``.
        """
        if self.wrong is None:
            return []
        with np.errstate(all="ignore"):
            try:
                value = self.wrong(task)
            except (ValueError, ZeroDivisionError, FloatingPointError):
                value = float("nan")
        if value is None:
            return []
        return list(value) if self.many else [value]

    def text(self, **fields):
        """The hint in the course's language, its fields filled in.

        Parameters
        ----------
        **fields
            The values of the hint's ``{fields}``.

        Returns
        -------
        str
            The translated hint.
        """
        return _(self.hint).format(**fields) if fields else _(self.hint)


@dataclass(frozen=True)
class Declaration:
    """What a check judges: the task's inputs, the right answer, the mistakes it recognises.

    Attributes
    ----------
    check : str
        The check's name, e.g. ``"check_rms"``.
    answer : str
        The name of the student's answer (the check's first parameter, or the exercise's
        variable the verdicts quote); "gain, offset" for a check of two answers.
    inputs : tuple of str
        The task's inputs: the check's other parameters.
    right : callable
        ``right(task)``: the right answer, computed from the inputs.
    general : str
        The hint for an answer that matches no recognised mistake (``N_()``).
    mistakes : tuple of Mistake
        The mistakes the check recognises, in the order their hints are given.
    derive : callable, optional
        ``derive(task)``: a dict of quantities the right answer and the mistakes share
        (centred points, residuals ...), added to ``task``.
    rtol, mistake_rtol, units, scale, scale_name, nan_hint
        How a number is judged (:meth:`judge`): the relative tolerance, a tighter one for
        matching a mistake where two mistakes give nearby values, the units shown, a scale
        ``scale(task)`` the distance is measured in (for an answer that may be zero) and its
        name (``N_()``), the hint for a NaN answer.
    """

    check: str
    answer: str
    inputs: tuple
    right: Callable
    general: str
    mistakes: tuple = ()
    derive: Callable | None = None
    rtol: float = 1e-6
    mistake_rtol: float | None = None
    units: str = ""
    scale: Callable | None = None
    scale_name: str = ""
    nan_hint: str = ""

    def task(self, **inputs):
        """The task's inputs as attributes, with the derived quantities and ``right``.

        Parameters
        ----------
        **inputs
            The check's inputs, by the names of ``inputs``.

        Returns
        -------
        types.SimpleNamespace
            The inputs, what ``derive`` computes from them, and ``right``, the right answer.
        """
        task = SimpleNamespace(**inputs)
        if self.derive is not None:
            for key, value in self.derive(task).items():
                setattr(task, key, value)
        task.right = self.right(task)
        return task

    def hints(self, answer, task, same, exclude_right=True, first=False, **fields):
        """The translated hints of the mistakes ``answer`` shows (each once, in order).

        Parameters
        ----------
        answer : object
            The student's answer, in the form the check has made sure of.
        task : types.SimpleNamespace
            The task, from :meth:`task`.
        same : callable
            ``same(answer, wrong)``: True when the answer is a mistake's wrong answer.
        exclude_right : bool or callable
            A mistake whose wrong answer is the right one for these inputs is not
            recognised; a callable ``exclude_right(wrong, right)`` compares them instead of
            ``same``.
        first : bool
            Only the first mistake found counts.
        **fields
            The values of the hints' ``{fields}``.

        Returns
        -------
        list of str
            The hints, in the course's language.
        """
        same_as_right = exclude_right if callable(exclude_right) else same
        found = []
        for mistake in self.mistakes:
            if mistake.recognise is not None:
                shown = bool(mistake.recognise(answer, task))
            else:
                shown = any(same(answer, wrong)
                            and not (exclude_right and same_as_right(wrong, task.right))
                            for wrong in mistake.answers(task))
            if shown and mistake.hint not in found:
                found.append(mistake.hint)
                if first:
                    break
        return [_(hint).format(**fields) if fields else _(hint) for hint in found]

    def judge(self, answer, task, name=None):
        """The verdict on a number: its form, then which way it is off and the hints.

        Parameters
        ----------
        answer : object
            The student's answer.
        task : types.SimpleNamespace
            The task, from :meth:`task`.
        name : str, optional
            The name the verdict quotes; default ``answer``.

        Returns
        -------
        Verdict
            Correct within ``rtol`` (of ``scale``); else which way and roughly how far
            the answer is off, with the hints of the mistakes whose wrong values it matches
            (within ``mistake_rtol``), or the general hint.
        """
        scale = None if self.scale is None else self.scale(task)
        name = self.answer if name is None else name
        try:
            value = number(answer, name, self.nan_hint or self.general)
        except WrongForm as form:
            return form.verdict(_(self.general))
        expected = task.right
        wrong = [value for mistake in self.mistakes for value in mistake.answers(task)
                 if not near(float(value), expected, self.rtol, scale)]   # no mistake if true
        if near(value, expected, self.rtol, scale) or accepts_rounded(value, expected, wrong):
            return Verdict(True, _("`{name}` = {value:.6g}{units}.").format(
                name=name, value=prose_number(value), units=self.units))
        message = _("`{name}` is {how}.").format(
            name=name, how=how_far(value, expected, scale, _(self.scale_name)))
        tolerance = self.mistake_rtol or self.rtol

        def same(got, wrong):
            wrong = float(wrong)
            return np.isfinite(wrong) and near(got, wrong, tolerance, scale)

        found = []
        for mistake in self.mistakes:           # a mistake whose value is the truth is no mistake
            if any(same(value, wrong) and not near(float(wrong), expected, self.rtol, scale)
                   for wrong in mistake.answers(task)) and mistake.hint not in found:
                found.append(mistake.hint)
        return Verdict(False, message, " ".join(_(hint) for hint in found) or _(self.general))


_DECLARATIONS = {}


def declare(declared):
    """Decorate a check with its :class:`Declaration` (``check.declaration``) and register it.

    Parameters
    ----------
    declared : Declaration
        The check's declaration; its ``check`` is the function's name.

    Returns
    -------
    callable
        The decorator.
    """
    def attach(check):
        if check.__name__ != declared.check:
            raise RsgeoError(_("{kind} is declared as {declared_check}").format(
                    kind=check.__name__, declared_check=declared.check))
        check.declaration = declared
        _DECLARATIONS[declared.check] = declared
        return check
    return attach


def declarations():
    """Every check's :class:`Declaration`, by the check's name.

    Returns
    -------
    dict of str to Declaration

    Examples
    --------
    >>> from rsgeo_course import exercises
    >>> exercises.declarations()["check_rms"].inputs
    ('predicted', 'observed')
    """
    return dict(_DECLARATIONS)


def declaration(check):
    """The :class:`Declaration` of a check.

    Parameters
    ----------
    check : str or callable
        A check of :mod:`rsgeo_course.exercises`, e.g. ``"check_rms"`` or ``check_rms``.

    Returns
    -------
    Declaration

    Raises
    ------
    rsgeo.errors.RsgeoError
        If ``check`` is not one of the checks.

    Examples
    --------
    >>> from rsgeo_course import exercises
    >>> exercises.declaration("check_skew").answer
    'skew_km'
    """
    name = getattr(check, "__name__", check)
    if name not in _DECLARATIONS:
        raise RsgeoError(_("{check!r} is not a check of rsgeo_course.exercises; it needs one "
                           "of {listed}").format(check=check, listed=', '.join(_DECLARATIONS)))
    return _DECLARATIONS[name]


def recognised_mistakes(check):
    """The hints a check gives: for each mistake it recognises, and its general hint.

    Read from the check's :class:`Declaration`, so a list made from it (the teaching guide's
    table) stays true when a check learns a new mistake.

    Parameters
    ----------
    check : str or callable
        A check of :mod:`rsgeo_course.exercises`, e.g. ``"check_rms"`` or ``check_rms``.

    Returns
    -------
    list of (str, str)
        ``(kind, hint)`` pairs, in English, each hint once: the declared mistakes' hints
        (``"mistake"``) in their order, then the general hint (``"general"``). ``{field}``
        stands for a value the check fills in.

    Raises
    ------
    rsgeo.errors.RsgeoError
        If ``check`` is not one of the checks.

    Examples
    --------
    >>> hints = recognised_mistakes("check_skew")
    >>> ("mistake", "That looks like metres; the check wants kilometres.") in hints
    True
    >>> [kind for kind, hint in hints].count("general")
    1
    """
    declared = declaration(check)
    found = []
    for mistake in declared.mistakes:
        if ("mistake", mistake.hint) not in found:
            found.append(("mistake", mistake.hint))
    if declared.general:
        found.append(("general", declared.general))
    return found


# -- The form of an answer ----------------------------------------------------------------------

class WrongForm(Exception):
    """An answer of the wrong form; carries the (translated) message a student sees."""

    def __init__(self, message, hint=""):
        super().__init__(message)
        self.message, self.hint = message, hint

    def verdict(self, hint=""):
        return Verdict(False, self.message, self.hint or hint)


def require(answer, name):
    if answer is Ellipsis:
        raise ExerciseNotSolved(_(
            "`{name}` is still `...`: this task is yours. Write your answer in the cell above, "
            "run it, then run this check again.").format(name=name))
    if answer is None:
        raise WrongForm(_("`{name}` is None: did your function return its value? "
                           "A function without `return` gives None.").format(name=name))
    return answer


def number(answer, name, nan_hint="", many=""):
    """``answer`` as one finite float; raises WrongForm (or ExerciseNotSolved) otherwise.

    ``nan_hint`` (English, translated here) goes with a NaN answer; ``many`` (translated) is
    the message for several values.
    """
    answer = require(answer, name)
    if isinstance(answer, (bool, np.bool_)):
        raise WrongForm(_("`{name}` is {value}, a yes/no value; the check needs a number.")
                         .format(name=name, value=answer))
    if isinstance(answer, (str, bytes)):
        raise WrongForm(_("`{name}` is the text {value!r}; the check needs a number, not a "
                           "string (no quotes).").format(name=name, value=answer))
    if isinstance(answer, (tuple, list)):
        if len(answer) == 1:
            if isinstance(answer, tuple):
                raise WrongForm(_("`{name}` is a tuple holding one value; the check needs the "
                                   "number itself: `{name}[0]` (a trailing comma, `x = 1.5,`, "
                                   "makes a tuple).").format(name=name))
            raise WrongForm(_("`{name}` is a list holding one value; the check needs the number "
                               "itself: `{name}[0]`.").format(name=name))
        raise WrongForm(many or (_("`{name}` is a tuple of {count} values; the check needs one "
                                    "number.") if isinstance(answer, tuple) else
                                  _("`{name}` is a list of {count} values; the check needs one "
                                    "number.")).format(name=name, count=len(answer)))
    try:
        array = np.asarray(answer)
    except Exception:                           # noqa: BLE001 - any object a student may pass
        array = np.asarray(None, dtype=object)
    if array.dtype.kind == "c":
        raise WrongForm(_("`{name}` is a complex number; the check needs a real one (a square "
                           "root of a negative number?).").format(name=name))
    if array.dtype.kind not in "iuf":
        raise WrongForm(_("`{name}` is a {kind}, not a number.").format(
            name=name, kind=type(answer).__name__))
    if array.ndim > 0:
        if array.size == 1:
            raise WrongForm(_("`{name}` is an array of shape {shape} holding one value; the "
                               "check needs the number itself: `{name}.item()`.").format(
                                   name=name, shape=array.shape))
        raise WrongForm(many or _("`{name}` is an array of shape {shape}, {size} values; the "
                                   "check needs one number.").format(
                                       name=name, shape=array.shape, size=array.size))
    # a float32 answer is the decimal it prints as (28.6, not 28.600000381469727)
    value = float(str(array[()])) if array.dtype == np.float32 else float(array)
    if not np.isfinite(value):
        raise WrongForm(_("`{name}` is {value}, not a finite number.").format(
            name=name, value=value), _(nan_hint) if nan_hint else "")
    return value


def integer(answer, name, what, many=""):
    """``answer`` as an int; a float with a fraction is a wrong form. ``what`` is translated."""
    value = number(answer, name, many=many)
    if not value.is_integer():
        raise WrongForm(_("`{name}` is {value:g}; {what} is a whole number.").format(
            name=name, value=prose_number(value), what=what))
    return int(value)


def listed(choices, show=str):
    """``a, b or c`` in the course's language."""
    return _("{some} or {last}").format(some=", ".join(map(show, choices[:-1])),
                                        last=show(choices[-1]))


def one_of(value, name, choices, what):
    """``value`` if it is one of ``choices``; ``what`` (translated) names what it is."""
    if value not in choices:
        raise WrongForm(_("`{name}` is {value}: {what} is one of {listed}.").format(
            name=name, value=value, what=what, listed=listed(choices)))
    return value


def two_numbers(answer, name):
    """``answer`` as two finite floats, a (col, row) position."""
    answer = require(answer, name)
    if isinstance(answer, (str, bytes)):
        raise WrongForm(_("`{name}` is text; the check needs two numbers (col, row).").format(
            name=name))
    try:
        array = np.asarray(answer, dtype=float).ravel()
    except (TypeError, ValueError):
        raise WrongForm(_("`{name}` is not two numbers (col, row).").format(name=name)) from None
    if array.size != 2:
        raise WrongForm((_("`{name}` holds one value; the check needs two, (col, row).")
                          if array.size == 1 else
                          _("`{name}` holds {size} values; the check needs two, (col, row).")
                          ).format(name=name, size=array.size))
    if not np.isfinite(array).all():
        raise WrongForm(_("`{name}` holds NaN or infinite values.").format(name=name))
    return array


# -- The value of an answer ---------------------------------------------------------------------

#: The one rule every numeric check adds to its own tolerance: an answer written with at least
#: MIN_DECIMALS decimals is right when it is the right answer rounded to that many decimals,
#: within ROUNDED_RELATIVE of it (0.00 is not 0.003), and no recognised mistake rounds to it too.
MIN_DECIMALS = 2
ROUNDED_RELATIVE = 0.01


def decimals_written(answer):
    """How many decimals ``answer`` is written with (Python's shortest repr): 22.51 has 2.

    Parameters
    ----------
    answer : float
        A number.

    Returns
    -------
    int
        Its decimals; 0 for a number written with an exponent, an infinity or NaN.

    Examples
    --------
    >>> decimals_written(22.51), decimals_written(3.0), decimals_written(0.1 + 0.2)
    (2, 0, 17)
    """
    text = repr(float(answer))
    if "e" in text or "n" in text:               # 1e-05, inf, nan: no rounding to speak of
        return 0
    fraction = text.split(".")[1].rstrip("0")
    return len(fraction)


def accepts_rounded(answer, right, wrong=()):
    """True when ``answer`` is ``right`` rounded to the decimals it is written with (2 or more).

    The one rule, besides each check's own tolerance, by which every numeric check (and the
    grader, exercises/judge.py) accepts an answer; the teaching guide states it. A recognised
    mistake that rounds to the same answer makes the rounding ambiguous: not accepted.

    Parameters
    ----------
    answer, right : float
        The student's answer and the right one, in the task's unit.
    wrong : iterable of float
        The values of the mistakes the check recognises.

    Returns
    -------
    bool

    Examples
    --------
    >>> accepts_rounded(22.51, 22.5137), accepts_rounded(22.52, 22.5137)
    (True, False)
    >>> accepts_rounded(0.0, 0.003), accepts_rounded(22.5, 22.5137)   # 0.00; one decimal
    (False, False)
    >>> accepts_rounded(22.51, 22.5137, wrong=[22.5098])             # a mistake rounds there too
    False
    """
    try:
        answer, right = float(answer), float(right)
    except (TypeError, ValueError):
        return False
    if not (np.isfinite(answer) and np.isfinite(right)):
        return False
    decimals = decimals_written(answer)
    if decimals < MIN_DECIMALS or decimals > 12:
        return False

    def rounds_to_answer(value):
        return np.isfinite(value) and abs(round(value, decimals) - answer) <= 1e-12 * max(
            1.0, abs(answer))

    return bool(rounds_to_answer(right) and abs(answer - right) <= ROUNDED_RELATIVE * abs(right)
                and not any(rounds_to_answer(float(value)) for value in wrong))


def near(answer, target, rtol, scale=None):
    if not np.isfinite(target):
        return False
    if scale is not None:
        return abs(answer - target) <= rtol * scale
    return bool(np.isclose(answer, target, rtol=rtol, atol=0))


def _bands(size, way, of=""):
    if size < 1e-3:
        phrase = _("close, but a little {way} (off by less than 0.1 %{of}, more than the check "
                   "allows)")
    elif size < 1e-2:
        phrase = _("slightly {way} (off by 0.1 to 1 %{of})")
    elif size < 0.1:
        phrase = _("{way} by 1 to 10 %{of}")
    elif size < 0.5:
        phrase = _("{way} by 10 to 50 %{of}")
    else:
        phrase = _("{way} by more than half{of}")
    return phrase.format(way=way, of=of)


def how_far(answer, expected, scale=None, scale_name=""):
    """Which way and roughly how far ``answer`` is from ``expected``, in words without either.

    With ``scale`` the distance is measured in fractions of it (for an expected value that
    may be zero; ``scale_name``, translated, names it); otherwise relative to ``expected``.

    Examples
    --------
    >>> how_far(3.0, 2.0)
    'between 1.5 and 2 times too large'
    >>> how_far(-2.0, 2.0)
    'the right size with the wrong sign'
    >>> how_far(0.5, 0.0, scale=10.0, scale_name="the step")
    'too large by 1 to 10 % of the step'
    """
    if answer != 0 and expected != 0 and np.sign(answer) != np.sign(expected):
        if np.isclose(-answer, expected, rtol=1e-2):
            return _("the right size with the wrong sign")
        return _("of the wrong sign, and its size is {how}").format(
            how=how_far(-answer, expected, scale, scale_name))
    if scale is not None:
        offset = (answer - expected) / scale
        return _bands(abs(offset), _("too large") if offset > 0 else _("too small"),
                      _(" of {scale}").format(scale=scale_name))
    if answer == 0:
        return _("zero, and it should not be")
    ratio = answer / expected
    if 0.5 < ratio < 1.5:
        return _bands(abs(ratio - 1), _("too large") if ratio > 1 else _("too small"))
    factor = ratio if ratio > 1 else 1 / ratio
    for low, high in ((1.5, 2), (2, 5), (5, 10), (10, 100)):
        if factor < high:
            return (_("between {low:g} and {high:g} times too large") if ratio > 1 else
                    _("between {low:g} and {high:g} times too small")).format(
                        low=prose_number(low), high=prose_number(high))
    return _("more than 100 times too large") if ratio > 1 else _("more than 100 times too small")


_PIXELS = N_("pixels")


def _off_by(off, units=_PIXELS):
    """``(col, row) is off by about … (right, down)``: how far and which way a position is off."""
    if off[0] > 0:
        direction = _("(right, down)") if off[1] > 0 else _("(right, up)")
    else:
        direction = _("(left, down)") if off[1] > 0 else _("(left, up)")
    distance = float(f"{np.hypot(*off):.2g}")       # two significant digits, never 1.3e+02
    return _("(col, row) is off by about {distance:g} {units} {direction}.").format(
        distance=prose_number(distance), units=_(units), direction=direction)


def position_verdict(declared, value, task, atol, correct, units=_PIXELS):
    """The verdict on a (col, row) ``value``: ``correct`` (translated) within ``atol`` of the
    right position; else which way it is off and the first declared mistake it shows (within
    ``atol``), or the general hint."""
    if np.allclose(value, task.right, rtol=0, atol=atol):
        return Verdict(True, correct)
    hints = declared.hints(value, task, lambda answer, wrong: np.allclose(
        answer, wrong, rtol=0, atol=atol), exclude_right=np.allclose, first=True)
    return Verdict(False, _off_by(value - task.right, units),
                   hints[0] if hints else _(declared.general))


def first_hint(hints, general):
    """The hints found, joined, else the general hint (both translated)."""
    return " ".join(dict.fromkeys(hints)) or _(general)
