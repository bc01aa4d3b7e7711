"""The exercise checks teach: every check is driven through the right answer, each mistake it
recognises (asserting that mistake's hint), the placeholder, and each wrong form of answer; no
verdict gives the expected value away.

Wrong answers are computed here the way a student would make the mistake (cos of degrees, a flat
Earth, RMS over 2n ...), independently of the check's own code, with the exercises' own settings.
"""

import functools
import math
import re
from pathlib import Path

import nbformat
import numpy as np
import pytest

from rsgeo import (
    accuracy,
    distortion,
    gcp,
    radiometry,
    registration,
    resample,
    synthetic,
    transforms,
)
from rsgeo_course import exercises
from rsgeo_course.exercises import ex01_distortions, ex04_resampling

ROOT = Path(__file__).resolve().parent.parent
R, RE, OMEGA, GM = 6371.0, 6378.137, 7.292115e-5, 398600.4418


# -- The exercises' settings and the students' answers, right and wrong -------------------------

def skew(lat=-30.0, inc=98.5, h=778.0, frame=113.0, lat_rad=True, inc_rad=True, zeta="cos",
         cos_phi=True, divide=True, speed_radius=R):
    phi = np.radians(lat) if lat_rad else lat
    i = np.radians(inc) if inc_rad else inc
    with np.errstate(invalid="ignore"):
        z = np.arcsin(abs(np.cos(i)) / (np.cos(phi) if divide else 1.0))
    t = frame / (speed_radius * np.sqrt(GM / (R + h) ** 3))
    factor = {"cos": np.cos(z), "sin": np.sin(z), "none": 1.0}[zeta]
    return OMEGA * RE * (np.cos(phi) if cos_phi else 1.0) * t * factor


def growth(curved=True, divide_by="z", ratio=False):
    theta, h = np.radians(10.3), 786.0
    if not curved:
        return 100 * (1 / np.cos(theta) ** 2 - 1)
    z = np.arcsin((R + h) / R * np.sin(theta))
    slant = R * np.sin(z - theta) / np.sin(theta)
    cos = {"z": np.cos(z), "theta": np.cos(theta), "nothing": 1.0}[divide_by]
    size = (slant / h) / cos
    return 100 * size if ratio else 100 * (size - 1)


def swath(kind="arc"):
    theta, h = np.radians(55.4), 833.0
    z = np.arcsin((R + h) / R * np.sin(theta))
    gamma = z - theta
    return {"arc": 2 * R * gamma, "flat": 2 * h * np.tan(theta), "half": R * gamma,
            "chord": 2 * R * np.sin(gamma), "degrees": 2 * R * np.degrees(gamma),
            "orbit": 2 * (R + h) * gamma}[kind]


@functools.cache
def georeferencing():
    pair = synthetic.distorted_pair(seed=2)
    gcps = pair.gcps
    points = gcps.map_xy[:5] - gcps.map_xy[:5].mean(axis=0)
    predicted = transforms.fit_polynomial(gcps.map_xy, gcps.image_xy, order=1)(gcps.map_xy)
    table = gcps.table(gcps.fit(2))
    blunder = str(table["residual"].idxmax())
    keep = np.array(gcps.ids) != blunder
    good = gcp.GCPSet(gcps.map_xy[keep], gcps.image_xy[keep])
    is_check = np.arange(len(good)) % 3 == 0
    return gcps, points, predicted, table, good, is_check


def rms_answer(kind="right"):
    gcps, _, predicted, *_ = georeferencing()
    d = predicted - gcps.image_xy
    squares = d[:, 0] ** 2 + d[:, 1] ** 2
    n = len(d)
    return {"right": np.sqrt(squares.sum() / n), "2n": np.sqrt(np.mean(d ** 2)),
            "no root": squares.mean(), "mean R": np.sqrt(squares).mean(),
            "no n": np.sqrt(squares.sum()), "dx only": np.sqrt(np.mean(d[:, 0] ** 2)),
            "n - m": np.sqrt(squares.sum() / (n - 3))}[kind]


def design(kind="right"):
    gcps, points, *_ = georeferencing()
    ones = np.ones(len(points))
    return {"right": np.column_stack([ones, points]), "transposed": np.vstack([ones, points.T]),
            "no ones": points.copy(), "swapped": np.column_stack([ones, points[:, ::-1]]),
            "raw": np.column_stack([ones, gcps.map_xy[:5]]),
            "degree 2": transforms.design_matrix(points, 2)}[kind]


@functools.cache
def pec_task():
    survey = synthetic.distorted_pair(n_gcps=40, blunder_size=3.0, seed=27).gcps
    is_check = np.arange(len(survey)) % 2 == 1
    gcp_image, gcp_map = survey.image_xy[~is_check], survey.map_xy[~is_check]
    to_map = transforms.fit_polynomial(gcp_image, gcp_map, order=2)
    check = to_map(survey.image_xy[is_check]) - survey.map_xy[is_check]
    return check, to_map(gcp_image) - gcp_map, 50_000


# the tables as Decreto 89.817 (art. 9) and the DSG's ET-CQDG print them, mm at the map's scale
PEC_PCD_MM = {"A": (0.28, 0.17), "B": (0.5, 0.3), "C": (0.8, 0.5), "D": (1.0, 0.6)}
DECREE_MM = {"A": (0.5, 0.3), "B": (0.8, 0.5), "C": (1.0, 0.6)}


def pec_answer(kind="right"):
    check, fit, scale = pec_task()
    errors = fit if kind == "fit" else check
    d = np.hypot(errors[:, 0], errors[:, 1])
    rms, mean = np.sqrt(np.mean(d**2)), d.mean()
    metres = {"mm": 1.0, "no 1000": scale}.get(kind, scale / 1000)
    table = DECREE_MM if kind == "decree" else PEC_PCD_MM
    for name, (pec, ep) in table.items():
        pec, ep = pec * metres, ep * metres
        within = np.mean(d <= pec) >= 0.9
        passes = {"rms vs pec": rms <= pec, "90 only": within,
                  "mean": within and mean <= ep}.get(kind, within and rms <= ep)
        if passes:
            return name
    return "none"


WINDOW, DX, DY = np.array([[10.0, 20.0], [30.0, 60.0]]), 0.3, 0.6


def bilinear(dx=DX, dy=DY, left=None, upper_only=False):
    upper = WINDOW[0, 0] * (1 - dx) + WINDOW[0, 1] * dx
    lower = WINDOW[1, 0] * (1 - dx) + WINDOW[1, 1] * dx
    return upper if upper_only else upper * (1 - dy) + lower * dy


@functools.cache
def step_edge():
    edge = np.where(np.arange(16) < 8, 50, 200).astype(np.uint8)[np.newaxis].repeat(16, axis=0)
    cols = np.linspace(2, 14, 241)
    return edge, cols, np.full_like(cols, 8.0)


def overshoot(kind="right"):
    edge, cols, rows = step_edge()
    floats = resample.interpolate(edge.astype(np.float64), cols, rows, "cubic")
    right = floats.max() - edge.max()
    if kind == "uint8":
        return resample.interpolate(edge, cols, rows, "cubic").max() - edge.max()
    if kind == "scipy":
        from scipy.ndimage import map_coordinates
        spline = map_coordinates(edge.astype(float), [rows - 0.5, cols - 0.5], order=3,
                                 mode="nearest")
        return spline.max() - edge.max()
    return {"right": right, "max": floats.max(), "negative": edge.max() - floats.max(),
            "fraction": right / 150, "percent": 100 * right / 150,
            "bilinear": resample.interpolate(edge.astype(np.float64), cols, rows, "bilinear").max()
            - edge.max()}[kind]


@functools.cache
def regression():
    pair = synthetic.contrast_pair(seed=4)
    return pair, radiometry.mean_filter(pair.x_image, 3), radiometry.mean_filter(pair.y_image, 3)


def gain_offset(kind="right"):
    _, x, y = regression()
    xs, ys = x.ravel(), y.ravel()
    gain = np.sum((xs - xs.mean()) * (ys - ys.mean())) / np.sum((xs - xs.mean()) ** 2)
    offset = ys.mean() - gain * xs.mean()
    if kind == "x on y":
        backwards, intercept = np.polyfit(ys, xs, 1)
        return backwards, intercept
    if kind == "ddof":
        return np.cov(xs, ys)[0, 1] / np.var(xs), offset
    if kind == "ratio":
        return ys.mean() / xs.mean(), 0.0
    if kind == "std":
        return ys.std() / xs.std(), offset
    if kind == "offset without gain":
        return gain, ys.mean() - xs.mean()
    if kind == "offset sign":
        return gain, ys.mean() + gain * xs.mean()
    return gain, offset


def levels(kind="right"):
    stretched = 0.885 * np.arange(256) + 27.107
    return {"right": len(np.unique(np.clip(np.trunc(stretched), 0, 255))),
            "floats": len(np.unique(stretched)),
            "rounded": len(np.unique(np.clip(np.round(stretched), 0, 255))),
            "lost": 256 - len(np.unique(np.trunc(stretched)))}[kind]


def filter_size(kind="right"):
    pair, x, y = regression()
    images, power = ((x, y), 1) if kind == "filtered twice" else ((pair.x_image, pair.y_image), 1)
    if kind == "r squared":
        power = 2
    r = {s: radiometry.fit_gain_offset(*images, smooth=s if s > 1 else None).r
         for s in (1, 3, 5, 7, 9)}
    if kind == "largest r":
        return max(r, key=r.get)
    return next(s for s in r if r[s] ** power >= 0.8)


REFERENCE = registration.Mesh([[0, 0], [300, 0], [0, 400]], [100, 200, 300])
ADJUSTMENT = registration.Mesh([[10, 5], [5, 395], [305, 10]], [110, 290, 190])
SOLUTION = np.array([1, 3, 2])


def fitness(kind="right", solution=SOLUTION):
    order = np.argsort(solution)
    pairs = np.triu_indices(3, 1)
    s_r, s_a = REFERENCE.areas, ADJUSTMENT.areas[order]
    d_r = REFERENCE.distances[pairs]
    d_a = (ADJUSTMENT.distances[pairs] if kind == "unpermuted distances"
           else ADJUSTMENT.distances[order][:, order][pairs])
    if kind == "adjustment sums":
        fs, fe = 1 - np.abs(s_r - s_a).sum() / s_a.sum(), 1 - np.abs(d_r - d_a).sum() / d_a.sum()
    elif kind == "not normalised":
        fs, fe = 1 - np.abs(s_r - s_a).mean(), 1 - np.abs(d_r - d_a).mean()
    else:
        fs, fe = 1 - np.abs(s_r - s_a).sum() / s_r.sum(), 1 - np.abs(d_r - d_a).sum() / d_r.sum()
    return {"fs only": fs, "fe only": fe, "errors": 0.5 * (1 - fs) + 0.5 * (1 - fe),
            "identity": fitness("right", np.array([1, 2, 3])) if kind == "identity" else None
            }.get(kind, 0.5 * fs + 0.5 * fe)


CHROMOSOME = np.array([0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0])


def decoded(kind="right"):
    genes = CHROMOSOME.reshape(-1, 8)
    weights = 2 ** np.arange(7, -1, -1)
    return {"right": genes @ weights, "lsb first": genes @ weights[::-1],
            "0-based": genes @ weights - 1, "popcount": genes.sum(axis=1),
            "whole": int("".join(map(str, CHROMOSOME)), 2), "grouped": genes,
            "bits": CHROMOSOME,
            "groups of 4": CHROMOSOME.reshape(-1, 4) @ 2 ** np.arange(3, -1, -1)
            }[kind]


@functools.cache
def suboptimal():
    reference8, adjustment8, truth = synthetic.synthetic_meshes(n=8, seed=5)
    poor = registration.genetic_match(reference8, adjustment8, seed=2, population_size=10,
                                  generations=15, mutation_rate=0.0)
    return poor.solution, truth


@functools.cache
def bias_task():
    """Exercises 4c's settings: a delivered RPC with a bias, five GCPs, a colleague's shift and
    twelve check points' residuals (measured minus RPC)."""
    from rsgeo import sensors

    scene = synthetic.raw_scene(off_nadir_deg=5.0, simulate=False)
    vendor = scene.sensor.with_knowledge_errors(roll_deg=-0.00003, pitch_deg=0.0009,
                                               yaw_deg=-0.001)
    rpc = sensors.fit_rpc_to_sensor(vendor, scene.crs, scene.bounds, scene.height_range)
    rows, cols = scene.sensor.shape
    layout = np.array([[0.15, 0.2], [0.85, 0.15], [0.2, 0.85], [0.8, 0.8], [0.45, 0.55]])
    gcps = scene.control_points(layout * (cols, rows), noise_px=0.3, seed=4)
    projected = np.column_stack(rpc.project(gcps.lon, gcps.lat, gcps.height))
    others = scene.control_points(5, noise_px=0.3, seed=11, margin=0.15)
    colleague = np.array([sensors.refine_rpc(rpc, others.rpc_gcps).parameters[k]
                          for k in ("a0", "b0")])
    checks = scene.control_points(12, noise_px=0.3, seed=12)
    residuals = checks.image_xy - np.column_stack(rpc.project(checks.lon, checks.lat,
                                                              checks.height))
    return gcps.image_xy, projected, residuals, colleague, 10.0


def bias_shift(kind="right"):
    measured, projected = bias_task()[:2]
    d = measured - projected
    return {"right": d.mean(axis=0), "sign": (projected - measured).mean(axis=0),
            "abs": np.abs(d).mean(axis=0), "rms": np.sqrt(np.mean(d ** 2, axis=0)),
            "swapped": d.mean(axis=0)[::-1], "median": np.median(d, axis=0)}[kind]


def compensated_rms(kind="right"):
    _, _, residuals, shift, size = bias_task()
    left = residuals + shift if kind == "plus" else residuals - shift
    if kind == "before":
        left = residuals
    squares = np.sum(left ** 2, axis=1)
    rms_px = np.sqrt(np.mean(squares))
    return {"right": rms_px * size, "plus": rms_px * size, "before": rms_px * size,
            "pixels": rms_px, "divided": rms_px / size,
            "mean distance": np.mean(np.sqrt(squares)) * size,
            "2n": np.sqrt(np.mean(left ** 2)) * size}[kind]


@functools.cache
def nat1_corners():
    """Exercise 2b.3's points: the nat1 scene's four corners and centre, SAD69 / UTM 23S."""
    from rsgeo import data

    nat1 = data.load("nat1")
    rows, cols = nat1.array.shape
    return np.array([nat1.transform @ (c, r) for c, r in [(0, 0), (cols, 0), (0, rows),
                                                          (cols, rows), (cols / 2, rows / 2)]])


def grid_gap(kind="right", pixel=25.0):
    """Grid (EPSG:5528) vs three parameters (EPSG:15485) at nat1's corners, as students err."""
    from rsgeo import crs

    corners = nat1_corners()
    grid, three = (crs.transform_points(corners, "EPSG:29193", "EPSG:31983", transformation=t)
                   for t in ("EPSG:5528", "EPSG:15485"))
    dx, dy = (grid - three).T
    gap = np.hypot(dx, dy)
    shifts = np.hypot(*(grid - corners).T), np.hypot(*(three - corners).T)
    return {"right": gap.max() / pixel, "metres": gap.max(), "grid shift": shifts[0].max() / pixel,
            "three shift": shifts[1].mean() / pixel,
            "lengths": np.abs(shifts[0] - shifts[1]).max() / pixel,
            "dx only": np.abs(dx).max() / pixel, "dy only": np.abs(dy).max() / pixel,
            "l1": (np.abs(dx) + np.abs(dy)).max() / pixel, "mean": gap.mean() / pixel,
            "min": gap.min() / pixel, "times": gap.max() * pixel}[kind]


# -- Each check: how to call it, its right answer, its expected value --------------------------

SKEW_ARGS = dict(latitude_deg=-30.0, frame_length_km=113.0, altitude_km=778.0,
                 inclination_deg=98.5)

CHECKS = {
    "skew": (lambda a: exercises.check_skew(a, **SKEW_ARGS), skew,
             lambda: abs(distortion.earth_rotation_skew(**SKEW_ARGS))),
    "growth": (lambda a: exercises.check_pixel_growth(a, 10.3, 786.0), growth,
               lambda: 100 * (float(distortion.pixel_size(10.3, 786.0)[1]) - 1)),
    "swath": (lambda a: exercises.check_swath(a, 55.4, 833.0), swath,
              lambda: distortion.swath_width(55.4, 833.0)),
    "design": (lambda a: exercises.check_design_matrix(a, georeferencing()[1], order=1), design,
               None),
    "rms": (lambda a: exercises.check_rms(a, georeferencing()[2], georeferencing()[0].image_xy),
            rms_answer,
            lambda: accuracy.rms_error(georeferencing()[2], georeferencing()[0].image_xy)),
    "blunder": (lambda a: exercises.check_blunder(a, georeferencing()[0], order=2),
                lambda: georeferencing()[3]["residual"].idxmax(), None),
    "degree": (lambda a: exercises.check_degree_choice(a, *georeferencing()[4:]),
               lambda: min((1, 2, 3), key=lambda n: accuracy.fit_with_check_points(
                   georeferencing()[4].map_xy, georeferencing()[4].image_xy, n,
                   georeferencing()[5])[2]), None),
    "pec": (lambda a: exercises.check_pec_class(a, *pec_task()), pec_answer, None),
    "bilinear": (lambda a: exercises.check_bilinear(a, WINDOW, DX, DY), bilinear, bilinear),
    "method": (exercises.check_method_for_classes, lambda: "nearest", None),
    "overshoot": (lambda a: exercises.check_overshoot(a, *step_edge()), overshoot, overshoot),
    "gain": (lambda a: exercises.check_gain_offset(a, gain_offset()[1], *regression()[1:]),
             lambda: gain_offset()[0], lambda: gain_offset()[0]),
    "offset": (lambda a: exercises.check_gain_offset(gain_offset()[0], a, *regression()[1:]),
               lambda: gain_offset()[1], lambda: gain_offset()[1]),
    "levels": (lambda a: exercises.check_truncation_levels(a, 0.885, 27.107), levels, None),
    "filter": (lambda a: exercises.check_filter_size(a, regression()[0].x_image,
                                                     regression()[0].y_image),
               filter_size, None),
    "fitness": (lambda a: exercises.check_fitness(a, SOLUTION, REFERENCE, ADJUSTMENT), fitness,
                fitness),
    "decode": (lambda a: exercises.check_decode(a, CHROMOSOME), decoded, None),
    "segment": (lambda a: exercises.check_suboptimal_segment(a, *suboptimal()),
                lambda: int(np.flatnonzero(suboptimal()[0] != suboptimal()[1])[0]) + 1, None),
    "gridgap": (lambda a: exercises.check_grid_vs_parameters(a, nat1_corners(), "EPSG:29193",
                                                             "EPSG:31983", pixel_size=25.0),
                grid_gap, grid_gap),
    "bias_shift": (lambda a: exercises.check_bias_shift(a, *bias_task()[:2]), bias_shift, None),
    "compensated_rms": (lambda a: exercises.check_compensated_rms(a, *bias_task()[2:]),
                        compensated_rms, compensated_rms),
}


@pytest.mark.parametrize("name", CHECKS)
def test_the_right_answer_is_correct(name):
    check, right, _ = CHECKS[name]
    verdict = check(right())
    assert verdict.ok, verdict
    assert repr(verdict).startswith("Correct")


@pytest.mark.parametrize("name", CHECKS)
def test_the_placeholder_says_the_task_is_yours(name):
    check, _, _ = CHECKS[name]
    with pytest.raises(exercises.ExerciseNotSolved, match="this task is yours"):
        check(...)


# -- Every recognised mistake gets its own hint --------------------------------------------------

MISTAKES = [
    ("skew", lambda: skew(zeta="none"), "cos ζ is missing"),
    ("skew", lambda: skew(zeta="sin"), "sin ζ where the formula has cos ζ"),
    ("skew", lambda: skew(cos_phi=False), "cos φ is missing"),
    ("skew", lambda: skew(speed_radius=R + 778.0), "satellite's own speed"),
    ("skew", lambda: skew(inc_rad=False), "take radians"),
    ("skew", lambda: skew(lat_rad=False, inc_rad=False), "radians"),     # NaN: arcsin of > 1
    ("skew", lambda: -skew(), "positive number"),
    ("skew", lambda: 1000 * skew(), "metres"),
    ("skew", lambda: -distortion.earth_rotation_offset(**SKEW_ARGS)[0], "only the offset's west"),
    ("skew", lambda: distortion.earth_rotation_offset(**SKEW_ARGS)[1], "only the offset's north"),
    ("growth", lambda: growth(curved=False), "flat-Earth growth"),
    ("growth", lambda: growth(divide_by="nothing"), "along-track growth"),
    ("growth", lambda: growth(divide_by="theta"), "not by cos θ"),
    ("growth", lambda: growth(ratio=True), "minus 100"),
    ("growth", lambda: growth() / 100, "multiply by 100"),
    ("swath", lambda: swath("flat"), "flat-Earth swath"),
    ("swath", lambda: swath("half"), "half the swath"),
    ("swath", lambda: swath("chord"), "chord"),
    ("swath", lambda: swath("degrees"), "γ must be in radians"),
    ("swath", lambda: swath("orbit"), "radius R"),
    ("swath", lambda: 1000 * swath(), "metres"),
    ("design", lambda: design("transposed"), "ROW per GCP"),
    ("design", lambda: design("no ones"), "constant term a0"),
    ("design", lambda: design("swapped"), "x and y are swapped"),
    ("design", lambda: design("raw"), "not the centred coordinates"),
    ("rms", lambda: rms_answer("2n"), "dividing by 2n"),
    ("rms", lambda: rms_answer("no root"), "square root is missing"),
    ("rms", lambda: rms_answer("mean R"), "mean of the residuals"),
    ("rms", lambda: rms_answer("no n"), "Divide the sum of squares by n"),
    ("rms", lambda: rms_answer("dx only"), "Both components count"),
    ("rms", lambda: rms_answer("n - m"), "mean error"),
    ("blunder", lambda: georeferencing()[3]["residual"].idxmin(), "SMALLEST residual"),
    ("blunder", lambda: georeferencing()[3]["residual"].nlargest(2).index[1],
     "drags its neighbours"),
    ("degree", lambda: 3, "lowest RMS on the GCPs used in the fit"),
    ("pec", lambda: pec_answer("rms vs pec"), "goes with the EP, not the PEC"),
    ("pec", lambda: pec_answer("90 only"), "RMS within the class's EP too"),
    ("pec", lambda: pec_answer("fit"), "GCPs' fitting residuals"),
    ("pec", lambda: pec_answer("mm"), "millimetres on the map"),
    ("pec", lambda: pec_answer("no 1000"), "divide by 1000"),
    ("pec", lambda: pec_answer("decree"), "Decreto 89.817's (printed maps"),
    ("pec", lambda: pec_answer("mean"), "not their mean"),
    ("bilinear", lambda: bilinear(dx=DY, dy=DX), "dx and dy are swapped"),
    ("bilinear", lambda: bilinear(dx=1 - DX, dy=1 - DY), "weights are reversed"),
    ("bilinear", lambda: bilinear(dx=1 - DX), "along the line are reversed"),
    ("bilinear", lambda: bilinear(dy=1 - DY), "between the lines are reversed"),
    ("bilinear", lambda: WINDOW.mean(), "plain mean"),
    ("bilinear", lambda: WINDOW[1, 0], "nearest pixel's value"),
    ("bilinear", lambda: bilinear(upper_only=True), "upper line only"),
    ("method", lambda: "bilinear", "invents class 4"),
    ("method", lambda: "cubic", "invents classes"),
    ("overshoot", lambda: overshoot("uint8"), "integer image"),
    ("overshoot", lambda: overshoot("max"), "subtract the image's own maximum"),
    ("overshoot", lambda: overshoot("negative"), "FROM the interpolated maximum"),
    ("overshoot", lambda: overshoot("fraction"), "fraction of the step"),
    ("overshoot", lambda: overshoot("percent"), "percentage of the step"),
    ("overshoot", lambda: overshoot("bilinear"), "never leave the range"),
    ("overshoot", lambda: overshoot("scipy"), "scipy's cubic spline"),
    ("gain", lambda: gain_offset("x on y")[0], "regressed X on Y"),
    ("gain", lambda: gain_offset("ddof")[0], "ddof"),
    ("gain", lambda: gain_offset("ratio")[0], "through the origin"),
    ("gain", lambda: gain_offset("std")[0], "reduced-major-axis"),
    ("offset", lambda: gain_offset("offset without gain")[1], "gain is missing"),
    ("offset", lambda: gain_offset("offset sign")[1], "Mind the sign"),
    ("levels", lambda: levels("floats"), "no two DNs merge"),
    ("levels", lambda: levels("rounded"), "You rounded"),
    ("levels", lambda: levels("lost"), "LOST"),
    ("filter", lambda: filter_size("largest r"), "largest r is not the goal"),
    ("filter", lambda: filter_size("r squared"), "not r²"),
    ("filter", lambda: filter_size("filtered twice"), "ORIGINAL images"),
    ("fitness", lambda: fitness("fs only"), "FS alone"),
    ("fitness", lambda: fitness("fe only"), "FE alone"),
    ("fitness", lambda: fitness("errors"), "the errors"),
    ("fitness", lambda: fitness("identity"), "identity matching"),
    ("fitness", lambda: fitness("adjustment sums"), "REFERENCE's sums"),
    ("fitness", lambda: fitness("unpermuted distances"), "Reorder the adjustment's distances"),
    ("fitness", lambda: fitness("not normalised"), "normalised"),
    ("decode", lambda: decoded("lsb first"), "least significant bit first"),
    ("decode", lambda: decoded("0-based"), "do not subtract 1"),
    ("decode", lambda: decoded("popcount"), "counted the 1 bits"),
    ("segment", lambda: int(np.flatnonzero(suboptimal()[0] != suboptimal()[1])[0]),
     "count from 0"),
    ("gridgap", lambda: grid_gap("metres"), "difference in metres"),
    ("gridgap", lambda: grid_gap("grid shift"), "the grid's shift itself"),
    ("gridgap", lambda: grid_gap("three shift"), "three-parameter shift itself"),
    ("gridgap", lambda: grid_gap("lengths"), "subtracted the lengths"),
    ("gridgap", lambda: grid_gap("dx only"), "only the easting's difference"),
    ("gridgap", lambda: grid_gap("dy only"), "only the northing's difference"),
    ("gridgap", lambda: grid_gap("l1"), "|dx| + |dy|"),
    ("gridgap", lambda: grid_gap("mean"), "mean distance"),
    ("gridgap", lambda: grid_gap("min"), "smallest distance"),
    ("gridgap", lambda: grid_gap("times"), "Multiplying by the pixel size"),
    ("bias_shift", lambda: bias_shift("sign"), "Mind the sign"),
    ("bias_shift", lambda: bias_shift("abs"), "absolute values"),
    ("bias_shift", lambda: bias_shift("rms"), "RMS of the residuals"),
    ("bias_shift", lambda: bias_shift("swapped"), "col and row are swapped"),
    ("bias_shift", lambda: bias_shift("median"), "median"),
    ("compensated_rms", lambda: compensated_rms("plus"), "Mind the sign"),
    ("compensated_rms", lambda: compensated_rms("before"), "before the compensation"),
    ("compensated_rms", lambda: compensated_rms("pixels"), "That is in pixels"),
    ("compensated_rms", lambda: compensated_rms("divided"), "do not divide"),
    ("compensated_rms", lambda: compensated_rms("mean distance"), "mean of the distances"),
    ("compensated_rms", lambda: compensated_rms("2n"), "Dividing by 2n"),
]


@pytest.mark.parametrize("name, answer, hint", MISTAKES,
                         ids=[f"{m[0]}-{m[2][:24]}" for m in MISTAKES])
def test_a_recognised_mistake_gets_its_hint(name, answer, hint):
    check, _, _ = CHECKS[name]
    verdict = check(answer())
    assert not verdict, f"{name}: the mistake passes as {verdict}"
    assert hint in verdict.hint, verdict
    assert repr(verdict).startswith("Not yet") and "Not yet" in verdict._repr_html_()


# -- Wrong forms get a message about the form ----------------------------------------------------

NUMERIC = ["skew", "growth", "swath", "rms", "bilinear", "overshoot", "gain", "offset", "fitness",
           "levels", "degree", "filter", "segment", "gridgap", "compensated_rms"]
FORMS = [
    (None, "did your function return its value"),
    ("2.5", "not a string"),
    (True, "yes/no"),
    ((2.5,), "trailing comma"),
    ([2.5], "[0]"),
    (np.array([2.5]), ".item()"),
    (np.array([1.0, 2.0]), "values"),
    (1 + 2j, "complex"),
    (float("nan"), "not a finite number"),
]


@pytest.mark.parametrize("name", NUMERIC)
@pytest.mark.parametrize("answer, message", FORMS, ids=[repr(f[0]) for f in FORMS])
def test_a_wrong_form_gets_a_message_about_the_form(name, answer, message):
    check, _, _ = CHECKS[name]
    verdict = check(answer)
    assert not verdict
    assert message in verdict.message, verdict
    assert "TypeError" not in repr(verdict) and "nan px" not in repr(verdict)


SPECIFIC_FORMS = [
    ("design", None, "did your function return its value"),
    ("design", [[1.0, 2.0], [3.0]], "not a table of numbers"),
    ("design", np.ones((1, 5, 3)), "it needs 2"),
    ("design", np.full((5, 3), np.nan), "NaN"),
    ("design", np.ones((4, 3)), "one row per GCP"),
    ("design", lambda: design("degree 2"), "degree-2 matrix"),
    ("blunder", 13, "Counted from 0, position 13 is the blunder's row"),
    ("blunder", 14, "Counted from 1, GCP number 14 is the blunder"),
    ("blunder", 3, "Neither the row at position 3"),
    ("blunder", 13.5, "whole number"),
    ("blunder", "p14", "spelled differently"),
    ("blunder", "P99", "not one of the GCP ids"),
    ("blunder", ["P14"], "ONE id"),
    ("blunder", None, "did your function return its value"),
    ("degree", 0, "one of 1, 2 or 3"),
    ("degree", 4, "one of 1, 2 or 3"),
    ("degree", 2.5, "whole number"),
    ("pec", "d", "write 'D'"),
    ("pec", "class D", "write 'D'"),
    ("pec", "None", "write 'none'"),
    ("pec", "E", "not a PEC-PCD class"),
    ("pec", None, "the string 'none'"),
    ("pec", 4, "not a class"),
    ("method", "near", "not one of resample.METHODS"),
    ("method", "Nearest", "lower case"),
    ("method", "nearest neighbour", "not one of resample.METHODS"),
    ("method", 0, "not a string"),
    ("method", None, "did your function return its value"),
    ("levels", 226.5, "whole number"),
    ("levels", lambda: np.unique(np.trunc(0.885 * np.arange(256) + 27.107)), "len("),
    ("filter", 2, "no centre pixel"),
    ("filter", 11, "sizes offered"),
    ("filter", (3, 3), "the side n"),
    ("decode", lambda: decoded("whole"), "whole chromosome as one number"),
    ("decode", lambda: decoded("grouped"), "grouped but not read"),
    ("decode", lambda: decoded("bits"), "bits themselves"),
    ("decode", lambda: decoded("groups of 4"), "groups of 4 bits"),
    ("decode", "3 1 4", "the text"),
    ("decode", [3.5, 1, 4], "fractions"),
    ("decode", 7, "one label per gene"),
    ("decode", None, "did your function return its value"),
    ("segment", 0, "numbered from 1"),
    ("segment", 9, "numbered 1 to 8"),
    ("segment", [2, 3], "ONE segment"),
    ("bias_shift", None, "did your function return its value"),
    ("bias_shift", "0.1 -1.3", "text"),
    ("bias_shift", [0.1], "holds one value"),
    ("bias_shift", [0.1, np.nan], "NaN"),
]


@pytest.mark.parametrize("name, answer, message", SPECIFIC_FORMS,
                         ids=[f"{f[0]}-{f[2][:20]}" for f in SPECIFIC_FORMS])
def test_a_task_specific_wrong_form(name, answer, message):
    check, _, _ = CHECKS[name]
    verdict = check(answer() if callable(answer) else answer)
    assert not verdict
    assert message in verdict.message, verdict


def test_a_gcp_index_is_not_called_a_wrong_gcp():
    # index 13 IS the blunder (P14): the message says so and how to turn it into an id
    verdict = CHECKS["blunder"][0](13)
    assert "not the blunder" not in verdict.message and "gcps.ids[13]" in verdict.message


def test_a_method_name_not_offered_is_not_told_it_averages():
    for name in ("near", "Nearest", "mode"):
        verdict = exercises.check_method_for_classes(name)
        assert "averag" not in verdict.message, verdict


# -- Which way and how far, never the expected value ------------------------------------------

def spellings(value):
    """The expected value written to 2-6 significant digits, as a student could read it."""
    value = float(value)
    found = set()
    for digits in range(2, 7):
        found.add(f"{value:#.{digits}g}".rstrip("."))
        if value != 0:
            decimals = digits - 1 - math.floor(math.log10(abs(value)))
            rounded = round(value, decimals)
            found.add(f"{rounded:.{max(decimals, 0)}f}")
    return {text for text in found if "e" not in text}


def leaks(text, value):
    return [s for s in spellings(value) if re.search(rf"(?<![\d.]){re.escape(s)}(?![\d])", text)]


WRONG_NUMBERS = [(name, answer) for name, answer, _ in MISTAKES if CHECKS[name][2] is not None]
WRONG_NUMBERS += [(name, lambda: 0.0) for name in CHECKS if CHECKS[name][2] is not None]
WRONG_NUMBERS += [(name, lambda n=name: 1.37 * float(CHECKS[n][2]())) for name in CHECKS
                  if CHECKS[name][2] is not None]


@pytest.mark.parametrize("name, answer", WRONG_NUMBERS,
                         ids=[f"{w[0]}-{i}" for i, w in enumerate(WRONG_NUMBERS)])
def test_no_verdict_gives_the_expected_value_away(name, answer):
    check, _, expected = CHECKS[name]
    verdict = check(answer())
    assert not verdict
    assert "should be" not in verdict.message
    assert not leaks(repr(verdict), expected()), (repr(verdict), leaks(repr(verdict), expected()))


def test_the_leak_detector_finds_a_leak():
    assert leaks("but it should be about 7.14824 km", 7.148244182498834)
    assert leaks("the swath is 2330 km", 2330.0635)
    assert not leaks("too small by 10 to 50 %", 7.148244182498834)


@pytest.mark.parametrize("factor, words", [
    (1 + 1e-5, "close, but a little too large"), (1 - 0.005, "slightly too small"),
    (1.05, "too large by 1 to 10 %"), (0.7, "too small by 10 to 50 %"),
    (1.8, "between 1.5 and 2 times too large"), (0.15, "between 5 and 10 times too small"),
    (-1.0, "the right size with the wrong sign"), (0.0, "zero"), (500.0, "more than 100 times"),
])
def test_the_verdict_says_which_way_and_roughly_how_far(factor, words):
    verdict = CHECKS["rms"][0](factor * rms_answer())
    assert not verdict and words in verdict.message, verdict
    assert "-0.0 %" not in verdict.message and "+0.0 %" not in verdict.message


def test_an_expected_value_of_zero_does_not_divide_by_zero():
    flat = np.full((8, 8), 90, np.uint8)
    cols, rows = np.linspace(2, 6, 9), np.full(9, 4.0)
    assert exercises.check_overshoot(0.0, flat, cols, rows)
    verdict = exercises.check_overshoot(3.0, flat, cols, rows)
    assert not verdict and "too large" in verdict.message and "range" in verdict.message


def test_degree_and_filter_verdicts_say_which_way():
    check = CHECKS["degree"][0]
    assert "higher degree" in check(1).message and "lower degree" in check(3).message
    check = CHECKS["filter"][0]
    assert "too small a window" in check(1).message and "smaller window" in check(7).message


def test_html_verdicts_are_escaped():
    verdict = exercises.Verdict(False, "`a` < b", "use <b>")
    assert ("&lt; b" in verdict._repr_html_()
            and "<b>" not in verdict._repr_html_().split("Hint")[1])


# -- What students read: no leaks, no dangling references -------------------------------------

def exercise_text():
    cells = [cell for path in sorted((ROOT / "exercises").glob("*.ipynb"))
             for cell in nbformat.read(path, as_version=4).cells]
    return cells


def test_exercise_setups_do_not_answer_another_task():
    for cell in exercise_text():
        if cell.cell_type == "code":
            assert "pair.blunder" not in cell.source, cell.source


def test_exercise_text_cites_the_course_not_the_papers_files():
    for cell in exercise_text():
        assert "paper 001" not in cell.source and "paper 000" not in cell.source
    for check in (exercises.check_fitness,):
        verdict = check(0.5, SOLUTION, REFERENCE, ADJUSTMENT)
        assert "paper 00" not in verdict.hint and "chapter 6" in verdict.hint


def test_the_earth_rotation_offset_points_west_and_the_task_asks_one_quantity():
    text = "\n".join(cell.source for cell in exercise_text() if cell.cell_type == "markdown")
    assert "eastward offset" not in text and "westward offset" not in text
    task = next(cell.source for cell in exercise_text() if ":label: ex-1-1" in cell.source)
    assert "**west**" in task and "**whole offset**" in task and "not the offset's west" in task


# -- The chapters print their own examples' answers: the exercises ask about other inputs ------

def chapter_1_numbers():
    """What chapter 1 prints about its frames and sensors, recomputed from its inputs."""
    skews, growths, swaths = [], [], []
    for frame in ex01_distortions._CHAPTER_1_FRAMES:
        east, north = distortion.earth_rotation_offset(*frame)
        skews += [abs(distortion.earth_rotation_skew(*frame)), -east, abs(north)]
    for scan in ex01_distortions._CHAPTER_1_SCANS:
        growths.append(100 * (float(distortion.pixel_size(*scan)[1]) - 1))
        swaths.append(distortion.swath_width(*scan))
    return {"skew": skews, "growth": growths, "swath": swaths}


@pytest.mark.parametrize("name", ["skew", "growth", "swath"])
def test_a_number_copied_from_chapter_1_is_wrong_and_recognised(name):
    check, right, _ = CHECKS[name]
    assert check(right()).ok
    for copied in chapter_1_numbers()[name]:
        verdict = check(round(copied, 2))           # as the chapter prints it
        assert not verdict.ok, (copied, verdict)
        assert "chapter 1 prints" in verdict.hint or "only the offset's" in verdict.hint, verdict


@pytest.mark.parametrize("check, arguments", [
    ("check_skew", {"latitude_deg": "-30.0", "frame_length_km": "113.0", "altitude_km": "778.0",
                    "inclination_deg": "98.5"}),
    ("check_pixel_growth", {"scan_angle_deg": "10.3", "altitude_km": "786.0"}),
    ("check_swath", {"half_angle_deg": "55.4", "altitude_km": "833.0"}),
])
def test_exercises_1_check_the_inputs_tested_here(check, arguments):
    assert exercise_check_call("ex01_distortions", check)[1] == arguments


def test_chapter_1_inputs_are_the_chapters_own():
    source = "\n".join(cell.source for cell in nbformat.read(
        ROOT / "book" / "01_systematic_distortions.ipynb", as_version=4).cells)
    for _latitude, frame, altitude, inclination in ex01_distortions._CHAPTER_1_FRAMES:
        assert (f"{altitude:g}" in source and f"{inclination:g}" in source
                and f"{frame:g}" in source)
    for angle, altitude in ex01_distortions._CHAPTER_1_SCANS:
        assert f"{altitude:g}" in source and (f"{angle:g}" in source or angle == 29.06)


def test_chapter_4_grid_inputs_are_the_hrc_scene():
    from rsgeo import data

    hrc = data.load("cbers2b_hrc")
    (shape, geotransform, resolutions), = ex04_resampling._CHAPTER_4_GRIDS
    assert tuple(hrc.array.shape[-2:]) == shape and hrc.transform.to_gdal() == geotransform


def exercise_check_call(notebook, check):
    """The positional and keyword arguments (as source) of the call of ``check`` in \
``notebook``."""
    import ast

    cells = nbformat.read(ROOT / "exercises" / f"{notebook}.ipynb", as_version=4).cells
    for cell in cells:
        if cell.cell_type == "code" and f"{check}(" in cell.source and "import" not in cell.source:
            call = ast.parse(cell.source).body[0].value
            return ([ast.unparse(a) for a in call.args],
                    {k.arg: ast.unparse(k.value) for k in call.keywords})
    raise AssertionError(f"{check} not called in {notebook}")


def test_exercise_2b_3_checks_the_points_tested_here():
    assert exercise_check_call("ex02b_datums", "check_grid_vs_parameters") == (
        ["gap_px", "corners", "nat1.crs", "'EPSG:31983'"], {"pixel_size": "25.0"})
    source = "\n".join(c.source for c in exercise_text())
    assert 'nat1 = data.load("nat1")' in source


def test_task_4_5_asks_for_another_grid_than_chapter_4s_table():
    import affine

    transform = affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0)
    args, keywords = exercise_check_call("ex04_resampling", "check_grid_extent")
    assert args == ["extent", "hrc_shape", "hrc_transform"] and keywords == {"resolution": "res"}
    source = "\n".join(c.source for c in exercise_text())
    assert "res = 25.0" in source and "-tr 25 25 -tap" in source
    (shape, _geotransform, (chapter_resolution,)), = ex04_resampling._CHAPTER_4_GRIDS
    right = resample.suggested_grid(shape, transform, resolution=25.0, tap=True)
    answer = (right[0].c, right[0].f, *right[1])
    assert exercises.check_grid_extent(answer, shape, transform, 25.0).ok
    for copied in ex04_resampling._chapter_4_grids()[1:]:      # [0]: the scene's own grid
        verdict = exercises.check_grid_extent(copied, shape, transform, 25.0)
        assert not verdict.ok and "chapter 4's table" in verdict.hint, verdict
    # the chapter's own task (20 m) is not told it copied: its hints stay the usual ones
    footprint = exercises.check_grid_extent((770595.0, 7370115.0, 351, 369), shape, transform,
                                            chapter_resolution)
    assert "chapter 4" not in footprint.hint


@pytest.mark.parametrize("answer, parts", [
    ((770580.0, 7370120.0, 352, 370), ["the west edge lies too far east",
                                       "the north edge lies too far south",
                                       "there are too many rows", "there are too many columns"]),
    ((770550.0, 7370150.0, 282, 297), ["the west edge lies too far west",
                                       "the north edge lies too far north"]),
    ((770575.0, 7370125.0, 281, 298), ["there are too few rows", "there are too many columns"]),
])
def test_the_grid_verdict_is_a_sentence_that_names_each_wrong_part(answer, parts):
    import affine

    transform = affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0)
    verdict = exercises.check_grid_extent(answer, (2810, 2954), transform, 25.0)
    assert verdict.message == "in `extent`, " + "; ".join(parts) + ".", verdict.message


def test_each_verdict_names_the_variable_the_student_wrote():
    """A check's verdict quotes its answer's name: the variable of the exercise's call."""
    import ast
    import inspect

    quoted = {"check_decode": "decoded"}          # its messages name the exercise's variable
    for path in sorted((ROOT / "exercises").glob("*.ipynb")):
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type != "code":
                continue
            for node in ast.walk(ast.parse(cell.source)):
                if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                        and node.func.id.startswith("check_") and node.args
                        and isinstance(node.args[0], ast.Name)):
                    continue
                check = getattr(exercises, node.func.id)
                parameters = inspect.signature(check).parameters
                given = {k.arg: ast.literal_eval(k.value) for k in node.keywords
                         if k.arg == "name"}
                default = parameters["name"].default if "name" in parameters else None
                name = given.get("name", quoted.get(node.func.id, default
                                                    or next(iter(parameters))))
                assert name == node.args[0].id, (path.name, ast.unparse(node))


def test_the_renamed_answers_are_quoted_by_their_names():
    pair = synthetic.distorted_pair(seed=2).gcps
    is_check = np.arange(len(pair)) % 3 == 0
    for answer in ("tps", "affine", 2):
        verdict = exercises.check_model_choice(answer, pair.map_xy, pair.image_xy, is_check,
                                               name="choice")
        assert verdict.message.startswith("`choice` is "), verdict.message
        assert "`model`" not in verdict.message
    points = [[775445.0, 7369105.0]]
    for answer in (0.0, "1.5", None):
        verdict = exercises.check_datum_shift_pixels(answer, points, 29191, 31981, 2.5,
                                                     name="hrc_shift_px")
        assert "`hrc_shift_px`" in verdict.message and "`shift_px`" not in verdict.message


def test_summaries_do_not_state_the_answers():
    text = "\n".join(cell.source for cell in exercise_text() if cell.cell_type == "markdown")
    for name in ("growth", "swath", "overshoot"):
        assert not leaks(text, CHECKS[name][2]()), name
    assert not re.search(r"about 7 %", text)


# -- Each check declares its inputs, its right answer and its mistakes ---------------------------

def test_every_check_is_declared_with_its_inputs():
    import inspect

    checks = [name for name in exercises.__all__ if name.startswith("check_")]
    assert sorted(exercises.declarations()) == sorted(checks)
    for name in checks:
        check = getattr(exercises, name)
        declared = exercises.declaration(name)
        assert check.declaration is declared and declared.check == name
        parameters = list(inspect.signature(check).parameters)
        # the inputs are the check's parameters after the answer (a quoted `name` aside)
        answers = len(declared.answer.split(", "))
        assert [p for p in parameters[answers:] if p != "name"] == list(declared.inputs), name
        assert declared.general or declared.mistakes, name
        assert all(isinstance(mistake.hint, str) and mistake.hint
                   for mistake in declared.mistakes), name
    with pytest.raises(ValueError, match="not a check"):
        exercises.declaration("print")


def test_a_declared_mistake_produces_the_answer_that_gets_its_hint():
    # the declaration's right answer and each value-mistake, fed back to the check
    declared = exercises.declaration("check_skew")
    task = declared.task(**SKEW_ARGS)
    assert task.right == pytest.approx(abs(distortion.earth_rotation_skew(**SKEW_ARGS)))
    assert exercises.check_skew(task.right, **SKEW_ARGS).ok
    for mistake in declared.mistakes:
        for wrong in mistake.answers(task):
            if np.isfinite(wrong) and not np.isclose(wrong, task.right, rtol=0.01):
                verdict = exercises.check_skew(wrong, **SKEW_ARGS)
                assert not verdict.ok and mistake.hint in verdict.hint, (wrong, verdict)


def test_the_listed_mistakes_are_the_declared_ones():
    for name, declared in exercises.declarations().items():
        listed = exercises.recognised_mistakes(name)
        assert [hint for kind, hint in listed if kind == "general"] == [declared.general]
        assert {hint for kind, hint in listed if kind == "mistake"} == {
            mistake.hint for mistake in declared.mistakes}


# -- In Portuguese, a verdict is Portuguese throughout --------------------------------------------

ENGLISH_WORDS = {"the", "is", "are", "of", "and", "not", "too", "with", "than", "by", "its", "it",
                 "this", "that", "check", "needs", "number", "between", "times", "wrong", "yet",
                 "one", "value", "values", "your", "you", "holds", "shape", "which", "from",
                 "large", "small", "text", "string", "off", "about", "degree", "lowest", "does",
                 "better", "matched", "segment", "distinct", "gives", "reaches", "window", "but",
                 "lies", "there", "many", "few", "columns", "edge", "blunder", "residual",
                 "matrix", "transposed", "missing", "maps", "points", "misses", "exactly",
                 "where", "or", "written", "spaces", "lower", "case", "choose", "changes",
                 "whole", "holding", "itself", "trailing", "comma", "tuple", "finite", "yes",
                 "did", "function", "return", "without", "still", "task", "yours", "write"}


def english_words(text):
    text = re.sub(r"`[^`]*`|'[^']*'|[\w.]*[._][\w.]+", " ", text)      # code, quoted values
    text = re.sub(r"\([^()]*\)", " ", text)                           # (col, row), (a, b, c, d)
    return set(re.findall(r"[A-Za-z]+", text)) & ENGLISH_WORDS


@pytest.fixture
def portuguese(monkeypatch):
    from rsgeo import language as _i18n

    monkeypatch.setenv("RSGEO_LANG", "pt_BR")
    monkeypatch.setattr(_i18n, "_chosen", None)


@pytest.mark.parametrize("name, answer", [
    ("gain", lambda: 1.37 * gain_offset()[0]),                 # "`gain` is too large ..."
    ("skew", lambda: (2.5,)),                                   # _number: a tuple
    ("skew", lambda: "2.5"),                                    # _number: a string
    ("rms", lambda: np.array([1.0, 2.0])),                      # _number: an array
    ("degree", lambda: 4),                                      # _one_of
    ("degree", lambda: 2.5),                                    # _integer
    ("blunder", lambda: 13),                                    # a position for an id
    ("design", lambda: design("transposed")),
    ("decode", lambda: decoded("groups of 4")),
    ("filter", lambda: 2),
    ("levels", lambda: levels("rounded")),
    ("segment", lambda: 0),
])
def test_a_portuguese_verdict_holds_no_english(portuguese, name, answer):
    verdict = CHECKS[name][0](answer())
    text = repr(verdict)
    assert text.startswith("Ainda não: ") and "\nDica: " in text, text
    assert not english_words(text), (english_words(text), text)


def test_the_english_word_finder_finds_english():
    assert english_words("Ainda não: `gain` is grande demais") == {"is"}
    assert not english_words("Ainda não: `gain` está grande demais, (col, row) e 'nearest'.")
