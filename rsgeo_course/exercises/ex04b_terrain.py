"""Checks of exercises 4b (chapter 4b, relief displacement, RPCs and the geoid)."""

import numpy as np

from rsgeo import relief, sensors

from .._i18n import N_, _
from .engine import Declaration, Mistake, WrongForm, declare, position_verdict, two_numbers

__all__ = ["check_displacement", "check_height_budget", "check_rpc_position",
           "check_geoid_shift"]

DISPLACEMENT = Declaration(
    check="check_displacement", answer="displacement_m", inputs=("height_m", "view_zenith_deg"),
    derive=lambda task: {"angle": np.radians(task.view_zenith_deg)},
    right=lambda task: relief.relief_displacement(task.height_m, task.view_zenith_deg),
    general=N_("The line of sight leans θ from the vertical: over a height h it moves h·tan θ "
               "sideways (np.tan takes radians)."),
    mistakes=(
        Mistake(N_("np.tan takes radians: np.tan(25) is the tangent of 25 radians. Convert the "
                   "angle with np.radians first."),
                lambda task: float(task.height_m * np.tan(task.view_zenith_deg))),
        Mistake(N_("That is h·sin θ; the displacement is h·tan θ (the horizontal leg of a "
                   "triangle whose vertical leg is h)."),
                lambda task: task.height_m * np.sin(task.angle)),
        Mistake(N_("That is h·cos θ; the displacement is h·tan θ."),
                lambda task: task.height_m * np.cos(task.angle)),
        Mistake(N_("You divided by tan θ; multiply: d = h·tan θ."),
                lambda task: float(task.height_m / np.tan(task.angle))),
        Mistake(N_("Give the answer in metres, not kilometres."),
                lambda task: task.height_m * np.tan(task.angle) / 1000),
    ),
    rtol=5e-3, units=" m")


@declare(DISPLACEMENT)
def check_displacement(displacement_m, height_m, view_zenith_deg):
    """Relief displacement by hand: a point ``height_m`` high seen at ``view_zenith_deg``.

    Parameters
    ----------
    displacement_m : float
        The student's answer, in metres on the ground.
    height_m : float
        Height of the point above the datum (m).
    view_zenith_deg : float
        View zenith angle (degrees).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``displacement_m`` is still ``...``.

    Examples
    --------
    >>> check_displacement(100.0, 100.0, 45.0)
    Correct: `displacement_m` = 100 m.
    """
    return DISPLACEMENT.judge(displacement_m, DISPLACEMENT.task(
        height_m=height_m, view_zenith_deg=view_zenith_deg))


HEIGHT_BUDGET = Declaration(
    check="check_height_budget", answer="height_error_m",
    inputs=("position_error_m", "view_zenith_deg"),
    derive=lambda task: {"angle": np.radians(task.view_zenith_deg)},
    right=lambda task: relief.height_error_budget(task.position_error_m, task.view_zenith_deg),
    general=N_("Solve Δx = Δh·tan θ for Δh."),
    mistakes=(
        Mistake(N_("You multiplied by tan θ: a height error Δh moves the point Δh·tan θ, so "
                   "divide the budget by tan θ."),
                lambda task: task.position_error_m * np.tan(task.angle)),
        Mistake(N_("np.tan takes radians: convert the angle with np.radians first."),
                lambda task: float(task.position_error_m / np.tan(task.view_zenith_deg))),
        Mistake(N_("That divides by sin θ; the displacement is Δh·tan θ, so divide by tan θ."),
                lambda task: task.position_error_m / np.sin(task.angle)),
    ),
    rtol=5e-3, units=" m")


@declare(HEIGHT_BUDGET)
def check_height_budget(height_error_m, position_error_m, view_zenith_deg):
    """The DEM height error that a horizontal position budget allows at a view zenith angle.

    Parameters
    ----------
    height_error_m : float
        The student's answer (m).
    position_error_m : float
        The allowed horizontal error (m).
    view_zenith_deg : float
        View zenith angle (degrees).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``height_error_m`` is still ``...``.

    Examples
    --------
    >>> check_height_budget(10.0, 10.0, 45.0)
    Correct: `height_error_m` = 10 m.
    """
    return HEIGHT_BUDGET.judge(height_error_m, HEIGHT_BUDGET.task(
        position_error_m=position_error_m, view_zenith_deg=view_zenith_deg))


def _rpc_derived(task):
    model = sensors.RPCModel.from_dict(task.rpc_mapping)
    return {"model": model,
            "flat": np.array([float(v) for v in model.project(task.lon, task.lat,
                                                              model.offsets["HEIGHT"])])}


RPC_POSITION = Declaration(
    check="check_rpc_position", answer="position",
    inputs=("rpc_mapping", "lon", "lat", "height"),
    derive=_rpc_derived,
    right=lambda task: np.array([float(v) for v in task.model.project(task.lon, task.lat,
                                                                      task.height)]),
    general=N_("Normalise lon, lat and height with the offsets and scales, evaluate the four "
               "20-term polynomials in GDAL's order, divide numerator by denominator, "
               "de-normalise with SAMP/LINE scale and offset, then add 0.5."),
    mistakes=(
        Mistake(N_("RPC sample and line are 0 at the centre of the first pixel; GDAL's (col, "
                   "row) are 0 at its corner: add 0.5 to both."),
                lambda task: task.right - 0.5),
        Mistake(N_("col and row are swapped: col comes from SAMP_*, row from LINE_*."),
                lambda task: task.right[::-1]),
        Mistake(N_("col and row are swapped (col from SAMP_*, row from LINE_*), and add 0.5 to "
                   "both."), lambda task: task.right[::-1] - 0.5),
        Mistake(N_("The height was left out: normalise it with HEIGHT_OFF and HEIGHT_SCALE "
                   "too."), lambda task: task.flat),
    ))


@declare(RPC_POSITION)
def check_rpc_position(position, rpc_mapping, lon, lat, height):
    """Reading an RPC: the image (col, row) of a ground point, GDAL's pixel convention.

    Parameters
    ----------
    position : (float, float)
        The student's (col, row), with (0, 0) at the image's top-left corner.
    rpc_mapping : mapping
        The RPC metadata the task gives (GDAL keys).
    lon, lat, height : float
        The ground point (degrees, degrees, metres).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``position`` is still ``...``.
    ValueError
        If ``rpc_mapping`` is not a valid RPC (the task's, not the student's, mistake).

    Examples
    --------
    >>> rpc = sensors.simple_rpc_dict()
    >>> check_rpc_position((500.5, 500.5), rpc, -34.9, -8.0, 0.0)
    Correct: (col, row) is where the RPC puts the point.
    """
    try:
        value = two_numbers(position, "position")
    except WrongForm as form:
        return form.verdict(_(RPC_POSITION.general))
    task = RPC_POSITION.task(rpc_mapping=rpc_mapping, lon=lon, lat=lat, height=height)
    return position_verdict(RPC_POSITION, value, task, 1e-3,
                             _("(col, row) is where the RPC puts the point."))


def _geoid_derived(task):
    angle = np.radians(task.view_zenith_deg)
    return {"angle": angle, "metres": -task.geoid_undulation_m * np.tan(angle)}


GEOID_SHIFT = Declaration(
    check="check_geoid_shift", answer="shift_px",
    inputs=("geoid_undulation_m", "view_zenith_deg", "pixel_m"),
    derive=_geoid_derived,
    right=lambda task: task.metres / task.pixel_m,
    general=N_("The RPC was given H where it needs h = H + N: every height is off by -N, and a "
               "height error Δh moves a point Δh·tan θ away from the nadir. Divide by the pixel "
               "size for pixels."),
    mistakes=(
        Mistake(N_("Mind the sign: the DEM's H is h - N, so the height the RPC got is off by -N. "
                   "With N > 0 the points are taken too low and move towards the nadir "
                   "(negative)."),
                lambda task: -task.right),
        Mistake(N_("That is N·sin θ; a height error moves a point Δh·tan θ (the horizontal leg "
                   "of a triangle whose vertical leg is Δh)."),
                lambda task: -task.geoid_undulation_m * np.sin(task.angle) / task.pixel_m),
        Mistake(N_("That is in metres on the ground; the task asks for pixels: divide by the "
                   "pixel size."),
                lambda task: task.metres),
        Mistake(N_("That is N itself, without the view angle: a height error moves a point "
                   "sideways by Δh·tan θ (at nadir it would not move at all)."),
                lambda task: [-task.geoid_undulation_m / task.pixel_m,
                              -task.geoid_undulation_m],
                many=True),
        Mistake(N_("np.tan takes radians: convert the angle with np.radians first."),
                lambda task: float(-task.geoid_undulation_m * np.tan(task.view_zenith_deg)
                                   / task.pixel_m)),
    ),
    rtol=5e-3, units=" px")


@declare(GEOID_SHIFT)
def check_geoid_shift(shift_px, geoid_undulation_m, view_zenith_deg, pixel_m):
    """Forgetting the geoid: how far an orthoimage moves when N is not added to the DEM.

    Parameters
    ----------
    shift_px : float
        The student's answer: the displacement of every point in pixels, positive away
        from the nadir, negative towards it.
    geoid_undulation_m : float
        The geoid undulation N at the scene (m): h = H + N.
    view_zenith_deg : float
        View zenith angle (degrees).
    pixel_m : float
        Pixel size on the ground (m).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``shift_px`` is still ``...``.

    Examples
    --------
    >>> check_geoid_shift(-1.0, 10.0, 45.0, 10.0)
    Correct: `shift_px` = -1 px.
    """
    return GEOID_SHIFT.judge(shift_px, GEOID_SHIFT.task(
        geoid_undulation_m=geoid_undulation_m, view_zenith_deg=view_zenith_deg,
        pixel_m=pixel_m))
