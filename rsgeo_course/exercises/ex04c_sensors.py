"""Checks of exercises 4c (chapter 4c, raw scenes and RPC bias compensation)."""

import numpy as np

from rsgeo.errors import GCPError
from rsgeo.validation import as_number, as_points

from .._i18n import N_, _
from .engine import Declaration, Mistake, WrongForm, declare, position_verdict, two_numbers

__all__ = ["check_bias_shift", "check_compensated_rms"]


def _residuals(measured, projected):
    measured = as_points(measured, "measured")
    projected = as_points(projected, "projected")
    if measured.shape != projected.shape:
        raise GCPError(_("measured and projected must hold the same GCPs, got shapes {a} and "
                         "{b}").format(a=measured.shape, b=projected.shape))
    return measured - projected


BIAS_SHIFT = Declaration(
    check="check_bias_shift", answer="shift", inputs=("measured", "projected"),
    derive=lambda task: {"d": _residuals(task.measured, task.projected)},
    right=lambda task: task.d.mean(axis=0),
    general=N_("The least-squares shift is the mean residual: for each GCP, measured (col, row) "
               "minus the RPC's (col, row); average the columns and the rows separately."),
    mistakes=(
        Mistake(N_("Mind the sign: the shift moves the RPC's positions onto the measured ones, "
                   "so it is measured minus RPC, not RPC minus measured."),
                lambda task: -task.right),
        Mistake(N_("You averaged the residuals' absolute values; the shift is the mean of the "
                   "signed residuals (a bias to the left and one to the right cancel)."),
                lambda task: np.abs(task.d).mean(axis=0)),
        Mistake(N_("That is the RMS of the residuals, which has no sign; the least-squares shift "
                   "is their plain mean."),
                lambda task: np.sqrt(np.mean(task.d ** 2, axis=0))),
        Mistake(N_("col and row are swapped: the first number is the shift in columns."),
                lambda task: task.right[::-1]),
        Mistake(N_("That is the median; least squares gives the mean of the residuals."),
                lambda task: np.median(task.d, axis=0)),
    ))


@declare(BIAS_SHIFT)
def check_bias_shift(shift, measured, projected):
    """The image-space shift that compensates an RPC's bias, from GCPs.

    Parameters
    ----------
    shift : (float, float)
        The student's (Δcol, Δrow), in pixels.
    measured : (n, 2) array_like
        The GCPs' measured image positions (col, row).
    projected : (n, 2) array_like
        Where the RPC puts the GCPs' ground points (col, row).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``shift`` is still ``...``.
    rsgeo.errors.GCPError
        If ``measured`` and ``projected`` are not two (n, 2) arrays of one shape.

    Examples
    --------
    >>> check_bias_shift((1.0, -2.0), [[11.0, 8.0], [21.0, 18.0]], [[10.0, 10.0], [20.0, 20.0]])
    Correct: (Δcol, Δrow) is the mean residual of the GCPs.
    """
    try:
        value = two_numbers(shift, "shift")
    except WrongForm as form:
        return form.verdict(_(BIAS_SHIFT.general))
    task = BIAS_SHIFT.task(measured=measured, projected=projected)
    return position_verdict(BIAS_SHIFT, value, task, 1e-3,
                             _("(Δcol, Δrow) is the mean residual of the GCPs."))


def _compensated(task):
    residuals = as_points(task.residuals, "residuals")
    shift = as_points(task.shift, "shift")[0]
    size = as_number(task.pixel_size, "pixel_size", low=1e-9, why="metres per pixel")
    return {"left": residuals - shift, "plus": residuals + shift, "raw": residuals,
            "size": size}


def _rms(d):
    return float(np.sqrt(np.mean(np.sum(d ** 2, axis=1))))


COMPENSATED_RMS = Declaration(
    check="check_compensated_rms", answer="rms_m", inputs=("residuals", "shift", "pixel_size"),
    derive=_compensated,
    right=lambda task: _rms(task.left) * task.size,
    general=N_("Subtract the shift from each check point's residual, then take the lecture's "
               "RMS, sqrt(Σ(dcol² + drow²) / n), and multiply by the pixel size."),
    mistakes=(
        Mistake(N_("Mind the sign: the residuals are measured minus RPC and so is the shift; "
                   "subtract it (adding it doubles the bias)."),
                lambda task: _rms(task.plus) * task.size),
        Mistake(N_("That is the check points' RMS before the compensation: subtract the shift "
                   "from each residual first."),
                lambda task: _rms(task.raw) * task.size),
        Mistake(N_("That is in pixels; multiply by the pixel size to get metres."),
                lambda task: _rms(task.left)),
        Mistake(N_("Multiply by the pixel size (metres per pixel), do not divide."),
                lambda task: _rms(task.left) / task.size),
        Mistake(N_("That is the mean of the distances; the RMS squares them, averages and takes "
                   "the root."),
                lambda task: float(np.mean(np.hypot(*task.left.T))) * task.size),
        Mistake(N_("Dividing by 2n (every coordinate apart) gives the RMS per coordinate; the "
                   "lecture's RMS sums dcol² + drow² per point and divides by n."),
                lambda task: float(np.sqrt(np.mean(task.left ** 2))) * task.size),
    ),
    rtol=0.01, mistake_rtol=0.01, units=" m")


@declare(COMPENSATED_RMS)
def check_compensated_rms(rms_m, residuals, shift, pixel_size):
    """The check points' RMS in metres after an RPC's bias is compensated by a shift.

    Parameters
    ----------
    rms_m : float
        The student's answer (m).
    residuals : (n, 2) array_like
        The check points' residuals before compensation: measured minus RPC (col, row), pixels.
    shift : (float, float)
        The compensating shift (Δcol, Δrow) in pixels, fitted to GCPs.
    pixel_size : float
        Metres per pixel.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``rms_m`` is still ``...``.
    ValueError
        If the inputs are malformed (the task's mistake, not the student's).

    Examples
    --------
    >>> check_compensated_rms(10.0, [[1.0, 1.0], [1.0, 3.0]], (1.0, 2.0), 10.0)
    Correct: `rms_m` = 10 m.
    """
    return COMPENSATED_RMS.judge(rms_m, COMPENSATED_RMS.task(
        residuals=residuals, shift=shift, pixel_size=pixel_size))
