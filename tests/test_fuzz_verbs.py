"""Hypothesis fuzzing of rsgeo's newer verbs, with test_fuzz's property and helpers.

The property, as in ``test_fuzz``: a call either raises an :class:`rsgeo.errors.RsgeoError` or a
``TypeError`` from rsgeo's own code (``call`` checks where it came from), or returns an answer
that a reference confirms. Spoils the documentation says are refused (NaN, text, booleans,
wrong shapes ...) must be refused. The references:

* ``asprs_horizontal``, ``asprs_vertical``, ``rms_error``, ``classify`` (PEC-PCD and Decreto
  89.817): NumPy in float64, the formulas written here (RMSE per axis, the NSSDA/ASPRS factors,
  the k-th smallest error with k = ceil(0.9 n), the classes' millimetres at the map's scale);
* ``geoid_undulation``, ``to_ellipsoidal``: PROJ through pyproj, a ``vgridshift`` pipeline on
  the shipped ``egm96_15.gtx`` by its path (rsgeo goes through EPSG:4979 -> EPSG:4326+5773);
* ``relief_displacement``: the textbook h tan(theta), NumPy in float64;
* ``FrameCamera``: ``ground_at_height`` then ``project`` gives the measured image points back,
  and the ground point lies on the plane asked for;
* ``RPCModel.project``: the RPC00B ratio of cubic polynomials written here (GDAL's term
  order); ``localize``: the round trip back to the ground; ``refine_rpc``: the least-squares
  bias (NumPy's ``lstsq`` on exact data) and the refined model's projection of the GCPs;
* ``band_misregistration``: a 64 x 64 scene moved by a known shift (Fourier shift theorem);
* ``data.save``: rasterio reads back the same pixels, transform, CRS and nodata.

Every example counts an outcome with ``hypothesis.event``: ``python -m pytest
tests/test_fuzz_verbs.py -p no:xdist --hypothesis-show-statistics`` prints them. Runs are
derandomized (test_fuzz's ``FUZZ`` settings).
"""

import math

import affine
import numpy as np
import pytest
import rasterio
from hypothesis import event, given, settings
from hypothesis import strategies as st
from pyproj import Transformer
from scipy.ndimage import fourier_shift, gaussian_filter
from test_fuzz import FUZZ, REFUSED, call, confirmed, mostly

from rsgeo import accuracy, data, heights, registration, relief, sensors
from rsgeo._proj import GRIDS

QUICK = settings(FUZZ, max_examples=40)

# -- spoiling one array at a time ----------------------------------------------------------------

ARRAY_SPOILS = ["nan", "inf", "empty", "columns", "flat", "text", "bool", "complex", "3d",
                "none", "huge", "list", "int"]
# what the documentation promises to refuse (huge values, lists and integers are answered)
MUST_REFUSE = {"nan", "inf", "empty", "columns", "flat", "text", "bool", "complex", "3d",
               "none"}


def spoiled(array, spoil, rng):
    """``array`` (float64, (n, k)) with one thing wrong: ``spoil`` from ARRAY_SPOILS."""
    array = np.array(array, dtype=np.float64)
    where = (rng.integers(0, array.shape[0]), rng.integers(0, array.shape[1])) \
        if array.size else None
    if spoil in ("nan", "inf") and where is not None:
        array[where] = np.nan if spoil == "nan" else -np.inf
        return array
    return {None: array, "nan": array, "inf": array, "empty": array[:0],
            "columns": np.hstack([array, array[:, :1]]), "flat": array.ravel(),
            "text": array.astype(str), "bool": array > 0, "complex": array + 1j,
            "3d": array[None], "none": np.where(array > 0, None, array).tolist(),
            "huge": array * 1e200, "list": array.tolist(),
            "int": np.round(array).astype(np.int64)}[spoil]


def as_float(value):
    return np.asarray(value, dtype=np.float64)


def close(got, expected, rtol=1e-12, atol=0.0):
    got, expected = np.asarray(got, dtype=np.float64), np.asarray(expected, dtype=np.float64)
    return got.shape == expected.shape and np.allclose(got, expected, rtol=rtol, atol=atol,
                                                       equal_nan=True)


errors_cases = st.fixed_dictionaries({
    "n": st.integers(1, 25), "seed": st.integers(0, 2**16),
    "scale": st.sampled_from([0.01, 1.0, 7.5, 300.0]),
    "anisotropy": st.sampled_from([1.0, 0.7, 0.3, 0.0]),
    "spoil": mostly(st.none(), st.sampled_from(ARRAY_SPOILS), weight=3)})


def _errors(case, columns=2):
    rng = np.random.default_rng(case["seed"])
    errors = rng.normal(0, case["scale"], (case["n"], columns))
    if columns == 2:
        errors[:, 1] *= case["anisotropy"]
    return errors, spoiled(errors, case["spoil"], rng)


# -- rsgeo.accuracy -------------------------------------------------------------------------------

def _reference_horizontal(errors):
    with np.errstate(over="ignore"):
        rmse_x, rmse_y = np.sqrt(np.mean(errors**2, axis=0))
    larger, smaller = max(rmse_x, rmse_y), min(rmse_x, rmse_y)
    ratio = smaller / larger if larger > 0 else 1.0
    rmse_r = math.sqrt(rmse_x**2 + rmse_y**2)
    if ratio >= 0.6:
        return rmse_x, rmse_y, rmse_r, 2.4477 * (rmse_x + rmse_y) / 2, 1.5175 * rmse_r, ratio
    return rmse_x, rmse_y, rmse_r, np.nan, np.nan, ratio


@QUICK
@given(case=errors_cases)
def test_asprs_horizontal_refuses_or_matches_numpy(case):
    good, errors = _errors(case)
    result = call("asprs_horizontal", accuracy.asprs_horizontal, errors)
    if result is REFUSED:
        assert case["spoil"] not in ("list", "int") or len(good) == 0
        return
    assert case["spoil"] not in MUST_REFUSE, f"asprs_horizontal answered {case['spoil']} errors"
    expected = _reference_horizontal(as_float(errors))
    got = (result.rmse_x, result.rmse_y, result.rmse_r, result.accuracy_95, result.ce90,
           result.axis_ratio)
    if not np.isfinite(expected[:3]).all():
        event("asprs_horizontal: float64 overflows (values near 1e200)")
    assert result.n_points == len(good)
    assert close(got, expected, rtol=1e-12), f"{got} != {expected}"
    confirmed("asprs_horizontal")


@pytest.mark.parametrize("dz", [np.array(["0.5", "1.5"]), [True, False],
                                np.array([1 + 1j, 2.0])], ids=["text", "bool", "complex"])
def test_asprs_vertical_refuses_text_booleans_and_complex(dz):
    # found by the fuzz below: asprs_vertical read text as numbers, booleans as 0/1 and complex
    # numbers without their imaginary part, where asprs_horizontal and classify refuse them
    with pytest.raises(TypeError, match="dz must be a number or numbers"):
        accuracy.asprs_vertical(dz)


@QUICK
@given(case=errors_cases)
def test_asprs_vertical_refuses_or_matches_numpy(case):
    good, errors = _errors(case, columns=1)
    if case["spoil"] not in ("columns", "3d", "none"):
        errors = np.asarray(errors)[:, 0] if np.ndim(errors) == 2 else errors
    result = call("asprs_vertical", accuracy.asprs_vertical, errors)
    if result is REFUSED:
        assert case["spoil"] not in ("list", "int", "flat", None), errors
        return
    assert case["spoil"] not in MUST_REFUSE - {"flat"}, f"answered {case['spoil']} dz"
    with np.errstate(over="ignore"):
        rmse = math.sqrt(np.mean(as_float(errors) ** 2))
    got = (result.rmse_z, result.le90, result.accuracy_95)
    assert close(got, (rmse, 1.6449 * rmse, 1.96 * rmse)), got
    assert result.n_points == len(good)
    confirmed("asprs_vertical")


@QUICK
@given(case=errors_cases, which=st.sampled_from(["predicted", "observed", "length"]))
def test_rms_error_refuses_or_matches_numpy(case, which):
    good, bad = _errors(case)
    rng = np.random.default_rng(case["seed"] + 1)
    other = rng.uniform(-1e3, 1e3, good.shape)
    if which == "length":                      # mismatched lengths, nothing else wrong
        predicted, observed = good, other[:-1] if len(other) > 1 else other[:0]
    else:
        predicted, observed = (bad, other) if which == "predicted" else (other, bad)
    result = call("rms_error", accuracy.rms_error, predicted, observed)
    if result is REFUSED:
        assert which == "length" or case["spoil"] not in ("list", "int", None)
        return
    assert which != "length", "rms_error answered points of different lengths"
    one_point = case["spoil"] == "flat" and case["n"] == 1      # [x, y]: one point
    assert one_point or case["spoil"] not in MUST_REFUSE, f"answered {case['spoil']} points"
    difference = as_float(predicted) - as_float(observed)
    with np.errstate(over="ignore"):
        expected = math.sqrt(np.mean(np.sum(difference**2, axis=1)))
    assert isinstance(result, float) and close(result, expected), (result, expected)
    confirmed("rms_error")


PEC_MM = {"PEC-PCD": {"A": (0.28, 0.17), "B": (0.5, 0.3), "C": (0.8, 0.5), "D": (1.0, 0.6)},
          "Decreto 89.817": {"A": (0.5, 0.3), "B": (0.8, 0.5), "C": (1.0, 0.6)}}
odd_scales = st.sampled_from([0, -25000, 0.5, float("nan"), float("inf"), "25000", True, None,
                              [25000], 1e300])


@QUICK
@given(case=errors_cases, distances=st.booleans(),
       scale=mostly(st.sampled_from([1000, 5000, 25000, 50_000.0, 250000]), odd_scales),
       standard=mostly(st.sampled_from(list(PEC_MM)), st.sampled_from(["pec-pcd", "", 3])))
def test_classify_refuses_or_matches_the_decree(case, distances, scale, standard):
    good, errors = _errors(case)
    if distances and case["spoil"] in (None, "huge", "list", "int"):
        errors = np.hypot(*as_float(errors).T)          # lengths: (n,)
    result = call("classify", accuracy.classify, errors, scale, standard)
    if result is REFUSED:
        ok_input = case["spoil"] in (None, "list", "int", "huge")
        assert not ok_input or standard not in PEC_MM or not (
            isinstance(scale, (int, float)) and not isinstance(scale, bool)
            and 1 <= scale < math.inf), "classify refused a valid call"
        return
    assert case["spoil"] not in MUST_REFUSE - {"flat"}, f"classify answered {case['spoil']}"
    assert standard in PEC_MM and not isinstance(scale, bool) and 1 <= float(scale) < math.inf
    d = as_float(errors)
    d = np.hypot(d[:, 0], d[:, 1]) if d.ndim == 2 else d
    n = len(d)
    rms = math.sqrt(np.mean(d**2))
    kth = float(np.sort(d)[math.ceil(round(0.9 * n, 9)) - 1])
    thresholds = {name: (pec * scale / 1000, ep * scale / 1000)
                  for name, (pec, ep) in PEC_MM[standard].items()}
    pec_test = {name: np.mean(d <= pec) >= 0.9 - 1e-12 for name, (pec, _) in thresholds.items()}
    ep_test = {name: rms <= ep for name, (_, ep) in thresholds.items()}
    best = next((name for name in thresholds if pec_test[name] and ep_test[name]), None)
    assert result.n_points == n and close(result.rms, rms) and result.percentile_90 == kth
    assert list(result.thresholds) == list(thresholds)
    assert close([result.thresholds[k] for k in thresholds], list(thresholds.values()))
    assert result.pec_test == pec_test and result.ep_test == ep_test
    assert result.best == best, (result.best, best)
    confirmed("classify", "a class" if best else "no class")


# -- rsgeo.heights --------------------------------------------------------------------------------

WEST, SOUTH, EAST, NORTH = heights.geoid_coverage()
VGRIDSHIFT = Transformer.from_pipeline(
    "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
    f"+step +proj=vgridshift +grids={GRIDS / 'egm96_15.gtx'} +multiplier=1 "
    "+step +proj=unitconvert +xy_in=rad +xy_out=deg")


def proj_undulation(lon, lat):
    lon, lat = as_float(lon), as_float(lat)
    _x, _y, n = VGRIDSHIFT.transform(lon.ravel(), lat.ravel(), np.zeros(lon.size))
    return np.asarray(n, dtype=np.float64).reshape(lon.shape)


POINT_SPOILS = ["nan", "outside", "text", "bool", "lengths", "inf", "complex", "none", "edge",
                "empty", "scalar", "list", "2d"]
POINT_REFUSED = {"nan", "outside", "text", "bool", "lengths", "inf", "complex", "none"}


@st.composite
def geoid_points(draw):
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    n = draw(st.integers(1, 8))
    lon, lat = rng.uniform(WEST, EAST, n), rng.uniform(SOUTH, NORTH, n)
    spoil = draw(mostly(st.none(), st.sampled_from(POINT_SPOILS), weight=3))
    if spoil == "nan":
        lat[0] = np.nan
    elif spoil == "inf":
        lon[-1] = np.inf
    elif spoil == "outside":
        lon[0] = draw(st.sampled_from([WEST - 1e-9, EAST + 0.5, 200.0, -1e300]))
    elif spoil == "edge":
        lon[0], lat[0] = draw(st.sampled_from([(WEST, SOUTH), (EAST, NORTH), (WEST, NORTH)]))
    spoilt = {"text": (lon.astype(str), lat), "bool": (lon, lat > -20),
              "lengths": (lon, lat[:-1] if n > 1 else lat[:0]),
              "complex": (lon + 0j, lat), "none": ([None] * n, lat),
              "empty": (lon[:0], lat[:0]), "scalar": (float(lon[0]), float(lat[0])),
              "list": (lon.tolist(), lat.tolist()),
              "2d": (lon.reshape(-1, 1), lat.reshape(-1, 1))}.get(spoil, (lon, lat))
    return spoil, spoilt


@QUICK
@given(points=geoid_points(), geoid=mostly(st.just("EGM96"), st.sampled_from(["EGM2008", ""])))
def test_geoid_undulation_refuses_or_matches_proj(points, geoid):
    spoil, (lon, lat) = points
    got = call("geoid_undulation", heights.geoid_undulation, lon, lat, geoid)
    if got is REFUSED:
        assert spoil in POINT_REFUSED or geoid != "EGM96", f"refused {spoil}"
        return
    assert spoil not in POINT_REFUSED and geoid == "EGM96", f"answered {spoil} / {geoid}"
    expected = proj_undulation(lon, lat)
    assert close(got, expected, rtol=0, atol=1e-9), (got, expected)
    confirmed("geoid_undulation", spoil or "")


@QUICK
@given(points=geoid_points(), seed=st.integers(0, 100),
       vertical=mostly(st.just("EGM96"), st.sampled_from(["ellipsoidal", "egm96", "geoid"])),
       height_spoil=mostly(st.none(), st.sampled_from(["nan", "text", "bool", "shape",
                                                       "huge", "scalar"])))
def test_to_ellipsoidal_refuses_or_adds_proj_undulation(points, seed, vertical, height_spoil):
    spoil, (lon, lat) = points
    shape = np.shape(lon)
    height = np.random.default_rng(seed).uniform(-100, 3000, shape)
    height = {None: height, "nan": np.full(shape, np.nan), "text": height.astype(str),
              "bool": height > 1000, "shape": np.append(height, 1.0), "huge": height * 1e300,
              "scalar": 10.0}[height_spoil]
    got = call("to_ellipsoidal", heights.to_ellipsoidal, height, lon, lat, vertical)
    if got is REFUSED:
        return
    assert height_spoil not in ("text", "bool"), "to_ellipsoidal answered heights of text/bool"
    assert vertical in ("EGM96", "ellipsoidal"), f"answered vertical={vertical!r}"
    if vertical == "ellipsoidal":
        assert close(got, as_float(height), rtol=0), "ellipsoidal heights changed"
        confirmed("to_ellipsoidal", "ellipsoidal")
        return
    assert spoil not in POINT_REFUSED, f"to_ellipsoidal answered {spoil} points"
    assert height_spoil not in ("shape",), "answered heights of another shape"
    expected = as_float(height) + proj_undulation(*np.broadcast_arrays(
        as_float(lon), as_float(lat)))
    expected = np.broadcast_to(expected, np.broadcast_shapes(np.shape(height), np.shape(lon)))
    assert close(got, expected, rtol=1e-15, atol=1e-9), (got, expected)
    confirmed("to_ellipsoidal", height_spoil or "")


# -- rsgeo.relief ---------------------------------------------------------------------------------

odd_values = st.sampled_from([float("nan"), float("inf"), "45", True, None, [], 1 + 1j,
                              [[1.0], [2.0, 3.0]]])


@QUICK
@given(height=mostly(st.one_of(st.floats(-1e4, 1e4), st.lists(st.floats(-1e4, 1e4),
                                                              max_size=5).map(np.array),
                               st.just(1e300)), odd_values),
       angle=mostly(st.one_of(st.floats(0, 89.9999), st.sampled_from([0, 45, 89.999999999])),
                    st.one_of(odd_values, st.sampled_from([90.0, -1e-9, 180.0, -5.0]))))
def test_relief_displacement_refuses_or_is_h_tan_theta(height, angle):
    got = call("relief_displacement", relief.relief_displacement, height, angle)
    try:
        h, a = np.asarray(height), np.asarray(angle)
        valid = (h.dtype.kind in "if" and a.dtype.kind in "if" and np.isfinite(h).all()
                 and np.isfinite(a).all() and ((a >= 0) & (a < 90)).all()
                 and np.broadcast_shapes(h.shape, a.shape) is not None)
    except ValueError:                 # ragged lists, shapes that do not broadcast
        valid = False
    if got is REFUSED:
        assert not valid, "refused a valid call"
        return
    assert h.dtype.kind in "iuf" and a.dtype.kind in "iuf", f"answered {height!r}, {angle!r}"
    assert ((a >= 0) & (a < 90)).all() and np.isfinite(h).all()
    expected = as_float(h) * np.tan(np.radians(as_float(a)))
    if not np.isfinite(expected).all():
        event("relief_displacement: an infinite answer for finite inputs")
    assert close(got, expected, rtol=1e-15), (got, expected)
    assert isinstance(got, float) == (expected.ndim == 0)
    confirmed("relief_displacement")


# -- rsgeo.sensors: frame camera ------------------------------------------------------------------

@st.composite
def cameras(draw):
    focal = draw(mostly(st.sampled_from([50.0, 153.0, 100.0]),
                        st.sampled_from([0.0, -100.0, float("nan"), "100", True])))
    size = draw(mostly(st.sampled_from([(2000, 1500), (640, 480)]),
                       st.sampled_from([(0, 10), (10.5, 20), (100,), ("a", 2)])))
    k1 = draw(st.sampled_from([0.0, 0.0, 1e-6, -1e-7]))
    interior = call("InteriorOrientation", sensors.InteriorOrientation, focal, 0.01, size,
                    (0.02, -0.01), k1)
    angles = draw(st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-180, 180)))
    centre = draw(mostly(st.tuples(st.floats(-1e5, 1e5), st.floats(-1e5, 1e5),
                                   st.floats(500, 5000)),
                         st.sampled_from([(0.0, float("nan"), 1000.0), (0, 0, float("inf")),
                                          ("0", 0, 1000), (0, 0, True)])))
    exterior = call("ExteriorOrientation", sensors.ExteriorOrientation, *centre, *angles)
    return interior, exterior


@QUICK
@given(camera=cameras(), seed=st.integers(0, 2**16), n=st.integers(1, 6),
       spoil=mostly(st.none(), st.sampled_from(["nan", "flat", "columns", "text", "bool",
                                                "heights", "above", "empty", "list"])))
def test_frame_camera_ground_at_height_then_project_round_trips(camera, seed, n, spoil):
    interior, exterior = camera
    if interior is REFUSED or exterior is REFUSED:
        return
    model = call("FrameCamera", sensors.FrameCamera, interior, exterior)
    assert model is not REFUSED
    rng = np.random.default_rng(seed)
    cols, rows = interior.size
    image_xy = rng.uniform(0, 1, (n, 2)) * (cols, rows)
    height = rng.uniform(-200, 400, n)
    if spoil == "above":
        height[0] = exterior.z0 + 10.0
    elif spoil == "heights":
        height = height[:-1] if n > 1 else np.ones(2)
    points = spoiled(image_xy, None if spoil in ("above", "heights") else spoil, rng)
    ground = call("ground_at_height", model.ground_at_height, points, height)
    if ground is REFUSED:
        assert spoil not in (None, "list"), "ground_at_height refused good points"
        return
    assert spoil in (None, "list", "empty"), f"ground_at_height answered {spoil}"
    assert ground.shape == (len(image_xy) if spoil != "empty" else 0, 3)
    if spoil == "empty":
        confirmed("ground_at_height", "empty")
        return
    assert close(ground[:, 2], height, rtol=0, atol=1e-9), "not on the plane asked for"
    back = call("project", model.project, ground)
    assert back is not REFUSED, "project refused the ground ground_at_height gave"
    assert close(back, image_xy, rtol=0, atol=1e-6), np.abs(back - image_xy).max()
    confirmed("FrameCamera round trip", "distortion" if interior.k1 else "")


# -- rsgeo.sensors: RPC ---------------------------------------------------------------------------

def _rpc_terms(L, P, H):
    return np.array([np.ones_like(L), L, P, H, L * P, L * H, P * H, L * L, P * P, H * H,
                     P * L * H, L**3, L * P * P, L * H * H, L * L * P, P**3, P * H * H,
                     L * L * H, P * P * H, H**3])


def reference_rpc_project(d, lon, lat, height):
    """RPC00B as written in the standard: GDAL's (col, row) = (sample + 0.5, line + 0.5)."""
    lon, lat, height = np.broadcast_arrays(as_float(lon), as_float(lat), as_float(height))
    terms = _rpc_terms((lon - d["LONG_OFF"]) / d["LONG_SCALE"],
                       (lat - d["LAT_OFF"]) / d["LAT_SCALE"],
                       (height - d["HEIGHT_OFF"]) / d["HEIGHT_SCALE"])

    def ratio(name):
        return (np.tensordot(d[f"{name}_NUM_COEFF"], terms, 1)
                / np.tensordot(d[f"{name}_DEN_COEFF"], terms, 1))
    return (ratio("SAMP") * d["SAMP_SCALE"] + d["SAMP_OFF"] + 0.5,
            ratio("LINE") * d["LINE_SCALE"] + d["LINE_OFF"] + 0.5)


def _rpc_dict(seed, strength):
    rng = np.random.default_rng(seed)
    d = sensors.simple_rpc_dict()
    for key, size in (("LINE_NUM_COEFF", 0.02), ("SAMP_NUM_COEFF", 0.02),
                      ("LINE_DEN_COEFF", 0.002), ("SAMP_DEN_COEFF", 0.002)):
        coefficients = np.array(d[key], dtype=np.float64)
        coefficients[1:] += rng.uniform(-1, 1, 19) * size * strength
        d[key] = coefficients.tolist()
    return d


DICT_SPOILS = ["scale 0", "missing", "19 coefficients", "text", "nan offset", "string coeffs"]


def _spoil_dict(d, spoil):
    d = dict(d)
    if spoil == "scale 0":
        d["LAT_SCALE"] = 0.0
    elif spoil == "missing":
        del d["LINE_OFF"]
    elif spoil == "19 coefficients":
        d["SAMP_NUM_COEFF"] = d["SAMP_NUM_COEFF"][:19]
    elif spoil == "text":
        d["SAMP_OFF"] = "five hundred"
    elif spoil == "nan offset":
        d["LONG_OFF"] = float("nan")
    elif spoil == "string coeffs":                      # GDAL's own form: accepted
        d["LINE_NUM_COEFF"] = " ".join(repr(c) for c in d["LINE_NUM_COEFF"])
        d["LINE_OFF"] = "500"
    return d


@QUICK
@given(seed=st.integers(0, 2**16), strength=st.sampled_from([0.0, 0.3, 1.0]),
       n=st.integers(1, 6),
       dict_spoil=mostly(st.none(), st.sampled_from(DICT_SPOILS), weight=4),
       point_spoil=mostly(st.none(), st.sampled_from(["nan", "lat 95", "text", "bool",
                                                      "lengths", "huge", "empty", "scalar",
                                                      "inf height"]), weight=3))
def test_rpc_project_matches_the_formula_and_localize_returns(seed, strength, n, dict_spoil,
                                                              point_spoil):
    d = _spoil_dict(_rpc_dict(seed, strength), dict_spoil)
    rpc = call("RPCModel.from_dict", sensors.RPCModel.from_dict, d)
    if rpc is REFUSED:
        assert dict_spoil not in (None, "string coeffs"), "from_dict refused a valid dict"
        return
    assert dict_spoil in (None, "string coeffs"), f"from_dict took {dict_spoil}"
    d = {k: (np.array(v.split(), dtype=float) if isinstance(v, str) and " " in v
             else as_float(v)) for k, v in d.items()}
    rng = np.random.default_rng(seed + 1)
    lon = -34.9 + rng.uniform(-0.04, 0.04, n)
    lat = -8.0 + rng.uniform(-0.04, 0.04, n)
    height = rng.uniform(-100, 500, n)
    if point_spoil == "nan":
        lon[0] = np.nan
    elif point_spoil == "lat 95":
        lat[-1] = 95.0
    elif point_spoil == "inf height":
        height[0] = np.inf
    lon, lat, height = {"text": (lon.astype(str), lat, height), "bool": (lon, lat, height > 0),
                        "lengths": (np.append(lon, -34.9), np.append(lat, [-8, -8]),
                                    height),
                        "huge": (lon * 1e300, lat, height), "empty": (lon[:0], lat[:0], 0.0),
                        "scalar": (float(lon[0]), float(lat[0]), 0.0)}.get(
        point_spoil, (lon, lat, height))
    got = call("RPCModel.project", rpc.project, lon, lat, height)
    if got is REFUSED:
        assert point_spoil not in (None, "empty", "scalar"), "project refused valid points"
        return
    assert point_spoil in (None, "empty", "scalar"), f"project answered {point_spoil}"
    expected = reference_rpc_project(d, lon, lat, height)
    assert close(got[0], expected[0], rtol=1e-12, atol=1e-9)
    assert close(got[1], expected[1], rtol=1e-12, atol=1e-9)
    back = call("RPCModel.localize", rpc.localize, got[0], got[1], height)
    if back is REFUSED:
        event("RPCModel.localize: refused to invert (did not converge)")
        assert strength > 0, "localize refused on the near-linear RPC"
        return
    assert close(back[0], lon, rtol=0, atol=1e-9) and close(back[1], lat, rtol=0, atol=1e-9)
    confirmed("RPCModel project/localize", point_spoil or "")


GCP_SPOILS = ["nan", "one gcp", "collinear", "kind", "text", "missing", "lengths", "array",
              "rpc", "inf"]


@QUICK
@given(seed=st.integers(0, 2**16), n=st.integers(1, 12),
       kind=st.sampled_from(["shift", "affine"]),
       bias=st.tuples(st.floats(-20, 20), st.floats(-1e-3, 1e-3), st.floats(-1e-3, 1e-3),
                      st.floats(-20, 20), st.floats(-1e-3, 1e-3), st.floats(-1e-3, 1e-3)),
       spoil=mostly(st.none(), st.sampled_from(GCP_SPOILS), weight=3))
def test_refine_rpc_refuses_or_recovers_the_least_squares_bias(seed, n, kind, bias, spoil):
    d = _rpc_dict(seed, 0.5)
    rpc = sensors.RPCModel.from_dict(d)
    rng = np.random.default_rng(seed)
    lon = -34.9 + rng.uniform(-0.04, 0.04, n)
    lat = -8.0 + rng.uniform(-0.04, 0.04, n)
    if spoil == "collinear":
        lat = -8.0 + (lon + 34.9)          # on one line on the ground and nearly in the image
    height = rng.uniform(0, 300, n)
    col, row = reference_rpc_project(d, lon, lat, height)
    a0, a1, a2, b0, b1, b2 = bias
    if kind == "shift":
        a1 = a2 = b1 = b2 = 0.0
    measured_col = col + a0 + a1 * col + a2 * row
    measured_row = row + b0 + b1 * col + b2 * row
    gcps = {"lon": lon, "lat": lat, "height": height, "col": measured_col, "row": measured_row}
    if spoil == "nan":
        gcps["col"] = np.where(np.arange(n) == 0, np.nan, measured_col)
    elif spoil == "inf":
        gcps["height"] = np.where(np.arange(n) == n - 1, np.inf, height)
    elif spoil == "one gcp":
        gcps = {k: v[:1] for k, v in gcps.items()}
    elif spoil == "text":
        gcps["row"] = measured_row.astype(str)
    elif spoil == "missing":
        del gcps["lat"]
    elif spoil == "lengths":
        gcps["lon"] = np.append(lon, -34.9)
    elif spoil == "array":
        gcps = np.column_stack([lon, lat, height, measured_col, measured_row])
    kind_arg = "similarity" if spoil == "kind" else kind
    rpc_arg = [1, 2, 3] if spoil == "rpc" else rpc
    refined = call("refine_rpc", sensors.refine_rpc, rpc_arg, gcps, kind_arg)
    used = n if spoil != "one gcp" else 1
    if refined is REFUSED:
        valid = spoil in (None, "array", "collinear", "one gcp")
        assert not valid or (kind == "affine" and (used < 3 or spoil == "collinear")), \
            f"refine_rpc refused {used} GCPs ({spoil})"
        return
    assert spoil in (None, "array", "collinear", "one gcp"), f"refine_rpc answered {spoil}"
    keep = slice(0, used)
    col, row = col[keep], row[keep]
    design = (np.ones((used, 1)) if kind == "shift"
              else np.column_stack([np.ones(used), col, row]))
    dcol = np.linalg.lstsq(design, measured_col[keep] - col, rcond=None)[0]
    drow = np.linalg.lstsq(design, measured_row[keep] - row, rcond=None)[0]
    p = refined.parameters
    got = ([p["a0"]] if kind == "shift" else [p["a0"], p["a1"], p["a2"]],
           [p["b0"]] if kind == "shift" else [p["b0"], p["b1"], p["b2"]])
    assert close(got[0], dcol, rtol=1e-6, atol=1e-6), (got, dcol)
    assert close(got[1], drow, rtol=1e-6, atol=1e-6), (got, drow)
    new_col, new_row = refined.project(lon[keep], lat[keep], height[keep])
    assert close(new_col, measured_col[keep], rtol=0, atol=1e-6)
    assert close(new_row, measured_row[keep], rtol=0, atol=1e-6)
    assert refined.rms < 1e-6
    confirmed("refine_rpc", kind)


# -- rsgeo.registration.band_misregistration ------------------------------------------------------

SCENE = gaussian_filter(np.random.default_rng(7).normal(size=(64, 64)), 2, mode="wrap")
BAND_SPOILS = ["nan", "2d", "one band", "window 100", "window 4", "text", "upsample 0",
               "feature", "names", "valid shape", "window 31.5", "upsample str", "constant"]


@QUICK
@given(shift=st.tuples(st.sampled_from([0.0, 1.0, -2.0, 0.25, -0.5, 1.75]),
                       st.sampled_from([0.0, -1.0, 2.0, 0.5, -0.25, 1.3])),
       inverted=st.booleans(),
       spoil=mostly(st.none(), st.sampled_from(BAND_SPOILS), weight=2))
def test_band_misregistration_refuses_or_finds_the_known_shift(shift, inverted, spoil):
    moved = np.fft.ifft2(fourier_shift(np.fft.fft2(SCENE), shift[::-1])).real
    bands = np.stack([SCENE, -moved if inverted else moved])
    kwargs = dict(window=32, upsample=20)
    if spoil == "nan":
        bands[1, 3, 4] = np.nan
    elif spoil == "2d":
        bands = bands[0]
    elif spoil == "one band":
        bands = bands[:1]
    elif spoil == "text":
        bands = bands.astype(str)
    elif spoil == "constant":
        bands = np.ones_like(bands)
    elif spoil is not None:
        key, value = {"window 100": ("window", 100), "window 4": ("window", 4),
                      "upsample 0": ("upsample", 0), "feature": ("feature", "phase"),
                      "names": ("names", ["only one"]), "valid shape": ("valid", np.ones(
                          (3, 3), bool)), "window 31.5": ("window", 31.5),
                      "upsample str": ("upsample", "20")}[spoil]
        kwargs[key] = value
    table = call("band_misregistration", registration.band_misregistration, bands, **kwargs)
    if table is REFUSED:
        assert spoil is not None, f"refused a scene moved by {shift}"
        return
    assert spoil is None, f"band_misregistration answered {spoil}"
    dx, dy = table[["dx (px)", "dy (px)"]].to_numpy()[0]
    assert abs(dx - shift[0]) <= 0.1 and abs(dy - shift[1]) <= 0.1, ((dx, dy), shift)
    confirmed("band_misregistration", "inverted" if inverted else "")


# -- rsgeo.data.save ------------------------------------------------------------------------------

SAVE_DTYPES = ["uint8", "int8", "uint16", "int16", "int32", "uint32", "int64", "uint64",
               "float16", "float32", "float64", ">i2", ">f8", "complex64", "bool"]
SAVE_SPOILS = ["1d", "4d", "rgb last", "nodata big", "nodata text", "nodata bool",
               "transform tuple", "transform flat", "crs", "folder", "empty"]


@QUICK
@given(dtype=st.sampled_from(SAVE_DTYPES), bands=st.sampled_from([None, 1, 2]),
       shape=st.tuples(st.integers(1, 5), st.integers(1, 5)), seed=st.integers(0, 2**16),
       crs=st.sampled_from([None, "EPSG:31983", 4326]),
       nodata=st.sampled_from([None, 0, 1, float("nan")]),
       spoil=mostly(st.none(), st.sampled_from(SAVE_SPOILS), weight=3))
def test_save_then_rasterio_reads_the_same(tmp_path_factory, dtype, bands, shape, seed, crs,
                                           nodata, spoil):
    rng = np.random.default_rng(seed)
    full = (bands, *shape) if bands else shape
    array = (rng.uniform(0, 100, full) + (1j if dtype.startswith("complex") else 0)).astype(
        dtype)
    transform = affine.Affine(10.0, 0, 500_000.0, 0, -10.0, 7_400_000.0)
    folder = tmp_path_factory.mktemp("save")
    path = folder / "out.tif"
    arguments = dict(transform=transform, crs=crs, nodata=nodata)
    if spoil == "1d":
        array = array.ravel()
    elif spoil == "4d":
        array = array[None, None]
    elif spoil == "rgb last":
        array = np.zeros((*shape, 3), dtype)
    elif spoil == "empty":
        array = array[..., :0]
    elif spoil == "nodata big":
        arguments["nodata"] = 1e40
    elif spoil == "nodata text":
        arguments["nodata"] = "0"
    elif spoil == "nodata bool":
        arguments["nodata"] = True
    elif spoil == "transform tuple":
        arguments["transform"] = tuple(transform)[:6]      # affine's order: refused
    elif spoil == "transform flat":
        arguments["transform"] = affine.Affine(0.0, 0, 500_000.0, 0, -10.0, 7_400_000.0)
    elif spoil == "crs":
        arguments["crs"] = "EPSG:0"
    elif spoil == "folder":
        path = folder / "missing" / "out.tif"
    written = call("save", data.save, path, array, **arguments)
    if written is REFUSED:
        assert not path.exists(), "a refused save left a file"
        if spoil is None:
            event(f"save: refused dtype {dtype}, nodata {nodata!r}")
        return
    assert spoil in (None, "rgb last") or (spoil == "nodata big" and array.dtype.kind in "fc"), \
        f"save answered {spoil}"
    with rasterio.open(written) as dataset:
        back = dataset.read()
        assert dataset.transform == arguments["transform"]
        expected_crs = None if crs is None else rasterio.crs.CRS.from_user_input(crs)
        assert dataset.crs == expected_crs
        given_nodata = arguments["nodata"]
        assert (dataset.nodata is None) == (given_nodata is None)
        if given_nodata is not None:
            assert dataset.nodata == given_nodata or (math.isnan(dataset.nodata)
                                                     and math.isnan(given_nodata))
    expected = array if array.ndim == 3 else array[None]
    assert back.shape == expected.shape
    assert np.array_equal(back, expected, equal_nan=True), "pixels changed"
    confirmed("save", str(np.dtype(dtype)))

