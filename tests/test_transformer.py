"""rsgeo._kernels.transformer: models evaluated inside the warp kernels, exactly and as GDAL
approximates.

The references: GDAL's exact GCP transformer and its approximate transformer
(``GDALApproxTransform``, gdalwarp's default ``-et 0.125``) through a VRT
(tests/gdal_reference.py), pixel for pixel; and the models' own ``__call__``.
"""

import affine
import numpy as np
import pytest
from test_resample import SOURCE_TRANSFORM, noise, noise_and_curved_gcps
from test_thin_plate import warp_case

from rsgeo import transforms
from rsgeo._kernels import transformer
from rsgeo.errors import RsgeoError
from rsgeo.resample import METHODS, grid_positions, warp

from gdal_reference import affine_source, gcp_source, gdal_warp
from gdal_tps_reference import tps_source

pytestmark = pytest.mark.gdal

DST_TRANSFORM = affine.Affine(7.0, 0, 600_400, 0, -7.0, 7_299_600)
SHAPE = (400, 400)


def strongly_curved_gcps(order):
    """GCPs of a mapping curved enough that GDAL's approximation splits most rows."""
    image, image_xy, map_xy = noise_and_curved_gcps()
    rng = np.random.default_rng(order)
    image_xy = rng.uniform(0, 320, (30, 2))
    u, v = image_xy[:, 0] - 160, image_xy[:, 1] - 160
    map_xy = np.column_stack([
        600_000 + 10 * image_xy[:, 0] + 0.4 * image_xy[:, 1] + 0.02 * u * v + 1e-4 * u**3,
        7_300_000 - 10 * image_xy[:, 1] + 0.5 * image_xy[:, 0] + 0.03 * u * u])
    return image, image_xy, map_xy


@pytest.mark.parametrize("order", [1, 2, 3])
def test_kernel_positions_are_the_model_s_own(order):
    _, image_xy, map_xy = strongly_curved_gcps(order)
    model = transforms.fit_polynomial(map_xy, image_xy, order)
    cols, rows = transformer.positions(transformer.pack(model, DST_TRANSFORM), SHAPE)
    x, y = grid_positions(SHAPE, DST_TRANSFORM)
    expected = model(np.column_stack([x.ravel(), y.ravel()]))
    # the same compiled evaluation: equal, not close
    assert np.array_equal(cols.ravel(), expected[:, 0])
    assert np.array_equal(rows.ravel(), expected[:, 1])


@pytest.mark.parametrize("kind", ["linear", "helmert", "projective"])
def test_matrix_models_in_the_kernel_equal_their_numpy_evaluation(kind):
    image, image_xy, map_xy = noise_and_curved_gcps()
    model = transforms.fit_transform(map_xy, image_xy, kind)
    got = warp(image, model, SHAPE, DST_TRANSFORM, method="bilinear")
    # a plain function is evaluated in NumPy, strip by strip: the reference path
    expected = warp(image, lambda points: model(points), SHAPE, DST_TRANSFORM, method="bilinear")
    assert np.count_nonzero(got != expected) == 0


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("order", [1, 2, 3])
@pytest.mark.parametrize("max_error", [0.125, 1.0])
def test_approximated_warp_matches_gdal_s_approximate_transformer(method, order, max_error):
    image, image_xy, map_xy = strongly_curved_gcps(order)
    model = transforms.fit_polynomial(map_xy, image_xy, order)
    # one VRT block for the whole grid: GDAL approximates each row over the grid's width
    expected = gdal_warp(image, gcp_source(image_xy, map_xy, order), DST_TRANSFORM, SHAPE,
                         method, 0, plain_kernels=True, block=SHAPE[1], max_error=max_error)
    got = warp(image, model, SHAPE, DST_TRANSFORM, method=method, dst_nodata=0, scale=1.0,
               error_threshold=max_error)
    assert np.count_nonzero(got != expected) == 0
    exact = warp(image, model, SHAPE, DST_TRANSFORM, method=method, dst_nodata=0, scale=1.0)
    # and the approximation did something: GDAL's own warps differ too
    if order > 1:
        assert np.count_nonzero(exact != expected) > 0


def test_approximated_affine_warp_matches_gdal():
    image = noise((300, 400))
    dst_transform = (SOURCE_TRANSFORM @ affine.Affine.translation(-20.3, -15.7)
                     @ affine.Affine.rotation(7) @ affine.Affine.scale(0.9))
    shape = (380, 450)
    expected = gdal_warp(image, affine_source(SOURCE_TRANSFORM), dst_transform, shape,
                         "bilinear", 0, plain_kernels=True, block=shape[1], max_error=0.125)
    got = warp(image, ~SOURCE_TRANSFORM, shape, dst_transform, method="bilinear", scale=1.0,
               error_threshold=0.125)
    assert np.count_nonzero(got != expected) == 0


def test_approximated_positions_stay_near_the_threshold():
    _, image_xy, map_xy = strongly_curved_gcps(3)
    model = transforms.fit_polynomial(map_xy, image_xy, 3)
    exact = transformer.positions(transformer.pack(model, DST_TRANSFORM), SHAPE)
    approximated = transformer.positions(
        transformer.pack(model, DST_TRANSFORM, error_threshold=0.125), SHAPE)
    error = np.abs(exact[0] - approximated[0]) + np.abs(exact[1] - approximated[1])
    # GDAL tests the error at each segment's middle only, so elsewhere it may exceed the
    # threshold a little (a quarter-pixel at most on a curve this smooth); most positions moved
    assert error.max() < 0.25
    assert np.count_nonzero(error) > error.size // 2


def test_short_rows_are_exact_as_in_gdal():
    _, image_xy, map_xy = strongly_curved_gcps(2)
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    shape = (3, 5)
    exact = transformer.positions(transformer.pack(model, DST_TRANSFORM), shape)
    approximated = transformer.positions(
        transformer.pack(model, DST_TRANSFORM, error_threshold=10.0), shape)
    assert np.array_equal(exact[0], approximated[0])


@pytest.mark.parametrize("method", METHODS)
def test_a_source_window_gives_the_same_pixels(method):
    image, image_xy, map_xy = noise_and_curved_gcps()
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    whole = warp(image, model, SHAPE, DST_TRANSFORM, method=method, scale=1.0)
    # the output's top-left quarter and the source pixels it reads (cubic: 2 more each side)
    cols, rows = transformer.positions(transformer.pack(model, DST_TRANSFORM), (200, 200))
    left, top = int(max(cols.min() - 3, 0)), int(max(rows.min() - 3, 0))
    right, bottom = int(min(cols.max() + 3, 320)), int(min(rows.max() + 3, 320))
    assert (left, top) != (0, 0) and (right, bottom) != (320, 320)   # a real window
    got = warp(image[top:bottom, left:right], model, (200, 200), DST_TRANSFORM, method=method,
               scale=1.0, src_offset=(left, top))
    assert np.count_nonzero(got != whole[:200, :200]) == 0


def test_error_threshold_needs_a_compiled_mapping():
    image, image_xy, map_xy = noise_and_curved_gcps()
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    with pytest.raises(RsgeoError, match="Python function"):
        warp(image, lambda points: model(points), SHAPE, DST_TRANSFORM, error_threshold=0.125)
    with pytest.raises(RsgeoError, match="error_threshold"):
        warp(image, model, SHAPE, DST_TRANSFORM, error_threshold=-1)


def test_src_offset_needs_a_scale_and_whole_numbers():
    image, image_xy, map_xy = noise_and_curved_gcps()
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    with pytest.raises(RsgeoError, match="scale"):
        warp(image, model, SHAPE, DST_TRANSFORM, src_offset=(1, 2))
    with pytest.raises((RsgeoError, TypeError)):
        warp(image, model, SHAPE, DST_TRANSFORM, src_offset=(1.5, 2), scale=1.0)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("n_gcps", [14, 200])
def test_approximated_tps_warp_matches_gdal_s_approximate_transformer(method, n_gcps):
    image, image_xy, map_xy, dst_transform = warp_case(n_gcps, 3)
    # gdalwarp -tps: the image -> map spline, inverted at every output cell
    model = transforms.fit_transform(image_xy, map_xy, "tps").inverse()
    expected = gdal_warp(image, tps_source(image_xy, map_xy), dst_transform, SHAPE, method, 0,
                         plain_kernels=True, block=SHAPE[1], max_error=0.125)
    got = warp(image, model, SHAPE, dst_transform, method=method, dst_nodata=0, scale=1.0,
               error_threshold=0.125)
    assert np.count_nonzero(got != expected) == 0
