"""rsgeo.resample against GDAL, bit for bit, plus properties and errors."""

import affine
import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsgeo import transforms
from rsgeo._kernels import resampling
from rsgeo.resample import METHODS, _warp, grid_positions, interpolate, keys_weights, warp

from gdal_reference import affine_source, gcp_source, gdal_warp

SOURCE_TRANSFORM = affine.Affine(10.0, 0, 500_000.0, 0, -10.0, 7_400_000.0)


def noise(shape, dtype="uint8", seed=0):
    rng = np.random.default_rng(seed)
    if np.dtype(dtype).kind == "f":
        return rng.normal(100, 50, shape).astype(dtype)
    info = np.iinfo(dtype)
    return rng.integers(info.min, int(info.max) + 1, shape, dtype=dtype)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("dtype", ["uint8", "int16", "uint16", "float32"])
def test_affine_warp_matches_gdal_bit_for_bit(method, dtype):
    # A rotation of 7° and a slight zoom in (scale 1/0.9): GDAL keeps its plain 2x2 and 4x4
    # kernels.
    image = noise((300, 400), dtype)
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                     @ affine.Affine.rotation(7) @ affine.Affine.scale(0.9))
    shape = (380, 450)
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method, 0)
    x, y = grid_positions(shape, dst_transform)
    cols, rows = ~SOURCE_TRANSFORM @ (x, y)
    got = interpolate(image, cols, rows, method, nodata=0)
    assert got.dtype == expected.dtype
    # float32 too: with a destination nodata GDAL's general path (GWKRealCase) weights and
    # adds in its own order, which rsgeo follows
    assert np.count_nonzero(got != expected) == 0
    # the same footprint: GDAL's AvoidNoData keeps valid pixels off the nodata value too
    inside = (cols >= 0) & (cols < 400) & (rows >= 0) & (rows < 300)
    assert np.array_equal(expected != 0, inside) or method == "nearest"


def noise_and_curved_gcps():
    """A 320 x 320 noise image and 12 GCPs of a mildly curved (degree-2) mapping to UTM-sized map
    coordinates: the polynomial cases of the GDAL cross-checks."""
    rng = np.random.default_rng(3)
    image = noise((320, 320), seed=3)
    image_xy = rng.uniform(0, 320, (12, 2))
    u, v = image_xy[:, 0] - 160, image_xy[:, 1] - 160
    map_xy = np.column_stack([
        600_000 + 10 * image_xy[:, 0] + 0.4 * image_xy[:, 1] + 0.002 * u * v,
        7_300_000 - 10 * image_xy[:, 1] + 0.5 * image_xy[:, 0] + 0.003 * u * u])
    return image, image_xy, map_xy


@pytest.mark.parametrize("method", METHODS)
def test_polynomial_warp_matches_gdal_bit_for_bit(method):
    image, image_xy, map_xy = noise_and_curved_gcps()
    # 7 m output pixels over 10 m input pixels: an up-sampling, where GDAL keeps the plain
    # kernels (at 9.5 m the shear makes its chunk scale fall below 0.95 and it widens them)
    dst_transform = affine.Affine(7.0, 0, 600_400, 0, -7.0, 7_299_600)
    shape = (400, 400)
    expected = gdal_warp(image, gcp_source(image_xy, map_xy, 2), dst_transform, shape, method, 0)
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    got = warp(image, model, shape, dst_transform, method=method, dst_nodata=0)
    assert np.count_nonzero(got != expected) == 0


def test_multiband_is_each_band():
    image = noise((3, 50, 60))
    cols, rows = np.meshgrid(np.linspace(-2, 62, 70), np.linspace(-2, 52, 40))
    together = interpolate(image, cols, rows, "cubic")
    assert together.shape == (3, 40, 70)
    for band in range(3):
        assert np.array_equal(together[band], interpolate(image[band], cols, rows, "cubic"))


def test_warp_in_strips_equals_one_strip():
    image = noise((100, 100))
    mapping = affine.Affine.rotation(3) @ affine.Affine.scale(0.8)
    assert np.array_equal(warp(image, mapping, (90, 90), method="cubic", strip_rows=7),
                          warp(image, mapping, (90, 90), method="cubic", strip_rows=1000))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 255), st.sampled_from(METHODS),
       st.lists(st.floats(0, 20), min_size=1, max_size=30),
       st.lists(st.floats(0, 15), min_size=1, max_size=30))
def test_constant_image_stays_constant(value, method, cols, rows):
    n = min(len(cols), len(rows))
    image = np.full((15, 20), value, dtype=np.uint8)
    cols, rows = np.array(cols[:n]), np.array(rows[:n])
    out = interpolate(image, cols, rows, method, nodata=0)
    # GDAL's rule for "inside": floor(position + 1e-10) within the image
    inside = (np.floor(cols + 1e-10) < 20) & (np.floor(rows + 1e-10) < 15)
    assert (out[~inside] == 0).all()
    # a valid pixel equal to nodata moves one step away (GDAL's AvoidNoData), except for nearest
    expected = value if (value != 0 or method == "nearest") else 1
    assert (out[inside] == expected).all()


@settings(max_examples=20, deadline=None)
@given(st.sampled_from(METHODS), st.integers(0, 2**31 - 1))
def test_identity_mapping_returns_the_image(method, seed):
    image = noise((30, 40), "float32", seed)
    rows, cols = np.mgrid[0:30, 0:40] + 0.5
    assert np.array_equal(interpolate(image, cols, rows, method, nodata=-9999.0), image)


@settings(max_examples=30, deadline=None)
@given(st.floats(-5, 5), st.floats(-5, 5), st.floats(-100, 100))
def test_bilinear_is_exact_on_planes(a, b, c):
    rows, cols = np.mgrid[0:20, 0:20] + 0.5
    plane = a * cols + b * rows + c
    rng = np.random.default_rng(0)
    at_c, at_r = rng.uniform(1, 19, 200), rng.uniform(1, 19, 200)
    got = interpolate(plane, at_c, at_r, "bilinear", nodata=np.nan)
    np.testing.assert_allclose(got, a * at_c + b * at_r + c, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2),
       st.floats(-0.1, 0.1), st.floats(-0.1, 0.1), st.floats(-0.1, 0.1))
def test_cubic_reproduces_quadratics_in_the_interior(a, b, cxx, cxy, cyy):
    rows, cols = np.mgrid[0:24, 0:24] + 0.5
    surface = a * cols + b * rows + cxx * cols**2 + cxy * cols * rows + cyy * rows**2
    rng = np.random.default_rng(1)
    at_c, at_r = rng.uniform(3, 20, 200), rng.uniform(3, 20, 200)
    got = interpolate(surface, at_c, at_r, "cubic", nodata=np.nan)
    expected = a * at_c + b * at_r + cxx * at_c**2 + cxy * at_c * at_r + cyy * at_r**2
    np.testing.assert_allclose(got, expected, atol=1e-8)


@pytest.mark.parametrize("kwargs, message", [
    (dict(cols=[np.nan], rows=[1.0]), "NaN or infinite"),
    (dict(cols=[np.inf], rows=[1.0]), "NaN or infinite"),
    (dict(cols=[1.0, 2.0], rows=[1.0]), "same shape"),
    (dict(cols=[1.0], rows=[1.0], method="lanczos"), "unknown method 'lanczos'"),
    (dict(cols=[1.0], rows=[1.0], nodata=300), "does not fit dtype uint8"),
    (dict(cols=[1.0], rows=[1.0], nodata=-1), "does not fit dtype uint8"),
])
def test_bad_input_is_a_clear_value_error(kwargs, message):
    image = np.zeros((4, 4), dtype=np.uint8)
    with pytest.raises(ValueError, match=message):
        interpolate(image, **kwargs)


@pytest.mark.parametrize("image, message", [(np.zeros(5), "1-D"), (np.zeros((2, 2, 2, 2)), "4-D"),
                                            (np.array([["a"]]), "integers or floats")])
def test_images_that_are_not_images(image, message):
    with pytest.raises(ValueError, match=message):
        interpolate(image, [0.5], [0.5])


def test_warp_rejects_a_bad_mapping_and_shape():
    image = np.zeros((4, 4), dtype=np.uint8)
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        warp(image, lambda points: points[:, 0], (2, 2))
    with pytest.raises(ValueError, match="two positive integers"):
        warp(image, affine.Affine.identity(), (0, 2))


# -- silent failures turned into errors ---------------------------------------


def test_warp_in_the_wrong_direction_is_an_error_not_an_empty_image():
    image = noise((300, 400))
    shape = (300, 400)
    # right: map -> image, the inverse of the raster's geotransform; the same grid gives the image
    # back
    assert np.array_equal(warp(image, ~SOURCE_TRANSFORM, shape, SOURCE_TRANSFORM), image)
    # wrong: the raster's own transform, pixel -> map
    with pytest.raises(ValueError, match=r"no output cell lands inside the source image: is your "
                                         r"mapping map → image \(u = f\(x, y\)\)\?"
                                         r".*~raster.transform"):
        warp(image, SOURCE_TRANSFORM, shape, SOURCE_TRANSFORM)


def test_a_model_fitted_image_to_map_is_an_error():
    image = noise((300, 400))
    rng = np.random.default_rng(5)
    image_xy = rng.uniform(0, 300, (8, 2))
    map_xy = np.column_stack(SOURCE_TRANSFORM @ (image_xy[:, 0], image_xy[:, 1]))
    right = transforms.fit_polynomial(map_xy, image_xy, 1)
    wrong = transforms.fit_polynomial(image_xy, map_xy, 1)
    assert np.array_equal(warp(image, right, (300, 400), SOURCE_TRANSFORM), image)
    with pytest.raises(ValueError, match=r"map → image.*fit_polynomial\(map_xy, image_xy"):
        warp(image, wrong, (300, 400), SOURCE_TRANSFORM)


def test_a_grid_that_partly_covers_the_source_is_fine():
    image = noise((50, 50))
    out = warp(image, affine.Affine.translation(40, 0), (50, 50), method="bilinear")
    assert (out[:, :10] != 0).all() and (out[:, 10:] == 0).all()


@pytest.mark.parametrize("shape", [(351, 369, 3), (351, 369, 4), (20, 17, 3)])
def test_bands_last_images_are_refused_with_the_fix(shape):
    image = np.zeros(shape, dtype=np.uint8)
    with pytest.raises(ValueError, match=r"bands last.*np\.moveaxis\(image, -1, 0\)"):
        warp(image, affine.Affine.identity(), shape[:2])
    with pytest.raises(ValueError, match="bands last"):
        interpolate(image, [0.5], [0.5])


@pytest.mark.parametrize("shape", [(3, 351, 369), (4, 10, 4), (3, 12, 3), (30, 12, 60)])
def test_bands_first_images_are_accepted(shape):
    image = noise(shape)
    assert warp(image, affine.Affine.identity(), shape[1:]).shape == shape


@pytest.mark.parametrize("shape", [351, 351.0, (351,), (2, 2, 2), ("a", 2), (2.5, 3), (0, 2),
                                   None])
def test_warp_shape_must_be_rows_cols(shape):
    with pytest.raises(ValueError, match=r"shape must be \(rows, cols\)"):
        warp(np.zeros((4, 4), dtype=np.uint8), affine.Affine.identity(), shape)


# -- the Numba kernels: threads, the affine path, dtypes ------------------------


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("dtype", ["uint8", "int16", "float32"])
def test_affine_warp_computes_positions_like_grid_positions(method, dtype):
    # warp evaluates an affine map pixel by pixel inside the kernel; it must give
    # exactly what interpolate gives at grid_positions' positions (the GDAL-checked path),
    # including the edges, nodata outside and several bands
    image = noise((2, 60, 70), dtype, seed=4)
    mapping = (affine.Affine.translation(-5.3, 3.1) @ affine.Affine.rotation(11)
               @ affine.Affine.scale(1.1, 0.9))
    shape = (64, 77)
    cols, rows = grid_positions(shape, mapping)
    expected = interpolate(image, cols, rows, method, nodata=7)
    got = warp(image, mapping, shape, method=method, dst_nodata=7)
    assert (expected == 7).any() and (expected != 7).any()     # both inside and outside
    assert np.array_equal(got, expected)


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="Numba may use one thread here")
@pytest.mark.parametrize("method", METHODS)
def test_two_threads_give_the_same_pixels_as_one(method):
    image = noise((3, 80, 90), "int16", seed=6)
    mapping = affine.Affine.rotation(4) @ affine.Affine.scale(0.9)
    one = warp(image, mapping, (85, 95), method=method, num_threads=1)
    two = warp(image, mapping, (85, 95), method=method, num_threads=2)
    assert np.array_equal(one, two)
    cols, rows = grid_positions((85, 95), mapping)
    assert np.array_equal(interpolate(image, cols, rows, method, num_threads=2), one)


@pytest.mark.parametrize("method", METHODS)
def test_a_long_list_of_positions_equals_the_same_positions_as_a_grid(method):
    # a 1-D list is cut into blocks of rows for the threads: the last, partial block too
    image = noise((40, 50), seed=8)
    rng = np.random.default_rng(8)
    cols, rows = rng.uniform(-3, 53, (2, 101, 97))
    grid = interpolate(image, cols, rows, method, num_threads=2)
    listed = interpolate(image, cols.ravel(), rows.ravel(), method, num_threads=2)
    assert np.array_equal(listed, grid.ravel())
    assert interpolate(image, np.array([]), np.array([]), method).shape == (0,)
    assert interpolate(image, 10.2, 20.7, method).shape == ()


@pytest.mark.parametrize("dtype", ["float16", ">u2", ">f8"])
def test_dtypes_numba_does_not_compute_in_still_work(dtype):
    # float16 is computed in float32; big-endian images in native byte order
    image = noise((30, 40), "uint16" if "u" in dtype else "float32", seed=9)
    cols, rows = np.meshgrid(np.linspace(-1, 41, 33), np.linspace(-1, 31, 25))
    for method in METHODS:
        got = interpolate(image.astype(dtype), cols, rows, method, nodata=0)
        native = image.astype(np.dtype(dtype).newbyteorder("="))
        expected = interpolate(image if dtype == "float16" else native, cols, rows, method,
                               nodata=0)
        assert got.dtype == np.dtype(dtype)
        if dtype == "float16":
            np.testing.assert_allclose(got, expected.astype(np.float16), rtol=1e-2)
        else:
            assert np.array_equal(got, expected)


def test_bilinear_edge_and_cubic_fallback_read_no_pixel_outside_the_image():
    # on a 2 x 2 image every position is at an edge: bilinear renormalises the
    # weights of the pixels that exist, cubic falls back to bilinear
    image = np.array([[10.0, 20.0], [30.0, 40.0]])
    cols = np.array([0.25, 1.0, 1.75, 0.0, 1.999])
    rows = np.array([0.25, 1.0, 1.75, 1.5, 0.5])
    expected = [10.0, 25.0, 40.0, 30.0, 20.0]
    for method in ("bilinear", "cubic"):
        np.testing.assert_allclose(interpolate(image, cols, rows, method, nodata=-1), expected)


@pytest.mark.parametrize("num_threads", [0, -1, 1.5, "2", None, 10**6])
def test_num_threads_must_be_a_whole_number_within_numba_s_threads(num_threads):
    image = np.zeros((4, 4), dtype=np.uint8)
    with pytest.raises(ValueError, match="num_threads must be a whole number from 1 to"):
        interpolate(image, [1.0], [1.0], num_threads=num_threads)
    with pytest.raises(ValueError, match="num_threads must be a whole number from 1 to"):
        warp(image, affine.Affine.identity(), (4, 4), num_threads=num_threads)


def test_avoid_nodata_on_every_integer_edge_case():
    # a valid interpolated value equal to nodata steps away from it: down, or up from the
    # dtype's minimum; nearest copies values as they are
    image = np.full((6, 6), 5, dtype=np.int16)
    assert interpolate(image, [3.0], [3.0], "bilinear", nodata=5)[0] == 4
    assert interpolate(image, [3.0], [3.0], "cubic", nodata=5)[0] == 4
    assert interpolate(image, [3.0], [3.0], "nearest", nodata=5)[0] == 5
    low = np.full((6, 6), -32768, dtype=np.int16)
    assert interpolate(low, [3.0], [3.0], "cubic", nodata=-32768)[0] == -32767
    floats = np.full((6, 6), 2.5, dtype=np.float32)
    assert interpolate(floats, [3.0], [3.0], "bilinear", nodata=2.5)[0] == np.nextafter(
        np.float32(2.5), np.float32(np.inf))


def test_keys_weights_reproduce_quadratics_and_match_keys_closed_form():
    # Keys (1981): with a = -0.5 cubic convolution reproduces every polynomial up to degree 2;
    # pixels at offsets -1, 0, 1, 2 from the pixel left of the position, t in [0, 1).
    t = np.linspace(0, 0.999, 37)
    offsets = np.array([-1.0, 0.0, 1.0, 2.0])[:, None]
    weights = keys_weights(t)
    for power in (0, 1, 2):
        np.testing.assert_allclose((weights * offsets**power).sum(axis=0), t**power, atol=1e-12)
    # Keys' eq. 15 written out independently: the four weights as cubics in t
    expected = np.stack([(-t**3 + 2 * t**2 - t) / 2, (3 * t**3 - 5 * t**2 + 2) / 2,
                         (-3 * t**3 + 4 * t**2 + t) / 2, (t**3 - t**2) / 2])
    np.testing.assert_allclose(weights, expected, atol=1e-15)
    # OpenCV's a = -0.75 keeps constants, is symmetric, but bends a straight line (only a = -0.5
    # reproduces it)
    opencv = keys_weights(t, a=-0.75)
    np.testing.assert_allclose(opencv.sum(axis=0), 1.0, atol=1e-12)
    np.testing.assert_allclose(keys_weights(0.5, a=-0.75), [-0.09375, 0.59375, 0.59375, -0.09375])
    assert np.abs((opencv * offsets).sum(axis=0) - t).max() > 0.01


# -- gdalwarp's common cases: no nodata, downsampling ---------------------------

from rsgeo.resample import grid_scale  # noqa: E402
from rsgeo.validation import as_scale  # noqa: E402

from gdal_reference import gdalwarp_reproject  # noqa: E402


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("dtype", ["uint8", "int16", "float32"])
def test_no_nodata_matches_gdal_without_dstnodata(method, dtype):
    # gdalwarp without -dstnodata: outside is 0 and valid zeros stay 0 (no AvoidNoData)
    image = noise((300, 400), dtype, seed=11)
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                     @ affine.Affine.rotation(7) @ affine.Affine.scale(0.9))
    shape = (380, 450)
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method,
                         None, plain_kernels=True)
    x, y = grid_positions(shape, dst_transform)
    cols, rows = ~SOURCE_TRANSFORM @ (x, y)
    got = interpolate(image, cols, rows, method, nodata=None)
    assert np.count_nonzero(got != expected) == 0
    inside = (cols >= 0) & (cols < 400) & (rows >= 0) & (rows < 300)
    assert (got[~inside] == 0).all()


def test_no_nodata_keeps_valid_zeros():
    image = np.zeros((6, 6), dtype=np.uint8)
    for method in METHODS:
        assert interpolate(image, [3.0, 7.0], [3.0, 3.0], method, nodata=None).tolist() == [0, 0]
    # with nodata=0 the valid zero moves to 1 (AvoidNoData): the difference is real
    assert interpolate(image, [3.0], [3.0], "bilinear", nodata=0)[0] == 1


@pytest.mark.parametrize("method", ["bilinear", "cubic"])
@pytest.mark.parametrize("scale", [(0.23, 0.23), (0.37, 0.5), (0.125, 0.125), (0.6, 1.0)])
@pytest.mark.parametrize("nodata", [0, None])
@pytest.mark.parametrize("dtype", ["uint8", "int16", "float32"])
def test_widened_kernels_match_gdal_with_forced_scale(method, scale, nodata, dtype):
    # GDAL's XSCALE / YSCALE warp options force the scale; below 0.95 GDAL widens its
    # bilinear and cubic kernels over 1/scale source pixels (GWKResample)
    image = noise((300, 400), dtype, seed=12)
    zoom = 0.8 / min(scale)
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                     @ affine.Affine.rotation(7) @ affine.Affine.scale(zoom))
    shape = (int(380 / zoom), int(450 / zoom))
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method,
                         nodata, scale=scale)
    x, y = grid_positions(shape, dst_transform)
    cols, rows = ~SOURCE_TRANSFORM @ (x, y)
    got = interpolate(image, cols, rows, method, nodata=nodata, scale=scale)
    assert np.count_nonzero(got != expected) == 0
    # and the widening is not a no-op: the plain kernel differs
    plain = interpolate(image, cols, rows, method, nodata=nodata)
    assert np.count_nonzero(plain != expected) > got.size / 10


DOWNSAMPLED_GRIDS = {
    "whole source, 4 px": (affine.Affine(40.0, 0, 500_000.0, 0, -40.0, 7_400_000.0), (75, 100)),
    "inside, 2.92 px": (affine.Affine(29.2, 0, 500_400.0, 0, -29.2, 7_399_600.0), (95, 119)),
    "inside, 4 px": (affine.Affine(40.0, 0, 500_400.0, 0, -40.0, 7_399_600.0), (70, 87)),
    "rotated": (SOURCE_TRANSFORM @ affine.Affine.translation(60.3, 15.7)
                @ affine.Affine.rotation(7) @ affine.Affine.scale(4.3), (60, 70)),
    "sheared": (SOURCE_TRANSFORM @ affine.Affine.translation(10, 12) @ affine.Affine.shear(5, 3)
                @ affine.Affine.scale(3.1), (100, 120)),
}


@pytest.mark.parametrize("grid", DOWNSAMPLED_GRIDS)
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("nodata", [0, None])
def test_warp_chooses_the_scale_as_gdalwarp_does(grid, method, nodata):
    dst_transform, shape = DOWNSAMPLED_GRIDS[grid]
    image = noise((300, 400), seed=13)
    expected = gdalwarp_reproject(image, SOURCE_TRANSFORM, dst_transform, shape, method, nodata)
    got = warp(image, ~SOURCE_TRANSFORM, shape, dst_transform, method=method, dst_nodata=nodata)
    assert np.count_nonzero(got != expected) == 0
    xscale, yscale = grid_scale(~SOURCE_TRANSFORM, shape, dst_transform, image.shape)
    assert xscale < 0.95 and yscale < 0.95


def test_grid_scale_follows_gdal_rules():
    source = affine.Affine.identity()
    # 120 output columns over 350.4 source columns: 1/2.92, too far from 1/3 to snap
    assert grid_scale(source, (100, 120), affine.Affine.scale(2.92)) == (120 / 350.4, 100 / 292)
    # within 0.05 of a whole reciprocal: exactly 1/3
    assert grid_scale(source, (100, 120), affine.Affine.scale(2.97)) == (1 / 3, 1 / 3)
    # cut at the image's right and bottom edges (GDAL's dfSrcXSizeRaw)
    assert grid_scale(source, (10, 10), affine.Affine(8, 0, 40, 0, 8, 0), (80, 100)) == (
        10 / 60, 1 / 8)
    # a grid off the image: nothing to widen
    assert grid_scale(source, (10, 10), affine.Affine.translation(500, 500), (80, 100)) == (
        1.0, 1.0)


@pytest.mark.parametrize("method", METHODS)
def test_the_hrc_scene_taken_to_the_ccd_grid_matches_gdalwarp(method):
    # the real case: 2.5 m HRC onto the 20 m CCD grid of the same ground, gdalwarp's own scale
    from rsgeo import data
    hrc, ccd = data.load("cbers2b_hrc"), data.load("cbers2b_rgb342")
    shape = ccd.array.shape[-2:]
    expected = gdalwarp_reproject(hrc.array, hrc.transform, ccd.transform, shape, method, None)
    got = warp(hrc.array, ~hrc.transform, shape, ccd.transform, method=method, dst_nodata=None)
    assert np.count_nonzero(got != expected) == 0
    assert grid_scale(~hrc.transform, shape, ccd.transform, hrc.array.shape) == (0.125, 0.125)


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["bilinear", "cubic"]), st.floats(0.05, 0.94), st.floats(0.05, 1.5),
       st.integers(0, 2**31 - 1))
def test_widened_kernels_keep_constants(method, xscale, yscale, seed):
    # the weights are renormalised, so a constant stays constant, at the edges too. (A ramp
    # does not: GDAL's taps run from 1 - n (cubic) or -n (bilinear) to n, n = ceil(R / scale),
    # which cuts a sliver off one side of the widened kernel.)
    rng = np.random.default_rng(seed)
    constant = np.full((80, 80), 7.0)
    at_c, at_r = rng.uniform(0, 80, 50), rng.uniform(0, 80, 50)
    np.testing.assert_allclose(
        interpolate(constant, at_c, at_r, method, nodata=np.nan, scale=(xscale, yscale)), 7.0)


@pytest.mark.parametrize("scale", [0, -0.5, (0.5, 0), np.nan, np.inf, (0.5, 0.5, 0.5), "half",
                                   None])
def test_scale_must_be_positive(scale):
    with pytest.raises(ValueError, match="scale must be one or two finite numbers above 0"):
        interpolate(np.zeros((4, 4), dtype=np.uint8), [1.0], [1.0], "bilinear", scale=scale)
    if scale is not None:
        with pytest.raises(ValueError, match="scale must be one or two finite numbers above 0"):
            warp(np.zeros((4, 4), dtype=np.uint8), affine.Affine.identity(), (4, 4), scale=scale)
    assert as_scale(0.5) == (0.5, 0.5)


# -- the output grid gdalwarp would choose ----------------------------------------

from rsgeo.resample import suggested_grid  # noqa: E402

from gdal_reference import gdal_suggested_grid  # noqa: E402


@pytest.mark.parametrize("shape, transform", [
    ((2810, 2954), affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0)),
    ((300, 400), affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0) @ affine.Affine.rotation(7)),
    ((351, 369), affine.Affine(20, 0, 770596.79, 0, -20, 7370112.81) @ affine.Affine.rotation(-13)
     @ affine.Affine.scale(1.0, 1.3)),
    ((57, 2000), affine.Affine(10, 2, 500_000.5, 1, -12, 7_400_000.25)),
])
def test_suggested_grid_equals_gdal_s_suggestion(shape, transform):
    expected_transform, expected_shape = gdal_suggested_grid(shape, transform)
    got_transform, got_shape = suggested_grid(shape, transform)
    assert got_shape == expected_shape
    assert tuple(got_transform)[:6] == tuple(expected_transform)[:6]


def test_suggested_grid_of_a_gcp_model_is_gdal_s_within_rounding():
    # GDAL fits its own first-order polynomial to the GCPs: the same plane, to rounding
    transform = affine.Affine(20, 0, 770596.79, 0, -20, 7370112.81) @ affine.Affine.rotation(5)
    rng = np.random.default_rng(2)
    image_xy = rng.uniform(0, 350, (8, 2))
    map_xy = np.column_stack(transform @ (image_xy[:, 0], image_xy[:, 1]))
    model = transforms.fit_polynomial(image_xy, map_xy, 1)
    expected_transform, expected_shape = gdal_suggested_grid(
        (351, 369), gcps=np.column_stack([image_xy, map_xy]))
    got_transform, got_shape = suggested_grid((351, 369), model)
    assert got_shape == expected_shape
    np.testing.assert_allclose(tuple(got_transform)[:6], tuple(expected_transform)[:6],
                               rtol=0, atol=1e-6)


def test_resolution_and_target_aligned_pixels():
    from rasterio.warp import aligned_target
    transform = affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0) @ affine.Affine.rotation(7)
    natural, (rows, cols) = suggested_grid((300, 400), transform)
    # -tr keeps the extent's top-left corner and cuts it into whole pixels, rounded
    grid, shape = suggested_grid((300, 400), transform, resolution=(20, 30))
    assert (grid.a, grid.e, grid.c, grid.f) == (20, -30, natural.c, natural.f)
    assert shape == (round(rows * natural.a / 30), round(cols * natural.a / 20))
    # -tap: edges on multiples of the resolution, the whole extent inside
    aligned, (a_rows, a_cols) = suggested_grid((300, 400), transform, resolution=20, tap=True)
    assert aligned.c % 20 == 0 and aligned.f % 20 == 0
    assert aligned.c <= natural.c and aligned.f >= natural.f
    assert aligned.c + 20 * a_cols >= natural.c + natural.a * cols
    assert aligned.f - 20 * a_rows <= natural.f - natural.a * rows
    # rasterio's -tap (its aligned_target) agrees
    reference, width, height = aligned_target(natural, cols, rows, 20)
    assert (tuple(reference)[:6], height, width) == (tuple(aligned)[:6], a_rows, a_cols)


@pytest.mark.parametrize("resolution", [0, -20, (20, 0), np.nan, "20 m", (20, 20, 20)])
def test_resolution_must_be_positive(resolution):
    with pytest.raises(ValueError, match="resolution must be one or two finite numbers above 0"):
        suggested_grid((10, 10), affine.Affine.identity(), resolution=resolution)


def test_suggested_grid_refuses_tap_without_resolution_and_flat_mappings():
    with pytest.raises(ValueError, match="tap=True needs a resolution"):
        suggested_grid((10, 10), affine.Affine.identity(), tap=True)
    with pytest.raises(ValueError, match="onto a point or a line"):
        suggested_grid((10, 10), lambda points: np.zeros_like(points))
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        suggested_grid((10, 10), lambda points: points[:, 0])


# -- GDAL's "average" ---------------------------------------------------------------

from rsgeo.resample import WARP_METHODS  # noqa: E402

AVERAGED_GRIDS = dict(DOWNSAMPLED_GRIDS, **{
    "beyond the edge": (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                        @ affine.Affine.rotation(7) @ affine.Affine.scale(4.3), (90, 110)),
    "upsampled": (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                  @ affine.Affine.rotation(7) @ affine.Affine.scale(0.7), (300, 400)),
})


@pytest.mark.parametrize("grid", AVERAGED_GRIDS)
@pytest.mark.parametrize("dtype", ["uint8", "int16", "float32"])
def test_average_matches_gdal(grid, dtype):
    dst_transform, shape = AVERAGED_GRIDS[grid]
    image = noise((300, 400), dtype, seed=14)
    scale = grid_scale(~SOURCE_TRANSFORM, shape, dst_transform, image.shape)
    for nodata in (0, None):
        expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape,
                             "average", nodata, scale=scale)
        got = warp(image, ~SOURCE_TRANSFORM, shape, dst_transform, method="average",
                   dst_nodata=nodata)
        assert np.count_nonzero(got != expected) == 0
    # gdalwarp's own scale, without nodata. (Upsampled, gdalwarp cuts this grid into
    # chunks and takes the corners relative to each chunk's source window, which moves
    # their last bits: a few float32 cells and 1 int16 cell in 120 000 differ.)
    if grid != "upsampled":
        expected = gdalwarp_reproject(image, SOURCE_TRANSFORM, dst_transform, shape, "average",
                                      None)
        assert np.count_nonzero(got != expected) == 0


def test_average_through_a_polynomial_matches_gdal():
    # a callable mapping: the cells' corners go through the model, strip by strip
    image, image_xy, map_xy = noise_and_curved_gcps()
    dst_transform = affine.Affine(37.0, 0, 600_400, 0, -37.0, 7_299_600)
    shape = (80, 80)
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    scale = grid_scale(model, shape, dst_transform, image.shape)
    expected = gdal_warp(image, gcp_source(image_xy, map_xy, 2), dst_transform, shape, "average",
                         0, scale=scale)
    got = warp(image, model, shape, dst_transform, method="average", dst_nodata=0, strip_rows=7)
    assert (got != 0).sum() > got.size / 2
    assert np.count_nonzero(got != expected) == 0


def test_average_is_the_block_mean_on_whole_blocks():
    # 4 x 4 blocks of a 40 x 40 image: plain block means, rounded half up, except that
    # GDAL's incremental mean may land a hair below an exact half (x.5 -> x)
    image = noise((40, 40), "int16", seed=15)
    got = warp(image, affine.Affine.scale(4.0), (10, 10), method="average", dst_nodata=None)
    mean = image.astype(float).reshape(10, 4, 10, 4).mean(axis=(1, 3))
    half = mean - np.floor(mean) == 0.5
    np.testing.assert_array_equal(got[~half], np.floor(mean + 0.5)[~half])
    assert np.isin(got[half] - np.floor(mean[half]), [0, 1]).all()
    assert "average" in WARP_METHODS and "average" not in METHODS
    with pytest.raises(ValueError, match="unknown method 'average'"):
        interpolate(image, [1.0], [1.0], "average")


# -- the exercises' checks for the output grid --------------------------------------

from rsgeo_course import exercises  # noqa: E402

TILTED = (affine.Affine.translation(770596.79, 7370112.81) @ affine.Affine.rotation(-8)
          @ affine.Affine.scale(20.0, -25.0))
HRC_TRANSFORM = affine.Affine(2.5, 0, 770595.0, 0, -2.5, 7370115.0)


def _pixel_size_by_hand(kind="right"):
    rows, cols = 351, 369
    (x0, x1), (y0, y1) = TILTED @ (np.array([0.0, cols]), np.array([0.0, rows]))
    diagonal = np.hypot(x1 - x0, y1 - y0)
    return {"right": diagonal / np.hypot(rows, cols), "width": 20.0, "height": 25.0,
            "mean": 22.5, "sum": diagonal / (rows + cols),
            "inverse": np.hypot(rows, cols) / diagonal}[kind]


@pytest.mark.parametrize("kind, hint", [("width", "pixel width alone"),
                                        ("height", "pixel height alone"),
                                        ("mean", "mean of width and height"),
                                        ("sum", "not rows + cols"), ("inverse", "Upside down")])
def test_pixel_size_check_recognises_mistakes(kind, hint):
    right = exercises.check_output_pixel_size(_pixel_size_by_hand(), (351, 369), TILTED)
    assert right.ok, right
    verdict = exercises.check_output_pixel_size(_pixel_size_by_hand(kind), (351, 369), TILTED)
    assert not verdict.ok and hint in verdict.hint
    expected = f"{_pixel_size_by_hand():.4g}"
    assert expected not in repr(verdict)
    with pytest.raises(exercises.ExerciseNotSolved):
        exercises.check_output_pixel_size(..., (351, 369), TILTED)
    assert "not a number" in repr(exercises.check_output_pixel_size({}, (351, 369), TILTED))


@pytest.mark.parametrize("answer, hint", [
    ((770595.0, 7370115.0, 352, 370), "footprint's own edges"),
    ((770600.0, 7370100.0, 352, 370), "Outwards"),
    ((770580.0, 7370120.0, 351, 369), "size without -tap"),
    ((770580.0, 7370120.0, 370, 352), "Rows come first"),
])
def test_grid_extent_check_recognises_mistakes(answer, hint):
    shape = (2810, 2954)
    right = exercises.check_grid_extent((770580.0, 7370120.0, 352, 370), shape, HRC_TRANSFORM, 20)
    assert right.ok, right
    verdict = exercises.check_grid_extent(answer, shape, HRC_TRANSFORM, 20)
    assert not verdict.ok and hint in verdict.hint
    assert "770580" not in repr(verdict) and "7370120" not in repr(verdict)
    assert "four numbers" in repr(exercises.check_grid_extent((1, 2), shape, HRC_TRANSFORM, 20))
    assert "four numbers" in repr(exercises.check_grid_extent("west", shape, HRC_TRANSFORM, 20))
    with pytest.raises(exercises.ExerciseNotSolved):
        exercises.check_grid_extent(..., shape, HRC_TRANSFORM, 20)
    with pytest.raises(ValueError, match="resolution must be"):
        exercises.check_grid_extent(answer, shape, HRC_TRANSFORM, 0)


# -- the reference: which GDAL, which path ----------------------------------------
# Every bit-for-bit test above and below compares with GDAL 3.10.3, the one inside the locked
# rasterio 1.4.4 wheel, through a VRTWarpedDataset with GDAL's exact transformer (gdal_warp):
# `gdalwarp -et 0`. A destination nodata there sends GDAL through GWKRealCase (bilinear
# GWKBilinearResample4Sample, cubic GWKCubicResample4Sample); without one, Byte, Int16, UInt16
# and Float32 go through the no-mask kernels (GWKBilinearResampleNoMasks4SampleT,
# GWKCubicResampleNoMasks4SampleT). gdalwarp_reproject is gdalwarp's default path instead
# (approximate transformer, chunked, the scale per chunk).

import rasterio  # noqa: E402

from gdal_reference import gdalwarp_reproject as _default_gdalwarp  # noqa: E402


def test_the_reference_is_the_locked_gdal():
    # the claims of tests/test_resample.py, the README and chapter 4 were measured with this
    # GDAL; another one (a new lock) must be checked again before they are repeated
    assert rasterio.__gdal_version__ == "3.10.3"


TIE_GRID = (affine.Affine(4.0, 0, 500_000.0, 0, -4.0, 7_400_000.0), (500, 750))


def composed_positions(shape, dst_transform):
    """Source positions from the composed affine map, as rsgeo computed them before."""
    a, b, c, d, e, f = (~SOURCE_TRANSFORM @ dst_transform)[:6]
    x = np.arange(shape[1]) + 0.5
    y = (np.arange(shape[0]) + 0.5)[:, np.newaxis]
    return a * x + (b * y + c), d * x + (e * y + f)


@pytest.mark.parametrize("method", ["bilinear", "cubic"])
@pytest.mark.parametrize("nodata", [0, None])
@pytest.mark.parametrize("dtype", ["uint8", "int16", "uint16", "int32", "float32", "float64"])
def test_an_enlargement_by_2_5_matches_gdal_on_every_tie(method, nodata, dtype):
    # North-up 10 m -> 4 m (scale 2.5): many values fall exactly half-way between two
    # integers, where the last bit of a position and the order of the kernel's operations
    # decide the rounding. GDAL takes each output centre to the map and back through the two
    # geotransforms (c + col * a + row * b, twice), and its general path (a destination nodata,
    # or a type without a no-mask kernel) adds the four weighted pixels in another order than
    # its no-mask bilinear. rsgeo did neither before: 1.2 % of the bilinear pixels differed.
    image = noise((200, 300), dtype, seed=0)
    dst_transform, shape = TIE_GRID
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method,
                         nodata)
    got = warp(image, ~SOURCE_TRANSFORM, shape, dst_transform, method=method, dst_nodata=nodata)
    assert np.count_nonzero(got != expected) == 0


def test_the_enlargement_by_2_5_is_a_case_of_ties():
    # the test above can fail: composed positions, or the other path's kernel, round
    # differently on more than 1 % of the bilinear pixels
    image = noise((200, 300), seed=0)
    dst_transform, shape = TIE_GRID
    for nodata in (0, None):
        expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape,
                             "bilinear", nodata)
        cols, rows = composed_positions(shape, dst_transform)
        composed = interpolate(image, cols, rows, "bilinear", nodata=nodata)
        assert np.count_nonzero(composed != expected) > 0.01 * image.size
    x, y = grid_positions(shape, dst_transform)
    cols, rows = ~SOURCE_TRANSFORM @ (x, y)
    plain = interpolate(image, cols, rows, "bilinear", nodata=None)       # no-mask kernel
    general = interpolate(image, cols, rows, "bilinear", nodata=0)        # GWKRealCase
    differ = np.count_nonzero(plain != general)
    assert differ > 0 and (np.abs(plain.astype(int) - general) <= 1).all()


@pytest.mark.parametrize("nodata", [0, None])
def test_gdalwarp_s_default_transformer_rounds_some_ties_the_other_way(nodata):
    # gdalwarp's default (and rasterio's reproject, always) interpolates the positions along
    # each row (GDALApproxTransform, 0.125 pixel): exact in real numbers for an affine map, not
    # in the last bits. rsgeo follows the exact transformer; the two differ only on .5 ties.
    image = noise((200, 300), seed=0)
    dst_transform, shape = TIE_GRID
    got = warp(image, ~SOURCE_TRANSFORM, shape, dst_transform, method="bilinear",
               dst_nodata=nodata)
    default = _default_gdalwarp(image, SOURCE_TRANSFORM, dst_transform, shape, "bilinear", nodata)
    exact = warp(image.astype(np.float64), ~SOURCE_TRANSFORM, shape, dst_transform,
                 method="bilinear", dst_nodata=None)
    differ = got != default
    assert 0.001 * got.size < np.count_nonzero(differ) < 0.01 * got.size
    assert (np.abs(got.astype(int) - default) <= 1).all()
    np.testing.assert_allclose(exact[differ] % 1, 0.5, atol=1e-9)


@pytest.mark.parametrize("method", ["bilinear", "cubic"])
def test_gdalwarp_widens_its_kernels_per_chunk_on_a_rotated_footprint(method):
    # A source rotated 13 degrees warped onto its own footprint grid at the same pixel size.
    # rsgeo's one scale for the grid is above 1 (plain kernels), as a VRT of GDAL's gives; but
    # gdalwarp splits the grid into chunks, and the bounding box of a chunk's source window is
    # cos + sin = 1.2 times wider than the chunk: scale 0.83 < 0.95, widened (blurred) kernels.
    # With -wo XSCALE=1 -wo YSCALE=1 gdalwarp agrees with rsgeo pixel for pixel.
    from rsgeo.resample import suggested_grid

    image = noise((400, 500), seed=1)
    rotated = SOURCE_TRANSFORM @ affine.Affine.rotation(13)
    dst_transform, shape = suggested_grid(image.shape, rotated, resolution=10.0)
    assert min(grid_scale(~rotated, shape, dst_transform, image.shape)) > 1
    got = warp(image, ~rotated, shape, dst_transform, method=method, dst_nodata=0)
    valid = got != 0
    vrt = gdal_warp(image, affine_source(rotated), dst_transform, shape, method, 0)
    assert np.count_nonzero(got != vrt) == 0
    default = _default_gdalwarp(image, rotated, dst_transform, shape, method, 0)
    assert np.count_nonzero(got[valid] != default[valid]) > 0.5 * valid.sum()
    fixed = _default_gdalwarp(image, rotated, dst_transform, shape, method, 0, XSCALE="1",
                              YSCALE="1")
    assert np.count_nonzero(got != fixed) == 0


# -- 64-bit images, a source nodata, clear errors, big outputs ------

from rsgeo.errors import GridError, ImageError  # noqa: E402
from rsgeo.validation import as_affine, as_output_shape  # noqa: E402

# a rotated (7°), enlarged (10 m to 4.1 m) output grid, warped with GDAL's exact transformer
_ROTATED = (affine.Affine.translation(500_003.0, 7_399_997.0) @ affine.Affine.rotation(7)
            @ affine.Affine.scale(4.1, -4.1))


@pytest.mark.parametrize("dtype, low, high", [("int64", -2**53, 2**53), ("uint64", 0, 2**53),
                                              ("int64", -5, 1000), ("uint64", 0, 1000)])
@pytest.mark.parametrize("method", ["bilinear", "cubic"])
def test_64_bit_step_edges_are_clamped_as_gdal_does(dtype, low, high, method):
    # uint64 cubic undershoots wrapped to 2**64 - 1 (no clamp at itemsize 8);
    # GDAL 3.10.3 clamps to the dtype's range after floor(v + 0.5)
    image = np.full((24, 24), low, dtype)
    image[:, 12:] = high
    image[5:9, 3:7] = high
    for nodata in (None, 7):
        expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), _ROTATED, (60, 60), method,
                             nodata, plain_kernels=True)
        got = warp(image, ~SOURCE_TRANSFORM, (60, 60), _ROTATED, method=method, dst_nodata=nodata,
                   scale=1)
        np.testing.assert_array_equal(got, expected)
    assert got.min() >= low if dtype == "uint64" else True


def test_uint64_cubic_undershoot_is_zero_not_a_wrapped_maximum():
    image = np.zeros((8, 8), np.uint64)
    image[:, 4:] = 100
    cols = np.linspace(0.0, 8.0, 33)[:-1]
    out = interpolate(image, cols, np.full_like(cols, 4.0), "cubic", nodata=None)
    signed = interpolate(image.astype(np.int64), cols, np.full_like(cols, 4.0), "cubic",
                         nodata=None)
    np.testing.assert_array_equal(out, np.clip(signed, 0, None).astype(np.uint64))


@pytest.mark.parametrize("value", [2**53 + 1, -(2**53) - 1])
@pytest.mark.parametrize("method", ["bilinear", "cubic", "average"])
def test_64_bit_values_float64_cannot_hold_are_refused(value, method):
    # float64 holds integers exactly only up to 2**53: 2**53 + 1 would come out as 2**53
    # (GDAL 3.10.3 gives 2**53 without a word, even for nearest)
    image = np.full((4, 4), value, np.int64)
    with pytest.raises(ImageError, match=r"beyond \+-2\*\*53.*nearest"):
        warp(image, affine.Affine.identity(), (4, 4), method=method)
    if method != "average":
        with pytest.raises(ImageError, match="float64"):
            interpolate(image, [1.0], [1.0], method)


def test_nearest_copies_64_bit_values_exactly():
    image = np.full((4, 4), 2**53 + 1, np.int64)
    assert interpolate(image, [1.5], [1.5], "nearest")[0] == 2**53 + 1
    big = np.full((4, 4), 2**64 - 1, np.uint64)
    assert warp(big, affine.Affine.identity(), (4, 4))[2, 2] == 2**64 - 1


def _holed(dtype, bands, hole, seed):
    rng = np.random.default_rng(seed)
    image = rng.integers(1, 250, (bands, 24, 24)).astype(dtype)
    image[rng.random(image.shape) < 0.15] = hole
    return image if bands > 1 else image[0]


@pytest.mark.parametrize("method", WARP_METHODS)
@pytest.mark.parametrize("dtype, hole", [("uint8", 0), ("float32", 0.0), ("float32", np.nan)])
@pytest.mark.parametrize("bands", [1, 2])
def test_src_nodata_matches_gdal_srcnodata(method, dtype, hole, bands):
    # GDAL 3.10.3, VRT warp with the exact transformer and <SrcNoDataReal>: one band's nodata
    # pixels are invalid; bilinear renormalises over the valid ones, cubic falls back to that
    # bilinear, average leaves them out, and a pixel invalid in every band is nodata
    image = _holed(dtype, bands, hole, seed=bands)
    for nodata in (255, None):
        expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), _ROTATED, (60, 60), method,
                             nodata, plain_kernels=method != "average", src_nodata=float(hole))
        got = warp(image, ~SOURCE_TRANSFORM, (60, 60), _ROTATED, method=method, dst_nodata=nodata,
                   scale=1 if method != "average" else None, src_nodata=hole)
        np.testing.assert_array_equal(got, expected)


def test_src_nodata_stops_nan_spreading():
    image = np.full((8, 8), 10.0, np.float32)
    image[4, 4] = np.nan
    cols, rows = np.meshgrid(np.arange(8) + 0.3, np.arange(8) + 0.3)
    for method, spread in (("bilinear", 4), ("cubic", 16)):
        plain = interpolate(image, cols, rows, method, nodata=-1.0)
        assert np.isnan(plain).sum() == spread    # GDAL's behaviour without a source nodata
        held = interpolate(image, cols, rows, method, nodata=-1.0, src_nodata=np.nan)
        assert not np.isnan(held).any()
        assert (held == -1.0).sum() == 1           # only the pixel inside the NaN one
        np.testing.assert_array_equal(held[held != -1.0], 10.0)


@pytest.mark.parametrize("src_nodata, message", [(300, "does not fit dtype uint8"),
                                                 (np.nan, "does not fit dtype uint8")])
def test_src_nodata_must_fit_the_dtype(src_nodata, message):
    with pytest.raises(ImageError, match=message):
        interpolate(np.zeros((4, 4), np.uint8), [1.0], [1.0], src_nodata=src_nodata)


def test_src_nodata_with_widened_kernels_is_refused_with_the_fix():
    with pytest.raises(ValueError, match="scale=1.*average"):
        interpolate(np.ones((8, 8), np.uint8), [1.0], [1.0], "bilinear", scale=0.5,
                    src_nodata=0)


@pytest.mark.parametrize("strip_rows, error, message", [
    (0, ValueError, r"strip_rows must be >= 1"), (-3, ValueError, r"strip_rows must be >= 1"),
    (2.5, ValueError, "whole number"), ("8", TypeError, "must be a number")])
def test_strip_rows_must_be_a_positive_integer(strip_rows, error, message):
    with pytest.raises(error, match=message):
        warp(np.ones((4, 4), np.uint8), lambda xy: xy, (4, 4), strip_rows=strip_rows)


@pytest.mark.parametrize("mapping, message", [
    (None, "callable model.*got NoneType"), (np.eye(3), "callable model.*got ndarray"),
    ((1.0, 0.0, 0.0, 0.0, 1.0, 0.0), r"from_gdal")])
def test_a_mapping_that_is_not_a_model_is_a_type_error(mapping, message):
    with pytest.raises(TypeError, match=message):
        warp(np.ones((4, 4), np.uint8), mapping, (4, 4))


def test_transform_must_be_a_finite_affine():
    image = np.ones((4, 4), np.uint8)
    with pytest.raises(TypeError, match=r"transform must be an affine.Affine.*from_gdal"):
        warp(image, lambda xy: xy, (4, 4), dst_transform=(0.0, 1.0, 0.0, 4.0, 0.0, -1.0))
    with pytest.raises(GridError, match="transform holds NaN"):
        warp(image, lambda xy: xy, (4, 4), dst_transform=affine.Affine(np.nan, 0, 0, 0, -1, 4))
    with pytest.raises(GridError, match="mapping holds NaN"):
        warp(image, affine.Affine(np.nan, 0, 0, 0, 1, 0), (4, 4))
    assert as_affine(affine.Affine.identity()) == affine.Affine.identity()


def test_an_output_too_big_for_memory_is_refused_before_allocating():
    with pytest.raises(GridError, match=r"GiB.*coarser resolution.*window"):
        warp(np.ones((4, 4), np.uint8), affine.Affine.identity(), (10**6, 10**6))
    with pytest.raises(GridError, match=r"8.0 GiB, more than the 1.0 GiB"):
        as_output_shape((2**15, 2**15), np.float32, bands=2, limit=2**30)
    assert as_output_shape((2**15, 2**15), np.float32, limit=2**32) == (2**15, 2**15)


@pytest.mark.parametrize("dtype", [np.float16, ">f4", ">u2"])
def test_float16_and_big_endian_are_converted_once_not_per_strip(dtype, monkeypatch):

    image = noise((20, 20), "float32" if np.dtype(dtype).kind == "f" else "uint16",
                  seed=3).astype(dtype)
    seen = []
    original = resampling.resample_pixels

    def spy(bands, *args, **kwargs):
        seen.append(bands.dtype)
        return original(bands, *args, **kwargs)

    monkeypatch.setattr(_warp, "resample_pixels", spy)
    out = warp(image, lambda xy: xy + 0.25, (20, 20), method="bilinear", strip_rows=4)
    assert len(seen) == 5 and all(d.isnative and d != np.float16 for d in seen)
    assert out.dtype == np.dtype(dtype)
    native = warp(image.astype(np.dtype(dtype).newbyteorder("=") if np.dtype(dtype) != np.float16
                               else np.float32), lambda xy: xy + 0.25, (20, 20),
                  method="bilinear")
    np.testing.assert_array_equal(out, native.astype(dtype))


@pytest.mark.parametrize("cols", [[1.0 + 1.0j], ["1.0"], [True]])
def test_positions_that_are_not_real_numbers_are_a_type_error(cols):
    # complex positions were silently made real (NumPy drops the imaginary part)
    with pytest.raises(TypeError, match=r"cols must be real numbers"):
        interpolate(np.ones((4, 4), np.uint8), cols, [1.0])
