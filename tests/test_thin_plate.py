"""rsgeo._kernels.thin_plate: GDAL's thin-plate spline, solved and evaluated as GDAL does, bit
for bit.

GDAL (3.10, through rasterio) is the reference for the values, SciPy's RBFInterpolator an
independent check of the maths, and gdalwarp through a VRT with GDAL's TPS transformer the
reference for warps.
"""

from pathlib import Path

import affine
import numpy as np
import pytest
from numba import njit
from scipy.interpolate import RBFInterpolator

from rsgeo import data, transforms
from rsgeo._kernels import thin_plate
from rsgeo.errors import GCPError, ModelError
from rsgeo.resample import warp

from gcp_samples import utm_gcps
from gdal_reference import gdal_warp
from gdal_tps_reference import gdal_spline, gdal_spline_inverse, tps_source

pytestmark = pytest.mark.gdal


def cbers():
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    return gcps.image_xy, gcps.map_xy


def inside(points, n, seed=1):
    """n random points in the bounding box of ``points``."""
    rng = np.random.default_rng(seed)
    low, high = points.min(axis=0), points.max(axis=0)
    return low + rng.random((n, 2)) * (high - low)


def evaluate(packed, points):
    out = np.empty_like(points)
    thin_plate.evaluate_many(packed, np.ascontiguousarray(points), out)
    return out


# 14 GCPs (the CBERS scene's), 200 and 2,000 random ones (GDAL autotest's precision case has
# 2,115): both directions of each, solved once for the module
SIZES = {"cbers14": cbers, "random200": lambda: utm_gcps(200, 7),
         "random2000": lambda: utm_gcps(2000, 8)}


# the 2,000-GCP splines take most of this module's time: the fast suite leaves them out
@pytest.fixture(scope="module", params=[pytest.param(name, marks=pytest.mark.slow)
                                        if name == "random2000" else name for name in SIZES])
def splines(request):
    image_xy, map_xy = SIZES[request.param]()
    return image_xy, map_xy, thin_plate.solve(image_xy, map_xy), thin_plate.solve(map_xy, image_xy)


def test_the_spline_passes_through_every_gcp(splines):
    image_xy, map_xy, forward, reverse = splines
    n = len(image_xy)
    # exact in exact arithmetic; what is left is the rounding of GDAL's sums (and of its faster
    # logarithm), which grows with the number of GCPs
    limit = 1e-9 if n < 100 else 1e-6
    assert np.abs(evaluate(reverse, map_xy) - image_xy).max() < limit        # pixels
    assert np.abs(evaluate(forward, image_xy) - map_xy).max() < limit * 20   # metres, 20 m/px


def test_the_spline_is_scipys_thin_plate_spline(splines):
    # an independent check of the maths: SciPy's RBFInterpolator with r² log r and a degree-1
    # polynomial is the same spline (its weights are twice GDAL's, its kernel half)
    image_xy, map_xy, forward, reverse = splines
    for src, dst, packed in ((map_xy, image_xy, reverse), (image_xy, map_xy, forward)):
        points = np.vstack([src, inside(src, 1000)])
        expected = RBFInterpolator(src, dst, kernel="thin_plate_spline", degree=1)(points)
        extent = np.ptp(dst, axis=0).max()
        assert np.abs(evaluate(packed, points) - expected).max() < 1e-9 * extent


def test_the_spline_is_gdals_to_the_last_bit(splines):
    image_xy, map_xy, forward, reverse = splines
    map_points = np.vstack([map_xy, inside(map_xy, 3000)])
    image_points = np.vstack([image_xy, inside(image_xy, 3000, seed=2)])
    # GDAL's spline map -> image: what rasterio's GCPTransformer(gcps, tps=True).rowcol gives
    got = evaluate(reverse, map_points)
    expected = gdal_spline(map_xy, image_xy, map_points)
    assert np.abs(got - expected).max() < 1e-6
    assert np.array_equal(got, expected)
    # and image -> map
    assert np.array_equal(evaluate(forward, image_points),
                          gdal_spline(image_xy, map_xy, image_points))


def test_the_inversion_is_gdals_map_to_pixel_to_the_last_bit(splines):
    # what gdalwarp -tps computes for each output cell's map point: the spline fitted
    # map -> image as a start, refined by Newton's method on the spline image -> map
    image_xy, map_xy, forward, reverse = splines
    points = np.vstack([map_xy, inside(map_xy, 3000)])
    packed = thin_plate.pack_inverse(forward, reverse)
    got = evaluate(packed, points)
    expected = gdal_spline_inverse(image_xy, map_xy, points)
    assert np.abs(got - expected).max() < 1e-6
    assert np.array_equal(got, expected)
    # it is not the start spline: the two differ between the GCPs
    assert np.abs(got - evaluate(reverse, points)).max() > 1e-3


def test_evaluate_is_callable_from_compiled_code():
    # the warp kernels call evaluate(packed, x, y) one point at a time
    @njit
    def one_by_one(packed, points):
        out = np.empty_like(points)
        for k in range(points.shape[0]):
            out[k, 0], out[k, 1] = thin_plate.evaluate(packed, points[k, 0], points[k, 1])
        return out

    image_xy, map_xy = cbers()
    points = inside(map_xy, 50)
    for packed in (thin_plate.solve(map_xy, image_xy),
                   thin_plate.pack_inverse(thin_plate.solve(image_xy, map_xy),
                                           thin_plate.solve(map_xy, image_xy))):
        assert np.array_equal(one_by_one(packed, points), evaluate(packed, points))


def test_gcps_nearly_on_one_line_are_gdals_one_dimensional_interpolation():
    # GDAL's VIZ_GEOREF_SPLINE_ONE_DIMENSIONAL: r² of x and y above 0.99 (a diagonal strip)
    rng = np.random.default_rng(5)
    t = rng.uniform(0, 1000, 30)
    src = np.column_stack([t, 0.5 * t + rng.normal(0, 5, 30)])
    dst = np.column_stack([2 * t + 7, 3 * t - 4 + rng.normal(0, 5, 30)])
    packed = thin_plate.solve(src, dst)
    assert packed[0] == thin_plate.ONE_DIMENSIONAL
    points = np.vstack([src, rng.uniform(-100, 1100, (500, 2))])
    assert np.array_equal(evaluate(packed, points), gdal_spline(src, dst, points))


def test_degenerate_gcps_are_refused():
    with pytest.raises(GCPError, match="at least 3"):
        thin_plate.solve([[0, 0], [1, 1]], [[0, 0], [1, 1]])
    with pytest.raises(GCPError, match="same x or the same y"):
        thin_plate.solve([[0, 0], [0, 1], [0, 2]], [[0, 0], [1, 1], [2, 2]])
    square = np.array([[0, 0], [10, 0], [0, 10], [10, 10], [10, 10]], dtype=float)
    with pytest.raises(GCPError, match="singular"):
        thin_plate.solve(square, square + [[0, 0], [0, 0], [0, 0], [0, 0], [1, 0]])


# --- TPSModel ---


def test_tps_model_evaluates_the_packed_spline():
    image_xy, map_xy = cbers()
    model = transforms.fit_transform(map_xy, image_xy, "tps")
    assert model.kernel_form() == ("tps", model.packed)
    assert not model.packed.flags.writeable
    points = inside(map_xy, 200)
    assert np.array_equal(model(points), gdal_spline(map_xy, image_xy, points))
    inverse = transforms.fit_transform(image_xy, map_xy, "tps").inverse()
    kind, packed = inverse.kernel_form()
    assert kind == "tps" and packed[0] == thin_plate.GDAL_INVERSE
    assert np.array_equal(inverse(points), gdal_spline_inverse(image_xy, map_xy, points))


@pytest.mark.slow
def test_tps_inverse_on_two_thousand_gcps_meets_gdal_autotests_bound():
    # GDAL autotest's bound (below, on its own GCPs) on 2,000 synthetic noisy GCPs: the spline
    # image -> map within 1e-3 map units of every GCP, and the inverse back to the GCPs' pixels
    image_xy, map_xy = utm_gcps(2000, 9)
    model = transforms.fit_transform(image_xy, map_xy, "tps")
    assert np.hypot(*(model(image_xy) - map_xy).T).max() < 1e-3
    back = model.inverse()(map_xy)
    np.testing.assert_allclose(back, image_xy, atol=1e-6)
    assert np.array_equal(back, gdal_spline_inverse(image_xy, map_xy, map_xy))


# --- GDAL autotest gcore/transformer.py, test_transformer_tps_precision, on its own GCPs ---


def gcps_2115():
    """GDAL autotest's gcore/data/gcps_2115.vrt (MIT licence): (pixel, line) and (x, y)."""
    table = np.loadtxt(Path(__file__).with_name("gdal_autotest_gcps_2115.csv"), delimiter=",",
                       comments="#")
    return table[:, :2], table[:, 2:]


def test_gdal_autotests_2115_gcps_are_fitted_in_both_directions():
    # near-coincident GCPs measured twice (4.5 cm apart, 0.88 m apart in dst): their slope is
    # 19.5 times the set's, under the guard's bound, and GDAL fits them; so does rsgeo
    image_xy, map_xy = gcps_2115()
    assert len(image_xy) == 2115
    for src, dst in ((image_xy, map_xy), (map_xy, image_xy)):
        model = transforms.fit_transform(src, dst, "tps")
        assert model.skipped == ()


@pytest.mark.slow
def test_gdal_autotests_tps_precision_on_its_2115_gcps():
    # what GDAL asserts: the spline pixel/line -> x/y within 1e-3 of every GCP (GDAL 3.10
    # through rasterio: 2.15e-5, and rsgeo's values are GDAL's to the last bit) ...
    image_xy, map_xy = gcps_2115()
    model = transforms.fit_transform(image_xy, map_xy, "tps")
    forward = model(image_xy)
    assert np.hypot(*(forward - map_xy).T).max() < 1e-3
    assert np.array_equal(forward, gdal_spline(image_xy, map_xy, image_xy))
    # ... back from there to the GCP within a relative 1e-5 (GDAL leaves out GCPs 172 and 1639
    # for one compiler; rsgeo meets it at every GCP) ...
    inverse = model.inverse()
    np.testing.assert_allclose(inverse(forward), image_xy, rtol=1e-5, atol=0)
    # ... and at the midpoints of consecutive GCPs, within 1e-3 px, but where the spline
    # folds between GCPs measured twice: GDAL's list of the points that do not converge
    folds = {775, 776, 777, 784, 785, 786, 787, 802, 813, 814, 1007, 1008, 1009, 1010, 1254,
             1558, 1634, 1638, 1957, 1984}
    middle = 0.5 * (image_xy[:-1] + image_xy[1:])
    kept = np.setdiff1d(np.arange(len(middle)), sorted(folds))
    np.testing.assert_allclose(inverse(model(middle[kept])), middle[kept], rtol=0, atol=1e-3)
    # where it folds, rsgeo says so instead of returning a point that misses its target
    with pytest.raises(ModelError, match="no inverse"):
        inverse(model(middle[[813]]))


def test_tps_refuses_a_near_pair_far_steeper_than_the_gcps():
    # 0.2 m apart in map, 0.8 px apart in the image, 80 times the GCPs' slope (0.05 px/m): the
    # spline would move the scene's centre by 30 px to pass through both
    image_xy, map_xy = cbers()
    with pytest.raises(GCPError, match=r"rows 4 and 14, 0\.2 apart in src and 0\.8 in dst, a "
                                       r"slope 80 times"):
        transforms.fit_transform(np.vstack([map_xy, map_xy[4] + [0.2, 0]]),
                                 np.vstack([image_xy, image_xy[4] + [0.8, 0]]), "tps")
    # 1 cm apart and agreeing (the pixel 0.0005 px away): fitted, through both
    near_map = np.vstack([map_xy, map_xy[4] + [0.01, 0]])
    near_image = np.vstack([image_xy, image_xy[4] + [0.0005, 0]])
    model = transforms.fit_transform(near_map, near_image, "tps")
    np.testing.assert_allclose(model(near_map), near_image, atol=1e-6)


@pytest.mark.parametrize("kind, order", [("tps", None), ("linear", None), ("helmert", None),
                                         ("projective", None), ("polynomial", 1),
                                         ("polynomial", 3)])
def test_every_kind_refuses_coordinates_whose_squares_overflow(kind, order):
    # a linear fit at 1e198 returned one point for every GCP, a polynomial NaN: refused
    image_xy, map_xy = cbers()
    with pytest.raises(GCPError, match=r"src coordinates as large as .*within \+/-1e\+75"):
        transforms.fit_transform(map_xy * 1e198, image_xy, kind, order)
    with pytest.raises(GCPError, match="dst coordinates"):
        transforms.fit_transform(map_xy, image_xy * 1e200, kind, order)
    model = transforms.fit_transform(map_xy * 1e68, image_xy, kind, order)    # within: fitted
    assert np.isfinite(model(map_xy * 1e68)).all()


# --- Warps: gdalwarp -tps -et 0, pixel for pixel ---


def warp_case(n_gcps, seed):
    """A 320 x 320 image, n GCPs with a curved image -> map relation, a 7 m output grid."""
    rng = np.random.default_rng(seed)
    image = rng.integers(0, 256, (320, 320), dtype=np.uint8)
    image_xy = rng.uniform(0, 320, (n_gcps, 2))
    u, v = image_xy[:, 0] - 160, image_xy[:, 1] - 160
    map_xy = np.column_stack([
        600_000 + 10 * image_xy[:, 0] + 0.4 * image_xy[:, 1] + 0.002 * u * v,
        7_300_000 - 10 * image_xy[:, 1] + 0.5 * image_xy[:, 0] + 0.003 * u * u])
    map_xy += rng.normal(0, 2, map_xy.shape)
    return image, image_xy, map_xy, affine.Affine(7.0, 0, 600_400, 0, -7.0, 7_299_600)


@pytest.mark.parametrize("n_gcps", [14, 200])
@pytest.mark.parametrize("method", ["nearest", "bilinear", "cubic"])
def test_warp_through_the_spline_is_gdalwarps_pixel_for_pixel(n_gcps, method):
    image, image_xy, map_xy, dst_transform = warp_case(n_gcps, 3)
    shape = (400, 400)
    expected = gdal_warp(image, tps_source(image_xy, map_xy), dst_transform, shape, method, 0)
    assert np.count_nonzero(expected) > shape[0] * shape[1] // 2
    # gdalwarp fits the spline image -> map and inverts it at every output cell
    model = transforms.fit_transform(image_xy, map_xy, "tps").inverse()
    # compiled inside the warp kernel (the inverse's kernel_form) ...
    assert np.array_equal(warp(image, model, shape, dst_transform, method=method, dst_nodata=0),
                          expected)
    # ... and evaluated point by point as any Python mapping
    assert np.array_equal(warp(image, lambda points: model(points), shape, dst_transform,
                               method=method, dst_nodata=0), expected)
