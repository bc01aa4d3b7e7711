"""Checks for the course's exercises: a friendly verdict, not a bare assert.

Every task in ``exercises/`` ends with a call such as ``check_rms(rms, ...)``.
The check recomputes the right answer with rsgeo and returns a
:class:`Verdict`: "Correct", or what is wrong and a hint. A task left as
``...`` (the student edition's placeholder) raises :class:`ExerciseNotSolved`,
so that running the notebook stops at the first task still to do, with a
message that says so.
"""

from dataclasses import dataclass

import numpy as np

from . import distortion, gcp, radiometry, resample


class ExerciseNotSolved(Exception):
    """Raised by a check when the answer is still the ``...`` placeholder."""


@dataclass
class Verdict:
    """The outcome of a check: ``ok``, and a message with a hint when not ok."""

    ok: bool
    message: str
    hint: str = ""

    def __bool__(self):
        return self.ok

    def __repr__(self):
        if self.ok:
            return f"Correct: {self.message}"
        return f"Not yet: {self.message}" + (f"\nHint: {self.hint}" if self.hint else "")

    def _repr_html_(self):
        colour, title = ("#1a7f37", "Correct") if self.ok else ("#b35900", "Not yet")
        hint = f"<br><em>Hint:</em> {self.hint}" if (self.hint and not self.ok) else ""
        return (f'<div class="rsgeo-verdict" style="border-left:4px solid {colour};padding:4px 8px">'
                f"<strong>{title}:</strong> {self.message}{hint}</div>")


def _require(answer, name):
    if answer is Ellipsis or answer is None:
        raise ExerciseNotSolved(
            f"`{name}` is still `...`: this task is yours. Write your answer in the cell above, "
            "run it, then run this check again.")
    return answer


def _close(answer, expected, name, rtol, hint, units=""):
    answer = float(_require(answer, name))
    if not np.isfinite(answer):
        return Verdict(False, f"`{name}` is {answer}, not a number.", hint)
    if np.isclose(answer, expected, rtol=rtol, atol=0):
        return Verdict(True, f"`{name}` = {answer:.6g}{units}.")
    return Verdict(False, f"`{name}` = {answer:.6g}{units}, but it should be about {expected:.6g}{units} "
                          f"(off by {100 * (answer - expected) / expected:+.1f} %).", hint)


# -- Chapter 1: systematic distortions --------------------------------------

def check_skew(skew_km, latitude_deg, frame_length_km, altitude_km, inclination_deg):
    """Earth-rotation offset of a frame, computed by hand from the lecture's model."""
    expected = distortion.earth_rotation_skew(latitude_deg, frame_length_km, altitude_km, inclination_deg)
    return _close(skew_km, expected, "skew_km", 0.01,
                  "t = frame length / ground-track speed, ground-track speed = R·sqrt(GM/(R+h)³); "
                  "Δx = ωe·Re·cos φ·t·cos ζ with sin ζ = |cos i| / cos φ.", " km")


def check_pixel_growth(growth_percent, scan_angle_deg, altitude_km):
    """Across-track growth (%) of a pixel at a scan angle, curved Earth."""
    _, across = distortion.pixel_size(scan_angle_deg, altitude_km)
    expected = 100 * (float(across) - 1.0)
    return _close(growth_percent, expected, "growth_percent", 0.02,
                  "Across-track size = β·s / cos z: the slant range s, and z from sin z = ((R+h)/R)·sin θ. "
                  "Growth = (size at θ / size at nadir − 1) × 100.", " %")


def check_swath(swath_km, half_angle_deg, altitude_km):
    """Swath width on a curved Earth."""
    expected = distortion.swath_width(half_angle_deg, altitude_km)
    return _close(swath_km, expected, "swath_km", 0.005,
                  "The angle at the Earth's centre is γ = z − θ; the swath is 2·R·γ (γ in radians).", " km")


# -- Chapters 2 and 3: georeferencing ---------------------------------------

def check_design_matrix(matrix, points, order=1):
    """The linear system's matrix for the lecture's polynomial of ``order``."""
    matrix = np.asarray(_require(matrix, "matrix"), dtype=float)
    expected = gcp.design_matrix(points, order)
    if matrix.shape != expected.shape:
        return Verdict(False, f"the matrix has shape {matrix.shape}; it needs one row per GCP and one "
                              f"column per term: {expected.shape}.",
                       f"Columns in the lecture's order: {', '.join(gcp.term_names(order))}.")
    wrong = ~np.isclose(matrix, expected).all(axis=0)
    if wrong.any():
        names = [gcp.term_names(order)[i] for i in np.flatnonzero(wrong)]
        return Verdict(False, f"the column(s) for {', '.join(names)} are not right.",
                       "Row i is (1, x_i, y_i) for degree 1: a column of ones, then the x, then the y.")
    return Verdict(True, f"a {matrix.shape[0]} × {matrix.shape[1]} design matrix, columns "
                         f"{', '.join(gcp.term_names(order))}.")


def check_rms(rms, predicted, observed):
    """The lecture's RMS computed by hand."""
    expected = gcp.rms_error(predicted, observed)
    verdict = _close(rms, expected, "rms", 1e-6,
                     "RMS = sqrt( (1/n) Σ (dx_i² + dy_i²) ): square each residual's length, average, root.",
                     " px")
    if not verdict.ok and np.isclose(float(rms) * np.sqrt(2), expected, rtol=1e-6):
        verdict.hint = "You averaged dx² and dy² separately (dividing by 2n): divide by n."
    return verdict


def check_blunder(gcp_id, gcps, order):
    """The id of the planted bad GCP in a GCPSet."""
    gcp_id = str(_require(gcp_id, "gcp_id"))
    _, _, distance = gcp.residuals(gcps.fit(order), gcps.map_xy, gcps.image_xy)
    worst = gcps.ids[int(np.argmax(distance))]
    if gcp_id == worst:
        return Verdict(True, f"GCP {gcp_id} is the blunder: its residual dwarfs the others'.")
    return Verdict(False, f"GCP {gcp_id} is not the blunder.",
                   "Fit the model, compute R_i for every GCP and look for the one far above the rest; "
                   "a blunder also drags its neighbours' residuals up.")


def check_degree_choice(order, gcps, is_check):
    """The degree with the smallest error on independent check points."""
    order = int(_require(order, "order"))
    errors = {n: gcp.check_point_errors(gcps.map_xy, gcps.image_xy, n, is_check)[2]
              for n in gcp.ORDERS if (~np.asarray(is_check)).sum() >= gcp.min_gcps(n)}
    best = min(errors, key=errors.get)
    if order == best:
        return Verdict(True, f"degree {order}: check-point RMS {errors[order]:.2f} px, the lowest.")
    return Verdict(False, f"degree {order} has a check-point RMS of {errors.get(order, float('nan')):.2f} px.",
                   "Compare the RMS on the check points, not on the GCPs used in the fit: "
                   "the fitting RMS always falls as the degree rises.")


# -- Chapter 4: resampling --------------------------------------------------

def check_bilinear(value, window, dx, dy):
    """Bilinear interpolation by hand in a 2 × 2 window at fractional offsets (dx, dy)."""
    window = np.asarray(window, dtype=float)
    wx, wy = resample.bilinear_weights(dx), resample.bilinear_weights(dy)
    expected = float(wy @ window @ wx)
    return _close(value, expected, "value", 1e-9,
                  "First interpolate along each of the two lines with weights (1 − dx, dx), "
                  "then between the two results with (1 − dy, dy).")


def check_method_for_classes(method):
    """The interpolator for a classified (thematic) map."""
    method = _require(method, "method")
    if method == "nearest":
        return Verdict(True, "nearest neighbour: class 3 next to class 5 must not become class 4.")
    return Verdict(False, f"{method!r} averages neighbouring values, inventing classes that are not there.",
                   "Which method only ever copies existing values?")


def check_overshoot(overshoot, image, cols, rows):
    """Largest amount by which cubic convolution exceeds the image's own maximum."""
    values = resample.interpolate(image.astype(np.float64), cols, rows, "cubic")
    expected = float(values.max() - image.max())
    return _close(overshoot, expected, "overshoot", 1e-6,
                  "Interpolate with method='cubic' on a float copy (so nothing is clipped) "
                  "and subtract the image's maximum from the interpolated maximum.")


# -- Chapter 5: the regression paper ----------------------------------------

def check_gain_offset(gain, offset, x, y):
    """Gain and offset of Y = gain·X + offset from the normal equations."""
    fit = radiometry.fit_gain_offset(x, y)
    first = _close(gain, fit.gain, "gain", 1e-6,
                   "gain = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)²; then offset = ȳ − gain·x̄.")
    if not first.ok:
        return first
    second = _close(offset, fit.offset, "offset", 1e-6, "offset = ȳ − gain·x̄.")
    if not second.ok:
        return second
    return Verdict(True, f"gain {fit.gain:.4f}, offset {fit.offset:.3f}.")


def check_truncation_levels(levels, gain, offset):
    """How many distinct DNs an 8-bit image with every value 0-255 keeps after gain/offset + truncation."""
    expected = len(np.unique(radiometry.apply_gain_offset(np.arange(256, dtype=np.uint8), gain, offset)))
    levels = int(_require(levels, "levels"))
    if levels == expected:
        return Verdict(True, f"{levels} distinct levels: a gain below 1 merges neighbouring DNs.")
    return Verdict(False, f"{levels} is not the number of distinct levels.",
                   "Apply the stretch to np.arange(256), truncate, clip, and count np.unique. "
                   "With gain < 1, some neighbouring DNs fall on the same integer.")


def check_filter_size(size, x_image, y_image, target_r=0.8, sizes=(1, 3, 5, 7, 9)):
    """The smallest mean-filter size whose regression reaches a correlation of ``target_r``."""
    size = int(_require(size, "size"))
    r = {s: radiometry.fit_gain_offset(x_image, y_image, smooth=s if s > 1 else None).r for s in sizes}
    good = [s for s in sizes if r[s] >= target_r]
    if not good:
        return Verdict(False, "no filter size in the list reaches the target here.")
    if size == good[0]:
        return Verdict(True, f"{size} × {size}: r = {r[size]:.3f}, the first to reach {target_r}.")
    return Verdict(False, f"{size} × {size} gives r = {r.get(size, float('nan')):.3f}.",
                   "Fit with smooth=3, 5, 7 ... and keep the smallest window whose r reaches the target: "
                   "a bigger window blurs the very detail a mosaic should keep.")


# -- Chapter 6: the genetic-algorithm paper ---------------------------------

def check_fitness(value, solution, reference, adjustment, alpha=0.5):
    """The paper's FA for a given solution, computed by hand."""
    from .matching import fitness

    expected = fitness(solution, reference, adjustment, alpha)
    return _close(value, expected, "value", 1e-6,
                  "FA = a·FS + (1 − a)·FE with FS = 1 − DMS and FE = 1 − DME (paper 001, eqs. 1-7).")


def check_decode(solution, chromosome):
    """A binary chromosome (8 bits per gene) decoded to reference labels."""
    from .matching import decode

    expected = decode(chromosome)
    solution = np.asarray(_require(solution, "solution"))
    if solution.shape == expected.shape and np.array_equal(solution, expected):
        return Verdict(True, f"solution {expected.tolist()}.")
    return Verdict(False, f"{solution.tolist()} is not what these bits encode.",
                   "Split the bits in groups of 8, most significant bit first, and read each group as "
                   "an integer.")


def check_suboptimal_segment(segment, result, truth):
    """Which adjustment segment (1-based) a sub-optimal GA run matched wrongly."""
    segment = int(_require(segment, "segment"))
    wrong = [k + 1 for k, (got, right) in enumerate(zip(result, truth)) if got != right]
    if segment in wrong:
        return Verdict(True, f"segment {segment} is matched to {result[segment - 1]}, "
                             f"not {truth[segment - 1]}.")
    return Verdict(False, f"segment {segment} is matched correctly.",
                   "Compare the GA's solution with the true one position by position.")
