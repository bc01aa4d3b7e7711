"""Checks of exercises 5 (chapter 5, the regression paper): gain and offset, truncation, filters.

References
----------
The regression paper: *Linear regression to match the contrast of overlapping aerial
photographs* (seed document 000 of this course).
"""

import numpy as np

from rsgeo import radiometry

from .._i18n import N_, _, prose_number
from .engine import (
    Declaration,
    Mistake,
    Verdict,
    WrongForm,
    declare,
    first_hint,
    how_far,
    integer,
    near,
    number,
    require,
)

__all__ = ["check_gain_offset", "check_truncation_levels", "check_filter_size"]


def _regression_derived(task):
    xs = np.asarray(task.x, dtype=float).ravel()
    ys = np.asarray(task.y, dtype=float).ravel()
    covariance = np.mean((xs - xs.mean()) * (ys - ys.mean()))
    return {"fit": radiometry.fit_gain_offset(task.x, task.y), "xs": xs, "ys": ys, "n": xs.size,
            "backwards": covariance / ys.var()}


_DDOF = N_("np.cov divides by n − 1 and np.var by n: use the same (ddof) in both.")
_OFFSET_SIGN = N_("Mind the sign: offset = ȳ − gain·x̄.")

GAIN_OFFSET = Declaration(
    check="check_gain_offset", answer="gain, offset", inputs=("x", "y"),
    derive=_regression_derived,
    right=lambda task: (task.fit.gain, task.fit.offset),
    general=N_("gain = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)²; then offset = ȳ − gain·x̄."),
    mistakes=(
        Mistake(N_("You regressed X on Y: X, the image to correct, is the independent variable; "
                   "divide the covariance by the variance of X."),
                lambda task: (task.backwards, None)),
        Mistake(N_("You fitted X = g·Y + o and inverted it: that is a different line. Regress Y "
                   "on X (divide the covariance by the variance of X)."),
                lambda task: (1 / task.backwards, None)),
        Mistake(_DDOF, lambda task: (task.fit.gain * task.n / (task.n - 1), None)),
        Mistake(_DDOF, lambda task: (task.fit.gain * (task.n - 1) / task.n, None)),
        Mistake(N_("ȳ / x̄ is a gain through the origin; least squares uses the covariance over "
                   "the variance of X."), lambda task: (task.ys.mean() / task.xs.mean(), None)),
        Mistake(N_("σy / σx is the reduced-major-axis gain; ordinary least squares multiplies it "
                   "by the correlation r."), lambda task: (task.ys.std() / task.xs.std(), None)),
        Mistake(N_("The gain is missing: offset = ȳ − gain·x̄."),
                lambda task: (task.fit.gain, task.ys.mean() - task.xs.mean())),
        Mistake(_OFFSET_SIGN,
                lambda task: (task.fit.gain, task.ys.mean() + task.fit.gain * task.xs.mean())),
        Mistake(_OFFSET_SIGN,
                lambda task: (task.fit.gain, task.fit.gain * task.xs.mean() - task.ys.mean())),
        Mistake(N_("x̄ and ȳ are swapped: offset = ȳ − gain·x̄."),
                lambda task: (task.fit.gain, task.xs.mean() - task.fit.gain * task.ys.mean())),
        Mistake(N_("offset = ȳ − gain·x̄: the line passes through the means.")),   # any other
    ))
_ANY_OFFSET = GAIN_OFFSET.mistakes[-1]


def _one_part(part, rtol=1e-6):
    """Compare a (gain, offset) answer with a mistake's on ``part`` (0 gain, 1 offset) alone;
    a mistake of the other part (None there) or with the other part wrong does not count."""
    def same(answer, wrong):
        if wrong[part] is None or (part == 1 and not near(answer[0], wrong[0], rtol)):
            return False
        return near(answer[part], float(wrong[part]), rtol)
    return same


@declare(GAIN_OFFSET)
def check_gain_offset(gain, offset, x, y):
    """Gain and offset of Y = gain·X + offset from the normal equations.

    Parameters
    ----------
    gain, offset : float
        The student's answers.
    x, y : ndarray
        The independent (X) and dependent (Y) images, same shape.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``gain`` or ``offset`` is still ``...``.

    References
    ----------
    The regression paper: *Linear regression to match the contrast of
    overlapping aerial photographs* (seed document 000 of this course).

    Examples
    --------
    >>> x = np.arange(10.0)
    >>> check_gain_offset(2.0, 1.0, x, 2 * x + 1)
    Correct: gain 2.0000, offset 1.000.
    """
    generic = GAIN_OFFSET.general
    try:
        require(gain, "gain"), require(offset, "offset")
        gain_value = number(gain, "gain", generic)
        offset_value = number(offset, "offset", generic)
    except WrongForm as form:
        return form.verdict(_(generic))
    task = GAIN_OFFSET.task(x=x, y=y)
    fit, answer = task.fit, (gain_value, offset_value)
    if not near(gain_value, fit.gain, 1e-6):
        hints = GAIN_OFFSET.hints(answer, task, _one_part(0),
                                  exclude_right=lambda wrong, right: near(wrong[0], right[0],
                                                                           1e-6))
        return Verdict(False, _("`gain` is {how}.").format(how=how_far(gain_value, fit.gain)),
                       " ".join(hints) or _(generic))
    if not near(offset_value, fit.offset, 1e-6):
        hints = GAIN_OFFSET.hints(answer, task, _one_part(1), exclude_right=lambda wrong, right:
                                  wrong[1] is not None and near(wrong[1], right[1], 1e-6))
        return Verdict(False, _("`gain` is right; `offset` is {how}.").format(
            how=how_far(offset_value, fit.offset)), " ".join(hints) or _ANY_OFFSET.text())
    return Verdict(True, _("gain {gain:.4f}, offset {offset:.3f}.").format(
        gain=prose_number(fit.gain), offset=prose_number(fit.offset)))


def _truncation_derived(task):
    dns = np.arange(256)
    return {"dns": dns, "stretched": task.gain * dns + task.offset}


TRUNCATION_LEVELS = Declaration(
    check="check_truncation_levels", answer="levels", inputs=("gain", "offset"),
    derive=_truncation_derived,
    right=lambda task: len(np.unique(radiometry.apply_gain_offset(
        task.dns.astype(np.uint8), task.gain, task.offset))),
    general=N_("Apply the stretch to np.arange(256), truncate, clip, and count np.unique. With "
               "gain < 1, some neighbouring DNs fall on the same integer."),
    mistakes=(
        Mistake(N_("256 would mean no two DNs merge; with gain < 1 some fall on the same integer "
                   "once truncated."), lambda task: 256),
        Mistake(N_("You rounded; the paper (IDRISI's SCALAR) truncates: np.trunc or "
                   ".astype(int)."),
                lambda task: len(np.unique(np.clip(np.round(task.stretched), 0, 255)))),
        Mistake(N_("Clip to 0-255 as well: an 8-bit image holds no other value."),
                lambda task: len(np.unique(np.trunc(task.stretched)))),
        Mistake(N_("That is how many levels are LOST; the task asks how many remain."),
                lambda task: 256 - task.right),
        Mistake(N_("Not every integer between the smallest and the largest output needs to be "
                   "hit: count the distinct values themselves."),
                lambda task: int(np.floor(task.stretched.max()))
                - int(np.floor(task.stretched.min())) + 1),
    ))


@declare(TRUNCATION_LEVELS)
def check_truncation_levels(levels, gain, offset):
    """How many distinct DNs an 8-bit image with every value 0-255 keeps after gain/offset +
    truncation.

    Parameters
    ----------
    levels : int
        The student's answer.
    gain, offset : float
        The stretch.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``levels`` is still ``...``.

    Examples
    --------
    >>> check_truncation_levels(128, 0.5, 0.0)
    Correct: 128 distinct levels: a gain below 1 merges neighbouring DNs.
    """
    task = TRUNCATION_LEVELS.task(gain=gain, offset=offset)
    try:
        levels = integer(levels, "levels", _("a count"), many=_(
            "`levels` holds many values (the levels themselves?); the check needs how many "
            "there are: len(...) of them."))
    except WrongForm as form:
        return form.verdict(_(TRUNCATION_LEVELS.general))
    if levels == task.right:
        return Verdict(True, _("{levels} distinct levels: a gain below 1 merges neighbouring "
                               "DNs.").format(levels=levels))
    hints = TRUNCATION_LEVELS.hints(levels, task, lambda answer, wrong: answer == wrong)
    return Verdict(False, _("`levels` is {how}.").format(how=how_far(levels, task.right)),
                   first_hint(hints, TRUNCATION_LEVELS.general))


def _filter_derived(task):
    def correlations(x, y):
        return {s: radiometry.fit_gain_offset(x, y, smooth=s if s > 1 else None).r
                for s in task.sizes}
    return {"r": correlations(task.x_image, task.y_image),
            "twice": lambda: correlations(radiometry.mean_filter(task.x_image, 3),
                                          radiometry.mean_filter(task.y_image, 3))}


def _smallest(task, r, key=lambda value: value):
    """The smallest size whose correlation (through ``key``) reaches the target."""
    return next((s for s in task.sizes if key(r[s]) >= task.target_r), None)


FILTER_SIZE = Declaration(
    check="check_filter_size", answer="size", inputs=("x_image", "y_image", "target_r", "sizes"),
    derive=_filter_derived,
    right=lambda task: _smallest(task, task.r),
    general=N_("Fit with smooth=3, 5, 7 ... and keep the smallest window whose r reaches the "
               "target: a bigger window blurs the very detail a mosaic should keep."),
    mistakes=(
        Mistake(N_("The largest r is not the goal: the SMALLEST window that reaches the target "
                   "keeps the most detail."), lambda task: max(task.r, key=task.r.get)),
        Mistake(N_("The target is for r, not r²."),
                lambda task: _smallest(task, task.r, key=lambda value: value ** 2)),
        Mistake(N_("Use the ORIGINAL images pair.x_image and pair.y_image: x and y are already "
                   "filtered with a 3 × 3 mean."), lambda task: _smallest(task, task.twice())),
    ))


@declare(FILTER_SIZE)
def check_filter_size(size, x_image, y_image, target_r=0.8, sizes=(1, 3, 5, 7, 9)):
    """The smallest mean-filter size whose regression reaches a correlation of ``target_r``.

    Parameters
    ----------
    size : int
        The student's answer, one of ``sizes`` (1 = no filter).
    x_image, y_image : ndarray
        The ORIGINAL (unfiltered) images.
    target_r : float
    sizes : tuple of int

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``size`` is still ``...``.

    References
    ----------
    The regression paper: *Linear regression to match the contrast of
    overlapping aerial photographs* (seed document 000 of this course).

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> pair = synthetic.contrast_pair(seed=4)
    >>> print(check_filter_size(4, pair.x_image, pair.y_image).message)
    `size` is 4: choose among the sizes offered, 1, 3, 5, 7, 9. An even window has no centre pixel.
    """
    generic = FILTER_SIZE.general
    try:
        size = integer(size, "size", _("a filter size (the side of the square window)"),
                        many=_("`size` holds several values; the check needs one number, the "
                               "side n of the n × n window."))
        if size not in sizes:
            message = _("`size` is {size}: choose among the sizes offered, {sizes}.").format(
                size=size, sizes=", ".join(map(str, sizes)))
            if size > 0 and size % 2 == 0:
                message += " " + _("An even window has no centre pixel.")
            raise WrongForm(message)
    except WrongForm as form:
        return form.verdict(_(generic))
    task = FILTER_SIZE.task(x_image=x_image, y_image=y_image, target_r=target_r, sizes=sizes)
    r, best = task.r, task.right
    if best is None:
        return Verdict(False, _("no filter size in the list reaches the target here."))
    if size == best:
        return Verdict(True, _("{size} × {size}: r = {r:.3f}, the first to reach {target}.")
                       .format(size=size, r=prose_number(r[size]),
                               target=prose_number(target_r)))
    hints = FILTER_SIZE.hints(size, task, lambda answer, wrong: answer == wrong)
    if r[size] < target_r:
        message = _("{size} × {size} gives r = {r:.3f}, below the target {target}: too small a "
                    "window.")
    else:
        message = _("{size} × {size} reaches r = {r:.3f}, but a smaller window reaches {target} "
                    "too.")
    return Verdict(False, message.format(size=size, r=prose_number(r[size]),
                                         target=prose_number(target_r)),
                   first_hint(hints, generic))
