"""rsgeo.resample against GDAL, bit for bit, plus properties and errors."""

import affine
import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gdal_reference import affine_source, gcp_source, gdal_warp
from rsgeo import gcp
from rsgeo.resample import METHODS, grid_positions, interpolate, keys_weights, warp

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
    # A rotation of 7° and a slight zoom in (scale 1/0.9): GDAL keeps its plain 2x2 and 4x4 kernels.
    image = noise((300, 400), dtype)
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                     @ affine.Affine.rotation(7) @ affine.Affine.scale(0.9))
    shape = (380, 450)
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape, method, 0)
    x, y = grid_positions(shape, dst_transform)
    cols, rows = ~SOURCE_TRANSFORM @ (x, y)
    got = interpolate(image, cols, rows, method, nodata=0)
    assert got.dtype == expected.dtype
    if dtype == "float32" and method != "nearest":
        # GDAL's float path orders a few operations differently: about 1 pixel in 8000
        # differs by one unit in the last place of float32; integer outputs are exact.
        np.testing.assert_array_max_ulp(got, expected, maxulp=1)
        assert np.count_nonzero(got != expected) < got.size / 2000
    else:
        assert np.count_nonzero(got != expected) == 0
    # the same footprint: GDAL's AvoidNoData keeps valid pixels off the nodata value too
    inside = (cols >= 0) & (cols < 400) & (rows >= 0) & (rows < 300)
    assert np.array_equal(expected != 0, inside) or method == "nearest"


@pytest.mark.parametrize("method", METHODS)
def test_polynomial_warp_matches_gdal_bit_for_bit(method):
    rng = np.random.default_rng(3)
    image = noise((320, 320), seed=3)
    image_xy = rng.uniform(0, 320, (12, 2))
    u, v = image_xy[:, 0] - 160, image_xy[:, 1] - 160
    map_xy = np.column_stack([600_000 + 10 * image_xy[:, 0] + 0.4 * image_xy[:, 1] + 0.002 * u * v,
                              7_300_000 - 10 * image_xy[:, 1] + 0.5 * image_xy[:, 0] + 0.003 * u * u])
    # 7 m output pixels over 10 m input pixels: an up-sampling, where GDAL keeps the plain
    # kernels (at 9.5 m the shear makes its chunk scale fall below 0.95 and it widens them)
    dst_transform = affine.Affine(7.0, 0, 600_400, 0, -7.0, 7_299_600)
    shape = (400, 400)
    expected = gdal_warp(image, gcp_source(image_xy, map_xy, 2), dst_transform, shape, method, 0)
    model = gcp.fit_polynomial(map_xy, image_xy, 2)
    got = warp(image, model, shape, dst_transform, method=method, nodata=0)
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
       st.lists(st.floats(0, 20), min_size=1, max_size=30), st.lists(st.floats(0, 15), min_size=1, max_size=30))
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
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-0.1, 0.1), st.floats(-0.1, 0.1), st.floats(-0.1, 0.1))
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
    # right: map -> image, the inverse of the raster's geotransform; the same grid gives the image back
    assert np.array_equal(warp(image, ~SOURCE_TRANSFORM, shape, SOURCE_TRANSFORM), image)
    # wrong: the raster's own transform, pixel -> map
    with pytest.raises(ValueError, match=r"no output cell lands inside the source image: is your "
                                         r"mapping map → image \(u = f\(x, y\)\)\?.*~raster.transform"):
        warp(image, SOURCE_TRANSFORM, shape, SOURCE_TRANSFORM)


def test_a_model_fitted_image_to_map_is_an_error():
    image = noise((300, 400))
    rng = np.random.default_rng(5)
    image_xy = rng.uniform(0, 300, (8, 2))
    map_xy = np.column_stack(SOURCE_TRANSFORM @ (image_xy[:, 0], image_xy[:, 1]))
    right = gcp.fit_polynomial(map_xy, image_xy, 1)
    wrong = gcp.fit_polynomial(image_xy, map_xy, 1)
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


@pytest.mark.parametrize("shape", [351, 351.0, (351,), (2, 2, 2), ("a", 2), (2.5, 3), (0, 2), None])
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
    got = warp(image, mapping, shape, method=method, nodata=7)
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
