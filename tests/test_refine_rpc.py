"""rsgeo.sensors.refine_rpc: RPC bias compensation in image space (Grodecki & Dial 2003,
Fraser & Hanley 2003), checked against a bias planted on purpose, GDAL's degree-1 GCP
polynomial and GDAL's RPC transformer (through rasterio)."""

import numpy as np
import pytest

from rsgeo import errors, synthetic
from rsgeo.sensors import (
    RefinedRPC,
    RPCModel,
    fit_rpc,
    fit_rpc_to_sensor,
    refine_rpc,
    simple_rpc_dict,
)

pytestmark = pytest.mark.gdal          # the cross-checks call GDAL through rasterio

SHIFT = {"a0": 2.75, "a1": 0.0, "a2": 0.0, "b0": -1.25, "b1": 0.0, "b2": 0.0}
AFFINE = {"a0": 1.5, "a1": 2e-4, "a2": -3e-4, "b0": -0.8, "b1": 1.5e-4, "b2": 4e-4}


def oblique_rpc():
    """An RPC of an oblique view (the sample moves with height), fitted like a vendor's."""
    mapping = simple_rpc_dict()
    mapping["SAMP_NUM_COEFF"][3] = 0.02
    mapping["LINE_NUM_COEFF"][1] = 0.01
    truth = RPCModel.from_dict(mapping)
    grid = np.meshgrid(np.linspace(-34.945, -34.855, 11), np.linspace(-8.045, -7.955, 11),
                       np.linspace(0.0, 400.0, 5), indexing="ij")
    lon, lat, h = (a.ravel() for a in grid)
    return fit_rpc(lon, lat, h, *truth.project(lon, lat, h))


def ground_points(n, seed):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-34.94, -34.86, n), rng.uniform(-8.04, -7.96, n),
            rng.uniform(0.0, 400.0, n))


def with_bias(rpc, lon, lat, h, p):
    col, row = rpc.project(lon, lat, h)
    return (col + p["a0"] + p["a1"] * col + p["a2"] * row,
            row + p["b0"] + p["b1"] * col + p["b2"] * row)


@pytest.mark.parametrize("kind, planted", [("shift", SHIFT), ("affine", AFFINE)])
def test_a_planted_bias_is_recovered_exactly_from_noise_free_gcps(kind, planted):
    rpc = oblique_rpc()
    lon, lat, h = ground_points(6, seed=1)
    col, row = with_bias(rpc, lon, lat, h, planted)
    refined = refine_rpc(rpc, {"lon": lon, "lat": lat, "height": h, "col": col, "row": row},
                         kind)
    assert isinstance(refined, RefinedRPC) and refined.kind == kind
    for name, value in planted.items():
        assert refined.parameters[name] == pytest.approx(value, abs=1e-9), name
    assert refined.rms < 1e-8 < refined.rms_before
    # and everywhere else, not only at the GCPs
    lon, lat, h = ground_points(200, seed=2)
    expected = np.column_stack(with_bias(rpc, lon, lat, h, planted))
    assert np.abs(np.column_stack(refined.project(lon, lat, h)) - expected).max() < 1e-8


def test_the_minimum_gcps_suffice_a_shift_from_one_an_affine_from_three():
    rpc = oblique_rpc()
    lon, lat, h = ground_points(3, seed=3)
    col, row = with_bias(rpc, lon, lat, h, AFFINE)
    one = refine_rpc(rpc, np.column_stack([lon, lat, h, col, row])[:1], "shift")
    assert one.rms < 1e-9                              # one GCP: the shift passes through it
    three = refine_rpc(rpc, np.column_stack([lon, lat, h, col, row]), "affine")
    assert three.parameters == pytest.approx(AFFINE, abs=1e-9)


def test_the_affine_is_gdals_degree_1_polynomial_and_the_shift_the_mean():
    """GDAL's GCP transformer fits a degree-1 polynomial by least squares to fewer than 6 GCPs
    (its automatic order): the affine from the RPC's positions to the measured ones."""
    from rasterio.control import GroundControlPoint
    from rasterio.transform import GCPTransformer

    rpc = oblique_rpc()
    lon, lat, h = ground_points(5, seed=4)
    col, row = with_bias(rpc, lon, lat, h, AFFINE)
    rng = np.random.default_rng(5)
    col, row = col + rng.normal(0, 0.5, 5), row + rng.normal(0, 0.5, 5)
    gcps = {"lon": lon, "lat": lat, "height": h, "col": col, "row": row}
    predicted = np.column_stack(rpc.project(lon, lat, h))
    measured = np.column_stack([col, row])
    points = [GroundControlPoint(row=p[1], col=p[0], x=m[0], y=m[1])
              for p, m in zip(predicted, measured)]
    where = ground_points(50, seed=13)
    at = np.column_stack(rpc.project(*where))
    with GCPTransformer(points) as gdal:
        expected = np.column_stack(gdal.xy(at[:, 1], at[:, 0], offset="ul"))
    refined = refine_rpc(rpc, gcps, "affine")
    assert np.abs(np.column_stack(refined.project(*where)) - expected).max() < 1e-8
    shift = refine_rpc(rpc, gcps, "shift")
    assert shift.parameters["a0"] == pytest.approx(np.mean(col - predicted[:, 0]), abs=1e-12)
    assert shift.parameters["b0"] == pytest.approx(np.mean(row - predicted[:, 1]), abs=1e-12)
    assert np.allclose(shift.residuals, measured - np.column_stack(shift.project(lon, lat, h)))
    assert np.allclose(shift.residuals_before, measured - predicted)


def test_localize_inverts_the_compensated_projection():
    rpc = oblique_rpc()
    lon, lat, h = ground_points(8, seed=6)
    refined = refine_rpc(rpc, np.column_stack([lon, lat, h, *with_bias(rpc, lon, lat, h,
                                                                       AFFINE)]), "affine")
    col, row = refined.project(lon, lat, h)
    back_lon, back_lat = refined.localize(col, row, h)
    assert np.abs(back_lon - lon).max() < 1e-9 and np.abs(back_lat - lat).max() < 1e-9


@pytest.mark.parametrize("kind, planted, limit", [("shift", SHIFT, 1e-6),
                                                  ("affine", AFFINE, 1e-3)])
def test_to_rpc_gives_gdal_an_rpc_that_places_points_as_the_compensated_model(kind, planted,
                                                                               limit):
    from rasterio.transform import RPCTransformer, TransformDirection

    rpc = oblique_rpc()
    lon, lat, h = ground_points(6, seed=7)
    refined = refine_rpc(rpc, np.column_stack([lon, lat, h, *with_bias(rpc, lon, lat, h,
                                                                       planted)]), kind)
    lon, lat, h = ground_points(300, seed=8)
    with RPCTransformer(refined.to_rpc().to_rasterio()) as gdal:
        col, row = gdal._transform(lon, lat, h, transform_direction=TransformDirection.reverse)
    expected = np.column_stack(refined.project(lon, lat, h))
    assert np.abs(np.column_stack([col, row]) - expected).max() < limit


def test_on_noisy_gcps_the_compensation_beats_none_at_check_points():
    """A vendor's RPC from a sensor whose attitude is off (the raw scene of chapter 4c)."""
    scene = synthetic.raw_scene(shape=(300, 280), nadir_pixel_m=20.0, simulate=False)
    vendor = scene.sensor.with_knowledge_errors(roll_deg=0.001, pitch_deg=-0.001, yaw_deg=0.004)
    rpc = fit_rpc_to_sensor(vendor, scene.crs, scene.bounds, scene.height_range)
    checks = scene.control_points(100, seed=9)
    truth = checks.true_image_xy

    def check_rms(model):
        error = np.column_stack(model.project(checks.lon, checks.lat, checks.height)) - truth
        return np.sqrt(np.mean(np.sum(error ** 2, axis=1)))

    before = check_rms(rpc)
    assert before > 1.0                                       # a bias of pixels
    for seed in range(4):
        gcps = scene.control_points(5, noise_px=0.3, seed=seed)
        for kind in ("shift", "affine"):
            after = check_rms(refine_rpc(rpc, gcps.rpc_gcps, kind))
            assert after < before / 3, (seed, kind, before, after)


def test_the_inputs_are_neither_modified_nor_kept():
    rpc = oblique_rpc()
    lon, lat, h = ground_points(5, seed=10)
    gcps = np.column_stack([lon, lat, h, *with_bias(rpc, lon, lat, h, AFFINE)])
    copy, coefficients = gcps.copy(), rpc.samp_num.copy()
    refined = refine_rpc(rpc, gcps, "affine")
    gcps[:, 3] += 100.0
    assert np.array_equal(rpc.samp_num, coefficients)
    assert refined.rms < 1e-8 and not np.shares_memory(refined.residuals, gcps)
    assert np.array_equal(copy[:, :3], gcps[:, :3])


def test_a_mapping_rpc_and_a_dataframe_of_gcps_are_accepted():
    import pandas as pd

    rpc = RPCModel.from_dict(simple_rpc_dict())
    lon, lat, h = ground_points(4, seed=11)
    col, row = with_bias(rpc, lon, lat, h, SHIFT)
    table = pd.DataFrame({"lon": lon, "lat": lat, "height": h, "col": col, "row": row})
    refined = refine_rpc(simple_rpc_dict(), table)             # kind="shift" by default
    assert refined.kind == "shift" and refined.parameters["a0"] == pytest.approx(2.75)


# -- Refusals: rsgeo errors that say what is needed ---------------------------------------------

def gcp_array(n=5, seed=12):
    rpc = RPCModel.from_dict(simple_rpc_dict())
    lon, lat, h = ground_points(n, seed)
    return rpc, np.column_stack([lon, lat, h, *rpc.project(lon, lat, h)])


@pytest.mark.parametrize("kind, n, needed", [("shift", 0, "at least 1 GCP"),
                                             ("affine", 2, "at least 3 GCP")])
def test_too_few_gcps_are_refused(kind, n, needed):
    rpc, gcps = gcp_array()
    with pytest.raises(errors.GCPError, match=needed):
        refine_rpc(rpc, gcps[:n], kind)


def test_collinear_gcps_are_refused_for_the_affine_but_not_for_the_shift():
    rpc = RPCModel.from_dict(simple_rpc_dict())
    lon = np.linspace(-34.93, -34.87, 5)
    lat = -8.0 + 0.5 * (lon + 34.9)                         # on one line, in the image too
    gcps = np.column_stack([lon, lat, np.zeros(5), *rpc.project(lon, lat, 0.0)])
    with pytest.raises(errors.GCPError, match="on one line"):
        refine_rpc(rpc, gcps, "affine")
    assert refine_rpc(rpc, gcps, "shift").rms < 1e-9


@pytest.mark.parametrize("column", [0, 2, 4])
def test_nan_gcps_are_refused(column):
    rpc, gcps = gcp_array()
    gcps[1, column] = np.nan
    with pytest.raises(errors.GCPError, match="NaN"):
        refine_rpc(rpc, gcps, "shift")


def test_mismatched_shapes_and_missing_columns_are_refused():
    rpc, gcps = gcp_array()
    with pytest.raises(errors.GCPError, match=r"\(n, 5\)"):
        refine_rpc(rpc, gcps[:, :4])
    mapping = {"lon": gcps[:, 0], "lat": gcps[:, 1], "height": gcps[:4, 2],
               "col": gcps[:, 3], "row": gcps[:, 4]}
    with pytest.raises(errors.GCPError, match="one size"):
        refine_rpc(rpc, mapping)
    del mapping["height"]
    with pytest.raises(errors.GCPError, match="lacks height"):
        refine_rpc(rpc, mapping)


def test_an_unknown_kind_and_wrong_types_are_refused():
    rpc, gcps = gcp_array()
    with pytest.raises(errors.RsgeoError, match="unknown kind 'similarity'"):
        refine_rpc(rpc, gcps, "similarity")
    with pytest.raises(TypeError):
        refine_rpc(rpc, gcps.astype(str))
    with pytest.raises(TypeError):
        refine_rpc(42, gcps)
    with pytest.raises(errors.RsgeoError, match="n must be"):
        refine_rpc(rpc, gcps, "affine").to_rpc(n=2)
