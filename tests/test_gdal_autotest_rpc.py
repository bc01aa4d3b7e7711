"""GDAL's own RPC and RPC-DEM tests, ported: ``autotest/gcore/transformer.py``
(``test_transformer_5``, ``_8``, ``_10``, ``_13``, ``_14``, ``_15``) and
``autotest/alg/warp.py`` (``test_warp_52``), GDAL, MIT licence.

The RPCs are the tests' own (``gdal_autotest/rpcs.json``: ``RPC_VRT`` is the RPC of
``autotest/gcore/data/rpc.vrt``); the DEMs ``transformer_13_dem.tif``,
``transformer_14_dem.tif`` and ``warp_52_dem.tif`` are autotest's data files, copied unchanged
into ``tests/gdal_autotest/``. Where GDAL inverts an RPC (pixel -> ground) it stops at 0.1 pixel
(``RPC_PIXEL_ERROR_THRESHOLD``), so a ground point GDAL returns is checked by projecting it back
(ground -> pixel, exact in both) within that 0.1 pixel; rsgeo's own inversion goes to 1e-8
pixel, so it agrees with GDAL's point to what 0.1 pixel is on the ground. Expected values are
autotest's, and where GDAL 3.10.3 (the lock's, inside rasterio) gives another, GDAL 3.10.3's
through ``rasterio.transform.RPCTransformer``, said at each.
"""

import json
import random
from pathlib import Path

import affine
import numpy as np
import pytest
import rasterio

from rsgeo.dem import dem_height
from rsgeo.errors import ImageError
from rsgeo.sensors import RPCModel

HERE = Path(__file__).parent / "gdal_autotest"
RPCS = json.loads((HERE / "rpcs.json").read_text())


def read_dem(name):
    with rasterio.open(HERE / name) as dataset:
        return dataset.read(1).astype(np.float64), dataset.transform, dataset.crs


def test_transformer_5_localize_at_two_heights():
    rpc = RPCModel.from_dict(RPCS["RPC_VRT"])
    lon, lat = rpc.localize(20.5, 10.5, 0.0)
    assert (lon, lat) == pytest.approx((125.64830100509131, 39.869433991997553), abs=1e-6)
    assert rpc.project(lon, lat, 0.0) == pytest.approx((20.5, 10.5), abs=0.05)
    lon, lat = rpc.localize(20.5, 10.5, 30.0)
    assert (lon, lat) == pytest.approx((125.64828521533849, 39.869345204440144), abs=1e-6)
    assert rpc.project(lon, lat, 30.0) == pytest.approx((20.5, 10.5), abs=0.05)


def test_transformer_5_dem_in_utm_with_height_scale():
    """A flat DEM of 15 m in EPSG:32652 read with RPC_HEIGHT_SCALE=2: the ground at 30 m."""
    from rasterio.warp import transform

    dem = np.full((100, 100), 15.0)
    gt = affine.Affine.from_gdal(213300, 200, 0, 4418700, 0, -200)
    lon, lat = 125.64828521533849, 39.869345204440144
    (x,), (y,) = transform("EPSG:4326", "EPSG:32652", [lon], [lat])
    height = 2 * dem_height(dem, gt, x, y)
    rpc = RPCModel.from_dict(RPCS["RPC_VRT"])
    assert rpc.localize(20.5, 10.5, height) == pytest.approx((lon, lat), abs=1e-6)


def test_transformer_8_a_dem_of_nodata_is_refused():
    """Every DEM cell nodata (-32768, Int16): GDAL's transform fails both ways; rsgeo refuses.

    Ported for bilinear sampling, rsgeo's one DEM interpolation (GDAL's test also runs
    nearest and cubic).
    """
    dem = np.full((100, 100), -32768, dtype=np.int16)
    gt = affine.Affine.from_gdal(213300, 1, 0, 4418700, 0, -1)
    with pytest.raises(ImageError, match="nodata holes"):
        dem_height(dem, gt, 213324.662167036, 4418634.47813677, dem_nodata=-32768)


def test_transformer_10_random_dem_and_a_vertical_shift():
    """GDAL's random DEM (Python's random, seed 0), with and without a geoid of +100 m.

    GDAL's DEM is a compound CRS whose vertical datum is a fake GTX grid of 100 m everywhere;
    with RPC_DEM_APPLY_VDATUM_SHIFT (the default) GDAL adds it to the DEM's heights. rsgeo's
    ``dem_vertical`` knows EGM96 only, so the 100 m are added here by hand. Bit for bit.
    """
    random.seed(0)
    values = [40 + int(10 * random.random()) for _ in range(100 * 100)]
    dem = np.array(values, dtype=np.uint8).reshape(100, 100)
    gt = affine.Affine.from_gdal(125.647968621436, 1.2111052640051412e-05, 0,
                                 39.869926216038, 0, -8.6569068979969188e-06)
    rpc = RPCModel.from_dict(RPCS["RPC_VRT"])
    lon, lat = 125.64828521533849, 39.869345204440144
    height = dem_height(dem, gt, lon, lat)
    assert rpc.project(lon, lat, height + 100.0) == pytest.approx(
        (27.31476045569616, -53.328814757762302), abs=1e-5)
    assert rpc.project(lon, lat, height) == pytest.approx(
        (21.445626206892484, 1.6460100520871492), abs=1e-5)


# GDAL's ground point for a pixel over a DEM, and the DEM cell it falls in: both points lie in
# the DEM's outer half cell, where GDAL 3.10 interpolates along the edge and GDAL 3.9 (and
# rsgeo before) took the nearest cell, 1.3 and 0.46 pixel away
DEM_EDGE_CASES = [
    # autotest's expected value, which GDAL 3.10.3 gives too
    ("TRANSFORMER_13", "transformer_13_dem.tif", (6600.0, 24.0),
     (-108.00069819119149, 39.15771125604824)),
    # GDAL 3.10.3's value; autotest's newer GDAL expects (0.000801360096912016,
    # -4.1346931131054286e-05) from a reworked inversion
    ("TRANSFORMER_14", "transformer_14_dem.tif", (45.0, 73.0),
     (0.0007880237212971428, -4.6762823665037024e-05)),
]


@pytest.mark.parametrize("name, dem_file, pixel, ground", DEM_EDGE_CASES,
                         ids=["test_transformer_13", "test_transformer_14"])
def test_dem_edge_heights_as_gdal_3_10(name, dem_file, pixel, ground):
    dem, gt, _crs = read_dem(dem_file)
    col, row = ~gt @ ground
    assert min(col, row, dem.shape[1] - col, dem.shape[0] - row) < 0.5     # the outer half cell
    rpc = RPCModel.from_dict(RPCS[name])
    height = dem_height(dem, gt, *ground)
    assert rpc.project(*ground, height) == pytest.approx(pixel, abs=0.1)


@pytest.mark.parametrize("name, dem_file, pixel, ground", DEM_EDGE_CASES,
                         ids=["test_transformer_13", "test_transformer_14"])
def test_dem_edge_cases_are_gdal_3_10s(name, dem_file, pixel, ground):
    """The expected ground points above are what the lock's GDAL returns."""
    from rasterio.transform import RPCTransformer

    rpc = RPCModel.from_dict(RPCS[name])
    with RPCTransformer(rpc.to_rasterio(), RPC_DEM=str(HERE / dem_file)) as transformer:
        lon, lat = transformer.xy(pixel[1], pixel[0], offset="ul")
    assert (lon, lat) == pytest.approx(ground, abs=1e-9)


def test_dem_edge_interpolates_along_the_edge():
    """A point in a DEM's outer half cell: linear along the edge, the edge's value across it."""
    dem = np.array([[0.0, 10.0, 20.0], [30.0, 40.0, 50.0], [60.0, 70.0, 80.0]])
    gt = affine.Affine(1, 0, 0, 0, -1, 3)
    # column 2.8 (beyond the last centre, 2.5), row 1.0 (halfway between rows 0 and 1)
    assert dem_height(dem, gt, 2.8, 2.0) == pytest.approx(35.0)
    # on the DEM's far edge (column 3) and corner: still on the DEM, as in GDAL 3.10
    assert dem_height(dem, gt, 3.0, 2.0) == pytest.approx(35.0)
    assert dem_height(dem, gt, 3.0, 0.0) == pytest.approx(80.0)
    with pytest.raises(ValueError, match="does not cover"):
        dem_height(dem, gt, -0.01, 2.0)


LONG_OFF_CASES = [("179.9", (0.0, 0.0), (180.02280735469199, 0.061069145746997976)),
                  ("-179.9", (6600.0, 4400.0), (-180.02313813793387, -0.061398913932229765))]


@pytest.mark.parametrize("long_off, pixel, ground", LONG_OFF_CASES, ids=["east", "west"])
def test_transformer_15_localize_across_the_antimeridian(long_off, pixel, ground):
    """An RPC centred 0.1° from the antimeridian; ground 50 m high (autotest's DEM is 50 m
    wherever it has data: a VRT of two tiles on either side, which GDAL samples at lon ± 360).
    """
    rpc = RPCModel.from_dict(dict(RPCS["TRANSFORMER_15"], LONG_OFF=long_off))
    lon, lat = rpc.localize(*pixel, 50.0)
    # GDAL's inversion stops at 0.1 px, about 3e-6° here; rsgeo's goes to 1e-8 px
    assert (lon, lat) == pytest.approx(ground, abs=3e-6)
    assert rpc.project(*ground, 50.0) == pytest.approx(pixel, abs=0.1)
    # the same ground a turn away (autotest projects both)
    other = ground[0] - 360 if ground[0] > 180 else ground[0] + 360
    assert rpc.project(other, ground[1], 50.0) == pytest.approx(pixel, abs=0.1)


@pytest.mark.parametrize("long_off, pixel, ground", LONG_OFF_CASES, ids=["east", "west"])
def test_transformer_15_against_gdal_3_10(long_off, pixel, ground):
    from rasterio.transform import RPCTransformer

    rpc = RPCModel.from_dict(dict(RPCS["TRANSFORMER_15"], LONG_OFF=long_off))
    with RPCTransformer(rpc.to_rasterio(), RPC_HEIGHT=50) as transformer:
        gdal = transformer.xy(pixel[1], pixel[0], offset="ul")
    assert rpc.localize(*pixel, 50.0) == pytest.approx(gdal, abs=3e-6)


@pytest.mark.slow
def test_warp_52_alpha_checksum():
    """autotest/alg/warp.py, test_warp_52: a 4096 x 4096 RPC image orthorectified onto a
    4096 x 4096 grid in EPSG:3857 with a DEM in EPSG:3857; its alpha band's GDAL checksum is
    3177 (3188 before GDAL 3.10 interpolated along the DEM's edges).

    GDAL's alpha is 255 where an output cell's position falls in the image (no source mask:
    every pixel valid, for cubic as for nearest), which is what ``orthorectify`` gives for an
    image of 255 with nodata 0 and nearest. The checksum is GDAL's own, through rasterio.
    """
    from rasterio.io import MemoryFile

    from rsgeo.ortho import orthorectify

    rpc = RPCModel.from_dict(RPCS["WARP_52"])
    dem, dem_gt, dem_crs = read_dem("warp_52_dem.tif")
    resolution = 4.77731426716
    grid = affine.Affine(resolution, 0, 8453323.83095, 0, -resolution, 4696291.0172)
    shape = (4096, 4096)
    image = np.full((4096, 4096), 255, dtype=np.uint8)
    alpha = orthorectify(image, rpc, dem, dem_gt, grid, shape, "nearest", nodata=0,
                         dst_crs="EPSG:3857", dem_crs=dem_crs, dem_vertical="ellipsoidal")
    with MemoryFile() as memory, memory.open(driver="GTiff", width=4096, height=4096, count=1,
                                             dtype="uint8", transform=grid) as dataset:
        dataset.write(alpha, 1)
        assert dataset.checksum(1) == 3177
