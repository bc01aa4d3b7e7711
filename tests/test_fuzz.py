"""Hypothesis fuzzing of rsgeo's core verbs: a clear refusal or an answer a reference confirms.

The property, for every verb ("Errors are part of the API" in the design): a call
either raises an :class:`rsgeo.errors.RsgeoError` or a ``TypeError`` *from rsgeo's own code*, or
returns an answer that a reference confirms. Never an exception from inside NumPy, SciPy, Numba,
rasterio or PROJ, and never an unconfirmed answer. The references:

* ``interpolate`` and ``warp``: GDAL's warper through a VRT (``rsgeo_course.gdal_reference``),
  pixel for pixel (64-bit integers to GDAL's double precision), but for AvoidNoData on floats (a
  valid float equal to nodata moves to the next float up, as GDAL does since 3.11; the reference is
  GDAL 3.10, which leaves it);
* ``orthorectify``: GDAL's RPC transformer with a DEM (``gdalwarp -rpc -to RPC_DEM=…``), but for
  rsgeo.ortho's one documented difference (a valid value equal to the nodata 0 is moved off
  it, GDAL's AvoidNoData, which GDAL's ``reproject`` does not apply);
* ``datum_shift``: PROJ through pyproj's own Transformer, with the grids rsgeo ships put on its
  path for the reference's call only
  (rasterio's GDAL searches one folder, its wheel's, so it has no grid and would use EPSG:15485);
* ``fit_transform``: exact data (``model(src)`` gives ``dst``), GDAL's TPS transformer for
  ``"tps"``, and for GCPs that disagree the least-squares fit (NumPy in float64, scikit-image's
  projective estimate); ``refine_gcps``: GDAL's stopping rule and a refit on the kept GCPs;
* ``fit_gain_offset``: NumPy in float64; ``apply_gain_offset``: exact rational arithmetic;
* ``genetic_match``: the fitness recomputed and the certified optimum (``optimum_match``);
* ``correlation_tiepoints``: images cut from one scene at a known shift;
* ``read_points`` / ``write_points``: the round trip, and files written by hand.

Inputs are drawn wide: NaN and infinities, empty and wrongly shaped arrays, every NumPy dtype
(int8 … uint64, float16/32/64, bool, complex, big-endian), lists, strings for numbers,
duplicated and collinear GCPs, huge and tiny values; mostly one bad thing at a time, so that
many examples reach an answer to confirm. Every example counts an outcome with
``hypothesis.event``: ``python -m pytest tests/test_fuzz.py -p no:xdist
--hypothesis-show-statistics`` prints them. Runs are derandomized (the same examples on every
machine, no example database).

The bugs in rsgeo that the fuzz found are explicit examples: those fixed (nodata's type, a
complex DEM, float16's kernel) run as any example; the one left (``CENTRE_BUG``) is a strict
``xfail`` test with the bug in its reason (once fixed it fails as "expected to fail" and the
mark goes), and the comparison leaves its pixels out (counted by an event), so that the rest
keeps being checked. ``datum_shift`` draws
coordinates up to 1e7; 1e30 has its own test (PROJ did not return on it).

Time: about 3 s with Numba's cache of rsgeo's kernels in place. The first run after a change to
one of rsgeo's compiled modules (which empties that cache) first compiles the loops the examples
reach: each interpolating loop for uint8 and for float64 (every other type is read as float64),
nearest for the four widths of its bits, a few CPU-seconds each.
"""

import math
import os
import signal
import traceback
import warnings
from fractions import Fraction
from pathlib import Path

import affine
import numpy as np
import pytest
import rasterio
from hypothesis import HealthCheck, Phase, event, example, given, settings
from hypothesis import strategies as st

import rsgeo
from rsgeo import accuracy, crs, gcp, ortho, radiometry, registration, sensors, transforms
from rsgeo.errors import RsgeoError
from rsgeo.resample import interpolate, warp
from rsgeo_course.gdal_reference import GDAL_TYPES as GDAL_REFERENCE_TYPES

from gdal_reference import affine_source, gdal_warp

FUZZ = settings(max_examples=60, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.filter_too_much])
# GDAL's answers cost milliseconds each: a failing example is reported as found, unshrunk
FUZZ_GDAL = settings(FUZZ, max_examples=50, phases=[Phase.explicit, Phase.generate])
RSGEO_DIR = Path(rsgeo.__file__).resolve().parent
REFUSED = object()
# CPU-seconds for one call on these small inputs, Numba compiling included (a few CPU-s
# per kernel on a cold cache): a hang guard with a wide margin, counted in CPU time, which
# a slow or loaded machine does not stretch as it stretches the clock
CPU_LIMIT = 900.0


class _TooSlow(Exception):
    pass


def _too_slow(signum, frame):
    raise _TooSlow

# the types GDAL 3.10 (inside rasterio 1.4.4) warps
GDAL_TYPES = GDAL_REFERENCE_TYPES

INT_DTYPES = ["int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"]
FLOAT_DTYPES = ["float16", "float32", "float64"]
ODD_DTYPES = ["bool", "complex64", "complex128", ">i2", ">u4", ">f4", ">f8", ">i8"]
ALL_DTYPES = INT_DTYPES + FLOAT_DTYPES + ODD_DTYPES


def call(verb, function, *args, **kwargs):
    """``function(*args, **kwargs)``, or REFUSED when rsgeo refused it itself.

    A RsgeoError or TypeError must come from a line of rsgeo (the innermost frame of its
    traceback): the same types raised inside NumPy, SciPy, Numba or rasterio fail the test, as
    does any other exception.
    """
    previous = signal.signal(signal.SIGPROF, _too_slow)
    signal.setitimer(signal.ITIMER_PROF, CPU_LIMIT)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = function(*args, **kwargs)
    except _TooSlow:
        raise AssertionError(f"{verb} used more than {CPU_LIMIT:g} CPU-s on a small input "
                             "(an argument it should have refused?)") from None
    except (RsgeoError, TypeError) as error:
        frame = traceback.extract_tb(error.__traceback__)[-1]
        origin = Path(frame.filename).resolve()
        if RSGEO_DIR not in origin.parents or not _raised_by_rsgeo(error, frame):
            raise AssertionError(
                f"{verb}: {type(error).__name__} raised inside a dependency "
                f"({frame.filename}:{frame.lineno}): {error}") from error
        event(f"{verb}: refused ({type(error).__name__})")
        if os.environ.get("RSGEO_FUZZ_VERBOSE"):       # what each refusal said
            print(f"{verb}: {type(error).__name__}: {error}"[:300])
        return REFUSED
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
    if any(issubclass(w.category, RuntimeWarning) for w in caught):
        event(f"{verb}: answered with a RuntimeWarning from a dependency")
    return result


def unchanged(before, after):
    """True when ``after`` holds what ``before`` held (NaN equal to NaN, any dtype)."""
    before, after = np.asarray(before), np.asarray(after)
    if before.shape != after.shape or before.dtype != after.dtype:
        return False
    if before.dtype.kind in "fc":
        return np.array_equal(before, after, equal_nan=True)
    return np.array_equal(before, after)


def _raised_by_rsgeo(error, frame):
    """An RsgeoError is rsgeo's; a TypeError must come from a ``raise`` statement of rsgeo (not
    from a NumPy ufunc or a builtin called on an rsgeo line): its statement starts within the
    few lines above the traceback's line."""
    if isinstance(error, RsgeoError):
        return True
    import linecache

    lines = [linecache.getline(frame.filename, n).lstrip()
             for n in range(max(frame.lineno - 4, 1), frame.lineno + 1)]
    return any(line.startswith("raise") for line in lines)


def confirmed(verb, detail=""):
    event(f"{verb}: confirmed answer" + (f" ({detail})" if detail else ""))


# -- strategies -----------------------------------------------------------------------------------

odd_numbers = st.one_of(
    st.just(float("nan")), st.just(float("inf")), st.just(-float("inf")), st.just("3"),
    st.just(True), st.just(None), st.just(2.5), st.just(0), st.just(-1), st.just(1e308),
    st.just(1e-308), st.just(2**70), st.complex_numbers(max_magnitude=4), st.just([1, 2]))


def mostly(good, bad, weight=5):
    """``good`` ``weight`` times out of ``weight + 1``: one bad thing at a time, not all.

    Drawn with ``sampled_from``, which keeps these odds: Hypothesis draws ``integers(0, weight)``
    at 0 about a third of the time, whatever ``weight``, so ``pick == 0`` would spoil far more
    examples than meant."""
    return st.sampled_from([False] * weight + [True]).flatmap(
        lambda spoil: bad if spoil else good)


def _values_for(dtype, rng, shape, extreme):
    dtype = np.dtype(dtype)
    if dtype.kind == "b":
        return rng.integers(0, 2, shape).astype(dtype)
    if dtype.kind in "iu":
        info = np.iinfo(dtype)
        if extreme:
            # step edges between the dtype's extremes: where clamping matters
            values = np.where(rng.integers(0, 2, shape) == 1, info.max, info.min)
            return values.astype(dtype)
        high = min(int(info.max), 255 if dtype.itemsize == 1 else 4000)
        return rng.integers(max(int(info.min), -high), high + 1, shape).astype(dtype)
    if dtype.kind == "c":
        return (rng.normal(100, 30, shape) + 1j).astype(dtype)
    if extreme:
        finfo = np.finfo(dtype)
        # float16 with -inf is an explicit example (a bug this fuzz found, fixed)
        infinity = np.nan if dtype == np.float16 else np.inf
        choices = np.array([finfo.max, -finfo.max, finfo.tiny, 0.0, np.nan, infinity, 1.0])
        return choices[rng.integers(0, len(choices), shape)].astype(dtype)
    return rng.normal(100, 40, shape).astype(dtype)


@st.composite
def valid_images(draw, max_side=24, dtypes=INT_DTYPES + FLOAT_DTYPES):
    """An image every verb must take: 2-D or a band stack, of a usual dtype, its values varied
    or at the dtype's extremes."""
    side = st.integers(2, max_side)
    shape = draw(st.one_of(st.tuples(side, side), st.tuples(st.just(2), side, side)))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    return _values_for(draw(st.sampled_from(dtypes)), rng, shape,
                       draw(st.sampled_from([False, False, True])))


@st.composite
def images(draw, max_side=24, dtypes=ALL_DTYPES):
    usual = [d for d in dtypes if d in INT_DTYPES + FLOAT_DTYPES]
    dtype = draw(mostly(st.sampled_from(usual), st.sampled_from(dtypes), 2))
    side = st.integers(2, max_side)
    shape = draw(mostly(st.one_of(st.tuples(side, side), st.sampled_from([(2, 12, 10)])),
                        st.sampled_from([(0, 5), (1, 1), (3, 4, 5, 6), (5,)]), 3))
    extreme = draw(st.sampled_from([False, False, True]))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    image = _values_for(dtype, rng, shape, extreme)
    return image


# -- interpolate and warp against GDAL ------------------------------------------------------------

SOURCE_TRANSFORM = affine.Affine(10.0, 0, 500_000.0, 0, -10.0, 7_400_000.0)


def _gdal_reference(image, dst_transform, shape, method, nodata):
    """GDAL's answer for the image's dtype, or None where GDAL has no such type."""
    native = image.astype(image.dtype.newbyteorder("=")) if image.dtype.byteorder == ">" \
        else image
    name = native.dtype.name
    if name == "float16":
        out = _gdal(native.astype(np.float32), dst_transform, shape, method, nodata)
        return out.astype(np.float16)
    if name not in GDAL_TYPES:
        return None
    return _gdal(native, dst_transform, shape, method, nodata)


def _gdal(image, dst_transform, shape, method, nodata):
    return gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method,
                     nodata, plain_kernels=True)


def _same_as_gdal(verb, got, image, dst_transform, shape, method, nodata):
    expected = _gdal_reference(image, dst_transform, shape, method, nodata)
    assert expected is not None, (
        f"{verb} answered for dtype {image.dtype} (no reference): it should refuse it")
    assert got.shape == expected.shape, (got.shape, expected.shape)
    assert got.dtype.newbyteorder("=") == expected.dtype.newbyteorder("=") or \
        image.dtype.name == "float16", (got.dtype, expected.dtype)
    got = got.astype(got.dtype.newbyteorder("="))
    if got.dtype.kind in "iu" and got.dtype.itemsize == 8:
        # GDAL warps 64-bit integers in double precision: agree to its rounding
        diff = np.abs(got.astype(object) - expected.astype(object))
        bound = np.maximum(np.abs(expected.astype(np.float64)) * 2.0**-50, 1.0)
        bad = np.flatnonzero(diff.astype(np.float64).ravel() > bound.ravel())
    elif got.dtype == np.float16:
        bad = np.flatnonzero(~np.isclose(got.astype(np.float64), expected.astype(np.float64),
                                         rtol=2e-3, atol=0, equal_nan=True).ravel())
    else:
        same = (got == expected) | (np.isnan(got) & np.isnan(expected)
                                    if got.dtype.kind == "f" else False)
        known = _centre_bug_pixels(image, dst_transform, shape, method)
        if known is not None:
            # CENTRE_BUG, a known bug (test_known_bug_nan_or_inf_beside_aligned_centres): these
            # pixels are left out, the others compared
            event(f"{verb}: CENTRE_BUG pixels left out of the comparison")
            same |= np.broadcast_to(known, same.shape)
        if got.dtype.kind == "f" and nodata is not None and method != "nearest":
            # AvoidNoData on floats: a valid value equal to nodata moves to the next float up
            # in rsgeo (test_resample's convention, as GDAL warps since 3.11, OSGeo/gdal#11713);
            # GDAL 3.10, the reference here, leaves it at nodata
            moved = ~same & (expected == nodata) & (got == _moved_off_nodata(nodata, got.dtype))
            if moved.any():
                event(f"{verb}: answered with AvoidNoData on floats, which GDAL 3.10 lacks")
            same |= moved
        bad = np.flatnonzero(~same.ravel())
    assert bad.size == 0, (
        f"{verb} differs from GDAL at {bad.size} of {got.size} pixels (first at flat index "
        f"{bad[0]}: rsgeo {got.ravel()[bad[0]]}, GDAL {expected.ravel()[bad[0]]}), "
        f"dtype {image.dtype}, method {method}, nodata {nodata}")


@st.composite
def grids(draw):
    """An output grid over the 10 m source: rotated, zoomed and shifted."""
    angle = draw(st.sampled_from([0.0, 7.0, -30.0, 90.0]))
    zoom = draw(st.sampled_from([1.0, 0.9, 0.5, 1.3]))
    dx, dy = draw(st.floats(-3, 3)), draw(st.floats(-3, 3))
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(dx, dy)
                     @ affine.Affine.rotation(angle) @ affine.Affine.scale(zoom))
    shape = (draw(st.integers(1, 20)), draw(st.integers(1, 20)))
    return dst_transform, shape


# a string, a bool and 2**64 are the explicit examples below (bugs the fuzz found, fixed)
nodatas = mostly(st.sampled_from([0, None, 1]),
                 st.sampled_from([255, -1, float("nan"), 1e40, 2.0**64]), 3)
# found by this fuzz, fixed: as_nodata checked no type (nodata='0' or 2**64 for an integer
# image raised NumPy's TypeError; '0' and True were taken as 0.0 and 1); now a TypeError or
# an ImageError of rsgeo's
NODATA_BUG_CASES = [(np.arange(-6, 6, dtype=np.int32).reshape(3, 4), nodata)
                    for nodata in (2**64, "0", True)] + [
                        (np.linspace(0, 1, 12).reshape(3, 4), nodata) for nodata in ("0", True)]


# found by this fuzz, fixed: given a float16 image, interpolate took GDAL's masked cubic
# kernel (chosen by the image's dtype, not the float32 it computes in), giving -inf or inf
# beside a -inf where float32 (and GDAL) give NaN
CENTRE_BUG = (
    "known bug in rsgeo/resample.py: at an exact pixel centre (a grid aligned with the source) "
    "bilinear and cubic weigh the neighbours by 0 and 0 x NaN or 0 x inf is NaN: a NaN or inf "
    "pixel makes 3 (bilinear) or up to 15 (cubic) neighbours NaN, where GDAL gives each "
    "pixel's own value")
ONE_INFINITE_PIXEL = np.zeros((6, 6), dtype=np.float32)
ONE_INFINITE_PIXEL[1, 1] = -np.inf
ONE_NAN_PIXEL = np.where(ONE_INFINITE_PIXEL == 0, 0, np.nan).astype(np.float64)
SHIFTED_GRID = (SOURCE_TRANSFORM @ affine.Affine.translation(0.3, 0.2), (6, 6))


def float16_bug_example(**arguments):
    """The float16 case beside a -inf (a bug this fuzz found, fixed) as an explicit example."""
    return _example(True, image=ONE_INFINITE_PIXEL.astype(np.float16), grid=SHIFTED_GRID,
                    method="cubic", nodata=None, **arguments)


def _centre_bug_pixels(image, dst_transform, shape, method):
    """CENTRE_BUG's output pixels: at an exact source pixel centre in both axes, with a NaN or
    an infinity within two source pixels (of any band); None when there are none."""
    if method not in ("bilinear", "cubic") or image.dtype.kind != "f":
        return None
    bands = image if image.ndim == 3 else image[np.newaxis]
    non_finite = ~np.isfinite(bands.astype(np.float64)).all(axis=0)
    cols, rows = _grid_positions(dst_transform, shape)
    exact = (np.mod(cols, 1) == 0.5) & (np.mod(rows, 1) == 0.5)
    if not (non_finite.any() and exact.any()):
        return None
    from scipy.ndimage import maximum_filter

    near = maximum_filter(non_finite, size=5, mode="constant")
    col, row = np.floor(cols).astype(np.int64), np.floor(rows).astype(np.int64)
    inside = exact & (col >= 0) & (row >= 0) & (col < near.shape[1]) & (row < near.shape[0])
    pixels = np.zeros(shape, dtype=bool)
    pixels[inside] = near[row[inside], col[inside]]
    return pixels if pixels.any() else None


def _example(as_case, **arguments):
    """An explicit example: of the test's arguments, or of its one argument ``case`` (a dict)."""
    return example(case=arguments) if as_case else example(**arguments)


def nodata_bug_examples(as_case=False, **arguments):
    """The nodata cases this fuzz found refused badly (fixed) as explicit examples."""
    def decorate(test):
        for image, nodata in NODATA_BUG_CASES:
            test = _example(as_case, image=image, nodata=nodata, **arguments)(test)
        return test
    return decorate


def check_nodata_taken(verb, nodata):
    """An answer took ``nodata``: it must be None or a number (not a bool, not a string)."""
    assert nodata is None or (isinstance(nodata, (int, float)) and not isinstance(nodata, bool)), (
        f"{verb} took nodata={nodata!r}")


def _grid_positions(dst_transform, shape):
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]] + 0.5
    x, y = dst_transform @ (cols, rows)
    return ~SOURCE_TRANSFORM @ (x, y)


POSITION_SPOILS = ["nan", "inf", "list", "strings", "shape", "empty", "1d", "complex", "int"]
INTERPOLATE_SPOILS = ["image", "method", "nodata"] + POSITION_SPOILS


@st.composite
def interpolate_cases(draw):
    """interpolate's arguments, all valid half the time, else one of them spoiled (or odd):
    ``spoil`` names the positions' spoiling, if any."""
    spoil = draw(st.sampled_from([None] * len(INTERPOLATE_SPOILS) + INTERPOLATE_SPOILS))
    methods = ["nearest", "bilinear", "cubic", "average"]
    return dict(
        image=draw(images() if spoil == "image" else valid_images()), grid=draw(grids()),
        method=draw(st.sampled_from(["lanczos", 3] if spoil == "method" else methods)),
        nodata=draw(nodatas if spoil == "nodata" else st.sampled_from([0, None, 1])),
        spoil=spoil if spoil in POSITION_SPOILS else None)


@pytest.mark.slow      # compiles every dtype x method kernel on a cold cache
@FUZZ_GDAL
@given(case=interpolate_cases())
@nodata_bug_examples(as_case=True, grid=(SOURCE_TRANSFORM, (3, 4)), method="nearest", spoil=None)
@float16_bug_example(spoil=None)
def test_interpolate_refuses_or_matches_gdal(case):
    image, grid, method, nodata, spoil = (case[name] for name in
                                          ("image", "grid", "method", "nodata", "spoil"))
    dst_transform, shape = grid
    cols, rows = _grid_positions(dst_transform, shape)
    if spoil == "nan":
        cols = cols.copy()
        cols.flat[0] = np.nan
    elif spoil == "inf":
        rows = rows.copy()
        rows.flat[-1] = -np.inf
    elif spoil == "list":
        cols, rows = cols.tolist(), rows.tolist()
    elif spoil == "strings":
        cols = cols.astype(str)
    elif spoil == "shape":
        rows = rows[:, :-1] if rows.shape[1] > 1 else rows[:-1]
    elif spoil == "empty":
        cols, rows = np.empty((0,)), np.empty((0,))
    elif spoil == "1d":
        cols, rows = cols.ravel(), rows.ravel()
    elif spoil == "complex":
        cols = cols + 0.5j
    elif spoil == "int":
        cols, rows = np.floor(cols).astype(np.int64), np.floor(rows).astype(np.int64)
    before = image.copy()
    got = call("interpolate", interpolate, image, cols, rows, method, nodata=nodata)
    assert unchanged(before, image), "interpolate modified its input"
    if got is REFUSED:
        return
    check_nodata_taken("interpolate", nodata)
    assert spoil not in ("nan", "inf", "strings", "shape", "complex"), (
        f"interpolate answered on spoiled positions ({spoil})")
    if spoil == "empty":
        assert np.asarray(got).size == 0
        confirmed("interpolate", "empty")
        return
    if spoil in ("list", "1d", "int"):
        expect_c, expect_r = np.asarray(cols, dtype=np.float64), np.asarray(rows, dtype=np.float64)
        # a reference through GDAL needs a grid: compare with rsgeo on the float positions,
        # which the unspoiled examples compare with GDAL
        again = interpolate(image, expect_c, expect_r, method, nodata=nodata)
        assert np.array_equal(got, again, equal_nan=True)
        confirmed("interpolate", "same as float positions")
        return
    _same_as_gdal("interpolate", got, image, dst_transform, shape, method, nodata)
    confirmed("interpolate")


@pytest.mark.slow      # compiles every dtype x method kernel on a cold cache
@FUZZ_GDAL
@given(image=images(), grid=grids(), method=st.sampled_from(["nearest", "bilinear", "cubic",
                                                           "average"]),
       nodata=nodatas,
       mapping_kind=mostly(st.sampled_from(["affine", "model"]),
                           st.sampled_from(["gdal tuple", "none", "array", "nan affine"])),
       strip_rows=mostly(st.sampled_from([256, 1, 3]), odd_numbers),
       bad_transform=mostly(st.none(), st.sampled_from(["nan", "tuple"])))
@nodata_bug_examples(grid=(SOURCE_TRANSFORM, (3, 4)), method="nearest", mapping_kind="affine",
                     strip_rows=256, bad_transform=None)
def test_warp_refuses_or_matches_gdal(image, grid, method, nodata, mapping_kind, strip_rows,
                                      bad_transform):
    dst_transform, shape = grid
    inverse = ~SOURCE_TRANSFORM
    if mapping_kind == "affine":
        mapping = inverse
    elif mapping_kind == "model":
        # map (x, y) -> source (col, row) as a fitted model (a callable, warped in strips)
        corners = np.array([[0, 0], [400, 0], [0, 300], [400, 300], [200, 150]], float)
        map_xy = np.column_stack(SOURCE_TRANSFORM @ (corners[:, 0], corners[:, 1]))
        mapping = transforms.fit_transform(map_xy, corners, "polynomial", 1)
    elif mapping_kind == "gdal tuple":
        mapping = inverse.to_gdal()
    elif mapping_kind == "none":
        mapping = None
    elif mapping_kind == "array":
        mapping = np.eye(3)
    else:
        mapping = affine.Affine(np.nan, 0, 0, 0, 1, 0)
    transform = dst_transform
    if bad_transform == "nan":
        transform = affine.Affine(np.nan, 0, 0, 0, -10, 0)
    elif bad_transform == "tuple":
        transform = tuple(dst_transform)[:6]
    before = image.copy()
    got = call("warp", warp, image, mapping, shape, transform, method=method, nodata=nodata,
               strip_rows=strip_rows, scale=1.0)
    assert unchanged(before, image), "warp modified its input"
    if got is REFUSED:
        return
    check_nodata_taken("warp", nodata)
    assert mapping_kind in ("affine", "model", "gdal tuple"), f"warp took mapping {mapping!r}"
    assert bad_transform != "nan", "warp answered on a NaN transform"
    if bad_transform == "tuple" or mapping_kind == "gdal tuple":
        pytest.fail("warp read a 6-tuple without saying in which order (GDAL's or Affine's)")
    _same_as_gdal("warp", got, image, dst_transform, shape, method, nodata)
    confirmed("warp")


@pytest.mark.parametrize("verb", ["interpolate", "warp"])
@pytest.mark.parametrize("image, method", [(ONE_NAN_PIXEL, "bilinear"),
                                           (ONE_INFINITE_PIXEL, "cubic")], ids=["nan", "inf"])
@pytest.mark.xfail(strict=True, raises=AssertionError, reason=CENTRE_BUG)
def test_known_bug_nan_or_inf_beside_aligned_centres(verb, image, method):
    # the source's own grid: every output pixel is a source pixel's centre; GDAL copies them
    shape = image.shape
    if verb == "interpolate":
        got = interpolate(image, *_grid_positions(SOURCE_TRANSFORM, shape), method, nodata=None)
    else:
        got = warp(image, ~SOURCE_TRANSFORM, shape, SOURCE_TRANSFORM, method=method,
                   dst_nodata=None)
    expected = _gdal_reference(image, SOURCE_TRANSFORM, shape, method, None)
    assert np.array_equal(expected, image, equal_nan=True)
    assert np.array_equal(got, expected, equal_nan=True), (
        f"{verb} makes {int(np.isnan(got).sum()) - int(np.isnan(expected).sum())} more NaN")


# -- fit_transform and refine_gcps ----------------------------------------------------------------

def _true_model(kind, order, rng):
    """A function src (n, 2) -> dst (n, 2) of the kind, on normalised coordinates."""
    a = rng.normal(0, 1, (2, 2)) + np.eye(2) * 2
    t = rng.normal(0, 100, 2)
    if kind == "linear":
        sx, sy = rng.uniform(0.5, 3, 2) * rng.choice([-1, 1], 2)
        return lambda p: np.column_stack([sx * p[:, 0] + t[0], sy * p[:, 1] + t[1]])
    if kind == "helmert":
        angle, scale = rng.uniform(-np.pi, np.pi), rng.uniform(0.1, 10)
        rot = scale * np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
        return lambda p: p @ rot.T + t
    if kind == "projective":
        h = np.vstack([np.column_stack([a, t]), [rng.normal(0, 1e-4, 2).tolist() + [1.0]]])

        def homography(p):
            q = np.column_stack([p, np.ones(len(p))]) @ h.T
            return q[:, :2] / q[:, 2:]
        return homography
    if kind == "polynomial":
        coefficients = rng.normal(0, 1, (2, 10)) * np.array([1, 1, 1] + [1e-3] * 3 + [1e-6] * 4)

        def polynomial(p):
            x, y = p[:, 0], p[:, 1]
            terms = np.column_stack([np.ones_like(x), x, y, x * x, x * y, y * y,
                                     x**3, x * x * y, x * y * y, y**3])[:, :{1: 3, 2: 6, 3: 10}[
                                         order]]
            return terms @ coefficients[:, :terms.shape[1]].T + t
        return polynomial
    return lambda p: p @ a.T + t       # tps: an affine map, which the spline reproduces


KIND_CHOICES = [(m.kind, m.order) for m in transforms.REGISTRY]


@st.composite
def gcp_sets(draw, kind_order):
    kind, order = kind_order
    n = draw(mostly(st.sampled_from([10, 15, 25]), st.sampled_from([0, 1, 2, 3, 4, 6]), 3))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    layout = draw(mostly(st.just("spread"), st.sampled_from([
        "collinear", "nearly collinear", "duplicated", "near duplicate", "huge offset", "tiny",
        "huge spread"]), 2))
    src = rng.uniform(0, 1000, (n, 2))
    if layout == "collinear":
        src[:, 1] = 2 * src[:, 0] + 5
    elif layout == "nearly collinear":
        src[:, 1] = 2 * src[:, 0] + 5 + rng.normal(0, 1e-7, n)
    elif layout == "duplicated" and n > 1:
        src[-1] = src[0]
    elif layout == "near duplicate" and n > 1:
        src[-1] = src[0] + 0.01
    elif layout == "huge offset":
        src += 7e6
    elif layout == "tiny":
        src *= 1e-9
    elif layout == "huge spread":
        src *= 1e12
    event(f"GCP layout {layout}")
    model = _true_model(kind, order, rng)
    dst = model(src)
    if layout in ("duplicated", "near duplicate") and n > 1 and draw(st.booleans()):
        dst[-1] += 50.0        # same place, different target: no model reproduces both
        layout += " with another target"
    spoil = draw(mostly(st.none(), st.sampled_from([
        "nan", "inf", "list", "strings", "float32", "int", "complex", "bool", "shape3", "1d",
        "lengths"]), 3))
    if spoil == "nan" and n:
        src[0, 0] = np.nan
    elif spoil == "inf" and n:
        dst[-1, 1] = np.inf
    elif spoil == "list":
        src, dst = src.tolist(), dst.tolist()
    elif spoil == "strings":
        src = src.astype(str)
    elif spoil == "float32":
        src, dst = src.astype(np.float32), dst.astype(np.float32)
    elif spoil == "int":
        src = np.round(src).astype(np.int64)
        dst = model(src.astype(np.float64))
    elif spoil == "complex":
        src = src + 0j
    elif spoil == "bool":
        src = src > 500
    elif spoil == "shape3":
        src = np.column_stack([src, src[:, :1]])
    elif spoil == "1d":
        src = src.ravel()
    elif spoil == "lengths" and n:
        dst = dst[:-1]
    return src, dst, layout, spoil


def _tolerance(dst):
    dst = np.asarray(dst, dtype=np.float64)
    spread = float(np.ptp(dst, axis=0).max()) if len(dst) else 0.0
    return 1e-6 * spread + 1e-9 * float(np.abs(dst).max(initial=0.0)) + 1e-12


def _least_squares_fit(kind, order, src, dst, model):
    """The least-squares model of ``kind`` at ``src``: NumPy in float64 on centred, scaled
    coordinates (the fitted values do not depend on them), scikit-image for "projective"."""
    centred = src - src.mean(axis=0)
    x, y = (centred / (np.abs(centred).max() or 1.0)).T
    if kind == "polynomial":
        design = np.column_stack([x ** (total - j) * y**j for total in range(order + 1)
                                  for j in range(total + 1)])
        return design @ np.linalg.lstsq(design, dst, rcond=None)[0]
    if kind == "linear":
        return np.column_stack([np.polyval(np.polyfit(v, dst[:, axis], 1), v)
                                for axis, v in enumerate((x, y))])
    if kind == "helmert":
        # u = a x - b y + c and flip·v = b x + a y + d, with the handedness the model chose
        flip = -1.0 if np.linalg.det(model.matrix[:2, :2]) < 0 else 1.0
        one, zero = np.ones_like(x), np.zeros_like(x)
        design = np.vstack([np.column_stack([x, -y, one, zero]),
                            np.column_stack([y, x, zero, one])])
        values = design @ np.linalg.lstsq(design, np.concatenate([dst[:, 0], flip * dst[:, 1]]),
                                          rcond=None)[0]
        return np.column_stack([values[:len(x)], flip * values[len(x):]])
    from skimage.transform import ProjectiveTransform

    assert kind == "projective", kind
    reference = ProjectiveTransform.from_estimate(src, dst)
    assert reference, f"scikit-image has no projective estimate here: {reference}"
    return reference(src)


def _gdal_tps(src, dst, points):
    from rasterio.control import GroundControlPoint
    from rasterio.transform import GCPTransformer

    gcps = [GroundControlPoint(row=r, col=c, x=x, y=y) for (c, r), (x, y) in zip(src, dst)]
    with GCPTransformer(gcps, tps=True) as transformer:
        xs, ys = transformer.xy(points[:, 1], points[:, 0], offset="ul")
    return np.column_stack([xs, ys])


@FUZZ
@given(data=st.data(), kind_order=st.sampled_from(KIND_CHOICES),
       order_arg=mostly(st.just("right"), st.sampled_from([True, 2.5, "2", 4, 0, None])))
def test_fit_transform_refuses_or_reproduces_exact_gcps(data, kind_order, order_arg):
    kind, order = kind_order
    src, dst, layout, spoil = data.draw(gcp_sets(kind_order))
    given_order = order if order_arg == "right" else order_arg
    event(f"fit_transform kind {kind}")
    src_before, dst_before = np.array(src, copy=True), np.array(dst, copy=True)
    model = call("fit_transform", transforms.fit_transform, src, dst, kind, given_order)
    assert unchanged(src_before, src) and unchanged(dst_before, dst), (
        "fit_transform modified its input")
    if model is REFUSED:
        return
    assert spoil not in ("nan", "inf", "strings", "complex", "bool", "shape3", "lengths"), (
        f"fit_transform accepted spoiled GCPs ({spoil})")
    assert given_order is order or (type(given_order) is int and given_order == order), (
        f"fit_transform took order={given_order!r} for kind {kind!r}")
    src64, dst64 = np.array(src, dtype=np.float64), np.array(dst, dtype=np.float64)   # copies
    # a spline passes through every GCP: two at (nearly) one place with different targets have
    # no spline; least squares fits them as it fits any GCPs that disagree (their residuals)
    assert "with another target" not in layout or kind != "tps", (
        f"fit_transform fitted {kind} to two GCPs at (nearly) one place with different targets")
    # the model copies its GCPs: editing the caller's arrays afterwards changes nothing
    predicted = np.asarray(model(src64), dtype=np.float64)
    if isinstance(src, np.ndarray) and src.dtype.kind == "f":
        src += 1000.0
        assert np.array_equal(np.asarray(model(src64)), predicted), (
            "the model kept the caller's src by reference")
    if "with another target" in layout:
        expected = _least_squares_fit(kind, order, src64, dst64, model)
        gap = np.abs(predicted - expected).max()
        assert gap <= _tolerance(dst64), (
            f"{kind} (order {order}) on {layout} GCPs differs from the least-squares fit by "
            f"{gap:g} at the GCPs (tolerance {_tolerance(dst64):g})")
        confirmed("fit_transform", f"{kind} least squares")
        return
    error = np.abs(predicted - dst64).max(initial=0.0)
    assert error <= _tolerance(dst64), (
        f"{kind} (order {order}) on {layout} GCPs: model(src) misses dst by {error:g} "
        f"(tolerance {_tolerance(dst64):g}) and no error was raised")
    if kind == "tps" and layout in ("spread", "huge offset") and len(src64) >= 3:
        lo, hi = src64.min(axis=0), src64.max(axis=0)
        inside = lo + (hi - lo) * np.random.default_rng(0).uniform(0.1, 0.9, (20, 2))
        reference = _gdal_tps(src64, dst64, inside)
        gap = np.abs(np.asarray(model(inside)) - reference).max()
        assert gap <= 1e-6 * (np.ptp(dst64, axis=0).max() + 1), f"TPS differs from GDAL by {gap}"
        confirmed("fit_transform", "GDAL TPS")
        return
    confirmed("fit_transform", kind)


@pytest.mark.parametrize("kind_order", [choice for choice in KIND_CHOICES if choice[0] != "tps"])
def test_least_squares_kinds_fit_gcps_that_disagree(kind_order):
    # the property's "with another target" layouts, made sure of (the property draws them
    # rarely): two GCPs at one place with targets 50 apart are fitted by least squares
    kind, order = kind_order
    rng = np.random.default_rng(4)
    src = rng.uniform(0, 1000, (12, 2))
    src[-1] = src[0]
    dst = _true_model(kind, order, rng)(src)
    dst[-1] += 50.0
    model = transforms.fit_transform(src, dst, kind, order)
    predicted = np.asarray(model(src))
    assert np.abs(predicted - dst).max() > 1.0         # the disagreement is in the residuals
    expected = _least_squares_fit(kind, order, src, dst, model)
    assert np.abs(predicted - expected).max() <= _tolerance(dst)


@FUZZ
@given(data=st.data(), kind_order=st.sampled_from(KIND_CHOICES),
       tolerance=mostly(st.sampled_from([1.0, 5.0, 0.0]), odd_numbers),
       min_gcps=mostly(st.none(), st.sampled_from([3, 4, 100, True, 2.5, -1, "4"]), 3),
       outliers=st.integers(0, 3))
def test_refine_gcps_refuses_or_stops_where_gdal_does(data, kind_order, tolerance, min_gcps,
                                                      outliers):
    kind, order = kind_order
    src, dst, layout, spoil = data.draw(gcp_sets(kind_order))
    if spoil is None and len(dst) > outliers:
        dst = np.array(dst, dtype=np.float64)
        dst[:outliers] += 40.0
    model_and_kept = call("refine_gcps", accuracy.refine_gcps, src, dst,
                          order if kind == "polynomial" else None, tolerance, min_gcps,
                          kind=kind)
    if model_and_kept is REFUSED:
        return
    assert spoil not in ("nan", "inf", "strings", "complex", "bool", "shape3", "lengths"), (
        f"refine_gcps accepted spoiled GCPs ({spoil})")
    assert isinstance(tolerance, (int, float)) and not isinstance(tolerance, bool) and \
        math.isfinite(tolerance) and tolerance >= 0, f"refine_gcps took tolerance={tolerance!r}"
    model, kept = model_and_kept
    src64, dst64 = np.asarray(src, dtype=np.float64), np.asarray(dst, dtype=np.float64)
    kept = np.asarray(kept, dtype=bool)
    floor = transforms.min_gcps(kind, order) if min_gcps is None else min_gcps
    assert kept.sum() >= floor
    residuals = np.hypot(*(np.asarray(model(src64[kept])) - dst64[kept]).T)
    # GDAL's rule: stop when no kept GCP's residual reaches the tolerance, or at min_gcps
    assert kept.sum() == floor or residuals.max(initial=0) < tolerance + _tolerance(dst64)
    refit = transforms.fit_transform(src64[kept], dst64[kept], kind, order)
    assert np.allclose(refit(src64), model(src64), rtol=0, atol=10 * _tolerance(dst64) + 1e-6)
    confirmed("refine_gcps")


# -- radiometry -----------------------------------------------------------------------------------

GAIN_OFFSET_SPOILS = ["x dtype", "x values", "x shape", "constant y", "other shape", "nan",
                      "huge", "list", "method", "smooth", "smooth on bands"]


@st.composite
def gain_offset_cases(draw):
    """(x, y, relation, method, smooth, spoil): valid half the time, else one thing spoiled.

    Valid: x of an integer or float dtype (big-endian too), 2-D or a band stack, of varied
    values (an integer dtype's extremes included), y a linear function of x, with or without
    noise, whose gain is at least 0.05 from zero (a zero gain makes y constant: no regression).
    """
    spoil = draw(st.sampled_from([None] * len(GAIN_OFFSET_SPOILS) + GAIN_OFFSET_SPOILS))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    if spoil == "x dtype":
        dtype = draw(st.sampled_from(["complex128", "bool"]))
    elif spoil == "x values":
        dtype = draw(st.sampled_from(FLOAT_DTYPES + [">f8"]))
    else:
        dtype = draw(st.sampled_from(INT_DTYPES + FLOAT_DTYPES + [">f8", ">i4"]))
    side = st.integers(2, 12)
    if spoil == "x shape":
        shape = draw(st.sampled_from([(0, 5), (1, 1), (1, 2), (5,), (3, 4, 5, 6)]))
    elif spoil == "smooth on bands":
        shape = (2, draw(side), draw(side))
    else:
        shape = draw(st.one_of(st.tuples(side, side), st.tuples(st.just(2), side, side)))
    extreme = spoil == "x values" or (np.dtype(dtype).kind in "iu" and draw(st.booleans()))
    x = _values_for(dtype, rng, shape, extreme)
    relation = spoil if spoil in ("constant y", "other shape", "nan", "huge", "list") else \
        draw(st.sampled_from(["linear", "noise"]))
    gain = draw(st.sampled_from([-1.0, 1.0])) * draw(st.floats(0.05, 3))
    offset = draw(st.floats(-100, 100))
    xf = x.astype(np.complex128 if x.dtype.kind == "c" else np.float64)
    if relation in ("linear", "list"):
        y = gain * xf + offset
    elif relation == "noise":
        y = gain * xf + offset + rng.normal(0, 5, x.shape)
    elif relation == "constant y":
        y = np.full(x.shape, 7.0)
    elif relation == "other shape":
        y = np.zeros(x.shape + (2,))
    elif relation == "nan":
        y = gain * xf + offset
        if y.size:
            y.flat[0] = np.nan
    else:
        with np.errstate(over="ignore"):
            y = xf * 1e300
    if relation == "list":
        y = y.tolist()
    method = "OLS" if spoil == "method" else draw(st.sampled_from(
        ["ols", "rma", "orthogonal", "theil_sen"]))
    if spoil == "smooth":
        smooth = draw(st.sampled_from([0, -1, 2.5, True, "3"]))
    elif spoil == "smooth on bands" or x.ndim == 2:
        smooth = draw(st.sampled_from([None, 3]) if spoil is None else st.just(3))
    else:
        smooth = None
    return x, y, relation, method, smooth, spoil


def _reference_fit(x, y, method):
    x, y = x.astype(np.float64).ravel(), y.astype(np.float64).ravel()
    with np.errstate(all="ignore"):
        dx, dy = x - x.mean(), y - y.mean()
        sxx, syy, sxy = (dx * dx).mean(), (dy * dy).mean(), (dx * dy).mean()
        if method == "ols":
            gain = sxy / sxx
        elif method == "rma":
            gain = np.sign(sxy) * np.sqrt(syy / sxx)
        else:
            gain = (syy - sxx + np.sqrt((syy - sxx) ** 2 + 4 * sxy**2)) / (2 * sxy)
        offset = y.mean() - gain * x.mean()
    return gain, offset


@FUZZ
@given(case=gain_offset_cases())
def test_fit_gain_offset_refuses_or_matches_numpy_float64(case):
    x, y, relation, method, smooth, spoil = case
    fit = call("fit_gain_offset", radiometry.fit_gain_offset, x, y, smooth=smooth, method=method)
    if fit is REFUSED:
        return
    assert x.dtype.kind in "iuf" and np.asarray(y).dtype.kind in "iuf", (
        f"fit_gain_offset answered on dtype {x.dtype} / {np.asarray(y).dtype}")
    assert relation not in ("other shape", "nan"), f"fit_gain_offset answered on {relation}"
    assert smooth is None or (isinstance(smooth, int) and not isinstance(smooth, bool)
                              and smooth >= 1), f"fit_gain_offset took smooth={smooth!r}"
    assert smooth is None or x.ndim == 2, "fit_gain_offset smoothed across a band stack"
    assert math.isfinite(fit.gain) and math.isfinite(fit.offset), (
        f"fit_gain_offset returned gain {fit.gain}, offset {fit.offset} ({relation}, {method})")
    y = np.asarray(y, dtype=np.float64)
    if smooth not in (None, 1):
        from scipy.ndimage import uniform_filter
        xs = uniform_filter(x.astype(np.float64), smooth, mode="nearest")
        ys = uniform_filter(y, smooth, mode="nearest")
    else:
        xs, ys = x.astype(np.float64), y
    if method == "theil_sen":
        if relation in ("linear", "list"):      # exact data: every pairwise slope is the gain
            np.testing.assert_allclose([fit.gain, fit.offset], _reference_fit(xs, ys, "ols"),
                                       rtol=1e-6, atol=1e-6)
        confirmed("fit_gain_offset", "theil-sen")
        return
    gain, offset = _reference_fit(xs, ys, method)
    scale = 1 + np.abs(ys).max(initial=0)
    assert np.isfinite(gain) and np.isfinite(offset), (
        f"float64 has no answer (gain {gain}) but fit_gain_offset gave {fit.gain}")
    np.testing.assert_allclose(fit.gain, gain, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(fit.offset, offset, rtol=1e-6, atol=1e-9 * scale)
    confirmed("fit_gain_offset", method)


def _exact_gain_offset(image, gain, offset, rounding):
    info = np.iinfo(image.dtype)
    g, o = Fraction(gain), Fraction(offset)
    out = []
    for value in image.ravel().tolist():
        v = g * int(value) + o
        v = math.trunc(v) if rounding == "truncate" else math.floor(v + Fraction(1, 2))
        out.append(min(max(v, int(info.min)), int(info.max)))
    return np.array(out, dtype=object).reshape(image.shape)


@FUZZ
@given(image=images(max_side=8, dtypes=INT_DTYPES + FLOAT_DTYPES + [">i4", ">u8", "bool",
                                                                    "complex64"]),
       gain=mostly(st.one_of(st.sampled_from([1.0, 4.0, 0.885, -1.0, 2.0]),
                             st.floats(-1e3, 1e3)), odd_numbers, 4),
       offset=mostly(st.one_of(st.sampled_from([0.0, 27.107, -0.5, 1.0]),
                               st.floats(-1e20, 1e20)), odd_numbers, 4),
       rounding=mostly(st.sampled_from(["truncate", "nearest"]), st.just("floor")))
def test_apply_gain_offset_refuses_or_is_exact(image, gain, offset, rounding):
    got = call("apply_gain_offset", radiometry.apply_gain_offset, image, gain, offset, rounding)
    if got is REFUSED:
        return
    assert image.dtype.kind in "iu", f"apply_gain_offset answered on dtype {image.dtype}"
    for name, value in (("gain", gain), ("offset", offset)):
        assert isinstance(value, (int, float)) and not isinstance(value, bool) and \
            math.isfinite(value), f"apply_gain_offset took {name}={value!r}"
    assert got.shape == image.shape and got.dtype == image.dtype
    exact = _exact_gain_offset(image, gain, offset, rounding)
    got_values = got.astype(object)
    integral = float(gain).is_integer() and float(offset).is_integer()
    # integer gain and offset: exactly; otherwise to float64's rounding of gain·value + offset
    bound = np.array([0 if integral else 1 + abs(e) * 2.0**-51 for e in exact.ravel()],
                     dtype=object).reshape(exact.shape)
    off = (np.abs(got_values - exact) > bound).astype(bool)
    assert not off.any(), (
        f"apply_gain_offset({image.dtype}, gain {gain}, offset {offset}, {rounding}): "
        f"{image.ravel()[off.ravel()][:3].tolist()} -> {got.ravel()[off.ravel()][:3].tolist()}, "
        f"exactly {exact.ravel()[off.ravel()][:3].tolist()}")
    confirmed("apply_gain_offset")


# -- genetic_match --------------------------------------------------------------------------------

@st.composite
def meshes(draw, min_n=3, max_n=5):
    n = draw(st.integers(min_n, max_n))
    rng = np.random.default_rng(draw(st.integers(0, 2**16)))
    return registration.Mesh(rng.uniform(0, 500, (n, 2)), rng.uniform(10, 500, n))


@FUZZ
@given(reference=mostly(meshes(), st.one_of(meshes(300, 300),
                                           st.just([[0, 0], [1, 1], [2, 0]]))),
       adjustment=meshes(),
       options=st.fixed_dictionaries({}, optional={
           "alpha": mostly(st.sampled_from([0.0, 0.5, 1.0]), odd_numbers),
           "population_size": mostly(st.sampled_from([2, 10, 30]), odd_numbers),
           "generations": mostly(st.sampled_from([1, 5, 20]), odd_numbers),
           "elite_fraction": mostly(st.sampled_from([0.0, 0.1, 1.0]), odd_numbers),
           "selection": st.sampled_from(["tournament", "roulette", "rank"]),
           "crossover_rate": mostly(st.sampled_from([0.0, 0.9]), odd_numbers),
           "mutation_rate": mostly(st.sampled_from([None, 0.0, 0.5]), odd_numbers),
           "tournament_size": mostly(st.sampled_from([1, 3, 40]), odd_numbers),
           "target_fitness": mostly(st.none(), odd_numbers),
           "encoding": st.sampled_from(["binary", "integer", "gray"]),
           "variant": st.sampled_from(["paper", "compact", "other"]),
           "stall_generations": mostly(st.sampled_from([None, 1, 5]), odd_numbers),
           "crossover": st.sampled_from([None, "one-point", "uniform", "two-point"]),
           "seed": mostly(st.integers(0, 2**32), odd_numbers)}))
def test_genetic_match_refuses_or_is_a_valid_solution_below_the_optimum(reference, adjustment,
                                                                        options):
    options = {"population_size": 20, "generations": 10, "seed": 0, **options}
    result = call("genetic_match", registration.genetic_match, reference, adjustment, **options)
    if result is REFUSED:
        return
    assert isinstance(reference, registration.Mesh)
    m, n = len(reference.areas), len(adjustment.areas)
    solution = np.asarray(result.solution)
    assert solution.shape == (n,) and solution.min() >= 0 and solution.max() <= m
    alpha, variant = options.get("alpha", 0.5), options.get("variant", "paper")
    again = registration.fitness(solution, reference, adjustment, alpha, variant)
    assert math.isfinite(result.fitness)
    np.testing.assert_allclose(result.fitness, again, rtol=1e-12, atol=1e-12)
    if m <= 5:
        optimum = registration.optimum_match(reference, adjustment, alpha, variant)
        assert result.fitness <= optimum.fitness + 1e-12
    confirmed("genetic_match")


# -- correlation_tiepoints ------------------------------------------------------------------------

@FUZZ_GDAL
@given(shift=st.tuples(st.integers(-4, 4), st.integers(-4, 4)),
       scene=st.sampled_from(["noise", "noise", "smooth", "float noise", "nan", "uint64"]),
       options=st.fixed_dictionaries({}, optional={
           "spacing": mostly(st.sampled_from([16, 24]), odd_numbers),
           "window": mostly(st.sampled_from([16, 32, 1, 200]), odd_numbers),
           "iterations": mostly(st.sampled_from([1, 2, 3]), odd_numbers),
           "upsample": mostly(st.sampled_from([1, 20]), odd_numbers),
           "min_contrast": mostly(st.sampled_from([2.0, 0.0]), odd_numbers),
           "min_reliability": mostly(st.sampled_from([8.0, 0.0]), odd_numbers),
           "tolerance": mostly(st.sampled_from([1.0, 0.5]), odd_numbers),
           "method": st.sampled_from(["nearest", "bilinear", "cubic", "spline"]),
           "taper": st.sampled_from([False, True, "yes", None]),
           "kind": st.sampled_from(["polynomial", "helmert", "tps", "warp"]),
           "seed": mostly(st.integers(0, 10), odd_numbers)}))
def test_correlation_tiepoints_refuse_or_find_the_known_shift(shift, scene, options):
    from scipy.ndimage import gaussian_filter

    rng = np.random.default_rng(7)
    base = rng.integers(0, 256, (112, 112)).astype(np.float64)
    if scene == "smooth":
        base = gaussian_filter(base, 4) * 20
    dx, dy = shift
    reference = base[16:96, 16:96]
    moving = base[16 + dy:96 + dy, 16 + dx:96 + dx]
    if scene == "noise":
        reference, moving = reference.astype(np.uint8), moving.astype(np.uint8)
    elif scene == "nan":
        moving = moving.copy()
        moving[3, 3] = np.nan
    elif scene == "uint64":
        reference, moving = reference.astype(np.uint64), moving.astype(np.uint64)
    options = {"spacing": 20, "window": 24, **options}
    if options.get("kind") not in (None, "polynomial"):
        options.setdefault("order", None)
    gcps = call("correlation_tiepoints", registration.correlation_tiepoints, reference, moving,
                **options)
    if gcps is REFUSED:
        return
    assert scene != "nan", "correlation_tiepoints answered on an image with NaN"
    for name in ("iterations", "upsample", "spacing", "window"):
        value = options.get(name, 1)
        assert isinstance(value, int) and not isinstance(value, bool) and value >= 1, (
            f"correlation_tiepoints took {name}={value!r}")
    for name in ("min_contrast", "min_reliability", "tolerance"):
        value = options.get(name, 1.0)
        assert isinstance(value, (int, float)) and not isinstance(value, bool) and \
            math.isfinite(value), f"correlation_tiepoints took {name}={value!r}"
    enabled = np.asarray(gcps.enabled, dtype=bool)
    truth = gcps.map_xy[enabled] - np.array([dx, dy])
    error = np.hypot(*(gcps.image_xy[enabled] - truth).T)
    assert error.max(initial=0) <= 0.25, (
        f"{enabled.sum()} 'reliable' tie points up to {error.max():.2f} px off the known shift "
        f"({dx}, {dy}) on the {scene} scene, options {options}")
    confirmed("correlation_tiepoints", f"{enabled.sum()} reliable")


# -- orthorectify against GDAL --------------------------------------------------------------------

def _small_rpc(n):
    rpc = sensors.simple_rpc_dict()
    half, degrees = n / 2, 0.045 * (n / 2) / 500
    rpc.update(LINE_OFF=half, SAMP_OFF=half, LINE_SCALE=half, SAMP_SCALE=half,
               LAT_SCALE=degrees, LONG_SCALE=degrees)
    return rpc, degrees


def _gdal_ortho(image, rpc, dem, dem_gt, dst_gt, shape, method, nodata):
    import tempfile

    from rasterio.warp import Resampling, reproject

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "dem.tif")
        with rasterio.open(path, "w", driver="GTiff", width=dem.shape[1], height=dem.shape[0],
                           count=1, dtype=dem.dtype, transform=dem_gt,
                           crs="EPSG:4326") as dataset:
            dataset.write(dem, 1)
        out = np.zeros(tuple(shape), dtype=image.dtype)
        reproject(image, out, rpcs=rpc.to_rasterio(), src_crs="EPSG:4326", dst_transform=dst_gt,
                  dst_crs="EPSG:4326", resampling=getattr(Resampling, method), dst_nodata=nodata,
                  src_nodata=None, init_dest_nodata=True, RPC_DEM=path,
                  RPC_DEMINTERPOLATION="bilinear")          # GDAL's own kernel scale
    return out


ORTHO_SPOILS = ["image", "method", "nodata", "dem", "dem transform", "dst_crs", "rpc", "shape"]
ORTHO_DTYPES = ["uint8", "int16", "uint16", "float32", "float64", "int64", ">i2", "float16"]


@st.composite
def ortho_cases(draw):
    """orthorectify's arguments, all valid half the time, else one of them spoiled (or odd)."""
    spoil = draw(st.sampled_from([None] * len(ORTHO_SPOILS) + ORTHO_SPOILS))

    def pick(name, good, bad):
        return draw(bad if spoil == name else good)

    image = draw(images(max_side=40, dtypes=ORTHO_DTYPES + ["bool", "complex64"])
                 if spoil == "image" else valid_images(max_side=40, dtypes=ORTHO_DTYPES))
    return dict(
        image=image,
        method=pick("method", st.sampled_from(["nearest", "bilinear", "cubic"]),
                    st.just("lanczos")),
        # a string or a bool are explicit examples below (found by this fuzz, fixed)
        nodata=pick("nodata", st.sampled_from([0, None]),
                    st.sampled_from([255, float("nan"), -1, 1e40])),
        # a complex DEM is the explicit example below (a known bug)
        dem_kind=pick("dem", st.just("hills"), st.sampled_from(["nan hole", "too small", "list"])),
        dem_transform_kind=pick("dem transform", st.just("affine"),
                                st.sampled_from(["gdal tuple", "affine tuple"])),
        dst_crs=pick("dst_crs", st.sampled_from([None, "EPSG:4326", 4326]),
                     st.sampled_from(["EPSG:99999", "not a crs"])),
        rpc_kind=pick("rpc", st.sampled_from(["model", "dict", "strings"]),
                      st.just("dict missing")),
        shape=pick("shape", st.sampled_from([(12, 12), (1, 30), (7, 20)]),
                   st.sampled_from([(0, 5), (12, -3), (2.5, 4), "12"])))


def _moved_off_nodata(nodata, dtype):
    """Where rsgeo's AvoidNoData moves a valid value equal to ``nodata`` (rsgeo.resample)."""
    if dtype.kind in "iu":
        return nodata + 1 if nodata == np.iinfo(dtype).min else nodata - 1
    return np.nextafter(dtype.type(nodata), dtype.type(np.inf))


COMPLEX_DEM = dict(image=np.arange(400, dtype=np.uint8).reshape(20, 20), method="nearest",
                   nodata=0, dem_kind="complex", dem_transform_kind="affine", dst_crs=None,
                   rpc_kind="dict", shape=(12, 12))


@FUZZ_GDAL
@given(case=ortho_cases())
@example(case=COMPLEX_DEM)
@example(case={**COMPLEX_DEM, "dem_kind": "hills", "nodata": "0"})
@example(case={**COMPLEX_DEM, "dem_kind": "hills", "nodata": True})
def test_orthorectify_refuses_or_matches_gdal(case):
    image, method, nodata, dem_kind, dem_transform_kind, dst_crs, rpc_kind, shape = (
        case[name] for name in ("image", "method", "nodata", "dem_kind", "dem_transform_kind",
                                "dst_crs", "rpc_kind", "shape"))
    n = image.shape[-1] if image.ndim >= 2 and image.shape[-1] > 0 else 20
    rpc_dict, degrees = _small_rpc(n)
    rpc_model = sensors.RPCModel.from_dict(rpc_dict)
    rpc = {"model": rpc_model, "dict": rpc_dict,
           "dict missing": {k: v for k, v in rpc_dict.items() if k != "LAT_OFF"},
           "strings": {k: (" ".join(map(str, v)) if isinstance(v, list) else str(v))
                       for k, v in rpc_dict.items()}}[rpc_kind]
    rng = np.random.default_rng(1)
    dem = rng.uniform(0, 300, (30, 30))
    dem_step = 2.4 * degrees / 30
    dem_gt = affine.Affine(dem_step, 0, -34.9 - 1.2 * degrees, 0, -dem_step, -8.0 + 1.2 * degrees)
    if dem_kind == "nan hole":
        # a band of holes from top to bottom, which every output grid (one row of 30 cells
        # too) crosses: a hole the grid never samples is rightly not refused
        dem[:, 10:20] = np.nan
    elif dem_kind == "too small":
        dem = dem[:3, :3]
    elif dem_kind == "list":
        dem = dem.tolist()
    elif dem_kind == "complex":
        dem = dem + 50j
    given_dem_gt = {"affine": dem_gt, "gdal tuple": dem_gt.to_gdal(),
                    "affine tuple": tuple(dem_gt)[:6]}[dem_transform_kind]
    rows_cols = shape if isinstance(shape, str) else tuple(shape)
    # the grid spans the image's footprint (2 x degrees) along its longer side, inside the DEM's
    longest = max(shape) if isinstance(shape, tuple) and min(shape) > 0 else 12
    step = 2 * degrees / longest
    grid = affine.Affine(step, 0, -34.9 - degrees, 0, -step, -8.0 + degrees)
    got = call("orthorectify", ortho.orthorectify, image, rpc, dem, given_dem_gt, grid,
               rows_cols, method, nodata=nodata, dst_crs=dst_crs, dem_vertical="ellipsoidal")
    if got is REFUSED:
        return
    check_nodata_taken("orthorectify", nodata)
    assert image.dtype.kind in "iuf" and dem_kind in ("hills", "list"), (
        f"orthorectify answered on image {image.dtype}, DEM {dem_kind}")
    assert dst_crs in (None, "EPSG:4326", 4326)
    assert rpc_kind != "dict missing"
    if dem_transform_kind == "affine tuple":
        pytest.fail("orthorectify read a 6-tuple in Affine order (as if GDAL's?)")
    dem64 = np.asarray(dem, dtype=np.float64)
    native = image.astype(image.dtype.newbyteorder("=")) if image.dtype.byteorder == ">" \
        else image
    if native.dtype == np.float16:
        native = native.astype(np.float32)
    if native.dtype.name not in GDAL_TYPES:
        pytest.fail(f"orthorectify answered for dtype {image.dtype} (no reference)")
    bands = native if native.ndim == 3 else native[np.newaxis]
    expected = np.stack([_gdal_ortho(band, rpc_model, dem64, dem_gt, grid, rows_cols, method,
                                     nodata) for band in bands])
    expected = expected if native.ndim == 3 else expected[0]
    got = np.asarray(got)
    got = got.astype(got.dtype.newbyteorder("="))
    if image.dtype == np.float16:
        same = np.isclose(got.astype(np.float64), expected.astype(np.float16).astype(np.float64),
                          rtol=2e-3, equal_nan=True)
    else:
        same = (got == expected) | (np.isnan(got) & np.isnan(expected)
                                    if got.dtype.kind == "f" else False)
    if nodata == 0 and method != "nearest" and not same.all():
        # terrain's documented difference (OSGeo/gdal#11711): a valid value that comes out as
        # the nodata 0 is moved one step off it by rsgeo (GDAL's AvoidNoData, as its VRT warps
        # do) and left at 0 by GDAL's reproject. Allowed where the value without nodata is 0.
        raw = np.asarray(ortho.orthorectify(image, rpc, dem, given_dem_gt, grid, rows_cols,
                                              method, nodata=None, dst_crs=dst_crs,
                                              dem_vertical="ellipsoidal"))
        moved = (~same & (expected == 0) & (raw == 0)
                 & (got == _moved_off_nodata(0, got.dtype)))
        if moved.any():
            event("orthorectify: answered with AvoidNoData where GDAL's reproject has none")
        same |= moved
    assert same.all(), (f"orthorectify differs from GDAL at {(~same).sum()} of {same.size} "
                        f"cells ({image.dtype}, {method}, nodata {nodata})")
    confirmed("orthorectify")


# -- datum_shift against PROJ ---------------------------------------------------------------------

def proj_with_rsgeo_grids(src_wkt, dst_wkt, xy):
    """PROJ's own answer with rsgeo's grids on its search path, for this call only.

    rsgeo reads its grids by path and never touches PROJ's search path; the reference puts
    them there (as a user who installed them would), then puts the path back as it was.
    """
    import pyproj
    from pyproj import Transformer

    from rsgeo._proj import GRIDS

    before = pyproj.datadir.get_data_dir()
    pyproj.datadir.append_data_dir(str(GRIDS))
    try:
        return Transformer.from_crs(src_wkt, dst_wkt, always_xy=True).transform(
            xy[:, 0], xy[:, 1])
    finally:
        pyproj.datadir.set_data_dir(before)


CRS_CHOICES = ["EPSG:29193", "EPSG:31983", "EPSG:29192", "EPSG:32723", "EPSG:4326", "EPSG:4618",
               31983, "EPSG:3857", "not a crs", "EPSG:999999", None, 3.5, "EPSG:5880"]
GEOGRAPHIC_CHOICES = ("EPSG:4326", "EPSG:4618")
# what a datum shift is for: one projection in one unit (or geographic) on two datums
LIKE_CRS_PAIRS = [("EPSG:29193", "EPSG:31983"), (31983, "EPSG:29193"),
                  ("EPSG:32723", "EPSG:31983"), ("EPSG:29193", "EPSG:32723"),
                  ("EPSG:4618", "EPSG:4326"), ("EPSG:4326", "EPSG:4618")]


def _area_of_use(crs):
    """EPSG's area of use of ``crs`` as PROJ gives it (WKT2's BBOX): west, south, east, north."""
    import re

    found = re.findall(r"BBOX\[([-+.\deE]+),([-+.\deE]+),([-+.\deE]+),([-+.\deE]+)\]",
                       crs.to_wkt(version="WKT2_2019"))
    if not found:
        return -180.0, -90.0, 180.0, 90.0
    south, west, north, east = (float(v) for v in found[-1])
    return west, south, east, north


@FUZZ
@given(crs_pair=mostly(st.sampled_from(LIKE_CRS_PAIRS),
                      st.tuples(st.sampled_from(CRS_CHOICES), st.sampled_from(CRS_CHOICES)), 1),
       where=mostly(st.just("native"), st.sampled_from(
           ["utm", "lonlat", "far", "huge", "nan", "empty", "list", "strings", "shape3"]), 2),
       n=st.integers(1, 5))
def test_datum_shift_refuses_or_matches_proj(crs_pair, where, n):
    from rasterio.crs import CRS
    from rasterio.warp import transform

    src_crs, dst_crs = crs_pair
    if where == "native":       # the coordinates src_crs has over south-east Brazil
        where = "lonlat" if src_crs in GEOGRAPHIC_CHOICES else "utm"
    rng = np.random.default_rng(n)
    points = {"utm": np.column_stack([rng.uniform(300e3, 700e3, n),
                                      rng.uniform(7.2e6, 7.6e6, n)]),
              "lonlat": np.column_stack([rng.uniform(-48, -42, n), rng.uniform(-24, -20, n)]),
              "far": np.column_stack([rng.uniform(-5e6, 5e6, n), rng.uniform(-5e6, 5e6, n)]),
              "huge": np.full((n, 2), 1e7), "nan": np.full((n, 2), np.nan),
              "empty": np.empty((0, 2)), "list": [[500000.0, 7400000.0]] * n,
              "strings": [["500000", "7400000"]] * n, "shape3": np.ones((n, 3))}[where]
    got = call("datum_shift", crs.datum_shift, points, src_crs, dst_crs)
    if got is REFUSED:
        return
    assert where not in ("nan", "shape3"), f"datum_shift answered on {where} points"
    src, dst = CRS.from_user_input(src_crs), CRS.from_user_input(dst_crs)
    assert src.linear_units == dst.linear_units, (
        f"datum_shift from {src_crs} ({src.linear_units}) to {dst_crs} ({dst.linear_units}): "
        "a 'shift' between different units")
    dx, dy, distance = (np.asarray(a, dtype=np.float64) for a in got)
    xy = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if not len(xy):
        assert dx.size == 0
        confirmed("datum_shift", "empty")
        return
    lon, lat = transform(src, "EPSG:4326", xy[:, 0].tolist(), xy[:, 1].tolist())
    for each_crs in (src, dst):
        west, south, east, north = _area_of_use(each_crs)
        assert all(west - 1e-9 <= x <= east + 1e-9 and south - 1e-9 <= y <= north + 1e-9
                   for x, y in zip(lon, lat)), (
            f"datum_shift answered for {where} points outside the area of use of {each_crs} "
            f"({west}, {south}, {east}, {north})")
    xs, ys = proj_with_rsgeo_grids(src.to_wkt(), dst.to_wkt(), xy)
    expect_dx, expect_dy = np.asarray(xs) - xy[:, 0], np.asarray(ys) - xy[:, 1]
    assert np.isfinite(expect_dx).all() and np.isfinite(expect_dy).all(), (
        f"PROJ cannot transform these points ({where}) but datum_shift answered {dx}")
    np.testing.assert_allclose(dx, expect_dx, atol=1e-6)
    np.testing.assert_allclose(dy, expect_dy, atol=1e-6)
    np.testing.assert_allclose(distance, np.hypot(expect_dx, expect_dy), atol=1e-6)
    # a shift between datums is metres, not kilometres: larger means the points or CRSs are wrong
    assert (distance < 1000).all() or src.linear_units not in ("metre", "meter"), (
        f"datum_shift({where} points, {src_crs} -> {dst_crs}) reports {distance.max():.0f} m")
    confirmed("datum_shift")


@pytest.mark.parametrize("src_crs, dst_crs", [("EPSG:3857", "EPSG:3857"),
                                              ("EPSG:29193", "EPSG:31983")])
def test_datum_shift_refuses_points_at_1e30(src_crs, dst_crs):
    # the property above draws |v| <= 1e7: PROJ's inverse Web Mercator, asked for longitude and
    # latitude of (1e30, 1e30) on rsgeo's area-of-use check, did not return
    with pytest.raises(RsgeoError):
        crs.datum_shift(np.full((2, 2), 1e30), src_crs, dst_crs)


# -- read_points / write_points -------------------------------------------------------------------

# WKT as QGIS may write it: one node per line (whitespace between nodes is valid WKT)
PRETTY_WKT = rasterio.crs.CRS.from_epsg(29191).to_wkt().replace("],", "],\n    ")
texts = st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=12)


@FUZZ
@given(n=st.integers(0, 6), seed=st.integers(0, 2**16),
       crs=st.sampled_from([None, "EPSG:31983", rasterio.crs.CRS.from_epsg(29191).to_wkt(),
                            "pretty"]),
       ids=st.one_of(st.none(), st.lists(texts, min_size=6, max_size=6)),
       notes=st.one_of(st.none(), st.lists(texts, min_size=6, max_size=6)),
       magnitude=st.sampled_from([1.0, 1e-12, 1e15, 7e6]),
       into=mostly(st.just("file"), st.sampled_from(["missing folder", "package data"])))
def test_write_then_read_points_gives_the_same_gcps(tmp_path_factory, n, seed, crs, ids, notes,
                                                     magnitude, into):
    rng = np.random.default_rng(seed)
    map_xy = rng.uniform(-1, 1, (n, 2)) * magnitude
    image_xy = rng.uniform(0, 500, (n, 2))
    enabled = rng.integers(0, 2, n).astype(bool)
    crs_text = PRETTY_WKT if crs == "pretty" else crs
    made = call("GCPSet", gcp.GCPSet, map_xy, image_xy, enabled=enabled,
                ids=None if ids is None else ids[:n], crs=crs_text,
                notes=None if notes is None else notes[:n])
    if made is REFUSED:
        return
    folder = tmp_path_factory.mktemp("points")
    path = {"file": folder / "gcps.points", "missing folder": folder / "nowhere" / "g.points",
            "package data": RSGEO_DIR / "data" / "fuzz_should_not_be_written.points"}[into]
    written = call("write_points", gcp.write_points, path, made)
    if written is REFUSED:
        assert not path.exists()
        return
    if into == "package data":
        path.unlink(missing_ok=True)
        pytest.fail("write_points wrote inside rsgeo's data folder")
    assert into == "file"
    back = call("read_points", gcp.read_points, path)
    assert back is not REFUSED, f"read_points refused what write_points wrote: {path.read_text()}"
    assert np.array_equal(back.map_xy.reshape(-1, 2), map_xy), "map_xy changed in the round trip"
    assert np.array_equal(back.image_xy.reshape(-1, 2), image_xy), "image_xy changed"
    assert np.array_equal(np.asarray(back.enabled, dtype=bool), enabled)
    if crs_text is not None:
        assert rasterio.crs.CRS.from_user_input(back.crs) == \
            rasterio.crs.CRS.from_user_input(crs_text), "the CRS changed in the round trip"
    if ids is not None:
        assert list(back.ids) == list(made.ids), "ids lost in the round trip"
    if notes is not None:
        assert list(back.notes) == list(made.notes), "notes lost in the round trip"
    confirmed("read/write_points")


ENABLE_SPELLINGS = {"1": True, "0": False, "true": True, "false": False, "TRUE": True,
                    "FALSE": False, "True": True, "False": False, "yes": True, "no": False,
                    " 0 ": False}


@FUZZ
@given(n=st.integers(0, 5), seed=st.integers(0, 2**16), bom=st.booleans(),
       newline=st.sampled_from(["\n", "\r\n"]), delimiter=st.sampled_from([",", "\t"]),
       enable=st.lists(st.sampled_from(sorted(ENABLE_SPELLINGS)), min_size=5, max_size=5),
       old_header=st.booleans(),
       damage=st.sampled_from([None] * 8 + ["binary", "missing column", "word for number",
                               "nan", "short row", "empty file"]))
def test_read_points_reads_hand_written_files_or_refuses(tmp_path_factory, n, seed, bom, newline,
                                                         delimiter, enable, old_header, damage):
    rng = np.random.default_rng(seed)
    map_xy = np.round(rng.uniform(3e5, 8e5, (n, 2)), 3)
    image_xy = np.round(rng.uniform(0, 500, (n, 2)), 3)
    names = ["mapX", "mapY", "pixelX" if old_header else "sourceX",
             "pixelY" if old_header else "sourceY", "enable"]
    if damage == "missing column":
        names[1] = "mapZ"
    lines = [delimiter.join(names)]
    for i in range(n):
        values = [repr(float(map_xy[i, 0])), repr(float(map_xy[i, 1])),
                  repr(float(image_xy[i, 0])), repr(float(-image_xy[i, 1])), enable[i]]
        if damage == "word for number" and i == 0:
            values[0] = "east"
        if damage == "nan" and i == 0:
            values[2] = "nan"
        if damage == "short row" and i == 0:
            values = values[:2]
        lines.append(delimiter.join(values))
    text = newline.join(lines) + newline
    data = (b"\xef\xbb\xbf" if bom else b"") + text.encode()
    if damage == "binary":
        data = bytes(rng.integers(0, 256, 200, dtype=np.uint8))
    elif damage == "empty file":
        data = b""
    path = tmp_path_factory.mktemp("hand") / "gcps.points"
    path.write_bytes(data)
    back = call("read_points", gcp.read_points, path)
    if back is REFUSED:
        return
    damaged_rows = damage in ("word for number", "nan", "short row") and n > 0
    assert damage not in ("binary", "missing column", "empty file") and not damaged_rows, (
        f"read_points read a file with damage '{damage}'")
    assert np.array_equal(np.asarray(back.map_xy).reshape(-1, 2), map_xy)
    assert np.array_equal(np.asarray(back.image_xy).reshape(-1, 2), image_xy)
    expected = [ENABLE_SPELLINGS[e] for e in enable[:n]]
    assert np.asarray(back.enabled, dtype=bool).tolist() == expected, (
        f"enable column {enable[:n]} read as {np.asarray(back.enabled).tolist()}")
    confirmed("read_points", "hand-written file")
