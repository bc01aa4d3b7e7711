"""Orthorectification with RPCs and a DEM, as GDAL does it; the orthoimage checked on the image.

Measured agreement with GDAL 3.10.3 through rasterio 1.4.4 (``tests/test_terrain.py``,
``tests/test_gdal_autotest_rpc.py``): :meth:`~rsgeo.sensors.RPCModel.project` is GDAL's
``RPCTransformer`` to the last bit at random (lon, lat, h); the DEM is sampled as GDAL 3.10
samples it (bilinear, interpolated along its edges); :func:`orthorectify` gives the pixels of
``reproject(..., rpcs=..., RPC_DEM=...)`` (GDAL's warper, whose transformer is exact when
``RPC_DEM`` is given, whatever ``tolerance`` says) bit for bit for nearest, bilinear and cubic,
with the output grid in EPSG:4326 or UTM, finer than the image or coarser (where GDAL widens
bilinear and cubic: rsgeo computes gdalwarp's kernel scale for the whole grid, one chunk of
gdalwarp's, or takes the ``scale`` given), and without a destination nodata or with nodata 255.
One difference remains: with nodata 0, a valid pixel whose cubic value rounds to 0 (Keys'
kernel overshoots below 0 beside dark pixels) is moved to 1 by rsgeo (GDAL's "AvoidNoData",
which rsgeo.resample applies as GDAL's VRT warps do) and left at 0 by ``reproject``: about
0.5 % of the valid pixels of a uniform-noise image, each by 1 DN. GDAL 3.10 replaces a valid
value that collides with the destination nodata inconsistently across its warp paths (its
developers made it consistent in GDAL 3.11).

How :func:`orthorectify` computes, strip of output rows by strip (GDAL's
warper asks its transformer row by row): one compiled pass (Numba) gives
each cell its longitude and latitude, its DEM height and its RPC position,
the RPC over a whole row at a time in vector instructions (several cells per
instruction, each cell's operations in GDAL's order, so the numbers do not
change); on a grid in EPSG:4326, the RPC's own CRS and the usual orthoimage
grid, the longitude and latitude come from the grid's geotransform, with no
PROJ. PROJ, which cannot run compiled, transforms a projected grid's cells
(and the DEM's, when the DEM is projected) strip by strip, through
``rasterio.warp.transform``. Then
:func:`rsgeo.resample.interpolate`, with the kernel scale gdalwarp computes.
``benchmarks/orthorectify.py`` times it against GDAL. Note that gdalwarp does
not approximate RPC + DEM by default: given ``RPC_DEM`` its error threshold is 0
(exact) unless ``-et`` says otherwise.
"""

from functools import partial

import numpy as np
from numba import njit

from ._grids import as_gdal, gdal_inverse, grid_centres, is_lon_lat, to_crs
from ._kernels._rows import run_in_row_blocks
from ._kernels.dem import dem_height_at
from ._kernels.rpc import rpc_point
from ._numba_cache import CACHE
from .dem import prepare_dem, raise_dem_problems, sample_dem
from .errors import GridError, ImageError
from .language import _, prose_number
from .registration import measure_shifts
from .resample import METHODS, grid_scale, interpolate
from .sensors import RPCModel
from .validation import (
    as_bands_first,
    as_image,
    as_integer,
    as_lon_lat_height,
    as_num_threads,
    as_output_shape,
    as_scale,
    as_shape,
    check_choice,
)

__all__ = ["orthorectify", "map_on_grid", "positional_error"]




# the columns of _ortho_positions' per-row counts
_OUTSIDE_DEM, _OVER_HOLE, _BAD_LON_LAT, _SEES_IMAGE = range(4)


@njit(cache=CACHE, nogil=True, error_model="numpy")
def _ortho_positions(dst_gt, first_row, width, lon, lat, dem_x, dem_y, dem, inverse, rpc,
                     image_width, image_height, cols, rows, counts, first_i, stop_i):
    """One strip of orthorectify in one compiled pass: each cell's DEM height and RPC position.

    Cell (i, j) of the strip (output row ``first_row + i``) is at flat index
    ``i * width + j``. Its longitude and latitude are ``lon``, ``lat`` (PROJ's, for a
    projected grid) or, when they are empty, its centre through ``dst_gt`` (a grid in
    EPSG:4326, as GDAL's GenImgProjTransform computes it); the DEM is sampled at ``dem_x``,
    ``dem_y`` (a DEM in another CRS) or, when empty, at the longitude and latitude. The RPC's
    (col, row) go to ``cols``, ``rows``. ``counts[i]`` gets row i's cells outside the DEM,
    over a DEM hole, with a longitude or latitude out of range (their position is set to
    (-1, -1), outside the image), and whose position falls inside the image. Only the strip's
    rows ``first_i`` to ``stop_i - 1`` are computed: threads share the strip's rows
    (``rsgeo._kernels._rows``). Returns 0.

    Each row goes in passes: coordinates, heights (the DEM's branches), then the RPC over the
    whole row, a loop without branches that the compiler turns into vector instructions
    (several cells per instruction, each cell's operations unchanged: error_model="numpy"
    lets a division by zero give infinity, as in C, instead of testing every division).
    """
    geographic_grid = lon.size == 0
    dem_on_lon_lat = dem_x.size == 0
    for i in range(first_i, stop_i):
        # the row's views, indexed from 0 (an index known not to be negative spares Numba's
        # wrap-around test, which kept the RPC's loop from vector instructions)
        first, stop = i * width, (i + 1) * width
        row_cols = cols[first:stop]
        row_rows = rows[first:stop]
        heights = np.empty(width)
        # the cells' longitude and latitude, held in cols and rows until the RPC replaces them
        if geographic_grid:
            centre_row = first_row + i + 0.5
            for j in range(width):
                centre_col = j + 0.5
                row_cols[j] = dst_gt[0] + centre_col * dst_gt[1] + centre_row * dst_gt[2]
                row_rows[j] = dst_gt[3] + centre_col * dst_gt[4] + centre_row * dst_gt[5]
        else:
            row_cols[:] = lon[first:stop]
            row_rows[:] = lat[first:stop]
        row_x = row_cols if dem_on_lon_lat else dem_x[first:stop]
        row_y = row_rows if dem_on_lon_lat else dem_y[first:stop]
        outside = 0
        holed = 0
        bad = 0
        for j in range(width):
            height, is_outside = dem_height_at(dem, inverse, row_x[j], row_y[j])
            if is_outside:
                outside += 1
            elif np.isnan(height):
                holed += 1
            elif not (-180.0 <= row_cols[j] <= 360.0 and -90.0 <= row_rows[j] <= 90.0):
                bad += 1
                height = np.nan
            heights[j] = height
        for j in range(width):
            row_cols[j], row_rows[j] = rpc_point(rpc, 0, row_cols[j], row_rows[j], heights[j])
        seen = 0
        for j in range(width):
            if np.isnan(heights[j]):
                row_cols[j] = -1.0
                row_rows[j] = -1.0
            elif 0.0 <= row_cols[j] < image_width and 0.0 <= row_rows[j] < image_height:
                seen += 1
        counts[i, _OUTSIDE_DEM] = outside
        counts[i, _OVER_HOLE] = holed
        counts[i, _BAD_LON_LAT] = bad
        counts[i, _SEES_IMAGE] = seen
    return 0


def _strip_coordinates(dst_gt, shape, start, stop, dst_crs, dem_crs, every=False):
    """Flat (lon, lat, dem_x, dem_y) of the cell centres of output rows start to stop.

    lon and lat come from PROJ for a projected grid, dem_x and dem_y for a DEM outside
    EPSG:4326; the others are empty (the compiled pass computes them from the grid), unless
    ``every``: then all four are computed, in NumPy, as GDAL does.
    """
    geographic, dem_geographic = is_lon_lat(dst_crs), is_lon_lat(dem_crs)
    lon = lat = dem_x = dem_y = _EMPTY
    if every or not geographic or not dem_geographic:
        x, y = (np.ravel(a) for a in np.broadcast_arrays(*grid_centres(dst_gt, shape, start,
                                                                         stop)))
        lon, lat = to_crs(x, y, dst_crs, "EPSG:4326")
    if every or not dem_geographic:
        dem_x, dem_y = to_crs(lon, lat, "EPSG:4326", dem_crs)
    if not every and geographic:
        lon = lat = _EMPTY
    return lon, lat, dem_x, dem_y


_EMPTY = np.empty(0)


def _gdalwarp_scale(rpc, prepared, dst_gt, shape, dst_crs, dem_crs, image_shape):
    """gdalwarp's XSCALE, YSCALE for an orthoimage: its grid's edges through the DEM and the RPC.

    As GDALWarpOperation::ComputeSourceWindow for one chunk (the whole grid): the grid's
    edge points go to longitude and latitude (PROJ), to the DEM (NaN off it: left out) and
    through the RPC into the image; :func:`rsgeo.resample.grid_scale` does the rest.
    """
    import affine

    def to_image(points):
        lon, lat = to_crs(points[:, 0], points[:, 1], dst_crs, "EPSG:4326")
        dem_x, dem_y = to_crs(lon, lat, "EPSG:4326", dem_crs)
        heights = sample_dem(prepared, dem_x, dem_y)[0]
        found = np.isfinite(heights) & (np.abs(lat) <= 90) & (np.abs(lon) <= 360)
        positions = np.full((len(points), 2), np.nan)
        positions[found] = np.column_stack(rpc.project(lon[found], lat[found],
                                                       heights[found]))
        return positions

    return grid_scale(to_image, shape, affine.Affine.from_gdal(*dst_gt), image_shape,
                      skip_failed=True)


# cells of one strip of orthorectify: 16 bytes each while it is computed (its source positions)
# on a grid in EPSG:4326, up to about 100 with PROJ's coordinates for a projected grid and DEM
_STRIP_CELLS = 2 ** 19


def orthorectify(image, rpc, dem, dem_transform, dst_transform, dst_shape, method="bilinear",
                 nodata=0, dst_crs=None, dem_crs=None, dem_nodata=None, num_threads=1,
                 strip_rows=None, dem_vertical=None, scale=None):
    """The orthoimage on an output grid: DEM height, RPC, interpolation, cell by cell.

    For each output cell centre: its longitude and latitude (through
    ``dst_crs`` when the grid is projected), its height from the DEM
    (bilinear, GDAL's :func:`~rsgeo.dem.dem_height`), the RPC's image position
    (:meth:`~rsgeo.sensors.RPCModel.project`), and the value there by
    :func:`rsgeo.resample.interpolate` (GDAL's kernels, widened as gdalwarp
    widens them when the output's pixels are larger than the image's: see
    ``scale``). This is ``gdalwarp -rpc -to RPC_DEM=dem.tif -to
    RPC_DEMINTERPOLATION=bilinear`` (whose error threshold is 0, the exact
    transformer, when ``RPC_DEM`` is given), tested pixel for pixel against
    GDAL 3.10.3's warper through ``rasterio.warp.reproject`` for nearest,
    bilinear and cubic, grids in EPSG:4326 and UTM finer and coarser than the
    image, with GDAL's own kernel scale and with XSCALE = YSCALE = 1
    (``tests/test_terrain.py``). gdalwarp computes the scale per chunk of its
    output: on an output too large for its warp memory (64 MB by default) its
    chunks may get other scales than this one, computed for the whole grid.

    Parameters
    ----------
    image : ndarray
        The raw image the RPC describes, (rows, cols) or (bands, rows, cols).
    rpc : RPCModel or mapping
        Its RPC (a mapping is read with :meth:`~rsgeo.sensors.RPCModel.from_dict`).
    dem : (rows, cols) array_like
        Heights (m) above what ``dem_vertical`` says; NaN marks holes.
    dem_transform : affine.Affine or sequence of 6 numbers
        The DEM's geotransform, in ``dem_crs``: an affine.Affine, or 6 numbers
        in GDAL's order (x0, pixel width, row rotation, y0, column rotation,
        pixel height), as :func:`rsgeo.data.save` reads them (a tuple in
        affine.Affine's order, pixel width first, is refused).
    dst_transform : affine.Affine or sequence of 6 numbers
        The output grid's geotransform, in ``dst_crs``; as ``dem_transform``.
    dst_shape : (rows, cols)
        Output grid size (refused if the output alone would not fit in
        this machine's memory).
    method : {"nearest", "bilinear", "cubic"}
        Interpolator for the image.
    nodata : number or None
        Value of output cells that see no pixel of the image.
    dst_crs, dem_crs : str, int or rasterio CRS, optional
        CRS of the output grid and of the DEM (see :func:`rsgeo.crs.as_crs`);
        None is EPSG:4326 (longitude, latitude in degrees).
    dem_nodata : float, optional
        DEM value marking holes, besides NaN.
    num_threads : int
        Threads for the compiled passes (DEM heights and RPC, interpolation)
        and for PROJ. The result does not depend on it.
    strip_rows : int, optional
        Output rows computed at a time (as :func:`rsgeo.resample.warp`):
        memory is the output plus one strip's working arrays, about 16
        bytes per cell with the grid and the DEM in EPSG:4326 (the source
        positions) and up to about 100 with PROJ's coordinates of a
        projected grid and DEM. By default about 2**19 cells a strip (256
        rows of a 2048-wide grid: 8 to 50 MB). The result does not depend
        on it.
    dem_vertical : {"ellipsoidal", "EGM96"}
        What the DEM's heights are above; required. An RPC takes heights
        above the WGS 84 ellipsoid, h = H + N; SRTM and Copernicus DEMs give
        H above a geoid (EGM96, EGM2008). "EGM96" adds the geoid undulation N
        (:func:`rsgeo.heights.geoid_on_grid`, at the DEM's cells) before the
        RPC, as ``gdalwarp`` does for a DEM whose CRS has the EGM96 height
        (``RPC_DEM_APPLY_VDATUM_SHIFT``); "ellipsoidal" takes the heights as
        they are (a DEM without a vertical CRS, in GDAL). Forgetting N moves
        every point N·tan θ.

    scale : float or (float, float), optional
        GDAL's XSCALE and YSCALE (``gdalwarp -wo XSCALE=… -wo YSCALE=…``):
        output pixels per image pixel along rows and columns; below 0.95,
        bilinear and cubic are widened over 1/scale image pixels, so that an
        orthoimage on a coarser grid averages the pixels under each cell
        instead of aliasing. By default gdalwarp's own: 21 points on each
        edge of the output grid taken through the DEM and the RPC into the
        image, the grid's columns (rows) over the width (height) of their
        bounding box there (:func:`rsgeo.resample.grid_scale`; edge points
        off the DEM are left out, as GDAL leaves out points its transformer
        fails on). Give 1 for the plain 2 × 2 and 4 × 4 kernels.

    Returns
    -------
    ndarray
        ``image``'s dtype, ``dst_shape`` (with bands first when several).

    Raises
    ------
    TypeError
        If a transform is neither an affine.Affine nor a sequence of numbers.
    ValueError
        If the image is not 2-D or 3-D, the method is unknown, the RPC
        mapping lacks keys, a transform is a 6-tuple in affine.Affine's order
        or its pixels have no area, a CRS is not one PROJ knows, the output
        would not fit in memory, ``strip_rows`` is not a positive whole
        number, the DEM does not cover the output grid (how
        many cells, the first one), the DEM has holes under the grid, the
        grid's longitudes or latitudes are out of range, or no output cell
        sees the image (a grid in the wrong place or CRS); if ``dem_vertical``
        is missing or unknown, or a DEM cell is outside the shipped geoid grid.

    References
    ----------
    GDAL, ``alg/gdal_rpc.cpp`` (``GDALRPCTransform``, ``GDALRPCGetDEMHeight``)
    and ``alg/gdalwarpkernel.cpp``.

    Examples
    --------
    >>> import affine
    >>> from rsgeo.sensors import simple_rpc_dict
    >>> rpc = RPCModel.from_dict(simple_rpc_dict())
    >>> image = np.arange(1000 * 1000, dtype=np.float32).reshape(1000, 1000)
    >>> dem = np.zeros((10, 10))
    >>> dem_gt = affine.Affine(0.01, 0, -34.95, 0, -0.01, -7.95)
    >>> grid = affine.Affine(0.001, 0, -34.91, 0, -0.001, -7.99)
    >>> ortho = orthorectify(image, rpc, dem, dem_gt, grid, (20, 20), "nearest",
    ...                      dem_vertical="EGM96")
    >>> ortho.shape
    (20, 20)
    """
    from .crs import as_crs
    from .heights import add_geoid, check_vertical

    image = as_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    rpc = rpc if isinstance(rpc, RPCModel) else RPCModel.from_dict(rpc)
    bands = image.shape[0] if image.ndim == 3 else 1
    shape = as_output_shape(dst_shape, image.dtype, bands, "dst_shape")
    strip_rows = (max(1, _STRIP_CELLS // shape[1]) if strip_rows is None
                  else as_integer(strip_rows, "strip_rows", low=1))
    scale = None if scale is None else as_scale(scale)
    dst_gt = as_gdal(dst_transform, "dst_transform")
    dst_crs = as_crs("EPSG:4326" if dst_crs is None else dst_crs, "dst_crs")
    dem_crs = as_crs("EPSG:4326" if dem_crs is None else dem_crs, "dem_crs")
    # a compound dem_crs states the DEM's vertical datum itself: refused if it contradicts
    check_vertical(dem_vertical, "dem_vertical", dem_crs, "dem_crs")
    prepared = prepare_dem(dem, dem_transform, dem_nodata)
    if dem_vertical != "ellipsoidal":
        # The RPC takes h = H + N. N is added once at the DEM's own cells and then interpolated
        # with the DEM, not looked up at every output cell as GDAL does: EGM96 is a 15' (28 km)
        # grid, bilinear inside each of its cells, so the two agree exactly where a DEM cell lies
        # inside one EGM96 cell and within 2 mm for a 90 m DEM where it straddles two (measured
        # over Brazil), N·tan θ of that is nothing, and it costs one lookup per DEM cell, not
        # one per output cell. Holes stay NaN. (rsgeo.heights.geoid_on_grid, added in place.)
        add_geoid(prepared[0], dem_transform, dem_crs, dem_vertical)
    height, width = image.shape[-2:]
    if scale is None:
        scale = _gdalwarp_scale(rpc, prepared, dst_gt, shape, dst_crs, dem_crs, (height, width))
    num_threads = as_num_threads(num_threads)
    out = np.empty((bands,) + shape, dtype=image.dtype)
    outside, holed = [0, 0.0, 0.0], [0, 0.0, 0.0]
    seen = False
    packed = rpc._packed()
    dem_work, dem_inverse = prepared[:2]
    strip_cells = min(strip_rows, shape[0]) * shape[1]
    cols, rows = np.empty(strip_cells), np.empty(strip_cells)
    counts = np.empty((min(strip_rows, shape[0]), 4), dtype=np.int64)
    # in strips of rows, as rsgeo.resample.warp: memory is the output plus one strip's
    # positions (each cell is computed alone, so the pixels do not depend on the strips)
    for start in range(0, shape[0], strip_rows):
        stop = min(start + strip_rows, shape[0])
        cells = (stop - start) * shape[1]
        # PROJ where a CRS is not the RPC's (it cannot run compiled), vectorised over the strip;
        # empty arrays tell the compiled pass to take the grid's or the DEM's own coordinates
        lon, lat, dem_x, dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                    dem_crs)
        # the strip's rows shared among threads: each call computes rows first .. last - 1
        run_in_row_blocks(partial(_ortho_positions, dst_gt, start, shape[1], lon, lat, dem_x,
                                  dem_y, dem_work, dem_inverse, packed, width, height, cols,
                                  rows, counts[:stop - start]),
                          stop - start, num_threads)
        found = counts[:stop - start].sum(axis=0)
        if found[_OUTSIDE_DEM] or found[_OVER_HOLE]:
            # the NumPy path of dem_height over this strip, for the messages' counts and
            # first points
            lon, lat, dem_x, dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                        dem_crs, every=True)
            _heights, strip_outside, strip_holed = sample_dem(prepared, dem_x, dem_y)
            for total, strip in ((outside, strip_outside), (holed, strip_holed)):
                if strip[0] and not total[0]:
                    total[1:] = strip[1:]
                total[0] += strip[0]
        if outside[0] or holed[0]:
            continue                      # counted over the whole grid, then refused below
        if found[_BAD_LON_LAT]:
            lon, lat, _dem_x, _dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                          dem_crs, every=True)
            as_lon_lat_height(lon, lat, 0.0)        # raises, naming the values out of range
        seen = seen or bool(found[_SEES_IMAGE])
        strip_shape = (stop - start, shape[1])
        out[:, start:stop] = interpolate(
            image, cols[:cells].reshape(strip_shape), rows[:cells].reshape(strip_shape),
            method, nodata=nodata, num_threads=num_threads, scale=scale).reshape(
                (bands,) + strip_shape)
    raise_dem_problems(prepared, outside, holed, shape[0] * shape[1])
    if not seen:
        raise GridError(_("no output cell sees the image ({height} x {width} px): the "
                          "grid is elsewhere; check dst_transform and dst_crs against "
                          "the RPC's area (lon {value:.4f}, lat {value2:.4f})").format(
                height=height, width=width, value=prose_number(rpc.offsets['LONG']),
                value2=prose_number(rpc.offsets['LAT'])))
    return out if image.ndim == 3 else out[0]


# -- Checking an orthoimage on the image itself --------------------------------

def map_on_grid(image, transform, dst_transform, dst_shape, method="bilinear", nodata=None):
    """A map image resampled onto another grid of the same CRS (GDAL's kernels).

    Each output cell centre is sent through ``~transform`` into ``image``
    and interpolated there by :func:`rsgeo.resample.interpolate`: the true
    ground on an orthoimage's grid, for :func:`positional_error`.

    Parameters
    ----------
    image : 2-D ndarray
        The map (e.g. the ground a simulation was made from).
    transform, dst_transform : affine.Affine
        Geotransforms of ``image`` and of the output grid, same CRS.
    dst_shape : (rows, cols)
        Output grid size.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number or None
        Value of cells outside ``image``.

    Returns
    -------
    ndarray
        ``image``'s dtype, ``dst_shape``.

    Raises
    ------
    ValueError
        If the image is not 2-D or the method is unknown.

    Examples
    --------
    >>> import affine
    >>> image = np.arange(16, dtype=np.float64).reshape(4, 4)
    >>> gt = affine.Affine(10, 0, 0, 0, -10, 40)
    >>> map_on_grid(image, gt, affine.Affine(20, 0, 0, 0, -20, 40), (2, 2)).tolist()
    [[2.5, 4.5], [10.5, 12.5]]
    """
    image = as_image(image)
    if image.ndim != 2:
        raise ImageError(_("image must be 2-D, got shape {image_shape}").format(
                image_shape=image.shape))
    check_choice(method, "method", METHODS)
    x, y = np.broadcast_arrays(*grid_centres(as_gdal(dst_transform, "dst_transform"),
                                              as_shape(dst_shape, "dst_shape")))
    inverse = gdal_inverse(as_gdal(transform, "transform"))
    cols = inverse[0] + x * inverse[1] + y * inverse[2]
    rows = inverse[3] + x * inverse[4] + y * inverse[5]
    return interpolate(image, cols, rows, method, nodata=nodata)


def positional_error(image, truth, step=64, window=64, nodata=0, upsample=100, taper=True):
    """Where a corrected image puts the ground, measured on the image against the truth.

    ``truth`` is the true ground on the same grid (:func:`map_on_grid` of
    the map a simulation was made from, or a reference orthoimage); at the
    check points of a regular grid the local shift between the two images'
    windows is measured by correlation (:func:`rsgeo.registration.measure_shifts`;
    Hann-tapered by default, which smooth images need), skipping windows that touch a ``nodata``
    pixel of ``image``. This measures
    the image itself (its DEM, model and resampling together), not the
    model's fit at points.

    Parameters
    ----------
    image, truth : (rows, cols) array_like
        The corrected image and the truth, same grid.
    step, window : int
        Spacing of the check points and size of their windows, pixels.
    nodata : number or None
        ``image``'s value outside its footprint.
    upsample : int
        Sub-pixel precision: 1 / upsample pixel.
    taper : bool
        Hann-tapered cross-correlation (True) or phase correlation.

    Returns
    -------
    pandas.DataFrame
        One row per check point: ``col``, ``row`` (its position),
        ``dcol``, ``drow`` (the shift that moves ``image`` onto ``truth``,
        pixels) and ``error`` (its length, pixels).

    Raises
    ------
    ValueError
        As :func:`rsgeo.registration.measure_shifts`, or if no window lies wholly
        inside the image's footprint.

    Examples
    --------
    >>> truth = np.random.default_rng(0).random((128, 128))
    >>> table = positional_error(np.roll(truth, 2, axis=1), truth, nodata=None)
    >>> table["dcol"].round(1).tolist(), table["drow"].round(1).tolist()
    ([-2.0, -2.0, -2.0, -2.0], [0.0, 0.0, 0.0, 0.0])
    """
    import pandas as pd

    image = np.asarray(image)
    valid = None if nodata is None else image != nodata
    points, shifts = measure_shifts(truth, image, step, window, upsample=upsample, taper=taper,
                                    valid=valid)
    if len(points) == 0:
        raise GridError(_("no check-point window lies wholly inside the image's footprint; use "
                          "a smaller window or step"))
    return pd.DataFrame({"col": points[:, 0], "row": points[:, 1], "dcol": shifts[:, 0],
                         "drow": shifts[:, 1], "error": np.hypot(shifts[:, 0], shifts[:, 1])})
