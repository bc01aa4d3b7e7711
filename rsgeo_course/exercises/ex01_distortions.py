"""Checks of exercises 1 (chapter 1, systematic distortions): skew, pixel growth, swath."""

import numpy as np

from rsgeo import distortion

from .._i18n import N_
from .engine import Declaration, Mistake, declare

__all__ = ["check_skew", "check_pixel_growth", "check_swath"]

# The scenes chapter 1 computes and prints (its inputs, as in book/01_systematic_distortions):
# an exercise asks about other inputs, and a check recognises an answer copied from the chapter
# by recomputing the chapter's numbers from these inputs.
#: (latitude, frame length km, altitude km, inclination) of the chapter's Earth-rotation frames
_CHAPTER_1_FRAMES = ((0.0, 185.0, 705.0, 98.2), (0.0, 113.0, 778.0, 98.5),
                     (-23.5, 113.0, 778.0, 98.5))
#: (scan or half angle in degrees, altitude km) of the pixel sizes and swaths the chapter prints
#: (MODIS; Landsat, CBERS CCD and SPOT at their half-angles; SPOT pointed 27° off nadir)
_CHAPTER_1_SCANS = ((55.0, 705.0), (7.5, 705.0), (4.2, 778.0), (2.06, 832.0), (29.06, 832.0))
_COPIED_SKEW = N_("That is a number chapter 1 prints for its own frames (another latitude or "
                  "satellite); compute the offset with this task's latitude, frame length, "
                  "altitude and inclination.")
_COPIED_SCAN = N_("That is a number chapter 1 prints for another sensor; compute it with this "
                  "task's scan angle and altitude.")
_RADIANS = N_("NaN here usually means np.arcsin got a value above 1: np.sin, np.cos and "
              "np.arcsin work in radians, so convert angles with np.radians first.")
_DEGREES_HINT = N_("np.cos and np.sin take radians: np.cos(-23.5) is the cosine of 23.5 "
                   "radians. Convert with np.radians first.")
_METRES = N_("That looks like metres; the check wants kilometres.")


def _as_printed(values, decimals):
    """``values`` and each rounded as a chapter prints it (a copied number is a rounded one)."""
    return [v for value in values for v in
            [float(value)] + [round(float(value), d) for d in decimals] if v != 0]


def _skew_by_hand(latitude, frame, altitude, inclination, radians=(True, True), speed_radius=None,
                  cos_phi=True, zeta="cos", divide_by_cos_phi=True):
    """The lecture's Earth-rotation offset, computed the way a student might (right or wrong)."""
    R, RE = distortion.EARTH_RADIUS_KM, distortion.EQUATORIAL_RADIUS_KM
    phi = np.radians(latitude) if radians[0] else latitude
    inc = np.radians(inclination) if radians[1] else inclination
    rate = np.sqrt(distortion.GM_KM3_S2 / (R + altitude) ** 3)
    speed = (R if speed_radius is None else speed_radius) * rate
    sine = abs(np.cos(inc)) / (np.cos(phi) if divide_by_cos_phi else 1.0)
    angle = np.arcsin(sine)
    factor = {"cos": np.cos(angle), "sin": np.sin(angle), "none": 1.0}[zeta]
    return (distortion.EARTH_ROTATION_RAD_S * RE * (np.cos(phi) if cos_phi else 1.0) * frame
            / speed * factor)


def _chapter_1_skews():
    """The offsets chapter 1 prints: each frame's size, west and north components (km)."""
    values = []
    for frame in _CHAPTER_1_FRAMES:
        east, north = distortion.earth_rotation_offset(*frame)
        values += [abs(distortion.earth_rotation_skew(*frame)), abs(east), abs(north)]
    return values


def _skew(**options):
    """A mistake of the skew: the lecture's formula computed with ``options``."""
    return lambda task: float(_skew_by_hand(*task.args, **options))


SKEW = Declaration(
    check="check_skew", answer="skew_km",
    inputs=("latitude_deg", "frame_length_km", "altitude_km", "inclination_deg"),
    derive=lambda task: {"args": (task.latitude_deg, task.frame_length_km, task.altitude_km,
                                  task.inclination_deg)},
    right=lambda task: abs(distortion.earth_rotation_skew(*task.args)),
    general=N_("t = frame length / ground-track speed, ground-track speed = R·sqrt(GM/(R+h)³); "
               "Δx = ωe·Re·cos φ·t·cos ζ with sin ζ = |cos i| / cos φ (chapter 1, Earth "
               "rotation)."),
    mistakes=(
        Mistake(_DEGREES_HINT, _skew(radians=(False, False))),
        Mistake(_DEGREES_HINT, _skew(radians=(False, True))),
        Mistake(_DEGREES_HINT, _skew(radians=(True, False))),
        Mistake(N_("The cos ζ is missing: the ground track is not a meridian, and only the part "
                   "of the Earth's motion across the track (cos ζ) shifts the lines."),
                _skew(zeta="none")),
        Mistake(N_("That is sin ζ where the formula has cos ζ: ζ is the track's angle from the "
                   "meridian."), _skew(zeta="sin")),
        Mistake(N_("The cos φ is missing: the ground moves at ωe·Re·cos φ at latitude φ, slower "
                   "than at the equator."), _skew(cos_phi=False)),
        Mistake(N_("sin ζ = |cos i| / cos φ: the track's angle from the meridian grows with the "
                   "latitude."), _skew(divide_by_cos_phi=False)),
        Mistake(N_("You used the satellite's own speed, (R + h)·sqrt(GM/(R + h)³); the frame is "
                   "imaged at the speed of the ground track, R·sqrt(GM/(R + h)³)."),
                lambda task: float(_skew_by_hand(
                    *task.args, speed_radius=distortion.EARTH_RADIUS_KM + task.altitude_km))),
        Mistake(N_("The check asks for the size of the offset, in km: a positive number."),
                lambda task: -task.right),
        Mistake(_METRES, lambda task: 1000 * task.right),
        Mistake(N_("That is only the offset's west component; the task asks for the whole "
                   "offset, across the ground track: Δx itself."),
                lambda task: abs(distortion.earth_rotation_offset(*task.args)[0])),
        Mistake(N_("That is only the offset's north component; the task asks for the whole "
                   "offset, across the ground track: Δx itself."),
                lambda task: abs(distortion.earth_rotation_offset(*task.args)[1])),
        Mistake(_COPIED_SKEW, lambda task: _as_printed(_chapter_1_skews(), (2,)), many=True),
    ),
    rtol=0.01, mistake_rtol=0.003, units=" km", nan_hint=_RADIANS)


@declare(SKEW)
def check_skew(skew_km, latitude_deg, frame_length_km, altitude_km, inclination_deg):
    """Earth-rotation offset of a frame, computed by hand from the lecture's model.

    The answer is the size (km, positive) of the whole offset of the frame's
    last line relative to its first: its length across the ground track, the
    lecture's Δx, not its west component. The chapter's own frames' numbers
    are recognised as copied.

    Parameters
    ----------
    skew_km : float
        The student's answer.
    latitude_deg, frame_length_km, altitude_km, inclination_deg : float
        The task's scene, as for :func:`rsgeo.distortion.earth_rotation_skew`.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``skew_km`` is still ``...``.

    Examples
    --------
    >>> check_skew(12.6, 0.0, 185.0, 705.0, 98.2)
    Correct: `skew_km` = 12.6 km.
    """
    task = SKEW.task(latitude_deg=latitude_deg, frame_length_km=frame_length_km,
                     altitude_km=altitude_km, inclination_deg=inclination_deg)
    return SKEW.judge(skew_km, task)


def _growth_derived(task):
    along, across = (float(size) for size in distortion.pixel_size(task.scan_angle_deg,
                                                                   task.altitude_km))
    return {"along": along, "across": across, "theta": np.radians(task.scan_angle_deg)}


def _chapter_1_growths(task):
    """The growths chapter 1 prints, curved and flat Earth, as printed."""
    copied = []
    for scan in _CHAPTER_1_SCANS:
        for curved in (True, False):
            sizes = distortion.pixel_size(*scan, curved_earth=curved)
            copied += _as_printed([100 * (float(size) - 1.0) for size in sizes], (2, 1))
    return copied


PIXEL_GROWTH = Declaration(
    check="check_pixel_growth", answer="growth_percent", inputs=("scan_angle_deg", "altitude_km"),
    derive=_growth_derived,
    right=lambda task: 100 * (task.across - 1.0),
    general=N_("Across-track size = β·s / cos z: the slant range s, and z from sin z = "
               "((R+h)/R)·sin θ. Growth = (size at θ / size at nadir − 1) × 100."),
    mistakes=(
        Mistake(N_("That is the flat-Earth growth, sec² θ − 1; on a curved Earth use the slant "
                   "range s and the zenith angle z: across = β·s / cos z."),
                lambda task: 100 * (1 / np.cos(task.theta) ** 2 - 1)),
        Mistake(N_("sec θ − 1 is the flat-Earth along-track growth; the task asks across-track, "
                   "on a curved Earth."), lambda task: 100 * (1 / np.cos(task.theta) - 1)),
        Mistake(N_("That is the along-track growth (β·s); across-track the pixel is also "
                   "tilted: divide by cos z."), lambda task: 100 * (task.along - 1.0)),
        Mistake(N_("Divide by cos z, the zenith angle seen from the ground, not by cos θ, the "
                   "scan angle: sin z = ((R + h)/R)·sin θ."),
                lambda task: 100 * (task.along / np.cos(task.theta) - 1.0)),
        Mistake(N_("That is the size relative to nadir in %; the growth is that minus 100."),
                lambda task: 100 * task.across),
        Mistake(N_("That is the size relative to nadir (a ratio); the growth is (ratio − 1) × "
                   "100, in %."), lambda task: task.across),
        Mistake(N_("That is a fraction; the check wants per cent: multiply by 100."),
                lambda task: task.across - 1.0),
        Mistake(_COPIED_SCAN, _chapter_1_growths, many=True),
    ),
    rtol=0.02, units=" %", nan_hint=_RADIANS)


@declare(PIXEL_GROWTH)
def check_pixel_growth(growth_percent, scan_angle_deg, altitude_km):
    """Across-track growth (%) of a pixel at a scan angle, curved Earth, relative to nadir.

    Parameters
    ----------
    growth_percent : float
        The student's answer, in per cent.
    scan_angle_deg, altitude_km : float
        The task's scan angle and altitude.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``growth_percent`` is still ``...``.

    Examples
    --------
    >>> check_pixel_growth(383.0, 55.0, 705.0)     # MODIS's edge pixel: 4.83 × the nadir one
    Correct: `growth_percent` = 383 %.
    """
    task = PIXEL_GROWTH.task(scan_angle_deg=scan_angle_deg, altitude_km=altitude_km)
    return PIXEL_GROWTH.judge(growth_percent, task)


def _swath_derived(task):
    theta = np.radians(task.half_angle_deg)
    zenith = np.radians(float(distortion.zenith_angle(task.half_angle_deg, task.altitude_km)))
    return {"R": distortion.EARTH_RADIUS_KM, "h": task.altitude_km, "theta": theta,
            "gamma": zenith - theta}


SWATH = Declaration(
    check="check_swath", answer="swath_km", inputs=("half_angle_deg", "altitude_km"),
    derive=_swath_derived,
    right=lambda task: distortion.swath_width(task.half_angle_deg, task.altitude_km),
    general=N_("The angle at the Earth's centre is γ = z − θ; the swath is 2·R·γ (γ in "
               "radians)."),
    mistakes=(
        Mistake(N_("2·h·tan θ is the flat-Earth swath; the Earth curves away under a wide scan, "
                   "so the swath is longer: 2·R·γ with γ = z − θ."),
                lambda task: 2 * task.h * np.tan(task.theta)),
        Mistake(N_("R·γ is half the swath, from nadir to one edge; the scan goes to both "
                   "sides."), lambda task: task.R * task.gamma),
        Mistake(N_("2·R·sin γ is the straight chord; the swath is the arc along the ground, "
                   "2·R·γ."), lambda task: 2 * task.R * np.sin(task.gamma)),
        Mistake(N_("γ must be in radians for the arc length R·γ."),
                lambda task: 2 * task.R * np.degrees(task.gamma)),
        Mistake(N_("γ = z − θ: subtract the scan angle from the zenith angle."),
                lambda task: 2 * task.R * (task.gamma + task.theta)),
        Mistake(N_("The arc is on the ground, radius R, not at the satellite's radius R + h."),
                lambda task: 2 * (task.R + task.h) * task.gamma),
        Mistake(_METRES, lambda task: 1000 * task.right),
        Mistake(_COPIED_SCAN, lambda task: _as_printed(
            [distortion.swath_width(*scan, curved_earth=curved)
             for scan in _CHAPTER_1_SCANS for curved in (True, False)], (1, 0)), many=True),
    ),
    rtol=0.005, units=" km", nan_hint=_RADIANS)


@declare(SWATH)
def check_swath(swath_km, half_angle_deg, altitude_km):
    """Swath width (km) on a curved Earth.

    Parameters
    ----------
    swath_km : float
        The student's answer.
    half_angle_deg, altitude_km : float
        The scan's half angle and the altitude.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``swath_km`` is still ``...``.

    Examples
    --------
    >>> check_swath(185.5, 7.5, 705.0)
    Correct: `swath_km` = 185.5 km.
    """
    task = SWATH.task(half_angle_deg=half_angle_deg, altitude_km=altitude_km)
    return SWATH.judge(swath_km, task)
