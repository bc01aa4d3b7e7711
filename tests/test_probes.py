"""Outside probes that found silent wrong answers or internal tracebacks, answered.

Each test is one probe: what it passed, and the rsgeo error (naming the argument and what is
needed) or the right answer it now gets.
"""

import affine
import numpy as np
import pytest

from rsgeo import accuracy, registration, relief
from rsgeo.errors import GCPError, GridError, ModelError, RsgeoError
from rsgeo.resample import warp
from rsgeo.sensors import RPCModel, refine_rpc
from rsgeo.sensors._frame import ExteriorOrientation, FrameCamera, InteriorOrientation
from rsgeo.sensors._rpc import simple_rpc_dict
from rsgeo.validation import as_affine, as_finite


def rpc():
    return RPCModel.from_dict(simple_rpc_dict())


# --- lens distortion that folds ---


def test_a_lens_whose_distortion_folds_within_the_image_is_refused():
    # k1 = -0.01 per mm²: a point 10 mm off axis lands on the principal point; the distorted
    # radius turns back at 5.77 mm, well inside a 48 x 36 mm frame
    with pytest.raises(ModelError, match=r"k1 = -0\.01 per mm² folds within the image.*"
                                         r"largest, 3\.849 mm, at rho = 5\.774 mm"):
        InteriorOrientation(100.0, 0.006, (8000, 6000), k1=-0.01)
    # the least k1 the message states is accepted, and a hair below it is not
    corner = np.hypot(24.0, 18.0)
    InteriorOrientation(100.0, 0.006, (8000, 6000), k1=-4 / (27 * corner**2) * 0.999)
    with pytest.raises(ModelError, match="folds within the image"):
        InteriorOrientation(100.0, 0.006, (8000, 6000), k1=-4 / (27 * corner**2) * 1.001)


def test_ground_points_beyond_the_fold_radius_are_refused_by_project():
    # a small frame (1.2 x 1.2 mm) keeps k1 = -0.01 monotonic over the image, but a ground
    # point 10 mm off axis in the photo would land on the principal point
    interior = InteriorOrientation(100.0, 0.006, (200, 200), k1=-0.01)
    camera = FrameCamera(interior, ExteriorOrientation(0.0, 0.0, 1000.0, 0.0, 0.0, 0.0))
    inside = camera.project([[0.5, 0.5, 0.0]])                       # 0.07 mm off axis
    assert np.isfinite(inside).all()
    with pytest.raises(ModelError, match=r"ground points \[1\] are 10 mm off axis.*5\.774 mm"):
        camera.project([[0.5, 0.5, 0.0], [100.0, 0.0, 0.0]])


def test_ground_at_height_takes_no_bool_or_text_for_a_height():
    interior = InteriorOrientation(100.0, 0.006, (8000, 6000))
    camera = FrameCamera(interior, ExteriorOrientation(0.0, 0.0, 1000.0, 0.0, 0.0, 0.0))
    with pytest.raises(TypeError, match="height must be a number"):
        camera.ground_at_height([[4000.0, 3000.0]], True)
    with pytest.raises(TypeError, match="height must be a number"):
        camera.ground_at_height([[4000.0, 3000.0]], "0")
    with pytest.raises(GCPError, match=r"one per point \(2\), got shape \(3,\)"):
        camera.ground_at_height([[4000.0, 3000.0], [10.0, 10.0]], [0.0, 1.0, 2.0])
    ground = camera.ground_at_height([[4000.0, 3000.0], [10.0, 10.0]], [0.0, 5.0])
    np.testing.assert_allclose(ground[:, 2], [0.0, 5.0], atol=1e-9)


# --- RPCs ---


def test_refine_rpc_refuses_gcps_far_outside_the_cube_and_names_a_swap():
    model = rpc()
    lon, lat = np.array([-34.91, -34.89, -34.90]), np.array([-8.01, -8.0, -7.99])
    col, row = model.project(lon, lat, 0.0)
    gcps = {"lon": lat, "lat": lon, "height": [0.0] * 3, "col": col, "row": row}   # swapped
    with pytest.raises(GCPError, match=r"GCPs \[0, 1, 2\] lie far outside.*normalised "
                                       r"longitude 597\.556.*look swapped"):
        refine_rpc(model, gcps)
    with pytest.raises(GCPError, match="check that lon and lat are degrees"):
        refine_rpc(model, {**gcps, "lon": lon + 5.0, "lat": lat})
    # up to 1.4 times the scales off the centre (outside the scene, inside the bound): fitted
    refined = refine_rpc(model, {**gcps, "lon": lon + 0.045, "lat": lat})
    assert abs(refined.parameters["a0"]) > 0


@pytest.mark.parametrize("change, error, message", [
    (lambda a: {**a, "offsets": {"LINE": 0.0}}, ModelError, "offsets lacks SAMP, LAT"),
    (lambda a: {**a, "scales": {**a["scales"], "LAT": 0.0}}, ModelError, "LAT are 0"),
    (lambda a: {**a, "line_num": a["line_num"][:10]}, ModelError,
     r"line_num must be the 20 coefficients.*shape \(10,\)"),
    (lambda a: {**a, "samp_den": np.zeros(20)}, ModelError, "samp_den is all zeros"),
    (lambda a: {**a, "line_den": [np.nan] * 20}, ModelError, "line_den holds NaN"),
    (lambda a: {**a, "offsets": {**a["offsets"], "LAT": np.inf}}, RsgeoError,
     r"offsets\['LAT'\] must be a finite number"),
    (lambda a: {**a, "offsets": {**a["offsets"], "LAT": "-8"}}, TypeError,
     r"offsets\['LAT'\] must be a number"),
    (lambda a: {**a, "scales": [1.0] * 5}, TypeError, "scales must be a dict"),
])
def test_rpc_model_built_directly_checks_its_coefficients(change, error, message):
    model = rpc()
    arguments = {"offsets": model.offsets, "scales": model.scales, "line_num": model.line_num,
                 "line_den": model.line_den, "samp_num": model.samp_num,
                 "samp_den": model.samp_den}
    with pytest.raises(error, match=message):
        RPCModel(**change(arguments))
    assert RPCModel(**arguments).project(-34.9, -8.0, 0.0) == (500.5, 500.5)


def test_rpc_verbs_say_which_lengths_differ():
    model = rpc()
    with pytest.raises(RsgeoError, match=r"lon, lat and height must have one shape.*lon \(3,\), "
                                         r"lat \(2,\)"):
        model.project([-34.9, -34.91, -34.92], [-8.0, -8.01], 0.0)
    with pytest.raises(RsgeoError, match=r"col, row and height must have one shape"):
        model.localize([1.0, 2.0, 3.0], [4.0, 5.0], 0.0)
    with pytest.raises(TypeError, match="height must be a number"):
        model.project(-34.9, -8.0, True)


# --- numbers that are not numbers, lengths that differ ---


@pytest.mark.parametrize("call, message", [
    (lambda: relief.relief_displacement(100, "30"), "view_zenith_deg must be a number"),
    (lambda: relief.relief_displacement(True, 30), "height_m must be a number"),
    (lambda: relief.relief_displacement([1, 2], [30, "x"]), "view_zenith_deg must be a number"),
    (lambda: relief.relief_displacement_photo(50.0, 100.0, "4500"), "flying_height_m must be"),
    (lambda: relief.height_error_budget(False, 30.0), "position_error_m must be a number"),
    (lambda: as_finite(np.array([1 + 2j]), "x"), "x must be a number"),
])
def test_booleans_and_text_are_never_taken_as_numbers(call, message):
    with pytest.raises(TypeError, match=message):
        call()


def test_relief_lengths_that_differ_are_named():
    with pytest.raises(RsgeoError, match=r"height_m and view_zenith_deg must have one shape.*"
                                         r"height_m \(3,\), view_zenith_deg \(2,\)"):
        relief.relief_displacement([1, 2, 3], [10, 20])
    with pytest.raises(RsgeoError, match=r"height_m and radial_distance_mm must have one shape"):
        relief.relief_displacement_photo([1, 2, 3], [10, 20], 1000.0)
    with pytest.raises(TypeError, match="position_error_m must be a number"):
        relief.height_error_budget(np.array([1.0, 2.0]), 30.0)
    np.testing.assert_allclose(relief.relief_displacement([0, 100], 45.0), [0, 100])


# --- accuracy, registration ---


def test_asprs_horizontal_refuses_a_flat_pair():
    with pytest.raises(GCPError, match=r"a flat pair \[3\.0, 4\.0\] could be one point or two "
                                       r"distances: give \[\[dx, dy\]\]"):
        accuracy.asprs_horizontal([3.0, 4.0])
    assert accuracy.asprs_horizontal([[3.0, 4.0]]).rmse_r == 5.0


def test_a_mesh_needs_a_positive_pixel_size():
    centroids, areas = [[0, 0], [10, 0], [0, 10]], [4.0, 5.0, 6.0]
    for size in (-1, 0):
        with pytest.raises(GridError, match=r"pixel_size must be a positive size"):
            registration.Mesh(centroids, areas, pixel_size=size)
    with pytest.raises(TypeError, match="pixel_size must be a number"):
        registration.Mesh(centroids, areas, pixel_size=True)
    mesh = registration.Mesh(centroids, areas, pixel_size=2)
    assert mesh.areas.tolist() == [16.0, 20.0, 24.0] and mesh.distances[0, 1] == 20.0


def test_band_misregistration_bounds_upsample():
    bands = np.random.default_rng(0).random((2, 128, 128))
    with pytest.raises(RsgeoError, match=r"upsample must be \[1, 1000\].*got 1000000"):
        registration.band_misregistration(bands, upsample=10**6)


# --- a singular affine ---


@pytest.mark.parametrize("singular", [affine.Affine(0, 0, 0, 0, 0, 0),
                                      affine.Affine(1, 2, 5, 2, 4, 7),
                                      affine.Affine(0.1, 0.2, 0, 0.2, 0.4, 0)])
def test_a_singular_affine_is_refused(singular):
    with pytest.raises(GridError, match=r"(?s)mapping .* is singular \(its determinant"):
        as_affine(singular, "mapping")
    with pytest.raises(GridError, match="is singular"):
        warp(np.ones((4, 4), np.uint8), singular, (4, 4), affine.Affine.identity())
    assert as_affine(affine.Affine(2, 0, 5, 0, -2, 7)) == affine.Affine(2, 0, 5, 0, -2, 7)


@pytest.mark.parametrize("verb", ["measure_shifts", "correlation_tiepoints"])
def test_the_correlation_bounds_its_upsampling_as_band_misregistration_does(verb):
    # (1.5 upsample)² complex numbers per window: 10**6 would ask for terabytes
    from rsgeo.registration import _tiepoints

    image = np.random.default_rng(0).random((128, 128))
    with pytest.raises(ValueError, match=r"upsample must be .*1000.*got 1000000"):
        if verb == "measure_shifts":
            _tiepoints.measure_shifts(image, image, upsample=10**6)
        else:
            _tiepoints.correlation_tiepoints(image, image, 32, 32, upsample=10**6)
