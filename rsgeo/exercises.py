"""Checks for the course's exercises: a verdict that teaches, not a bare assert.

Every task in ``exercises/`` ends with a call such as ``check_rms(rms, ...)``.
The check recomputes the right answer with rsgeo and returns a
:class:`Verdict`: "Correct", or "Not yet" with what is wrong and a hint.

A check judges an answer in this order:

1. the placeholder ``...`` (the student edition's) raises
   :class:`ExerciseNotSolved`, so that running the notebook stops at the
   first task still to do;
2. the answer's *form*: ``None`` (a function that returned nothing), a string,
   a tuple, an array where one number is needed, a GCP index where an id is
   needed, a method name or a degree outside the offered choices, NaN; each
   gets a message about the form;
3. its *value*: which way and roughly how far it is off (never the expected
   value itself), with the hint for the mistake the check recognises. A
   mistake is recognised by recomputing the wrong answer it produces (cos of
   an angle in degrees, a flat Earth, RMS over 2n, least significant bit
   first ...) and comparing; an answer that matches no known mistake gets the
   task's general hint.
"""

import ast
import html
import inspect
from dataclasses import dataclass

import affine
import numpy as np

from . import distortion, gcp, georef, radiometry, resample
from . import terrain
from . import tiepoints
from ._checks import as_points, as_shape
from ._i18n import _
from .matching import BITS_PER_GENE, decode, fitness

__all__ = [
    "ExerciseNotSolved", "Verdict", "check_skew", "check_pixel_growth", "check_swath",
    "check_design_matrix", "check_rms", "check_blunder", "check_degree_choice",
    "check_bilinear", "check_method_for_classes", "check_overshoot", "check_gain_offset",
    "check_truncation_levels", "check_filter_size", "check_fitness", "check_decode",
    "check_suboptimal_segment", "check_datum_shift_pixels",
    "check_helmert", "check_projective_matrix", "check_model_choice",
    "check_output_pixel_size", "check_grid_extent",
    "recognised_mistakes",
    "check_displacement", "check_height_budget", "check_rpc_position",
    "check_keypoint_position", "check_composed_tiepoint", "check_check_point_error",
]


class ExerciseNotSolved(Exception):
    """Raised by a check when the answer is still the ``...`` placeholder."""


@dataclass
class Verdict:
    """The outcome of a check: ``ok``, and a message with a hint when not ok.

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

    # Shown in the course's language (rsgeo._i18n: RSGEO_LANG=pt_BR gives "Correto"): the labels,
    # and a message or hint written as one sentence in a check (locales/update.py puts every such
    # sentence of this module in the catalogue); a composed message (_judge, _how_far) is
    # translated when the check composes it.
    def __repr__(self):
        if self.ok:
            return _("Correct") + f": {_(self.message)}"
        hint = "\n" + _("Hint") + f": {_(self.hint)}" if self.hint else ""
        return _("Not yet") + f": {_(self.message)}" + hint

    def _repr_html_(self):
        colour, title = ("#1a7f37", _("Correct")) if self.ok else ("#b35900", _("Not yet"))
        hint = ("<br><em>" + _("Hint") + f":</em> {html.escape(_(self.hint))}"
                if (self.hint and not self.ok) else "")
        return (f'<div class="rsgeo-verdict" style="border-left:4px solid {colour};padding:4px 8px">'
                f"<strong>{title}:</strong> {html.escape(_(self.message))}{hint}</div>")


# -- The form of an answer ---------------------------------------------------

class _WrongForm(Exception):
    """An answer of the wrong form; carries the message a student sees."""

    def __init__(self, message, hint=""):
        super().__init__(message)
        self.message, self.hint = message, hint

    def verdict(self, hint=""):
        return Verdict(False, self.message, self.hint or hint)


def _require(answer, name):
    if answer is Ellipsis:
        raise ExerciseNotSolved(_(
            "`{name}` is still `...`: this task is yours. Write your answer in the cell above, "
            "run it, then run this check again.").format(name=name))
    if answer is None:
        raise _WrongForm(_("`{name}` is None: did your function return its value? "
                           "A function without `return` gives None.").format(name=name))
    return answer


def _number(answer, name, nan_hint="", many=""):
    """``answer`` as one finite float; raises _WrongForm (or ExerciseNotSolved) otherwise."""
    answer = _require(answer, name)
    if isinstance(answer, (bool, np.bool_)):
        raise _WrongForm(f"`{name}` is {answer}, a yes/no value; the check needs a number.")
    if isinstance(answer, (str, bytes)):
        raise _WrongForm(f"`{name}` is the text {answer!r}; the check needs a number, not a string "
                         "(no quotes).")
    if isinstance(answer, (tuple, list)):
        kind = type(answer).__name__
        if len(answer) == 1:
            raise _WrongForm(f"`{name}` is a {kind} holding one value; the check needs the number "
                             f"itself: `{name}[0]`" + (" (a trailing comma, `x = 1.5,`, makes a tuple)."
                                                      if kind == "tuple" else "."))
        raise _WrongForm(many or f"`{name}` is a {kind} of {len(answer)} values; the check needs one "
                                 "number.")
    try:
        array = np.asarray(answer)
    except Exception:                                     # noqa: BLE001 - any object a student may pass
        array = np.asarray(None, dtype=object)
    if array.dtype.kind == "c":
        raise _WrongForm(f"`{name}` is a complex number; the check needs a real one "
                         "(a square root of a negative number?).")
    if array.dtype.kind not in "iuf":
        raise _WrongForm(f"`{name}` is a {type(answer).__name__}, not a number.")
    if array.ndim > 0:
        if array.size == 1:
            raise _WrongForm(f"`{name}` is an array of shape {array.shape} holding one value; the "
                             f"check needs the number itself: `{name}.item()`.")
        raise _WrongForm(many or f"`{name}` is an array of shape {array.shape}, {array.size} values; the "
                                 "check needs one number.")
    value = float(array)
    if not np.isfinite(value):
        raise _WrongForm(f"`{name}` is {value}, not a finite number.", nan_hint)
    return value


def _integer(answer, name, what, many=""):
    """``answer`` as an int; a float with a fraction is a wrong form."""
    value = _number(answer, name, many=many)
    if not value.is_integer():
        raise _WrongForm(f"`{name}` is {value:g}; {what} is a whole number.")
    return int(value)


def _one_of(value, name, choices, what):
    if value not in choices:
        listed = ", ".join(map(str, choices[:-1])) + f" or {choices[-1]}"
        raise _WrongForm(f"`{name}` is {value}: {what} is one of {listed}.")
    return value


# -- The value of an answer --------------------------------------------------

def _near(answer, target, rtol, scale=None):
    if not np.isfinite(target):
        return False
    if scale is not None:
        return abs(answer - target) <= rtol * scale
    return bool(np.isclose(answer, target, rtol=rtol, atol=0))


def _bands(size, way, of=""):
    # each phrase through gettext (rsgeo._i18n), filled after translation
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


def _how_far(answer, expected, scale=None, scale_name=""):
    """Which way and roughly how far ``answer`` is from ``expected``, in words without either.

    With ``scale`` the distance is measured in fractions of it (for an
    expected value that may be zero); otherwise relative to ``expected``.

    Examples
    --------
    >>> _how_far(3.0, 2.0)
    'between 1.5 and 2 times too large'
    >>> _how_far(-2.0, 2.0)
    'the right size with the wrong sign'
    >>> _how_far(0.5, 0.0, scale=10.0, scale_name="the step")
    'too large by 1 to 10 % of the step'
    """
    if answer != 0 and expected != 0 and np.sign(answer) != np.sign(expected):
        if np.isclose(-answer, expected, rtol=1e-2):
            return _("the right size with the wrong sign")
        return _("of the wrong sign, and its size is {how}").format(
            how=_how_far(-answer, expected, scale, scale_name))
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
                    _("between {low:g} and {high:g} times too small")).format(low=low, high=high)
    return _("more than 100 times too large") if ratio > 1 else _("more than 100 times too small")


def _judge(answer, name, expected, rtol, hint, mistakes=(), units="", scale=None, scale_name="",
           nan_hint="", mistake_rtol=None):
    """The verdict on a number: its form, then which way it is off and the hint for a known mistake.

    ``mistakes`` is a sequence of (wrong value, hint): the value a mistake
    produces; every mistake the answer matches contributes its hint, and an
    answer that matches none gets ``hint``. A mistake matches within
    ``mistake_rtol`` (default ``rtol``): tighter where two mistakes give
    nearby values.
    """
    try:
        value = _number(answer, name, nan_hint or hint)
    except _WrongForm as form:
        return form.verdict(hint)
    if _near(value, expected, rtol, scale):
        return Verdict(True, f"`{name}` = {value:.6g}{units}.")
    message = _("`{name}` is {how}.").format(name=name,
                                            how=_how_far(value, expected, scale, scale_name))
    found = _matched(value, expected, rtol, mistakes, scale, mistake_rtol)
    return Verdict(False, message, found or hint)


def _matched(value, expected, rtol, mistakes, scale=None, mistake_rtol=None):
    """The hints of the mistakes whose wrong value ``value`` matches (and that differ from the truth)."""
    hints = []
    for wrong, hint in mistakes:
        wrong = float(wrong)
        if (np.isfinite(wrong) and _near(value, wrong, mistake_rtol or rtol, scale)
                and not _near(wrong, expected, rtol, scale) and hint not in hints):
            hints.append(hint)
    return " ".join(_(hint) for hint in hints)        # each in the course's language


def _quiet(function, *args, **kwargs):
    """A mistake's value, or NaN where the mistake makes no number at all."""
    with np.errstate(all="ignore"):
        try:
            return float(function(*args, **kwargs))
        except (ValueError, ZeroDivisionError, FloatingPointError):
            return float("nan")


# -- Chapter 1: systematic distortions --------------------------------------

# The scenes chapter 1 computes and prints (its inputs, as in book/01_systematic_distortions):
# an exercise asks about other inputs, and a check recognises an answer copied from the chapter
# by recomputing the chapter's numbers from these inputs.
#: (latitude, frame length km, altitude km, inclination) of the chapter's Earth-rotation frames
_CHAPTER_1_FRAMES = ((0.0, 185.0, 705.0, 98.2), (0.0, 113.0, 778.0, 98.5),
                     (-23.5, 113.0, 778.0, 98.5))
#: (scan or half angle in degrees, altitude km) of the pixel sizes and swaths the chapter prints
#: (MODIS; Landsat, CBERS CCD and SPOT at their half-angles; SPOT pointed 27° off nadir)
_CHAPTER_1_SCANS = ((55.0, 705.0), (7.5, 705.0), (4.2, 778.0), (2.06, 832.0), (29.06, 832.0))
_COPIED_SKEW = ("That is a number chapter 1 prints for its own frames (another latitude or "
                "satellite); compute the offset with this task's latitude, frame length, "
                "altitude and inclination.")
_COPIED_SCAN = ("That is a number chapter 1 prints for another sensor; compute it with this "
                "task's scan angle and altitude.")


def _as_printed(values, decimals):
    """``values`` and each rounded as a chapter prints it (a copied number is a rounded one)."""
    return [v for value in values for v in
            [float(value)] + [round(float(value), d) for d in decimals] if v != 0]


_RADIANS = ("NaN here usually means np.arcsin got a value above 1: np.sin, np.cos and np.arcsin "
            "work in radians, so convert angles with np.radians first.")
_DEGREES_HINT = ("np.cos and np.sin take radians: np.cos(-23.5) is the cosine of 23.5 radians. "
                 "Convert with np.radians first.")


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
    return distortion.EARTH_ROTATION_RAD_S * RE * (np.cos(phi) if cos_phi else 1.0) * frame / speed * factor


def _chapter_1_skews():
    """The offsets chapter 1 prints: each frame's size, west and north components (km)."""
    values = []
    for frame in _CHAPTER_1_FRAMES:
        east, north = distortion.earth_rotation_offset(*frame)
        values += [abs(distortion.earth_rotation_skew(*frame)), abs(east), abs(north)]
    return values


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
    args = (latitude_deg, frame_length_km, altitude_km, inclination_deg)
    expected = abs(distortion.earth_rotation_skew(*args))
    R = distortion.EARTH_RADIUS_KM
    mistakes = [
        (_quiet(_skew_by_hand, *args, radians=(False, False)), _DEGREES_HINT),
        (_quiet(_skew_by_hand, *args, radians=(False, True)), _DEGREES_HINT),
        (_quiet(_skew_by_hand, *args, radians=(True, False)), _DEGREES_HINT),
        (_quiet(_skew_by_hand, *args, zeta="none"),
         "The cos ζ is missing: the ground track is not a meridian, and only the part of the Earth's "
         "motion across the track (cos ζ) shifts the lines."),
        (_quiet(_skew_by_hand, *args, zeta="sin"),
         "That is sin ζ where the formula has cos ζ: ζ is the track's angle from the meridian."),
        (_quiet(_skew_by_hand, *args, cos_phi=False),
         "The cos φ is missing: the ground moves at ωe·Re·cos φ at latitude φ, slower than at the "
         "equator."),
        (_quiet(_skew_by_hand, *args, divide_by_cos_phi=False),
         "sin ζ = |cos i| / cos φ: the track's angle from the meridian grows with the latitude."),
        (_quiet(_skew_by_hand, *args, speed_radius=R + altitude_km),
         "You used the satellite's own speed, (R + h)·sqrt(GM/(R + h)³); the frame is imaged at the "
         "speed of the ground track, R·sqrt(GM/(R + h)³)."),
        (-expected, "The check asks for the size of the offset, in km: a positive number."),
        (1000 * expected, "That looks like metres; the check wants kilometres."),
        (abs(distortion.earth_rotation_offset(*args)[0]),
         "That is only the offset's west component; the task asks for the whole offset, "
         "across the ground track: Δx itself."),
        (abs(distortion.earth_rotation_offset(*args)[1]),
         "That is only the offset's north component; the task asks for the whole offset, "
         "across the ground track: Δx itself."),
    ]
    mistakes += [(copied, _COPIED_SKEW) for copied in _as_printed(_chapter_1_skews(), (2,))]
    return _judge(skew_km, "skew_km", expected, 0.01,
                  "t = frame length / ground-track speed, ground-track speed = R·sqrt(GM/(R+h)³); "
                  "Δx = ωe·Re·cos φ·t·cos ζ with sin ζ = |cos i| / cos φ (chapter 1, Earth rotation).",
                  mistakes, " km", nan_hint=_RADIANS, mistake_rtol=0.003)


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
    along, across = (float(size) for size in distortion.pixel_size(scan_angle_deg, altitude_km))
    expected = 100 * (across - 1.0)
    theta = np.radians(scan_angle_deg)
    mistakes = [
        (100 * (1 / np.cos(theta) ** 2 - 1),
         "That is the flat-Earth growth, sec² θ − 1; on a curved Earth use the slant range s and the "
         "zenith angle z: across = β·s / cos z."),
        (100 * (1 / np.cos(theta) - 1),
         "sec θ − 1 is the flat-Earth along-track growth; the task asks across-track, on a curved Earth."),
        (100 * (along - 1.0),
         "That is the along-track growth (β·s); across-track the pixel is also tilted: divide by cos z."),
        (100 * (along / np.cos(theta) - 1.0),
         "Divide by cos z, the zenith angle seen from the ground, not by cos θ, the scan angle: "
         "sin z = ((R + h)/R)·sin θ."),
        (100 * across, "That is the size relative to nadir in %; the growth is that minus 100."),
        (across, "That is the size relative to nadir (a ratio); the growth is (ratio − 1) × 100, in %."),
        (across - 1.0, "That is a fraction; the check wants per cent: multiply by 100."),
    ]
    for scan in _CHAPTER_1_SCANS:           # the growths chapter 1 prints, curved and flat Earth
        for curved in (True, False):
            sizes = distortion.pixel_size(*scan, curved_earth=curved)
            mistakes += [(copied, _COPIED_SCAN) for copied in
                         _as_printed([100 * (float(size) - 1.0) for size in sizes], (2, 1))]
    return _judge(growth_percent, "growth_percent", expected, 0.02,
                  "Across-track size = β·s / cos z: the slant range s, and z from sin z = ((R+h)/R)·sin θ. "
                  "Growth = (size at θ / size at nadir − 1) × 100.", mistakes, " %", nan_hint=_RADIANS)


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
    expected = distortion.swath_width(half_angle_deg, altitude_km)
    R, h = distortion.EARTH_RADIUS_KM, altitude_km
    theta = np.radians(half_angle_deg)
    gamma = np.radians(float(distortion.zenith_angle(half_angle_deg, altitude_km))) - theta
    mistakes = [
        (2 * h * np.tan(theta),
         "2·h·tan θ is the flat-Earth swath; the Earth curves away under a wide scan, so the swath is "
         "longer: 2·R·γ with γ = z − θ."),
        (R * gamma, "R·γ is half the swath, from nadir to one edge; the scan goes to both sides."),
        (2 * R * np.sin(gamma), "2·R·sin γ is the straight chord; the swath is the arc along the ground, "
                                "2·R·γ."),
        (2 * R * np.degrees(gamma), "γ must be in radians for the arc length R·γ."),
        (2 * R * (gamma + theta), "γ = z − θ: subtract the scan angle from the zenith angle."),
        (2 * (R + h) * gamma, "The arc is on the ground, radius R, not at the satellite's radius R + h."),
        (1000 * expected, "That looks like metres; the check wants kilometres."),
    ]
    swaths = [distortion.swath_width(*scan, curved_earth=curved)
              for scan in _CHAPTER_1_SCANS for curved in (True, False)]
    mistakes += [(copied, _COPIED_SCAN) for copied in _as_printed(swaths, (1, 0))]
    return _judge(swath_km, "swath_km", expected, 0.005,
                  "The angle at the Earth's centre is γ = z − θ; the swath is 2·R·γ (γ in radians).",
                  mistakes, " km", nan_hint=_RADIANS)


# -- Chapters 2 and 3: georeferencing ---------------------------------------

def check_design_matrix(matrix, points, order=1):
    """The linear system's matrix for the lecture's polynomial of ``order``.

    Parameters
    ----------
    matrix : (n, m) array_like
        The student's matrix.
    points : (n, 2) array_like
        The GCPs' (centred) coordinates the task gives.
    order : {1, 2, 3}

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``matrix`` is still ``...``.

    Examples
    --------
    >>> check_design_matrix([[1, 0, 0], [1, 1, 0], [1, 0, 1]], [[0, 0], [1, 0], [0, 1]])
    Correct: a 3 × 3 design matrix, columns 1, x, y.
    """
    names = gcp.term_names(order)
    layout = f"Columns in the lecture's order: {', '.join(names)}; one row per GCP."
    try:
        matrix = _require(matrix, "matrix")
        try:
            array = np.asarray(matrix, dtype=float)
        except (TypeError, ValueError):
            raise _WrongForm("`matrix` is not a table of numbers (rows of different lengths, or text?)."
                             ) from None
        if array.ndim != 2:
            raise _WrongForm(f"`matrix` has {array.ndim} dimension(s), shape {array.shape}; it needs 2: "
                             "one row per GCP, one column per term.")
        if not np.isfinite(array).all():
            raise _WrongForm("`matrix` holds NaN or infinite values.")
    except _WrongForm as form:
        return form.verdict(layout)
    points = np.asarray(points, dtype=float)
    expected = gcp.design_matrix(points, order)
    n, m = expected.shape
    if array.shape != expected.shape:
        if array.shape == (m, n) and np.allclose(array.T, expected):
            return Verdict(False, f"`matrix` has shape {array.shape}: it is transposed.",
                           "One ROW per GCP and one column per term: use np.column_stack, or .T.")
        if array.shape == (n, m - 1) and np.allclose(array, expected[:, 1:]):
            return Verdict(False, f"`matrix` has shape {array.shape}: a column is missing.",
                           "The first column is all ones: it multiplies the constant term a0.")
        for other in gcp.ORDERS:
            if other != order and array.shape == (n, gcp.min_gcps(other)) and np.allclose(
                    array, gcp.design_matrix(points, other)):
                return Verdict(False, f"`matrix` is the degree-{other} matrix; the task asks for degree "
                                      f"{order}.", layout)
        return Verdict(False, f"`matrix` has shape {array.shape}; it needs one row per GCP and one "
                              f"column per term, ({n}, {m}).", layout)
    wrong = ~np.isclose(array, expected).all(axis=0)
    if not wrong.any():
        return Verdict(True, f"a {n} × {m} design matrix, columns {', '.join(names)}.")
    message = f"the column(s) for {', '.join(names[i] for i in np.flatnonzero(wrong))} are not right."
    if np.allclose(array, gcp.design_matrix(points[:, ::-1], order)):
        return Verdict(False, message, "x and y are swapped: x (easting, points[:, 0]) comes before y "
                                       "(northing, points[:, 1]).")
    shift = array[:, 1:3] - expected[:, 1:3]
    if np.allclose(shift, shift[0]) and not np.allclose(shift[0], 0):
        return Verdict(False, message, "These are not the centred coordinates of `points` (each column is "
                                       "off by a constant): build the matrix from `points` itself.")
    if wrong[0]:
        return Verdict(False, message, "The first column is all ones: it multiplies the constant term a0.")
    return Verdict(False, message, layout)


def check_rms(rms, predicted, observed):
    """The lecture's RMS computed by hand.

    Parameters
    ----------
    rms : float
        The student's answer, in pixels.
    predicted, observed : (n, 2) array_like
        The model's positions of the GCPs and the GCPs' own positions.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``rms`` is still ``...``.

    Examples
    --------
    >>> check_rms(np.sqrt(125 / 4), [[3, 4], [6, 8]], [[0, 0], [0, 0]]).hint
    'You averaged dx² and dy² separately (dividing by 2n): sum them per GCP, then divide by n.'
    """
    difference = as_points(predicted, "predicted") - as_points(observed, "observed")
    squares = np.sum(difference ** 2, axis=1)
    n = len(squares)
    expected = gcp.rms_error(predicted, observed)
    mistakes = [
        (np.sqrt(squares.sum() / (2 * n)),
         "You averaged dx² and dy² separately (dividing by 2n): sum them per GCP, then divide by n."),
        (squares.mean(), "The square root is missing: RMS = sqrt( (1/n) Σ R_i² )."),
        (np.sqrt(squares).mean(), "That is the mean of the residuals R_i; RMS squares them first, "
                                  "averages, then takes the root."),
        (np.sqrt(squares.sum()), "Divide the sum of squares by n before the square root."),
        (np.sqrt(np.mean(difference[:, 0] ** 2)), "Both components count: R_i² = dx_i² + dy_i²."),
        (np.sqrt(np.mean(difference[:, 1] ** 2)), "Both components count: R_i² = dx_i² + dy_i²."),
    ]
    mistakes += [(np.sqrt(squares.sum() / (n - k)),
                  "You divided by n − k (QGIS's 'mean error' divides by n − m); the lecture's RMS "
                  "divides by n.") for k in (1, 2, 3) if n > k]
    return _judge(rms, "rms", expected, 1e-6,
                  "RMS = sqrt( (1/n) Σ (dx_i² + dy_i²) ): square each residual's length, average, root.",
                  mistakes, " px")


def check_blunder(gcp_id, gcps, order):
    """The id of the planted bad GCP in a GCPSet.

    Parameters
    ----------
    gcp_id : str
        The student's answer, an id from ``gcps.ids`` such as ``"P07"``.
    gcps : GCPSet
    order : {1, 2, 3}
        The degree of the model the task fits.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``gcp_id`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_blunder(13, gcps, order=2).message)      # a position, not an id
    `gcp_id` is the number 13, not a GCP id: ids are strings such as 'P01'. Counted from 0, position 13 is the blunder's row: give its id, `gcps.ids[13]`.
    """
    ids = list(gcps.ids)
    generic = ("Fit the model, compute R_i for every GCP and look for the one far above the rest; "
               "a blunder also drags its neighbours' residuals up.")
    dx, dy, distance = gcp.residuals(gcps.fit(order), gcps.map_xy, gcps.image_xy)
    worst = ids[int(np.argmax(distance))]
    try:
        gcp_id = _require(gcp_id, "gcp_id")
        if isinstance(gcp_id, (bool, np.bool_)):
            raise _WrongForm(f"`gcp_id` is {gcp_id}; the check needs a GCP id such as {ids[0]!r}.")
        if not isinstance(gcp_id, (str, np.str_)):
            return _blunder_by_number(gcp_id, ids, worst, generic)
    except _WrongForm as form:
        return form.verdict(generic)
    gcp_id = str(gcp_id)
    if gcp_id == worst:
        return Verdict(True, f"GCP {gcp_id} is the blunder: its residual dwarfs the others'.")
    if gcp_id not in ids:
        spelled = [i for i in ids if i.upper() == gcp_id.strip().upper()]
        if spelled:
            return Verdict(False, f"{gcp_id!r} is spelled differently from the ids, which are written "
                                  f"like {ids[0]!r} (capitals and spaces count).", generic)
        return Verdict(False, f"{gcp_id!r} is not one of the GCP ids ({ids[0]!r} to {ids[-1]!r}).", generic)
    k = ids.index(gcp_id)
    rank = np.argsort(-distance)
    single = np.maximum(np.abs(dx), np.abs(dy))
    mistakes = [
        (ids[int(np.argmin(distance))], "That GCP has the SMALLEST residual; the blunder has the largest."),
        (ids[int(rank[1])], "Its residual is high because the blunder drags its neighbours' up: "
                            "look for the one far above all the rest."),
        (ids[int(np.argmax(single))], "Compare the lengths R_i = sqrt(dx² + dy²), not one component."),
    ]
    if order != 1:
        _, _, linear = gcp.residuals(gcps.fit(1), gcps.map_xy, gcps.image_xy)
        mistakes.append((ids[int(np.argmax(linear))],
                         f"That is the worst GCP of a degree-1 fit; the task fits degree {order}, "
                         "and a degree-1 model cannot follow the image's curvature."))
    hints = [hint for wrong, hint in mistakes if wrong == gcp_id and wrong != worst]
    return Verdict(False, f"GCP {gcp_id} is not the blunder: its residual, {distance[k]:.2f} px, is not "
                          "the one that stands out.", " ".join(dict.fromkeys(hints)) or generic)


def _blunder_by_number(answer, ids, worst, generic):
    """A number (or array) given where a GCP id is needed: a form message, with what the number means."""
    if isinstance(answer, (list, tuple)) or np.ndim(answer) > 0:
        size = len(answer)
        raise _WrongForm(f"`gcp_id` holds {size} value(s); the check needs ONE id, a string such as "
                         f"{ids[0]!r}" + (": take it out with `gcp_id[0]`." if size == 1 else "."))
    number = _integer(answer, "gcp_id", "a position in the table")
    intro = f"`gcp_id` is the number {number}, not a GCP id: ids are strings such as {ids[0]!r}. "
    if 0 <= number < len(ids) and ids[number] == worst:
        return Verdict(False, intro + f"Counted from 0, position {number} is the blunder's row: give its id, "
                                      f"`gcps.ids[{number}]`.",
                       "`table['residual'].idxmax()` gives the id directly; `np.argmax` gives a position.")
    if 1 <= number <= len(ids) and ids[number - 1] == worst:
        return Verdict(False, intro + f"Counted from 1, GCP number {number} is the blunder: give its id, "
                                      "the string, as it appears in `gcps.ids`.", generic)
    return Verdict(False, intro + f"Neither the row at position {number} (from 0) nor GCP number "
                                  f"{number} (from 1) is the blunder.", generic)


def check_degree_choice(order, gcps, is_check):
    """The degree with the smallest error on independent check points.

    Parameters
    ----------
    order : int
        The student's answer, 1, 2 or 3.
    gcps : GCPSet
    is_check : (n,) array_like of bool
        The check points; the others are fitted.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``order`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_degree_choice(4, gcps, np.arange(16) % 3 == 0).message)
    `order` is 4: the degree is one of 1, 2 or 3.
    """
    is_check = np.asarray(is_check, dtype=bool)
    offered = tuple(n for n in gcp.ORDERS if (~is_check).sum() >= gcp.min_gcps(n))
    generic = ("Compare the RMS on the check points, not on the GCPs used in the fit: "
               "the fitting RMS always falls as the degree rises.")
    try:
        order = _one_of(_integer(order, "order", "a degree"), "order", offered, "the degree")
    except _WrongForm as form:
        return form.verdict(generic)
    fits = {n: gcp.fit_with_check_points(gcps.map_xy, gcps.image_xy, n, is_check) for n in offered}
    errors = {n: fit[2] for n, fit in fits.items()}
    best = min(errors, key=errors.get)
    if order == best:
        return Verdict(True, f"degree {order}: check-point RMS {errors[order]:.2f} px, the lowest.")
    fitting = {n: fit[1] for n, fit in fits.items()}
    everything = {n: gcp.rms_error(gcp.fit_polynomial(gcps.map_xy, gcps.image_xy, n)(gcps.map_xy),
                                   gcps.image_xy) for n in offered}
    mistakes = [
        (min(fitting, key=fitting.get), "That degree has the lowest RMS on the GCPs used in the fit, "
                                        "which always falls as the degree rises: judge on the check points."),
        (min(everything, key=everything.get), "That is the lowest RMS of a fit on ALL the points; the "
                                              "check points must stay out of the fit to judge it."),
    ]
    way = "lower" if best < order else "higher"
    hints = [hint for wrong, hint in mistakes if wrong == order]
    return Verdict(False, f"degree {order} has a check-point RMS of {errors[order]:.2f} px; a {way} degree "
                          "does better on the check points.", " ".join(dict.fromkeys(hints)) or generic)


def check_datum_shift_pixels(shift_px, map_xy, src_crs, dst_crs, pixel_size, name="shift_px"):
    """The mean size of a datum shift at some points, in pixels of a given size.

    Parameters
    ----------
    shift_px : float
        The student's answer: the mean distance each point moves from
        ``src_crs`` to ``dst_crs``, divided by the pixel size.
    map_xy : (n, 2) array_like
        The points' map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio CRS
        E.g. SAD69 / UTM 21S and SIRGAS 2000 / UTM 21S.
    pixel_size : float
        Metres per pixel (20 for the CBERS CCD).
    name : str, optional
        The name of the student's variable, which the verdict quotes
        (``"hrc_shift_px"`` in exercise 2b.2).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``shift_px`` is still ``...``.
    ValueError
        For a CRS that PROJ does not know or a pixel size that is not positive.

    Examples
    --------
    >>> check_datum_shift_pixels(0.0, [[775445.0, 7369105.0]], 29191, 31981, 20.0).ok
    False
    >>> check_datum_shift_pixels(0.0, [[775445.0, 7369105.0]], 29191, 31981, 2.5,
    ...                          name="hrc_shift_px").message
    '`hrc_shift_px` is zero, and it should not be.'
    """
    size = float(pixel_size)
    if not np.isfinite(size) or size <= 0:
        raise ValueError(f"pixel_size must be a positive number of metres, got {pixel_size!r}")
    dx, dy, distance = georef.datum_shift(as_points(map_xy, "map_xy"), src_crs, dst_crs)
    expected = float(np.mean(distance)) / size
    mistakes = [
        (np.mean(distance), "That is the shift in metres; divide by the pixel size to get pixels."),
        (np.mean(np.abs(dx)) / size, "That is only the easting's change; the shift is the distance "
                                     "sqrt(dx² + dy²)."),
        (np.mean(np.abs(dy)) / size, "That is only the northing's change; the shift is the distance "
                                     "sqrt(dx² + dy²)."),
        (np.mean(np.abs(dx) + np.abs(dy)) / size,
         "|dx| + |dy| overstates the distance; use sqrt(dx² + dy²)."),
        (np.mean(distance) * size, "Multiplying by the pixel size gives metres², not pixels: divide."),
        (np.mean(dx) / size, "The shift's size is a distance, sqrt(dx² + dy²), not dx alone."),
    ]
    return _judge(shift_px, name, expected, 0.01,
                  "Transform the points with rsgeo.georef.transform_points, take each point's "
                  "distance sqrt(dx² + dy²), average, and divide by the pixel size.",
                  mistakes, " px", mistake_rtol=0.01)


# -- Chapter 4: resampling --------------------------------------------------

def check_bilinear(value, window, dx, dy):
    """Bilinear interpolation by hand in a 2 × 2 window at fractional offsets (dx, dy).

    Parameters
    ----------
    value : float
        The student's answer.
    window : (2, 2) array_like
        The window, upper-left pixel centre at (0, 0).
    dx, dy : float
        Offsets to the right and down, in [0, 1).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``value`` is still ``...``.

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: ``GWKBilinearResample4Sample``.

    Examples
    --------
    >>> check_bilinear(15.0, [[10, 20], [10, 20]], 0.5, 0.5)
    Correct: `value` = 15.
    """
    window = np.asarray(window, dtype=float)

    def by_hand(wx, wy):
        return float(resample.bilinear_weights(wy) @ window @ resample.bilinear_weights(wx))

    expected = by_hand(dx, dy)
    swap = "dx and dy are swapped: dx moves to the right, along a line (between columns), dy down."
    mistakes = [
        (by_hand(dy, dx), swap),
        (float(resample.bilinear_weights(dx) @ window @ resample.bilinear_weights(dy)), swap),
        (by_hand(1 - dx, 1 - dy), "The weights are reversed: the pixel nearer the point weighs more, so the "
                                  "left pixel gets 1 − dx and the right one dx."),
        (by_hand(1 - dx, dy), "The weights along the line are reversed: the left pixel gets 1 − dx."),
        (by_hand(dx, 1 - dy), "The weights between the lines are reversed: the upper line gets 1 − dy."),
        (window.mean(), "That is the plain mean of the four pixels; bilinear weights them by closeness."),
        (window[int(dy >= 0.5), int(dx >= 0.5)], "That is the nearest pixel's value; bilinear weights all four."),
        (float(window[0] @ resample.bilinear_weights(dx)),
         "You interpolated along the upper line only; do the lower line too, then between the two."),
    ]
    return _judge(value, "value", expected, 1e-9,
                  "First interpolate along each of the two lines with weights (1 − dx, dx), "
                  "then between the two results with (1 − dy, dy).", mistakes)


def check_method_for_classes(method):
    """The interpolator for a classified (thematic) map: one of ``resample.METHODS``.

    Parameters
    ----------
    method : str
        The student's answer.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``method`` is still ``...``.

    Examples
    --------
    >>> check_method_for_classes("Nearest")
    Not yet: 'Nearest' is not written as in resample.METHODS: 'nearest', 'bilinear', 'cubic' (lower case, no spaces).
    Hint: Which method only ever copies existing values?
    """
    generic = "Which method only ever copies existing values?"
    listed = ", ".join(map(repr, resample.METHODS))
    try:
        method = _require(method, "method")
    except _WrongForm as form:
        return form.verdict(generic)
    if not isinstance(method, str):
        return Verdict(False, f"`method` is not a string ({type(method).__name__}); the check needs a name from "
                              f"resample.METHODS, a string: {listed}.", generic)
    if method == "nearest":
        return Verdict(True, "nearest neighbour: class 3 next to class 5 must not become class 4.")
    if method == "bilinear":
        return Verdict(False, "'bilinear' changes a classified map's values.",
                       "Bilinear averages the four neighbouring values: between class 3 and class 5 it "
                       "invents class 4. " + generic)
    if method == "cubic":
        return Verdict(False, "'cubic' changes a classified map's values.",
                       "Cubic convolution averages sixteen neighbours with weights that can be negative: "
                       "it invents classes, even values outside the legend. " + generic)
    if method.strip().lower() in resample.METHODS:
        return Verdict(False, f"{method!r} is not written as in resample.METHODS: {listed} "
                              "(lower case, no spaces).", generic)
    return Verdict(False, f"{method!r} is not one of resample.METHODS: choose one of {listed}, "
                          "written exactly so.", generic)


def check_overshoot(overshoot, image, cols, rows):
    """Largest amount by which cubic convolution exceeds the image's own maximum.

    Parameters
    ----------
    overshoot : float
        The student's answer, in DN.
    image : 2-D ndarray
        The task's image.
    cols, rows : array_like
        The positions to interpolate at.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``overshoot`` is still ``...``.

    Examples
    --------
    >>> check_overshoot(0.0, np.full((6, 6), 9, np.uint8), [2.5, 3.1], [3.0, 3.0])
    Correct: `overshoot` = 0 DN.
    """
    image = np.asarray(image)
    values = resample.interpolate(image.astype(np.float64), cols, rows, "cubic")
    expected = float(values.max() - image.max())
    height = float(image.max()) - float(image.min())
    scale = height if height > 0 else 1.0
    rounded = resample.interpolate(image, cols, rows, "cubic")
    mistakes = [
        (float(rounded.max()) - float(image.max()),
         "Your interpolated values are whole numbers: you interpolated the integer image, which GDAL's "
         "rules round (and clip); interpolate image.astype(np.float64)."),
        (float(values.max()), "That is the largest interpolated value; subtract the image's own maximum."),
        (-expected, "Subtract the image's maximum FROM the interpolated maximum (the excess is positive)."),
        (float(values.min() - image.min()), "That is the undershoot below the minimum, negative; the task "
                                            "asks how far the values go ABOVE the maximum."),
        (expected / scale, "That is a fraction of the step's height; the check wants DN."),
        (100 * expected / scale, "That is a percentage of the step's height; the check wants DN."),
        (0.0, "Zero: nearest and bilinear never leave the range of their neighbours, cubic convolution "
              "does (negative lobes); interpolate a float copy with method='cubic'."),
    ]
    try:
        from scipy.ndimage import map_coordinates

        spline = map_coordinates(image.astype(np.float64), [np.asarray(rows) - 0.5, np.asarray(cols) - 0.5],
                                 order=3, mode="nearest")
        mistakes.append((float(spline.max() - image.max()),
                         "That is scipy's cubic spline, not Keys' cubic convolution (a = −0.5, GDAL's "
                         "'cubic'): use rsgeo.resample.interpolate with method='cubic'."))
    except ImportError:                                    # pragma: no cover - scipy is a dependency
        pass
    return _judge(overshoot, "overshoot", expected, 1e-6,
                  "Interpolate with method='cubic' on a float copy (so nothing is clipped) "
                  "and subtract the image's maximum from the interpolated maximum.", mistakes, " DN",
                  scale=scale, scale_name="the image's range (its step height)")


def check_output_pixel_size(pixel_size, src_shape, transform):
    """The pixel size gdalwarp chooses for a source: its diagonal rule.

    Parameters
    ----------
    pixel_size : float
        The student's answer, in map units (metres).
    src_shape : (rows, cols)
        The source image's size.
    transform : affine.Affine
        The source's geotransform (pixel -> map).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``pixel_size`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> check_output_pixel_size(20.0, (100, 100), affine.Affine(20, 0, 0, 0, -20, 0))
    Correct: `pixel_size` = 20 m.
    """
    rows, cols = as_shape(src_shape, "src_shape")
    grid, _ = resample.suggested_grid((rows, cols), transform)
    expected = float(grid.a)
    corners_x, corners_y = transform @ (np.array([0.0, cols, 0.0, cols]),
                                        np.array([0.0, rows, rows, 0.0]))
    box = np.hypot(np.ptp(corners_x), np.ptp(corners_y))
    diagonal = np.hypot(corners_x[1] - corners_x[0], corners_y[1] - corners_y[0])
    x_size, y_size = np.hypot(transform.a, transform.d), np.hypot(transform.b, transform.e)
    mistakes = [
        (x_size, "That is the source's pixel width alone; gdalwarp keeps the number of pixels "
                 "along the diagonal, which mixes width and height."),
        (y_size, "That is the source's pixel height alone; gdalwarp keeps the number of pixels "
                 "along the diagonal, which mixes width and height."),
        ((x_size + y_size) / 2, "The mean of width and height is not the rule: divide the "
                                "diagonal's length on the map by its length in pixels."),
        (box / np.hypot(rows, cols), "That is the diagonal of the bounding box; the rule uses "
                                     "the top-left to bottom-right corner of the image itself."),
        (diagonal / (rows + cols), "Divide by the diagonal in pixels, sqrt(rows² + cols²), not "
                                   "rows + cols."),
        (np.hypot(rows, cols) / diagonal, "Upside down: map length over pixel count."),
    ]
    return _judge(pixel_size, "pixel_size", expected, 1e-6,
                  "Take the top-left (0, 0) and bottom-right (cols, rows) corners to the map "
                  "with the transform, and divide the distance between them by "
                  "sqrt(rows² + cols²).", mistakes, " m", mistake_rtol=1e-4)


#: The grids chapter 4's table prints (book/04_resampling): the HRC scene's shape and
#: geotransform (GDAL order), and the resolutions (``-tr``) it is warped to, with and without -tap.
_CHAPTER_4_GRIDS = (((2810, 2954), (770595.0, 2.5, 0.0, 7370115.0, 0.0, -2.5), (20.0,)),)


def _chapter_4_grids():
    """(west, north, rows, cols) of each grid chapter 4's table prints."""
    grids = []
    for shape, geotransform, resolutions in _CHAPTER_4_GRIDS:
        transform = affine.Affine.from_gdal(*geotransform)
        options = [dict()] + [dict(resolution=size, tap=tap) for size in resolutions
                              for tap in (False, True)]
        for option in options:
            grid, (rows, cols) = resample.suggested_grid(shape, transform, **option)
            grids.append((grid.c, grid.f, rows, cols))
    return grids


def check_grid_extent(extent, src_shape, transform, resolution):
    """West, north, rows and cols of gdalwarp's grid with ``-tr resolution -tap``.

    Parameters
    ----------
    extent : sequence of four numbers
        The student's answer: (west, north, rows, cols).
    src_shape : (rows, cols)
        The source image's size.
    transform : affine.Affine
        The source's geotransform (pixel -> map).
    resolution : float
        The output pixel size (``-tr``).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``extent`` is still ``...``.
    ValueError
        If ``resolution`` is not a positive number.

    Examples
    --------
    >>> import affine
    >>> check_grid_extent((0.0, 40.0, 2, 2), (4, 4), affine.Affine(10, 0, 0, 0, -10, 40), 20)
    Correct: `extent` = (west 0, north 40, 2 rows, 2 cols).
    """
    size = resample.check_resolution(resolution)[0]
    grid, (rows, cols) = resample.suggested_grid(src_shape, transform, resolution=size, tap=True)
    natural, (n_rows, n_cols) = resample.suggested_grid(src_shape, transform)
    answer = _require(extent, "extent")
    generic = ("Find the footprint's edges (the corners through the transform), move them out "
               "to multiples of the resolution, then count pixels between them.")
    form = ("`extent` must be four numbers, (west, north, rows, cols): the grid's left edge and "
            "top edge in metres, then its size in pixels.")
    try:
        values = [float(v) for v in np.asarray(answer, dtype=object).ravel()]
    except (TypeError, ValueError):
        return Verdict(False, form)
    if len(values) != 4 or not np.isfinite(values).all():
        return Verdict(False, form)
    west, north, n_r, n_c = values
    if [west, north, n_r, n_c] == [grid.c, grid.f, rows, cols]:
        return Verdict(True, _("`extent` = (west {west:.10g}, north {north:.10g}, {rows} rows, "
                               "{cols} cols).").format(west=west, north=north, rows=int(n_r),
                                                       cols=int(n_c)))
    # which parts are off and which way, never by how much (that would give the answer away)
    problems = []
    if west != grid.c:
        problems.append(_("the west edge lies too far west") if west < grid.c
                        else _("the west edge lies too far east"))
    if north != grid.f:
        problems.append(_("the north edge lies too far north") if north > grid.f
                        else _("the north edge lies too far south"))
    if n_r != rows:
        problems.append(_("there are too many rows") if n_r > rows
                        else _("there are too few rows"))
    if n_c != cols:
        problems.append(_("there are too many columns") if n_c > cols
                        else _("there are too few columns"))
    message = _("in `extent`, {problems}.").format(problems="; ".join(problems))
    own = [(natural.c, natural.f, n_rows, n_cols)] + [
        (g.c, g.f, *shape) for g, shape in (resample.suggested_grid(
            src_shape, transform, resolution=size, tap=tap) for tap in (False, True))]
    if (west, north, n_r, n_c) in set(_chapter_4_grids()) - set(own):
        hint = ("Those are the numbers of chapter 4's table, made for the chapter's own "
                "resolution; this task asks for another one: move the edges to multiples of "
                "this task's resolution and count its pixels.")
    elif (west, north) == (natural.c, natural.f):
        hint = ("Those are the footprint's own edges; -tap moves them outwards to multiples of "
                "the resolution: floor(west / res) * res, ceil(north / res) * res.")
    elif west == np.ceil(natural.c / size) * size or north == np.floor(natural.f / size) * size:
        hint = ("Outwards: the west edge goes down (floor), the north edge up (ceil), so the "
                "whole scene stays inside the grid.")
    elif (n_r, n_c) == (round(n_rows * natural.a / size), round(n_cols * natural.a / size)):
        hint = ("That is the size without -tap; after moving the edges outwards, count the "
                "pixels between them: (east - west) / res and (north - south) / res.")
    elif (n_r, n_c) == (cols, rows):
        hint = "Rows come first, then columns: (west, north, rows, cols)."
    else:
        hint = generic
    return Verdict(False, message, hint)


# -- Chapter 5: the regression paper ----------------------------------------

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
    generic = "gain = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)²; then offset = ȳ − gain·x̄."
    try:
        _require(gain, "gain"), _require(offset, "offset")
        gain_value = _number(gain, "gain", generic)
        offset_value = _number(offset, "offset", generic)
    except _WrongForm as form:
        return form.verdict(generic)
    fit = radiometry.fit_gain_offset(x, y)
    xs, ys = np.asarray(x, dtype=float).ravel(), np.asarray(y, dtype=float).ravel()
    n = xs.size
    covariance = np.mean((xs - xs.mean()) * (ys - ys.mean()))
    backwards = covariance / ys.var()
    gain_mistakes = [
        (backwards, "You regressed X on Y: X, the image to correct, is the independent variable; "
                    "divide the covariance by the variance of X."),
        (1 / backwards, "You fitted X = g·Y + o and inverted it: that is a different line. Regress Y on X "
                        "(divide the covariance by the variance of X)."),
        (fit.gain * n / (n - 1), "np.cov divides by n − 1 and np.var by n: use the same (ddof) in both."),
        (fit.gain * (n - 1) / n, "np.cov divides by n − 1 and np.var by n: use the same (ddof) in both."),
        (ys.mean() / xs.mean(), "ȳ / x̄ is a gain through the origin; least squares uses the covariance "
                                "over the variance of X."),
        (ys.std() / xs.std(), "σy / σx is the reduced-major-axis gain; ordinary least squares multiplies it "
                              "by the correlation r."),
    ]
    if not _near(gain_value, fit.gain, 1e-6):
        message = f"`gain` is {_how_far(gain_value, fit.gain)}."
        return Verdict(False, message, _matched(gain_value, fit.gain, 1e-6, gain_mistakes) or generic)
    offset_mistakes = [
        (ys.mean() - xs.mean(), "The gain is missing: offset = ȳ − gain·x̄."),
        (ys.mean() + fit.gain * xs.mean(), "Mind the sign: offset = ȳ − gain·x̄."),
        (fit.gain * xs.mean() - ys.mean(), "Mind the sign: offset = ȳ − gain·x̄."),
        (xs.mean() - fit.gain * ys.mean(), "x̄ and ȳ are swapped: offset = ȳ − gain·x̄."),
    ]
    if not _near(offset_value, fit.offset, 1e-6):
        message = f"`gain` is right; `offset` is {_how_far(offset_value, fit.offset)}."
        return Verdict(False, message, _matched(offset_value, fit.offset, 1e-6, offset_mistakes)
                       or "offset = ȳ − gain·x̄: the line passes through the means.")
    return Verdict(True, f"gain {fit.gain:.4f}, offset {fit.offset:.3f}.")


def check_truncation_levels(levels, gain, offset):
    """How many distinct DNs an 8-bit image with every value 0-255 keeps after gain/offset + truncation.

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
    generic = ("Apply the stretch to np.arange(256), truncate, clip, and count np.unique. "
               "With gain < 1, some neighbouring DNs fall on the same integer.")
    dns = np.arange(256)
    stretched = gain * dns + offset
    expected = len(np.unique(radiometry.apply_gain_offset(dns.astype(np.uint8), gain, offset)))
    try:
        levels = _integer(levels, "levels", "a count",
                          many="`levels` holds many values (the levels themselves?); the check needs how "
                               "many there are: len(...) of them.")
    except _WrongForm as form:
        return form.verdict(generic)
    if levels == expected:
        return Verdict(True, f"{levels} distinct levels: a gain below 1 merges neighbouring DNs.")
    mistakes = [
        (256, "256 would mean no two DNs merge; with gain < 1 some fall on the same integer once truncated."),
        (len(np.unique(np.clip(np.round(stretched), 0, 255))),
         "You rounded; the paper (IDRISI's SCALAR) truncates: np.trunc or .astype(int)."),
        (len(np.unique(np.trunc(stretched))), "Clip to 0-255 as well: an 8-bit image holds no other value."),
        (256 - expected, "That is how many levels are LOST; the task asks how many remain."),
        (int(np.floor(stretched.max())) - int(np.floor(stretched.min())) + 1,
         "Not every integer between the smallest and the largest output needs to be hit: count the "
         "distinct values themselves."),
    ]
    hints = [hint for wrong, hint in mistakes if wrong == levels and wrong != expected]
    return Verdict(False, f"`levels` is {_how_far(levels, expected)}.",
                   " ".join(dict.fromkeys(hints)) or generic)


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
    generic = ("Fit with smooth=3, 5, 7 ... and keep the smallest window whose r reaches the target: "
               "a bigger window blurs the very detail a mosaic should keep.")
    try:
        size = _integer(size, "size", "a filter size (the side of the square window)",
                        many="`size` holds several values; the check needs one number, the side n of "
                             "the n × n window.")
        if size not in sizes:
            even = " An even window has no centre pixel." if size > 0 and size % 2 == 0 else ""
            raise _WrongForm(f"`size` is {size}: choose among the sizes offered, "
                             f"{', '.join(map(str, sizes))}.{even}")
    except _WrongForm as form:
        return form.verdict(generic)

    def correlations(x, y):
        return {s: radiometry.fit_gain_offset(x, y, smooth=s if s > 1 else None).r for s in sizes}

    def smallest(r, key=lambda value: value):
        return next((s for s in sizes if key(r[s]) >= target_r), None)

    r = correlations(x_image, y_image)
    best = smallest(r)
    if best is None:
        return Verdict(False, "no filter size in the list reaches the target here.")
    if size == best:
        return Verdict(True, f"{size} × {size}: r = {r[size]:.3f}, the first to reach {target_r}.")
    twice = correlations(radiometry.mean_filter(x_image, 3), radiometry.mean_filter(y_image, 3))
    mistakes = [
        (max(r, key=r.get), "The largest r is not the goal: the SMALLEST window that reaches the target "
                            "keeps the most detail."),
        (smallest(r, key=lambda value: value ** 2), "The target is for r, not r²."),
        (smallest(twice), "Use the ORIGINAL images pair.x_image and pair.y_image: x and y are already "
                          "filtered with a 3 × 3 mean."),
    ]
    hints = [hint for wrong, hint in mistakes if wrong == size and wrong != best]
    if r[size] < target_r:
        message = f"{size} × {size} gives r = {r[size]:.3f}, below the target {target_r}: too small a window."
    else:
        message = f"{size} × {size} reaches r = {r[size]:.3f}, but a smaller window reaches {target_r} too."
    return Verdict(False, message, " ".join(dict.fromkeys(hints)) or generic)


# -- Chapter 6: the genetic-algorithm paper ---------------------------------

_FITNESS_SECTION = "chapter 6, section 'The fitness and the genetic algorithm'"


def _fitness_variants(solution, reference, adjustment, alpha):
    """The fitness as a student might compute it wrongly, for a one-to-one solution: (value, hint)."""
    truth = fitness(solution, reference, adjustment, alpha)
    variants = [
        (fitness(solution, reference, adjustment, 1.0), "That is FS alone; FA also weighs the layout, FE."),
        (fitness(solution, reference, adjustment, 0.0), "That is FE alone; FA also weighs the sizes, FS."),
        (1 - truth, "That is a·DMS + (1 − a)·DME, the errors: FS = 1 − DMS and FE = 1 − DME."),
        (fitness(np.arange(1, len(adjustment) + 1), reference, adjustment, alpha)
         if len(adjustment) <= len(reference) else np.nan,
         "That is the fitness of the identity matching [1, 2, 3 ...]; pair segments as `solution` says."),
    ]
    solution = np.asarray(solution)
    if sorted(solution.tolist()) != list(range(1, len(reference) + 1)):
        return variants
    order = np.argsort(solution)                  # adjustment segment of each reference label
    pairs = np.triu_indices(len(reference), 1)
    s_r, s_a = reference.areas, adjustment.areas[order]
    d_r, d_a = reference.distances[pairs], adjustment.distances[order][:, order][pairs]

    def combine(fs, fe):
        return alpha * fs + (1 - alpha) * fe

    fs = 1 - np.abs(s_r - s_a).sum() / s_r.sum()
    fe = 1 - np.abs(d_r - d_a).sum() / d_r.sum()
    variants += [
        (combine(1 - np.abs(s_r - s_a).sum() / s_a.sum(), 1 - np.abs(d_r - d_a).sum() / d_a.sum()),
         "Normalise by the REFERENCE's sums, Σ S_R and Σ D_R."),
        (combine(1 - np.abs(s_r - s_a).sum() / s_a.sum(), fe), "Normalise DMS by Σ S_R, the reference's areas."),
        (combine(fs, 1 - np.abs(d_r - d_a).sum() / d_a.sum()),
         "Normalise DME by Σ D_R, the reference's distances."),
        (combine(1 - np.abs(s_r - adjustment.areas).sum() / s_r.sum(), fe),
         "Compare each reference segment's area with the area of ITS matched adjustment segment."),
        (combine(fs, 1 - np.abs(d_r - adjustment.distances[pairs]).sum() / d_r.sum()),
         "Reorder the adjustment's distances by the matching too: D_A between the segments matched to "
         "reference j and j'."),
        (combine(1 - np.abs(s_r - s_a).mean(), 1 - np.abs(d_r - d_a).mean()),
         "DMS and DME are normalised: divide the summed differences by Σ S_R and Σ D_R."),
    ]
    return variants


def check_fitness(value, solution, reference, adjustment, alpha=0.5):
    """The paper's FA for a given solution, computed by hand.

    Parameters
    ----------
    value : float
        The student's answer.
    solution : (n,) array_like of int
        solution[k] = reference label of adjustment segment k (1-based).
    reference, adjustment : Mesh
    alpha : float

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``value`` is still ``...``.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), eqs. 1-7.

    Examples
    --------
    >>> from rsgeo.matching import Mesh
    >>> mesh = Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    >>> check_fitness(1.0, [1, 2, 3], mesh, mesh)
    Correct: `value` = 1.
    """
    expected = fitness(solution, reference, adjustment, alpha)
    return _judge(value, "value", expected, 1e-6,
                  "FA = a·FS + (1 − a)·FE with FS = 1 − Σ|S_R − S_A| / Σ S_R and "
                  f"FE = 1 − Σ|D_R − D_A| / Σ D_R ({_FITNESS_SECTION}).",
                  _fitness_variants(solution, reference, adjustment, alpha))


def check_decode(solution, chromosome):
    """A binary chromosome (8 bits per gene, most significant first) decoded to reference labels.

    Parameters
    ----------
    solution : (n,) array_like of int
        The student's answer (``decoded`` in the exercise, the name its messages use).
    chromosome : (8n,) array_like of 0 and 1

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``decoded`` is still ``...``.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), section 3 (8 bits per gene).

    Examples
    --------
    >>> check_decode([3, 5], [0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 1])
    Correct: decoded [3, 5].
    """
    bits = np.asarray(chromosome, dtype=np.int64)
    genes = bits.reshape(-1, BITS_PER_GENE)
    expected = decode(bits)
    generic = ("Split the bits in groups of 8, most significant bit first, and read each group as "
               "an integer: bit k from the right weighs 2^k.")
    try:
        answer = _require(solution, "decoded")
        if isinstance(answer, (str, bytes)):
            raise _WrongForm(f"`decoded` is the text {answer!r}; the check needs an array of integers.")
        try:
            array = np.asarray(answer, dtype=float)
        except (TypeError, ValueError):
            raise _WrongForm("`decoded` is not an array of numbers.") from None
        if array.ndim == 0:
            if int(array) == int(bits @ 2 ** np.arange(bits.size - 1, -1, -1)):
                raise _WrongForm("`decoded` is one integer: you read the whole chromosome as one number. "
                                 "Each gene of 8 bits is one label.")
            raise _WrongForm(f"`decoded` is one number; the check needs one label per gene, "
                             f"{len(expected)} of them.")
        if array.shape == genes.shape:
            raise _WrongForm(f"`decoded` has shape {array.shape}: the bits are grouped but not read as "
                             "integers yet.")
        if array.shape == bits.shape and np.array_equal(array, bits):
            raise _WrongForm("`decoded` is the chromosome's bits themselves; decode them into labels.")
        if array.ndim != 1:
            raise _WrongForm(f"`decoded` has shape {array.shape}; the check needs a flat array of "
                             f"{len(expected)} labels.")
        if array.shape != expected.shape:
            groups = {size: bits.reshape(-1, size) @ 2 ** np.arange(size - 1, -1, -1)
                      for size in range(1, bits.size + 1) if bits.size % size == 0}
            size = next((s for s, g in groups.items() if g.shape == array.shape
                         and np.array_equal(g, array)), None)
            detail = f" (groups of {size} bits; a gene has {BITS_PER_GENE})" if size else ""
            raise _WrongForm(f"`decoded` has {array.size} labels{detail}; {bits.size} bits at "
                             f"{BITS_PER_GENE} per gene make {len(expected)}.")
        if not np.all(array == np.round(array)):
            raise _WrongForm("`decoded` holds fractions; labels are whole numbers.")
    except _WrongForm as form:
        return form.verdict(generic)
    if np.array_equal(array, expected):
        return Verdict(True, f"decoded {expected.tolist()}.")
    mistakes = [
        (genes[:, ::-1] @ 2 ** np.arange(BITS_PER_GENE - 1, -1, -1),
         "You read the least significant bit first; the first bit of a gene is the MOST significant."),
        (expected - 1, "Labels are 1-based as they are: do not subtract 1 (0 means 'no match')."),
        (expected + 1, "Do not add 1: the bits already encode the 1-based label."),
        (genes.sum(axis=1), "You counted the 1 bits; each bit has a weight, 2^k, by its position."),
    ]
    hints = [hint for wrong, hint in mistakes if np.array_equal(wrong, array)
             and not np.array_equal(wrong, expected)]
    wrong = np.flatnonzero(array != expected) + 1
    return Verdict(False, f"`decoded` is not what these bits encode: gene(s) {', '.join(map(str, wrong))} "
                          "differ.", " ".join(dict.fromkeys(hints)) or generic)


def check_suboptimal_segment(segment, result, truth):
    """Which adjustment segment (1-based) a sub-optimal GA run matched wrongly.

    Parameters
    ----------
    segment : int
        The student's answer, an adjustment segment numbered from 1.
    result, truth : (n,) array_like of int
        The GA's solution and the true one.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``segment`` is still ``...``.

    Examples
    --------
    >>> check_suboptimal_segment(2, [1, 3, 3], [1, 2, 3])
    Correct: segment 2 is matched to 3, not 2.
    """
    result, truth = np.asarray(result), np.asarray(truth)
    n = len(truth)
    generic = "Compare the GA's solution with the true one position by position; segments count from 1."
    try:
        segment = _integer(segment, "segment", "a segment number",
                           many="`segment` holds several values; the check needs ONE segment number "
                                "(any one of the wrongly matched).")
        if not 1 <= segment <= n:
            zero = " Segments are numbered from 1, not from 0." if segment == 0 else ""
            raise _WrongForm(f"`segment` is {segment}: the adjustment segments are numbered 1 to {n}.{zero}")
    except _WrongForm as form:
        return form.verdict(generic)
    wrong = [k + 1 for k in range(n) if result[k] != truth[k]]
    if segment in wrong:
        return Verdict(True, f"segment {segment} is matched to {result[segment - 1]}, "
                             f"not {truth[segment - 1]}.")
    hint = generic
    if segment + 1 in wrong:
        hint = ("Did you count from 0 (np.flatnonzero gives 0-based positions)? Segments are numbered "
                "from 1: add 1.")
    return Verdict(False, f"segment {segment} is matched correctly.", hint)


# -- Chapter 3b: choosing a transformation model ------------------------------

_HELMERT_NAMES = ("a", "b", "c", "d")


def _four_numbers(answer, name):
    answer = _require(answer, name)
    if isinstance(answer, (str, bytes)):
        raise _WrongForm(f"`{name}` is text; the check needs four numbers (a, b, c, d).")
    try:
        array = np.asarray(answer, dtype=float).ravel()
    except (TypeError, ValueError):
        raise _WrongForm(f"`{name}` is not four numbers (a, b, c, d).") from None
    if array.size != 4:
        raise _WrongForm(f"`{name}` holds {array.size} value(s); the Helmert model has four "
                         "unknowns, (a, b, c, d).")
    if not np.isfinite(array).all():
        raise _WrongForm(f"`{name}` holds NaN or infinite values.")
    return array


def check_helmert(parameters, src, dst):
    """A Helmert (similarity) model fitted by hand: u = a x - b y + c, v = b x + a y + d.

    Parameters
    ----------
    parameters : sequence of 4 floats
        The student's (a, b, c, d), by least squares on all the points.
    src, dst : (n, 2) array_like
        The points the task gives (both systems with y up).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``parameters`` is still ``...``.

    Examples
    --------
    >>> src = np.array([[0, 0], [10, 0], [0, 10], [10, 10]], dtype=float)
    >>> check_helmert([2, 0, 1, 1], src, src * 2 + 1)
    Correct: (a, b, c, d) fit all the points by least squares.
    """
    general = ("Two rows per point: [x, -y, 1, 0] for u and [y, x, 0, 1] for v; solve the "
               "2n × 4 system with np.linalg.lstsq.")
    try:
        value = _four_numbers(parameters, "parameters")
    except _WrongForm as form:
        return form.verdict(general)
    src = as_points(src, "src")
    dst = as_points(dst, "dst")
    matrix = gcp.fit_transform(src, dst, "helmert").matrix
    expected = np.array([matrix[0, 0], matrix[1, 0], matrix[0, 2], matrix[1, 2]])
    scale = np.abs(expected).max()
    if np.allclose(value, expected, rtol=1e-6, atol=1e-9 * scale):
        return Verdict(True, "(a, b, c, d) fit all the points by least squares.")
    wrong = [name for name, got, want in zip(_HELMERT_NAMES, value, expected)
             if not np.isclose(got, want, rtol=1e-6, atol=1e-9 * scale)]
    message = f"{', '.join(wrong)} {'is' if len(wrong) == 1 else 'are'} not right"
    if len(wrong) == 1:
        i = _HELMERT_NAMES.index(wrong[0])
        message += f": `{wrong[0]}` is {_how_far(value[i], expected[i])}"
    message += "."
    exact = gcp.fit_transform(src[:2], dst[:2], "helmert").matrix
    mistakes = [
        (np.array([expected[0], -expected[1], expected[2], expected[3]]),
         "b has the wrong sign: the model is u = a x − b y + c, v = b x + a y + d."),
        (np.array([exact[0, 0], exact[1, 0], exact[0, 2], exact[1, 2]]),
         "That is the exact model through the first two points; use every point, by least "
         "squares."),
        (np.array([expected[2], expected[3], expected[0], expected[1]]),
         "The order is (a, b, c, d): the scale-rotation pair first, then the shifts."),
    ]
    for wrong_value, hint in mistakes:
        if np.allclose(value, wrong_value, rtol=1e-6, atol=1e-9 * scale):
            return Verdict(False, message, hint)
    return Verdict(False, message, general)


def check_projective_matrix(matrix, src, dst):
    """A projective (homography) matrix computed from exactly four points.

    Parameters
    ----------
    matrix : (3, 3) array_like
        The student's homography, mapping ``src`` to ``dst`` (any scale).
    src, dst : (4, 2) array_like
        The four points the task gives.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``matrix`` is still ``...``.

    Examples
    --------
    >>> src = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    >>> check_projective_matrix(np.diag([2.0, 2.0, 1.0]), src, src * 2)
    Correct: the matrix maps the four points exactly.
    """
    general = ("Multiply out the denominator: u (c1 x + c2 y + 1) = a0 + a1 x + a2 y gives one "
               "linear equation in the 8 unknowns per coordinate; solve the 8 × 8 system and put "
               "h33 = 1.")
    try:
        matrix = _require(matrix, "matrix")
        try:
            array = np.asarray(matrix, dtype=float)
        except (TypeError, ValueError):
            raise _WrongForm("`matrix` is not a 3 × 3 table of numbers.") from None
        if array.shape != (3, 3):
            raise _WrongForm(f"`matrix` has shape {array.shape}; a homography is 3 × 3 "
                             "(reshape the 8 unknowns and h33 = 1).")
        if not np.isfinite(array).all():
            raise _WrongForm("`matrix` holds NaN or infinite values.")
        if abs(array[2, 2]) < 1e-12:
            raise _WrongForm("`matrix[2, 2]` is zero; with the usual convention it is 1.")
    except _WrongForm as form:
        return form.verdict(general)
    src = as_points(src, "src")
    dst = as_points(dst, "dst")

    def miss(h, a, b):
        with np.errstate(all="ignore"):
            mapped = np.column_stack([a, np.ones(len(a))]) @ h.T
            return float(np.max(np.hypot(*(mapped[:, :2] / mapped[:, 2:] - b).T)))

    extent = float(np.abs(dst - dst.mean(axis=0)).max())
    error = miss(array, src, dst)
    if error <= 1e-6 * extent:
        return Verdict(True, "the matrix maps the four points exactly.")
    message = f"the matrix misses the points by up to {error:.3g} (in dst units)."
    if miss(array.T, src, dst) <= 1e-6 * extent:
        return Verdict(False, message, "The matrix is transposed: H @ [x, y, 1] must give "
                                       "[u·w, v·w, w], so row 0 holds the u coefficients.")
    if miss(array, dst, src) <= 1e-6 * extent:
        return Verdict(False, message, "It maps dst to src: the task asks for src -> dst.")
    if np.allclose(array[2, :2], 0):
        return Verdict(False, message, "The last row is (0, 0, 1): that is an affine model, which "
                                       "cannot pass through four general points. " + general)
    return Verdict(False, message, general)


def check_model_choice(model, src, dst, is_check, name="model"):
    """The model (a label of ``rsgeo.gcp.GEOREFERENCER_MODELS``) with the lowest check-point RMS.

    Parameters
    ----------
    model : str
        The student's answer, e.g. "polynomial 1".
    src, dst : (n, 2) array_like
        All points (map -> image).
    is_check : (n,) array_like of bool
        The check points; the others are fitted.
    name : str, optional
        The name of the student's variable, which the verdict quotes
        (``"choice"`` in exercise 3b.3).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``model`` is still ``...``.

    Examples
    --------
    >>> from rsgeo import synthetic
    >>> gcps = synthetic.distorted_pair(seed=2).gcps
    >>> print(check_model_choice("affine", gcps.map_xy, gcps.image_xy,
    ...                          np.arange(16) % 3 == 0).message)
    `model` is 'affine': the model is one of 'linear', 'helmert', 'polynomial 1', 'polynomial 2', 'projective' or 'tps'.
    """
    is_check = np.asarray(is_check, dtype=bool)
    fitted = int((~is_check).sum())
    models = [m for m in gcp.GEOREFERENCER_MODELS if fitted > gcp.min_gcps(m[1], m[2])]
    labels = [label for label, _, _ in models]
    generic = ("Fit each model on the GCPs that are not check points and compare their RMS on "
               "the check points; the fitting RMS always prefers more parameters.")
    try:
        model = _require(model, name)
        if not isinstance(model, str):
            raise _WrongForm(_("`{name}` is {value!r}; the check needs the model's name as "
                               "text, e.g. 'polynomial 1'.").format(name=name, value=model))
        if model not in labels:
            listed = (", ".join(repr(label) for label in labels[:-1]) + " " + _("or")
                      + f" {labels[-1]!r}")
            raise _WrongForm(_("`{name}` is {value!r}: the model is one of {listed}.").format(
                name=name, value=model, listed=listed))
    except _WrongForm as form:
        return form.verdict(generic)
    table = gcp.compare_models(src, dst, is_check, models)
    check = table["check RMS (px)"]
    best = check.idxmin()
    if model == best:
        return Verdict(True, _("`{name}` is {value!r}: check-point RMS {rms:.2f} px, the "
                               "lowest.").format(name=name, value=model, rms=check[model]))
    hints = []
    if model == table["fitting RMS (px)"].idxmin():
        hints.append("That model has the lowest RMS on the GCPs used in the fit (a TPS's is "
                     "always zero): judge on the check points.")
    everything = gcp.compare_models(src, dst, None, models)["fitting RMS (px)"]
    if model == everything.idxmin() and not hints:
        hints.append("That is the lowest RMS of a fit on ALL the points; the check points must "
                     "stay out of the fit.")
    return Verdict(False, _("`{name}` is {value!r}, whose check-point RMS is {rms:.2f} px; "
                            "another model does better on the check points.").format(
                                name=name, value=model, rms=check[model]),
                   " ".join(hints) or generic)


# -- For instructors: what each check recognises -------------------------------

def _hint_text(node, strings):
    """The text of a hint expression (a string, an f-string, a sum of them, a name bound to one,
    ``_("...")``), with f-string fields shown as ``{expression}``; None for anything else."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(part.value if isinstance(part, ast.Constant)
                       else strings.get(getattr(part.value, "id", None),
                                        "{" + ast.unparse(part.value) + "}")
                       for part in node.values)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _hint_text(node.left, strings), _hint_text(node.right, strings)
        return None if left is None or right is None else left + right
    if isinstance(node, ast.Name):
        return strings.get(node.id)
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "_"
            and len(node.args) == 1):
        return _hint_text(node.args[0], strings)
    return None


def recognised_mistakes(check):
    """The hints a check gives: for each mistake it recognises, and its general hint.

    Read from the check's own source, so a list made from it (the teaching guide's table)
    stays true when a check learns a new mistake. A hint is the text paired with a
    mistake's wrong value (``(wrong, hint)``), the hint of a ``Verdict(False, ...)`` or a
    form error, or the general hint (passed to the judging helper or named ``generic``).

    Parameters
    ----------
    check : str or callable
        A check of this module, e.g. ``"check_rms"`` or :func:`check_rms`.

    Returns
    -------
    list of (str, str)
        ``(kind, hint)`` pairs in the order of the source, each hint once; ``kind`` is
        ``"mistake"`` or ``"general"``. f-string fields appear as ``{expression}``.

    Raises
    ------
    ValueError
        If ``check`` is not one of this module's ``check_...`` functions.

    Examples
    --------
    >>> hints = recognised_mistakes("check_skew")
    >>> ("mistake", "That looks like metres; the check wants kilometres.") in hints
    True
    >>> [kind for kind, hint in hints].count("general")
    1
    """
    name = getattr(check, "__name__", check)
    checks = [entry for entry, value in globals().items()
              if entry.startswith("check_") and inspect.isfunction(value)]
    if name not in checks:
        raise ValueError(f"{check!r} is not a check of rsgeo.exercises; it needs one of "
                         f"{', '.join(checks)}")
    tree = ast.parse(inspect.getsource(globals()[name]))
    helpers = {node.func.id for node in ast.walk(tree) if isinstance(node, ast.Call)
               and isinstance(node.func, ast.Name) and node.func.id.startswith("_")
               and inspect.isfunction(globals().get(node.func.id))}
    for helper in sorted(helpers):              # the private helpers it calls, one level down
        tree.body += ast.parse(inspect.getsource(globals()[helper])).body
    strings = {key: value for key, value in globals().items() if isinstance(value, str)}
    for node in ast.walk(tree):                 # local names bound to a hint's text
        if (isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)):
            text = _hint_text(node.value, strings)
            if text is not None:
                strings[node.targets[0].id] = text
    found = []

    def add(kind, node):
        text = _hint_text(node, strings)
        if text and len(text) > 20 and text not in [hint for _kind, hint in found]:
            found.append((kind, text))

    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "generic":
            add("general", node.value)
        elif isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "hint":
            add("mistake", node.value)          # a check that picks one of several hints
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "append" and len(node.args) == 1):
            add("mistake", node.args[0])
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            arguments = {keyword.arg: keyword.value for keyword in node.keywords}
            if node.func.id == "_judge" and len(node.args) >= 5:
                add("general", node.args[4])
            elif node.func.id in ("Verdict", "_WrongForm"):
                hint = node.args[2 if node.func.id == "Verdict" else 1:][:1] or [
                    arguments.get("hint")]
                if hint[0] is not None and not (isinstance(hint[0], ast.Name)
                                                and hint[0].id == "generic"):
                    add("mistake", hint[0])
        elif (isinstance(node, ast.Tuple) and len(node.elts) == 2
              and _hint_text(node.elts[0], {}) is None):
            add("mistake", node.elts[1])
    return found


# -- Chapter 4b: relief displacement and RPCs ---------------------------------

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
    expected = terrain.relief_displacement(height_m, view_zenith_deg)
    angle = np.radians(view_zenith_deg)
    mistakes = [
        (_quiet(lambda: height_m * np.tan(view_zenith_deg)),
         "np.tan takes radians: np.tan(25) is the tangent of 25 radians. Convert the angle "
         "with np.radians first."),
        (height_m * np.sin(angle), "That is h·sin θ; the displacement is h·tan θ (the "
                                   "horizontal leg of a triangle whose vertical leg is h)."),
        (height_m * np.cos(angle), "That is h·cos θ; the displacement is h·tan θ."),
        (_quiet(lambda: height_m / np.tan(angle)), "You divided by tan θ; multiply: d = h·tan θ."),
        (height_m * np.tan(angle) / 1000, "Give the answer in metres, not kilometres."),
    ]
    return _judge(displacement_m, "displacement_m", expected, 5e-3,
                  "The line of sight leans θ from the vertical: over a height h it moves "
                  "h·tan θ sideways (np.tan takes radians).", mistakes, units=" m")


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
    expected = terrain.height_error_budget(position_error_m, view_zenith_deg)
    angle = np.radians(view_zenith_deg)
    mistakes = [
        (position_error_m * np.tan(angle), "You multiplied by tan θ: a height error Δh moves the "
                                           "point Δh·tan θ, so divide the budget by tan θ."),
        (_quiet(lambda: position_error_m / np.tan(view_zenith_deg)),
         "np.tan takes radians: convert the angle with np.radians first."),
        (position_error_m / np.sin(angle), "That divides by sin θ; the displacement is Δh·tan θ, "
                                           "so divide by tan θ."),
    ]
    return _judge(height_error_m, "height_error_m", expected, 5e-3,
                  "Solve Δx = Δh·tan θ for Δh.", mistakes, units=" m")


def _two_numbers(answer, name):
    answer = _require(answer, name)
    if isinstance(answer, (str, bytes)):
        raise _WrongForm(f"`{name}` is text; the check needs two numbers (col, row).")
    try:
        array = np.asarray(answer, dtype=float).ravel()
    except (TypeError, ValueError):
        raise _WrongForm(f"`{name}` is not two numbers (col, row).") from None
    if array.size != 2:
        raise _WrongForm(f"`{name}` holds {array.size} value(s); the check needs two, (col, row).")
    if not np.isfinite(array).all():
        raise _WrongForm(f"`{name}` holds NaN or infinite values.")
    return array


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
    >>> rpc = terrain.simple_rpc_dict()
    >>> check_rpc_position((500.5, 500.5), rpc, -34.9, -8.0, 0.0)
    Correct: (col, row) is where the RPC puts the point.
    """
    generic = ("Normalise lon, lat and height with the offsets and scales, evaluate the four "
               "20-term polynomials in GDAL's order, divide numerator by denominator, "
               "de-normalise with SAMP/LINE scale and offset, then add 0.5.")
    try:
        value = _two_numbers(position, "position")
    except _WrongForm as form:
        return form.verdict(generic)
    model = terrain.RPCModel.from_dict(rpc_mapping)
    expected = np.array([float(v) for v in model.project(lon, lat, height)])
    if np.allclose(value, expected, rtol=0, atol=1e-3):
        return Verdict(True, "(col, row) is where the RPC puts the point.")
    off = value - expected
    message = (f"(col, row) is off by about {np.hypot(*off):.2g} pixels "
               f"({'right' if off[0] > 0 else 'left'}, {'down' if off[1] > 0 else 'up'}).")
    flat = np.array([float(v) for v in model.project(lon, lat, model.offsets["HEIGHT"])])
    mistakes = [
        (expected - 0.5, "RPC sample and line are 0 at the centre of the first pixel; GDAL's "
                         "(col, row) are 0 at its corner: add 0.5 to both."),
        (expected[::-1], "col and row are swapped: col comes from SAMP_*, row from LINE_*."),
        (expected[::-1] - 0.5, "col and row are swapped (col from SAMP_*, row from LINE_*), and "
                               "add 0.5 to both."),
        (flat, "The height was left out: normalise it with HEIGHT_OFF and HEIGHT_SCALE too."),
    ]
    for wrong, hint in mistakes:
        if np.allclose(value, wrong, rtol=0, atol=1e-3) and not np.allclose(wrong, expected):
            return Verdict(False, message, hint)
    return Verdict(False, message, generic)


# -- Chapter 6c: automatic registration ---------------------------------------

def check_keypoint_position(position, keypoint):
    """A scikit-image keypoint, (row, col) with pixel centres at whole numbers, in GDAL's (col, row).

    Parameters
    ----------
    position : (float, float)
        The student's (col, row), with (0, 0) at the image's top-left corner.
    keypoint : (float, float)
        The keypoint as scikit-image gives it (``SIFT().keypoints[k]``): (row, col).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``position`` is still ``...``.

    Examples
    --------
    >>> check_keypoint_position((20.5, 10.5), (10.0, 20.0))
    Correct: (col, row) is the keypoint in GDAL's convention.
    """
    general = ("scikit-image gives (row, col) with the first pixel's centre at (0, 0); GDAL's "
               "(col, row) has the first pixel's corner at (0, 0).")
    try:
        value = _two_numbers(position, "position")
    except _WrongForm as form:
        return form.verdict(general)
    row, col = (float(v) for v in np.ravel(keypoint)[:2])
    expected = np.array([col + 0.5, row + 0.5])
    if np.allclose(value, expected, rtol=0, atol=1e-6):
        return Verdict(True, "(col, row) is the keypoint in GDAL's convention.")
    off = value - expected
    message = (f"(col, row) is off by about {np.hypot(*off):.2g} pixels "
               f"({'right' if off[0] > 0 else 'left'}, {'down' if off[1] > 0 else 'up'}).")
    mistakes = [
        (expected - 0.5, "Half a pixel is missing: a pixel's centre is 0.5 from its corner, so add "
                         "0.5 to both coordinates."),
        (expected - 1.0, "The half pixel goes the other way: GDAL's coordinates are 0.5 larger "
                         "than scikit-image's at the same pixel centre."),
        (expected[::-1], "The order is swapped: scikit-image gives (row, col), the check wants "
                         "(col, row)."),
        (expected[::-1] - 0.5, "The order is swapped (scikit-image gives (row, col)), and half a "
                               "pixel is missing: add 0.5 to both."),
    ]
    for wrong, hint in mistakes:
        if np.allclose(value, wrong, rtol=0, atol=1e-6) and not np.allclose(wrong, expected):
            return Verdict(False, message, hint)
    return Verdict(False, message, general)


def _apply_affine(transform, point):
    return np.array(transform @ (float(point[0]), float(point[1])))


def check_composed_tiepoint(position, centre, shift, estimate, reference_transform):
    """A correlation tie point composed by hand: where the window's feature is in the moving image.

    The moving image was resampled onto the reference grid through ``estimate``
    (map -> moving (col, row)); ``phase_cross_correlation(reference_window,
    resampled_window)`` returned ``shift`` = (drow, dcol). The feature at the
    window centre p is at p - (dcol, drow) on the resampled grid, so in the
    moving image at ``estimate(reference_transform(p - (dcol, drow)))``.

    Parameters
    ----------
    position : (float, float)
        The student's (col, row) in the moving image.
    centre : (float, float)
        The window's centre (col, row) on the reference grid.
    shift : (float, float)
        (drow, dcol), as scikit-image returns it.
    estimate : affine.Affine
        Map (x, y) -> moving image (col, row).
    reference_transform : affine.Affine
        Reference pixel (col, row) -> map (x, y).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``position`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> to_map = affine.Affine(20, 0, 0, 0, -20, 0)
    >>> check_composed_tiepoint((10.0, 8.0), (12, 9), (1.0, 2.0), ~to_map, to_map)
    Correct: (col, row) is where the window's feature is in the moving image.
    """
    general = ("Move the window centre by minus the shift, (col − dcol, row − drow), take that "
               "reference pixel to the map with the reference transform, then to the moving "
               "image with the estimate.")
    try:
        value = _two_numbers(position, "position")
    except _WrongForm as form:
        return form.verdict(general)
    centre = np.asarray(centre, dtype=float).ravel()
    drow, dcol = (float(v) for v in np.ravel(shift)[:2])

    def composed(point, through_map=True):
        return _apply_affine(estimate, _apply_affine(reference_transform, point)
                             if through_map else point)

    expected = composed(centre - [dcol, drow])
    if np.allclose(value, expected, rtol=0, atol=1e-6):
        return Verdict(True, "(col, row) is where the window's feature is in the moving image.")
    off = value - expected
    message = (f"(col, row) is off by about {np.hypot(*off):.2g} moving-image pixels "
               f"({'right' if off[0] > 0 else 'left'}, {'down' if off[1] > 0 else 'up'}).")
    mistakes = [
        (composed(centre + [dcol, drow]), "The shift registers the moving window onto the "
                                          "reference one: the feature is at the centre minus "
                                          "the shift, not plus."),
        (composed(centre - [drow, dcol]), "scikit-image's shift is (drow, dcol), rows first; "
                                          "subtract dcol from the column and drow from the row."),
        (centre - [dcol, drow], "That is the position on the reference grid; the tie point needs "
                                "it in the moving image: through the reference transform to the "
                                "map, then through the estimate."),
        (composed(centre - [dcol, drow], through_map=False),
         "The reference transform is missing: a reference pixel must go to the map first."),
    ]
    for wrong, hint in mistakes:
        if np.allclose(value, wrong, rtol=0, atol=1e-6) and not np.allclose(wrong, expected):
            return Verdict(False, message, hint)
    return Verdict(False, message, general)


def check_check_point_error(error_px, model, truth, transform, shape, step=10, pixel_size=None):
    """The check-point error of a registration: RMS distance to the truth over a grid, in pixels.

    Parameters
    ----------
    error_px : float
        The student's RMS, in pixels of the image the models map to.
    model, truth : callable or affine.Affine
        Map (x, y) -> image (col, row): the fitted model and the known answer.
    transform : affine.Affine
        Pixel -> map of the grid of check points (every ``step``-th cell centre).
    shape : (rows, cols)
        That grid's size.
    step : int
        Spacing of the check points, cells.
    pixel_size : float, optional
        The image's pixel size (map units), to recognise an answer in metres.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``error_px`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> model = affine.Affine.translation(0.3, 0.4)
    >>> check_check_point_error(0.5, model, affine.Affine.identity(), affine.Affine.identity(),
    ...                         (20, 20))
    Correct: `error_px` = 0.5 px.
    """
    general = ("At each check point take the two models' (col, row), the distance between them, "
               "then the lecture's RMS: square, average, root.")
    rows, cols = as_shape(shape)
    grid_rows, grid_cols = np.mgrid[0:rows:int(step), 0:cols:int(step)] + 0.5
    map_xy = np.column_stack(transform @ (grid_cols.ravel(), grid_rows.ravel()))

    def apply(mapping):
        if callable(mapping):
            return np.asarray(mapping(map_xy), dtype=float)
        return np.column_stack(mapping @ (map_xy[:, 0], map_xy[:, 1]))   # an affine.Affine

    distance = np.hypot(*(apply(model) - apply(truth)).T)
    expected = tiepoints.grid_error(model, truth, transform, shape, step)
    mistakes = [
        (float(distance.mean()), "That is the mean distance; the lecture's RMS squares the "
                                 "distances before averaging and takes the root after."),
        (expected / np.sqrt(2), "That divides by 2n: the squared distance of a point is "
                                "dcol² + drow², one number per point; average over the n points."),
        (float(distance.max()), "That is the largest distance, not the RMS."),
    ]
    if pixel_size:
        mistakes.append((expected * pixel_size, "That looks like map units; the check wants "
                                                "pixels of the image."))
    return _judge(error_px, "error_px", expected, 1e-3, general, mistakes, units=" px",
                  mistake_rtol=1e-3)

