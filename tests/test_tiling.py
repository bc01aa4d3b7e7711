"""rsgeo.resample: a warp made tile by tile equals one warp, pixel for pixel (no seams).

The reference is one rsgeo.resample.warp call over the whole grid (itself checked against GDAL in
test_resample.py and test_transformer.py). The output grids here are north-up with pixel sizes
and origins that add up exactly in binary (see rsgeo.resample's notes); the mappings carry the
rotations and curvature.
"""

import affine
import numpy as np
import pytest
import rasterio
from test_resample import noise, noise_and_curved_gcps

from rsgeo import resample, transforms
from rsgeo.errors import GridError, ImageError, RsgeoError
from rsgeo.ortho import orthorectify
from rsgeo.resample import WARP_METHODS, grid_scale, warp
from rsgeo.sensors import RPCModel, simple_rpc_dict

# a 320 x 320 source of 10 m pixels (noise_and_curved_gcps' image); its GCPs map it to
# x 600 000 .. 603 300, y 7 296 800 .. 7 300 100 (with the curvature)
SOURCE_SHAPE = (320, 320)
# rotated by 7°: an affine source whose rows are not the map's
ROTATED_SOURCE = (affine.Affine(10.0, 0, 600_000.0, 0, -10.0, 7_300_000.0)
                  @ affine.Affine.rotation(7))
# 7 m pixels (an enlargement) over a window that reaches beyond the source on the left, right
# and bottom: some tiles fully inside, some partly, some wholly outside
GRID = affine.Affine(7.0, 0, 599_300.0, 0, -7.0, 7_300_140.0)
GRID_SHAPE = (600, 650)
# 28 m pixels over the same ground: a downsampling, scale < 0.95 (widened kernels)
COARSE_GRID = affine.Affine(28.0, 0, 599_300.0, 0, -28.0, 7_300_140.0)
COARSE_SHAPE = (150, 163)
TILE = (96, 112)                  # divides neither grid
MAPPINGS = ("affine", "polynomial 2", "tps", "callable")


def mapping_of(kind):
    """(image, map -> image mapping) of one kind."""
    image, image_xy, map_xy = noise_and_curved_gcps()
    if kind == "affine":
        return image, ~ROTATED_SOURCE
    if kind == "polynomial 2":
        return image, transforms.fit_polynomial(map_xy, image_xy, 2)
    if kind == "tps":
        return image, transforms.fit_transform(map_xy, image_xy, "tps")
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    return image, lambda points: model(points)   # a Python function: warp's NumPy path


def one_shot(image, mapping, shape, transform, method, kind, **options):
    """warp over the whole grid, in one call."""
    return warp(image, mapping, shape, transform, method=method, **options)


def window_kinds(mapping, shape, transform, tile_shape, method, scale):
    """How many tiles read nothing, a window cut by the source's edges, an inner window."""
    kinds = {"none": 0, "edge": 0, "inner": 0}
    for tile in resample.tiles(shape, transform, tile_shape):
        window = resample.source_window(mapping, tile.shape, tile.transform, SOURCE_SHAPE,
                                      method, scale)
        if window is None:
            kinds["none"] += 1
        elif (window.row_off == 0 or window.col_off == 0
              or window.row_off + window.rows == SOURCE_SHAPE[0]
              or window.col_off + window.cols == SOURCE_SHAPE[1]):
            kinds["edge"] += 1
        else:
            kinds["inner"] += 1
    return kinds


@pytest.mark.parametrize("method", WARP_METHODS)
@pytest.mark.parametrize("kind", MAPPINGS)
def test_tiles_equal_one_warp(kind, method):
    image, mapping = mapping_of(kind)
    whole = one_shot(image, mapping, GRID_SHAPE, GRID, method, kind)
    tiled = resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, tile_shape=TILE, method=method)
    assert tiled.dtype == whole.dtype
    assert np.count_nonzero(tiled != whole) == 0
    # the grid has tiles of every kind: all nodata, cut by the source's edges, inside
    scale = grid_scale(mapping, GRID_SHAPE, GRID, SOURCE_SHAPE)
    assert min(window_kinds(mapping, GRID_SHAPE, GRID, TILE, method, scale).values()) > 0


@pytest.mark.parametrize("method", WARP_METHODS)
@pytest.mark.parametrize("kind", MAPPINGS)
def test_downsampled_tiles_equal_one_warp(kind, method):
    image, mapping = mapping_of(kind)
    scale = grid_scale(mapping, COARSE_SHAPE, COARSE_GRID, SOURCE_SHAPE)
    assert max(scale) < 0.95            # bilinear and cubic are widened over 1/scale pixels
    whole = one_shot(image, mapping, COARSE_SHAPE, COARSE_GRID, method, kind)
    tiled = resample.warp_tiled(image, mapping, COARSE_SHAPE, COARSE_GRID, tile_shape=(40, 48),
                              method=method)
    assert np.count_nonzero(tiled != whole) == 0


@pytest.mark.parametrize("method", ["nearest", "bilinear", "cubic"])
def test_float_bands_and_no_destination_nodata(method):
    # float32 (every last bit shows) with two bands, gdalwarp without -dstnodata
    _, mapping = mapping_of("polynomial 2")
    image = np.stack([noise(SOURCE_SHAPE, "float32", seed) for seed in (1, 2)])
    whole = warp(image, mapping, GRID_SHAPE, GRID, method=method, dst_nodata=None)
    tiled = resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, tile_shape=(50, 70),
                                method=method,
                              dst_nodata=None)
    assert tiled.shape == (2,) + GRID_SHAPE
    assert np.count_nonzero(tiled != whole) == 0


def test_source_nodata_is_respected_as_in_one_warp():
    _, mapping = mapping_of("affine")
    image = noise(SOURCE_SHAPE, "uint8", 4)
    image[100:180, 90:200] = 7
    whole = warp(image, mapping, GRID_SHAPE, GRID, method="bilinear", src_nodata=7)
    tiled = resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, tile_shape=TILE,
                                method="bilinear",
                              src_nodata=7)
    assert np.count_nonzero(tiled != whole) == 0


def test_approximated_tiles_as_wide_as_the_grid_equal_one_approximated_warp():
    # GDAL's approximation works along a row: a tile spanning the grid's rows is the same row
    _, image_xy, map_xy = noise_and_curved_gcps()
    image = noise(SOURCE_SHAPE, "float32", 5)
    model = transforms.fit_polynomial(map_xy, image_xy, 3)
    whole = warp(image, model, GRID_SHAPE, GRID, method="bilinear", error_threshold=0.125)
    exact = warp(image, model, GRID_SHAPE, GRID, method="bilinear")
    assert np.count_nonzero(whole != exact) > 0          # the approximation did something
    tiled = resample.warp_tiled(image, model, GRID_SHAPE, GRID, tile_shape=(64, GRID_SHAPE[1]),
                              method="bilinear", error_threshold=0.125)
    assert np.count_nonzero(tiled != whole) == 0


def test_tiles_of_a_grid_that_does_not_add_up_in_binary():
    # each tile is a window of the grid (dst_offset), as gdalwarp's chunks: a tile's own
    # geotransform would round its origin and move its cell centres in the last bit
    _, mapping = mapping_of("affine")
    image = noise(SOURCE_SHAPE, "float32", 6)
    grid = affine.Affine(7.123456789, 0.3, 599_300.37, 0.2, -7.123456789, 7_300_140.91)
    whole = warp(image, mapping, GRID_SHAPE, grid, method="bilinear")
    tiled = resample.warp_tiled(image, mapping, GRID_SHAPE, grid, tile_shape=TILE,
                                method="bilinear")
    assert np.count_nonzero(tiled != whole) == 0


# -- tiles and windows ----------------------------------------------------------------


def test_tiles_cover_the_grid_once_with_the_grid_s_geotransform():
    cover = np.zeros(GRID_SHAPE, dtype=int)
    for tile in resample.tiles(GRID_SHAPE, GRID, TILE):
        rows, cols = tile.shape
        cover[tile.row:tile.row + rows, tile.col:tile.col + cols] += 1
        # the tile's pixel (0, 0) corner is the grid's (tile.col, tile.row) corner
        assert tile.transform @ (0, 0) == GRID @ (tile.col, tile.row)
        assert tile.transform @ (cols, rows) == GRID @ (tile.col + cols, tile.row + rows)
        assert rows <= TILE[0] and cols <= TILE[1]
    assert (cover == 1).all()


def test_source_window_of_a_shift_is_its_box_widened_by_the_kernel_s_reach():
    shift = affine.Affine.translation(100.0, 50.0)      # output (x, y) reads source (x + 100, ...)
    identity = affine.Affine.identity()
    # centres at cols 100.5 .. 119.5, rows 50.5 .. 59.5 (average: corners 100 .. 120, 50 .. 60)
    expected = {"nearest": (49, 99, 12, 22), "bilinear": (48, 98, 14, 24),
                "cubic": (47, 97, 16, 26), "average": (48, 98, 15, 25)}
    for method, window in expected.items():
        got = resample.source_window(shift, (10, 20), identity, (300, 400), method)
        assert tuple(got) == window, method
    # cut at the source's edges, never inside them
    assert tuple(resample.source_window(affine.Affine.translation(-5.0, 295.0), (10, 20),
                                      identity, (300, 400), "cubic")) == (292, 0, 8, 18)
    # downsampling by 4: cubic reaches ceil(2 / 0.25) + 2 = 10 pixels
    assert tuple(resample.source_window(shift, (10, 20), identity, (300, 400), "cubic",
                                      scale=0.25)) == (40, 90, 30, 40)


def test_a_tile_outside_the_source_reads_nothing():
    shift = affine.Affine.translation(100.0, 50.0)
    beyond = affine.Affine.translation(300.5, 0)        # cols 400.5 .. : right of the image
    assert resample.source_window(shift, (10, 20), beyond, (300, 400), "cubic") is None
    # within the kernel's reach of the image but no centre inside: still nothing to read
    assert resample.source_window(shift, (10, 20), affine.Affine.translation(-120.0, 0),
                                (300, 400), "cubic") is None


# -- files in and out ---------------------------------------------------------------------


def write_raster(path, image, transform=None):
    bands = image if image.ndim == 3 else image[np.newaxis]
    with rasterio.open(path, "w", driver="GTiff", width=bands.shape[2], height=bands.shape[1],
                       count=bands.shape[0], dtype=bands.dtype.name,
                       transform=transform or affine.Affine.identity()) as dataset:
        dataset.write(bands)
    return path


class ReadRecorder:
    """An open rasterio dataset that records the windows read from it."""

    def __init__(self, dataset):
        self.dataset = dataset
        self.windows = []

    def read(self, *args, window=None, **kwargs):
        self.windows.append(window)
        return self.dataset.read(*args, window=window, **kwargs)

    def __getattr__(self, name):
        return getattr(self.dataset, name)


def test_a_file_is_read_window_by_window_and_written_tile_by_tile(tmp_path):
    image, mapping = mapping_of("polynomial 2")
    image = np.stack([image, 255 - image])
    source = write_raster(tmp_path / "source.tif", image, ROTATED_SOURCE)
    whole = warp(image, mapping, GRID_SHAPE, GRID, method="cubic")
    with rasterio.open(source) as dataset, rasterio.open(
            tmp_path / "out.tif", "w", driver="GTiff", width=GRID_SHAPE[1],
            height=GRID_SHAPE[0], count=2, dtype="uint8", transform=GRID, tiled=True,
            blockxsize=128, blockysize=128) as out:
        recorder = ReadRecorder(dataset)
        returned = resample.warp_tiled(recorder, mapping, GRID_SHAPE, GRID, tile_shape=TILE,
                                     method="cubic", out=out)
        assert returned is out
    with rasterio.open(tmp_path / "out.tif") as written:
        assert np.count_nonzero(written.read() != whole) == 0
    # every read is one tile's window, smaller than the source (an enlargement: 7 m pixels
    # over 10 m, so a 96 x 112 tile reads at most some 80 x 90 pixels)
    assert recorder.windows and all(w.width < 100 and w.height < 100 for w in recorder.windows)


def test_a_path_source_gives_a_2d_array_for_one_band(tmp_path):
    image, mapping = mapping_of("affine")
    source = write_raster(tmp_path / "source.tif", image)
    tiled = resample.warp_tiled(source, mapping, GRID_SHAPE, GRID, tile_shape=TILE,
                                method="bilinear")
    whole = warp(image, mapping, GRID_SHAPE, GRID, method="bilinear")
    assert tiled.shape == GRID_SHAPE
    assert np.count_nonzero(tiled != whole) == 0


def test_into_a_given_array():
    image, mapping = mapping_of("affine")
    out = np.full(GRID_SHAPE, 9, dtype=np.uint8)
    returned = resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, tile_shape=TILE, out=out)
    assert returned is out
    assert np.count_nonzero(out != warp(image, mapping, GRID_SHAPE, GRID)) == 0


# -- Dask -----------------------------------------------------------------------------------


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("method", ["nearest", "cubic", "average"])
def test_dask_with_one_and_two_workers_equals_one_warp(tmp_path, method, workers):
    dask = pytest.importorskip("dask")
    image, mapping = mapping_of("polynomial 2")
    source = write_raster(tmp_path / "source.tif", image)
    array = resample.warp_dask(source, mapping, GRID_SHAPE, GRID, tile_shape=TILE, method=method)
    assert array.chunks[0][0] == TILE[0] and array.chunks[1][0] == TILE[1]
    with dask.config.set(scheduler="threads", num_workers=workers):
        tiled = array.compute()
    whole = warp(image, mapping, GRID_SHAPE, GRID, method=method)
    assert np.count_nonzero(tiled != whole) == 0


def test_dask_processes_equal_one_warp(tmp_path):
    # each worker process unpickles the model, opens the file and reads its windows
    dask = pytest.importorskip("dask")
    image, mapping = mapping_of("affine")
    image = np.stack([image, 255 - image])
    source = write_raster(tmp_path / "source.tif", image)
    array = resample.warp_dask(source, mapping, GRID_SHAPE, GRID, tile_shape=(300, 330),
                               method="bilinear")
    with dask.config.set(scheduler="processes", num_workers=2):
        tiled = array.compute()
    whole = warp(image, mapping, GRID_SHAPE, GRID, method="bilinear")
    assert tiled.shape == (2,) + GRID_SHAPE
    assert np.count_nonzero(tiled != whole) == 0


# -- orthorectify, tile by tile ----------------------------------------------------------


def test_tiles_of_orthorectify_equal_one_orthorectify():
    rpc = RPCModel.from_dict(simple_rpc_dict())
    image = noise((1000, 1000), "float32", 7)
    dem = np.random.default_rng(8).uniform(0, 300, (12, 12))
    dem_transform = affine.Affine(0.01, 0, -34.96, 0, -0.01, -7.94)
    # 2**-10 degree pixels, latitudes within one binade (-4 .. -8): the sums are exact
    grid = affine.Affine(2.0**-10, 0, -34.93, 0, -2.0**-10, -7.951)
    shape = (40, 60)
    whole = orthorectify(image, rpc, dem, dem_transform, grid, shape, "cubic",
                         dem_vertical="ellipsoidal")
    tiled = np.empty_like(whole)
    for tile in resample.tiles(shape, grid, (16, 25)):
        rows, cols = tile.shape
        tiled[tile.row:tile.row + rows, tile.col:tile.col + cols] = orthorectify(
            image, rpc, dem, dem_transform, tile.transform, tile.shape, "cubic",
            dem_vertical="ellipsoidal")
    assert np.count_nonzero(tiled != whole) == 0


# -- errors ------------------------------------------------------------------------------


@pytest.mark.parametrize("tile_shape", [(0, 64), (64, -1), (64, 2.5), 64, (64, 64, 1)])
def test_a_tile_shape_must_be_two_positive_integers(tile_shape):
    image, mapping = mapping_of("affine")
    with pytest.raises(GridError, match="tile_shape"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, tile_shape=tile_shape)
    with pytest.raises(GridError, match="tile_shape"):
        resample.tiles(GRID_SHAPE, GRID, tile_shape)


def test_out_must_match_the_result():
    image, mapping = mapping_of("affine")
    with pytest.raises(GridError, match="out has shape"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, out=np.empty((10, 10), np.uint8))
    with pytest.raises(ImageError, match="dtype"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, out=np.empty(GRID_SHAPE))
    with pytest.raises(TypeError, match="out must be"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, out=[[0]])


def test_out_must_be_a_raster_open_for_writing(tmp_path):
    image, mapping = mapping_of("affine")
    path = write_raster(tmp_path / "out.tif", np.zeros(GRID_SHAPE, np.uint8))
    with rasterio.open(path) as readonly, pytest.raises(ImageError, match="mode"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, out=readonly)
    with rasterio.open(path, "r+") as wrong, pytest.raises(GridError, match="band"):
        resample.warp_tiled(image, mapping, (100, 100), GRID, out=wrong)


def test_a_grid_that_lands_nowhere_is_refused(tmp_path):
    image, mapping = mapping_of("affine")
    # the raster's own geotransform (image -> map) instead of its inverse
    with pytest.raises(GridError, match="no output cell lands"):
        resample.warp_tiled(image, ROTATED_SOURCE, GRID_SHAPE, GRID, tile_shape=TILE)
    source = write_raster(tmp_path / "source.tif", image)
    with pytest.raises(GridError, match="no output cell lands"):
        resample.warp_dask(source, ROTATED_SOURCE, GRID_SHAPE, GRID, tile_shape=TILE)


def test_other_arguments_are_checked_before_any_tile():
    image, mapping = mapping_of("affine")
    with pytest.raises(RsgeoError, match="method"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, method="lanczos")
    with pytest.raises(ImageError, match="nodata"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, GRID, dst_nodata=300)
    with pytest.raises(TypeError, match="mapping"):
        resample.warp_tiled(image, "north up", GRID_SHAPE, GRID)
    with pytest.raises(TypeError, match="affine.Affine"):
        resample.warp_tiled(image, mapping, GRID_SHAPE, tuple(GRID.to_gdal()))
    with pytest.raises(TypeError, match="source_path"):
        resample.warp_dask(image, mapping, GRID_SHAPE, GRID)
    with pytest.raises(RsgeoError, match="error_threshold"):
        resample.source_window(mapping, TILE, GRID, SOURCE_SHAPE, error_threshold=-1)
