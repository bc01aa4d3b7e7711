"""Scenes larger than memory: a warp made tile by tile, in one process or on Dask.

Production warpers never hold a whole scene. gdalwarp cuts the output grid
into chunks that fit its warp memory (``-wm``), asks its transformer where
each chunk's cells fall in the source, reads only that *source window*
(widened by the kernel's reach) and warps the chunk from it. rsgeo does the
same here: :func:`tiles` cuts an output grid into tiles (a tile is a smaller
grid: its shape, and the grid's geotransform moved to its first cell, as
gdalwarp's ``-te``/``-ts`` of one tile), :func:`source_window` finds the
source pixels a tile reads, and :func:`warp_tiled` warps tile after tile
from those windows, reading them from an array or from a raster file, and
writing each tile into an array or into a raster open for writing: memory
is one tile, its window and its positions (plus the output, when it is an
array). :func:`warp_dask` builds the same tiles as a Dask array
(``dask.array.map_blocks``, one block per tile, each reading its own window
from the file), to be computed by Dask's schedulers on one machine or on a
cluster.

**Seam-free.** Every tile is warped with the kernel scale of the *whole*
grid (:func:`rsgeo.resample.grid_scale`, GDAL's XSCALE/YSCALE: gdalwarp, in
contrast, computes one per chunk, which is why its chunks can differ at
their seams when it downsamples or the source is rotated), and its window
reaches past every position by the kernel's reach, clipped only at the
source's own edges, so each kernel sees exactly the pixels, and the edges,
it sees in the whole source. The result equals one :func:`rsgeo.resample.warp`
call over the grid, pixel for pixel (tested: 0 differing pixels, for
nearest, bilinear, cubic and average, affine, polynomial and thin-plate
spline mappings and Python callables, tiles that do not divide the grid,
tiles partly or wholly outside the source, downsampling), when
``error_threshold`` is 0: GDAL's approximation interpolates along each row
of a tile, so approximated tiles narrower than the grid differ from one
approximated warp in the last bits of their positions (as gdalwarp's chunks
do); tiles as wide as the grid are equal again.

Each tile is warped as a *window* of the grid
(``warp(..., dst_offset=(col, row))``), as gdalwarp's kernel warps a chunk
(``iDstX + 0.5 + nDstXOff`` with the grid's geotransform): a tile's own
geotransform, the grid's ``@ Affine.translation(col, row)``, would round its
origin and move its cell centres in the last bit wherever the pixel size is
not a binary fraction (0.001 degree, the pixel size
:func:`rsgeo.resample.suggested_grid` derives without a resolution); so
would gdalwarp run with ``-te``/``-ts`` per tile.

**georeference, tile by tile.** :func:`rsgeo.resample.georeference` fits the
GCPs, takes gdalwarp's suggested grid and warps. For a scene larger than
memory, make the same three steps with the tiled warp::

    import rasterio
    from rsgeo import gcp, resample

    gcps = gcp.read_points("scene.tif.points")
    model = gcps.fit(2)                      # map (x, y) -> image (col, row)
    reverse = model.reverse()                # image -> map, for the footprint
    with rasterio.open("scene.tif") as source:
        src_shape = source.height, source.width
    transform, shape = resample.suggested_grid(src_shape, reverse, resolution=20.0)
    with rasterio.open("corrected.tif", "w", driver="GTiff", height=shape[0],
                       width=shape[1], count=1, dtype="uint8", crs=gcps.crs,
                       transform=transform, nodata=0, tiled=True) as out:
        resample.warp_tiled("scene.tif", model, shape, transform, method="cubic", out=out)

(``model.inverse()`` for models without ``reverse``; with another output
CRS, the mapping is ``rsgeo.resample.CRSMapping(model, gcps.crs, dst_crs)``
and the footprint the reverse model followed by
:func:`rsgeo.crs.transform_points`.) The pixels are
:func:`~rsgeo.resample.georeference`'s: the same grid, model and kernel scale
(a resolution in whole metres keeps the grid's sums exact).

**orthorectify, tile by tile.** :func:`rsgeo.ortho.orthorectify` takes
its output grid (``dst_transform``, ``dst_shape``) and computes each cell
alone, with the plain kernels (scale 1), so a tile of :func:`tiles` is one
call with the tile's transform and shape, and the tiles join without seams
(tested). The raw image is still passed whole: it has no source window yet.

References
----------
GDAL, ``alg/gdalwarpoperation.cpp`` (``GDALWarpOperation::ChunkAndWarpImage``,
``ComputeSourceWindow``: chunks, their source windows and the kernel's
extra pixels, ``nResWinSize``) and ``apps/gdalwarp_lib.cpp`` (``-te``,
``-ts``, ``-wm``).
"""

import functools
import os
from typing import NamedTuple

import affine
import numpy as np

from .._deprecated import renamed_arguments
from .._kernels.resampling import GDAL_INDEX_EPSILON, RADIUS, WARP_METHODS
from .._kernels.transformer import pack, positions
from ..errors import GridError, ImageError
from ..language import N_, _
from ..validation import (
    as_affine,
    as_bands_first,
    as_image,
    as_nodata,
    as_num_threads,
    as_number,
    as_output_shape,
    as_scale,
    as_shape,
    check_choice,
)
from ._warp import (
    call_mapping,
    check_mapping,
    grid_positions,
    grid_scale,
    nothing_lands_message,
    warp,
)

__all__ = ["Tile", "SourceWindow", "tiles", "source_window", "warp_tiled", "warp_dask"]

# lattice of cell centres warp_dask samples to refuse a grid that lands nowhere
_LATTICE = 65


class Tile(NamedTuple):
    """One tile of an output grid: where it starts in the grid, its shape and geotransform."""

    row: int
    col: int
    shape: tuple
    transform: affine.Affine


class SourceWindow(NamedTuple):
    """The source pixels a tile reads: rows ``row_off`` to ``row_off + rows``, likewise cols."""

    row_off: int
    col_off: int
    rows: int
    cols: int

    def slices(self):
        """The window as (row slice, col slice), for indexing an array's last two axes.

        Returns
        -------
        (slice, slice)
        """
        return (slice(self.row_off, self.row_off + self.rows),
                slice(self.col_off, self.col_off + self.cols))

    def rasterio(self):
        """The window as a ``rasterio.windows.Window`` (col_off, row_off, width, height).

        Returns
        -------
        rasterio.windows.Window
        """
        from rasterio.windows import Window

        return Window(self.col_off, self.row_off, self.cols, self.rows)


def tiles(shape, transform=None, tile_shape=(1024, 1024)):
    """Cut an output grid into tiles, row by row: each a grid of its own.

    Parameters
    ----------
    shape : (rows, cols)
        The whole output grid's size.
    transform : affine.Affine, optional
        Its geotransform (pixel corner -> map); identity if omitted.
    tile_shape : (rows, cols)
        The size of a tile; the last row and column of tiles are cut to the grid.

    Returns
    -------
    list of Tile
        ``Tile(row, col, shape, transform)``: the tile's first cell in the
        grid, its (rows, cols) and its geotransform, the grid's times
        ``Affine.translation(col, row)``.

    Raises
    ------
    rsgeo.errors.GridError
        If ``shape`` or ``tile_shape`` is not two positive integers, or the
        transform holds NaN or infinity.
    TypeError
        If ``transform`` is not an ``affine.Affine``.

    Examples
    --------
    >>> grid = tiles((300, 200), tile_shape=(128, 128))
    >>> len(grid), grid[-1].row, grid[-1].col, grid[-1].shape
    (6, 256, 128, (44, 72))
    >>> tiles((4, 4), affine.Affine(10, 0, 500, 0, -10, 800), (2, 2))[3].transform.c
    520.0
    """
    rows, cols = as_shape(shape)
    tile_rows, tile_cols = as_shape(tile_shape, "tile_shape")
    to_map = as_affine(transform) if transform is not None else affine.Affine.identity()
    return [Tile(row, col, (min(tile_rows, rows - row), min(tile_cols, cols - col)),
                 to_map @ affine.Affine.translation(col, row))
            for row in range(0, rows, tile_rows) for col in range(0, cols, tile_cols)]


def _reach(method, scale):
    """Source pixels a kernel reads beyond the pixel under a position, (x, y).

    Nearest reads that pixel (1: one more against rounding); bilinear 2
    x 2 (2); cubic 4 x 4 (3); when bilinear or cubic is widened (a scale
    below 0.95), ceil(radius / scale) + 2 along an axis whose scale is below
    1 (GDAL's taps, from the pixel left of and above the position); average
    reads between its cell's corners (2 beyond the corners' pixels).
    """
    xscale, yscale = scale
    if method == "average":
        return 2, 2
    if method == "nearest":
        return 1, 1
    if xscale >= 0.95 and yscale >= 0.95:
        return {"bilinear": 2, "cubic": 3}[method], {"bilinear": 2, "cubic": 3}[method]
    radius = RADIUS[method]
    return tuple(int(np.ceil(radius / value)) + 2 if value < 1.0 else radius + 2
                 for value in (xscale, yscale))


def _tile_positions(mapping, tile_shape, tile_transform, method, error_threshold):
    """Where a tile's cell centres (average: its cell corners) fall in the source: cols, rows.

    A compiled mapping gives the kernels' own positions (rsgeo._kernels.transformer);
    any other is called at the cells' map coordinates, as warp calls it.
    """
    rows, cols = tile_shape
    if method == "average":
        # the cells' corners: one more row and column, half a cell up and left of the centres
        tile_shape = (rows + 1, cols + 1)
        tile_transform = tile_transform @ affine.Affine.translation(-0.5, -0.5)
        error_threshold = 0.0          # average takes its corners exactly
    packed = pack(mapping, tile_transform, error_threshold=error_threshold)
    if packed is not None:
        return positions(packed, tile_shape)
    x, y = grid_positions(tile_shape, tile_transform)
    source = call_mapping(mapping, x, y)
    return source[:, 0], source[:, 1]


def _window_and_span(mapping, tile_shape, tile_transform, src_shape, method, scale,
                     error_threshold):
    """(SourceWindow or None, the positions' span (col min, col max, row min, row max) or None).

    The window is None when no position lands in the source (for average:
    when the cells' corners all miss it); the span says where the tile went.
    """
    cols, rows = _tile_positions(mapping, tile_shape, tile_transform, method, error_threshold)
    finite = np.isfinite(cols) & np.isfinite(rows)
    if not finite.any():
        return None, None
    cols, rows = cols[finite], rows[finite]
    col_min, col_max, row_min, row_max = cols.min(), cols.max(), rows.min(), rows.max()
    span = (col_min, col_max, row_min, row_max)
    height, width = src_shape
    if method == "average":
        # GDAL's test of a cell against the source (_cell_span): its corners' box meets it
        lands = (col_max > -GDAL_INDEX_EPSILON and col_min < width + GDAL_INDEX_EPSILON
                 and row_max > -GDAL_INDEX_EPSILON and row_min < height + GDAL_INDEX_EPSILON)
    else:
        # GDAL's rule, as rsgeo.resample's kernels apply it: [0, W) x [0, H)
        lands = bool(np.any((cols >= 0.0) & (rows >= 0.0)
                            & (np.floor(cols + GDAL_INDEX_EPSILON) < width)
                            & (np.floor(rows + GDAL_INDEX_EPSILON) < height)))
    if not lands:
        return None, span
    x_reach, y_reach = _reach(method, scale)
    # in floats first: a wild position (1e300) must not become a huge integer
    left = int(max(np.floor(col_min) - x_reach, 0.0))
    right = int(min(np.floor(col_max) + 1.0 + x_reach, float(width)))
    top = int(max(np.floor(row_min) - y_reach, 0.0))
    bottom = int(min(np.floor(row_max) + 1.0 + y_reach, float(height)))
    if left >= right or top >= bottom:
        return None, span
    return SourceWindow(top, left, bottom - top, right - left), span


def source_window(mapping, tile_shape, tile_transform, src_shape, method="nearest",
                  scale=(1.0, 1.0), error_threshold=0.0):
    """The source pixels a tile of the output grid reads, or None if it reads none.

    The bounding box of where the tile's cells fall in the source (their
    centres; for "average" their corners), widened by the kernel's reach and
    cut to the source: inside it the kernels see the pixels, and the image
    edges, they see in the whole source, so a warp of the window (with
    ``src_offset`` and the whole grid's ``scale``) gives the tile's pixels
    of the whole warp. As GDAL's ``ComputeSourceWindow``, with every cell's
    position, not a sample: a curved model can reach farther inside a tile
    than at its edges.

    Parameters
    ----------
    mapping : callable or affine.Affine
        Map (x, y) -> source (col, row), as in :func:`rsgeo.resample.warp`.
    tile_shape : (rows, cols)
        The tile's size.
    tile_transform : affine.Affine
        The tile's geotransform (:func:`tiles` gives it).
    src_shape : (rows, cols)
        The whole source's size.
    method : {"nearest", "bilinear", "cubic", "average"}
        The kernel, whose reach widens the window.
    scale : float or (float, float)
        The whole warp's kernel scale (XSCALE, YSCALE): below 0.95, bilinear
        and cubic reach over 1/scale source pixels.
    error_threshold : float
        The warp's approximation threshold (0: exact), so that the window
        holds the approximated positions the kernels will use.

    Returns
    -------
    SourceWindow or None
        ``SourceWindow(row_off, col_off, rows, cols)``; None when no cell of
        the tile falls inside the source (the tile is all nodata).

    Raises
    ------
    rsgeo.errors.GridError
        If a shape is not two positive integers, or ``tile_transform`` holds
        NaN or infinity.
    ValueError
        If the method is unknown, ``scale`` is not positive, ``error_threshold``
        is negative, or ``mapping`` does not return an (n, 2) array.
    TypeError
        If ``mapping`` is neither callable nor an ``affine.Affine``, or
        ``tile_transform`` is not an ``affine.Affine``.

    References
    ----------
    GDAL, ``alg/gdalwarpoperation.cpp``: ``ComputeSourceWindow`` and its
    ``nResWinSize``, the kernel's extra pixels.

    Examples
    --------
    >>> shift = affine.Affine.translation(100, 50)       # output (x, y) -> source (x + 100, ...)
    >>> source_window(shift, (10, 20), affine.Affine.identity(), (300, 400), "bilinear")
    SourceWindow(row_off=48, col_off=98, rows=14, cols=24)
    >>> source_window(shift, (10, 20), affine.Affine.translation(500, 0), (300, 400)) is None
    True
    """
    tile_shape = as_shape(tile_shape, "tile_shape")
    tile_transform = as_affine(tile_transform, "tile_transform")
    src_shape = as_shape(src_shape, "src_shape")
    check_choice(method, "method", WARP_METHODS)
    check_mapping(mapping)
    scale = as_scale(scale)
    error_threshold = as_number(error_threshold, "error_threshold", low=0.0,
                                why=N_("source pixels; 0 for exact positions"))
    return _window_and_span(mapping, tile_shape, tile_transform, src_shape, method, scale,
                            error_threshold)[0]


# -- sources and outputs --------------------------------------------------------


class _ArraySource:
    """An image in memory, read window by window (a view: warp copies what it needs)."""

    def __init__(self, image):
        self.image = as_bands_first(as_image(image, "source"), "source")
        self.shape = self.image.shape[-2:]
        self.bands = self.image.shape[0] if self.image.ndim == 3 else 1
        self.ndim = self.image.ndim
        self.dtype = self.image.dtype

    def read(self, window):
        rows, cols = window.slices()
        return self.image[..., rows, cols]

    def close(self):
        pass


class _RasterSource:
    """A raster file (or an open rasterio dataset), read window by window from the disk."""

    def __init__(self, source):
        import rasterio

        self.owned = isinstance(source, (str, os.PathLike))
        self.dataset = rasterio.open(source) if self.owned else source
        dtypes = set(self.dataset.dtypes)
        if len(dtypes) != 1:
            self.close()
            raise ImageError(_(
                "source {name} has bands of several dtypes ({dtypes}); a warp needs one dtype "
                "for all bands: convert it first, e.g. with gdal_translate -ot").format(
                    name=self.dataset.name, dtypes=", ".join(sorted(dtypes))))
        self.shape = (self.dataset.height, self.dataset.width)
        self.bands = self.dataset.count
        # one band reads as a 2-D image, as dataset.read(1) does
        self.ndim = 3 if self.bands > 1 else 2
        self.dtype = np.dtype(dtypes.pop())

    def read(self, window):
        if self.ndim == 2:
            return self.dataset.read(1, window=window.rasterio())
        return self.dataset.read(window=window.rasterio())

    def close(self):
        if self.owned:
            self.dataset.close()


def _open_source(source):
    """The source as an object with shape, bands, ndim, dtype, read(window) and close()."""
    if isinstance(source, (str, os.PathLike)) or hasattr(source, "read"):
        return _RasterSource(source)
    return _ArraySource(source)


def _check_out(out, source, shape):
    """Refuse an output whose shape, bands or dtype differ from the warp's result."""
    expected = (source.bands,) + shape if source.ndim == 3 else shape
    if isinstance(out, np.ndarray):
        if out.shape != expected:
            raise GridError(_(
                "out has shape {got}, but the warp gives {expected} (the grid's shape, bands "
                "first when the source has several); allocate it with that shape").format(
                    got=out.shape, expected=expected))
        if out.dtype != source.dtype:
            raise ImageError(_(
                "out has dtype {got}, but the warp gives the source's dtype {expected}; "
                "allocate out with dtype {expected}").format(got=out.dtype,
                                                             expected=source.dtype))
        return
    if not hasattr(out, "mode"):
        raise TypeError(_(
            "out must be a NumPy array or a rasterio dataset open for writing, got "
            "{kind}").format(kind=type(out).__name__))
    if out.mode not in ("w", "r+") or not hasattr(out, "write"):
        raise ImageError(_(
            "out ({name}) is open for reading (mode {mode!r}); open it with mode 'w' or "
            "'r+'").format(name=out.name, mode=out.mode))
    got = (out.count, out.height, out.width)
    if got != (source.bands,) + shape:
        raise GridError(_(
            "out ({name}) has {got[0]} band(s) of {got[1]} x {got[2]} pixels, but the warp "
            "gives {bands} band(s) of {rows} x {cols}; create it with the grid's shape and the "
            "source's band count").format(name=out.name, got=got, bands=source.bands,
                                           rows=shape[0], cols=shape[1]))
    if set(out.dtypes) != {source.dtype.name}:
        raise ImageError(_(
            "out ({name}) holds {got}, but the warp gives the source's dtype {expected}; "
            "create it with dtype={expected!r}").format(
                name=out.name, got=", ".join(sorted(set(out.dtypes))),
                expected=source.dtype.name))


def _store_tile(out, tile, pixels):
    """Write a tile's pixels into the output array or raster."""
    rows, cols = tile.shape
    if isinstance(out, np.ndarray):
        out[..., tile.row:tile.row + rows, tile.col:tile.col + cols] = pixels
        return
    from rasterio.windows import Window

    window = Window(tile.col, tile.row, cols, rows)
    if pixels.ndim == 2:
        out.write(pixels, 1, window=window)
    else:
        out.write(pixels, window=window)


def _warp_one_tile(source, mapping, grid_transform, tile, method, nodata, scale,
                   error_threshold, src_nodata, num_threads, fill):
    """A tile's pixels and whether any landed: (pixels, landed, span).

    The tile is warped as a window of the whole grid (``dst_offset``), as
    gdalwarp warps a chunk: its cells' centres are the grid's, to the last bit.
    """
    window, span = _window_and_span(mapping, tile.shape, tile.transform, source.shape, method,
                                    scale, error_threshold)
    tile_shape = (source.bands,) + tile.shape if source.ndim == 3 else tile.shape
    if window is None:
        return np.full(tile_shape, fill, dtype=source.dtype), False, span
    try:
        pixels = warp(source.read(window), mapping, tile.shape, grid_transform, method=method,
                      dst_nodata=nodata, num_threads=num_threads, scale=scale,
                      src_nodata=src_nodata, error_threshold=error_threshold,
                      src_offset=(window.col_off, window.row_off),
                      dst_offset=(tile.col, tile.row))
    except GridError:
        # the tile's window meets the source but none of its cells lands inside (every
        # other GridError of warp concerns arguments checked before the first tile): the
        # whole warp gives these cells nodata too
        return np.full(tile_shape, fill, dtype=source.dtype), False, span
    return pixels, True, span


@renamed_arguments(
    ("source", "mapping", "shape", "transform", "tile_shape", "method", "nodata",
     "num_threads", "error_threshold", "out", "scale", "src_nodata"),
    {"shape": "dst_shape", "transform": "dst_transform", "nodata": "dst_nodata"})
def warp_tiled(source, mapping, dst_shape, dst_transform=None, *, tile_shape=(1024, 1024),
               method="nearest", dst_nodata=0, num_threads=1, error_threshold=0.0, out=None,
               scale=None, src_nodata=None):
    """:func:`rsgeo.resample.warp` made tile by tile, each tile from its own source window.

    The output grid is cut into tiles (:func:`tiles`); each tile's source
    window (:func:`source_window`) is read, from the array or from the
    file, and warped with the whole grid's kernel scale; the tile is written
    into ``out``. The pixels are one ``warp`` call's, with no seams (see the
    module's notes: with ``error_threshold`` > 0, tiles as wide as the grid).
    Memory: one tile, its window and
    its positions, plus ``out`` when it is an array.

    Parameters
    ----------
    source : ndarray, path or rasterio dataset
        The source image (2-D, or 3-D bands first), or a raster file (a path,
        or a dataset open for reading), of which only each tile's window is
        read; a one-band raster reads as a 2-D image.
    mapping : callable or affine.Affine
        Map (x, y) -> source (col, row), as in :func:`rsgeo.resample.warp`.
    dst_shape : (rows, cols)
        The whole output grid's size.
    dst_transform : affine.Affine, optional
        Its geotransform; identity (output pixel coordinates) if omitted.
    tile_shape : (rows, cols)
        Size of a tile; the result does not depend on it.
    method : {"nearest", "bilinear", "cubic", "average"}
        As in :func:`rsgeo.resample.warp`.
    dst_nodata : number or None
        As in :func:`rsgeo.resample.warp`.
    num_threads : int
        Threads for each tile's kernel.
    error_threshold : float
        GDAL's approximation (see :func:`rsgeo.resample.warp`), along each
        row of a tile: equal to one warp only with tiles as wide as the grid.
    out : ndarray or rasterio dataset, optional
        Where to write: an array of the result's shape and dtype, or a
        raster open for writing (mode "w" or "r+") with the grid's size, the
        source's band count and dtype. A new array if omitted.
    scale : float or (float, float), optional
        The kernel scale (XSCALE, YSCALE); the whole grid's
        (:func:`rsgeo.resample.grid_scale`) if omitted, as one warp takes it.
    src_nodata : number or None
        The source's nodata (gdalwarp's ``-srcnodata``), as in
        :func:`rsgeo.resample.warp`; a raster's own nodata is not read
        unless given here (``src_nodata=dataset.nodata``).

    Returns
    -------
    ndarray or rasterio dataset
        ``out`` (the new array when it was omitted): ``shape``, or bands
        first, in the source's dtype.

    Raises
    ------
    ValueError
        As :func:`rsgeo.resample.warp` (no cell of the whole grid lands in
        the source, an unknown method, a nodata that does not fit the
        dtype, ...); if ``shape`` or ``tile_shape`` is not two positive
        integers; if ``out`` differs from the result in shape, bands or
        dtype, or is a raster open for reading; if the raster's bands differ
        in dtype.
    TypeError
        As :func:`rsgeo.resample.warp`; if ``out`` is neither an array nor a
        rasterio dataset.

    References
    ----------
    GDAL, ``alg/gdalwarpoperation.cpp``: ``ChunkAndWarpImage`` and
    ``ComputeSourceWindow``.

    Examples
    --------
    >>> image = np.arange(300 * 400, dtype=np.float32).reshape(300, 400)
    >>> mapping = affine.Affine.rotation(3) @ affine.Affine.scale(0.9)
    >>> whole = warp(image, mapping, (250, 350), method="cubic")
    >>> tiled = warp_tiled(image, mapping, (250, 350), tile_shape=(64, 100), method="cubic")
    >>> int(np.count_nonzero(tiled != whole))
    0
    """
    shape, transform, nodata = dst_shape, dst_transform, dst_nodata
    shape = as_shape(shape)
    tile_list = tiles(shape, transform, tile_shape)
    check_choice(method, "method", WARP_METHODS)
    check_mapping(mapping)
    num_threads = as_num_threads(num_threads)
    error_threshold = as_number(error_threshold, "error_threshold", low=0.0,
                                why=N_("source pixels; 0 for exact positions"))
    source = _open_source(source)
    try:
        nodata = as_nodata(nodata, source.dtype)
        if out is None:
            as_output_shape(shape, source.dtype, source.bands)
            out = np.empty((source.bands,) + shape if source.ndim == 3 else shape,
                           dtype=source.dtype)
        else:
            _check_out(out, source, shape)
        to_map = as_affine(transform) if transform is not None else affine.Affine.identity()
        scale = (as_scale(scale) if scale is not None
                 else grid_scale(mapping, shape, to_map, source.shape))
        fill = 0 if nodata is None else nodata
        landed = False
        spans = []
        for tile in tile_list:
            pixels, tile_landed, span = _warp_one_tile(source, mapping, to_map, tile, method,
                                                       nodata, scale, error_threshold,
                                                       src_nodata, num_threads, fill)
            _store_tile(out, tile, pixels)
            landed = landed or tile_landed
            if span is not None and not landed:
                spans.append(span)
        if not landed:
            height, width = source.shape
            raise GridError(nothing_lands_message(
                mapping, spans or [(np.nan,) * 4], width, height))
    finally:
        source.close()
    return out


# -- Dask -------------------------------------------------------------------------


def _dask_block(block_info=None, *, path, mapping, transform, method, nodata, scale,
                error_threshold, src_nodata):
    """One block of warp_dask: opens the file, reads the tile's window, warps the tile."""
    location = block_info[None]["array-location"]
    (row, row_stop), (col, col_stop) = location[-2:]
    tile = Tile(row, col, (row_stop - row, col_stop - col),
                transform @ affine.Affine.translation(col, row))
    source = _RasterSource(path)
    try:
        fill = 0 if nodata is None else nodata
        pixels, _landed, _span = _warp_one_tile(source, mapping, transform, tile, method,
                                                nodata, scale, error_threshold, src_nodata, 1,
                                                fill)
    finally:
        source.close()
    return pixels


def _check_grid_meets_source(mapping, shape, transform, src_shape):
    """Refuse a grid whose cells all fall outside the source, from a lattice of its cells.

    A coarse check (warp_dask's blocks are computed later, each alone): a
    lattice of cell centres, the grid's edges included, is taken to the
    source; if none lands inside and their bounding box misses the source,
    the mapping goes the wrong way or the grid is elsewhere.
    """
    rows, cols = shape
    lattice_cols, lattice_rows = np.meshgrid(
        np.unique(np.linspace(0, cols - 1, _LATTICE).round()) + 0.5,
        np.unique(np.linspace(0, rows - 1, _LATTICE).round()) + 0.5)
    x, y = transform @ (lattice_cols.ravel(), lattice_rows.ravel())
    source = call_mapping(mapping, x, y)
    finite = np.isfinite(source).all(axis=1)
    height, width = src_shape
    if finite.any():
        col, row = source[finite, 0], source[finite, 1]
        inside = (col >= 0) & (row >= 0) & (col < width) & (row < height)
        meets = (col.max() >= 0 and row.max() >= 0 and col.min() < width
                 and row.min() < height)
        if inside.any() or meets:
            return
        spans = [(col.min(), col.max(), row.min(), row.max())]
    else:
        spans = [(np.nan,) * 4]
    raise GridError(nothing_lands_message(mapping, spans, width, height))


@renamed_arguments(
    ("source_path", "mapping", "shape", "transform", "tile_shape", "method", "nodata",
     "error_threshold", "scale", "src_nodata"),
    {"shape": "dst_shape", "transform": "dst_transform", "nodata": "dst_nodata"})
def warp_dask(source_path, mapping, dst_shape, dst_transform=None, *, tile_shape=(1024, 1024),
              method="nearest", dst_nodata=0, error_threshold=0.0, scale=None, src_nodata=None):
    """The tiled warp as a Dask array: one block per tile, each reading its own window.

    Built with ``dask.array.map_blocks`` over the output tiles; a block
    opens the raster file, reads its tile's source window
    (:func:`source_window`) and warps it with the whole grid's kernel scale,
    as :func:`warp_tiled` does, so nothing larger than a tile travels
    between Dask's workers (the graph holds the path, the mapping and a few
    numbers). Computed by any Dask scheduler, the array is one
    :func:`rsgeo.resample.warp` call's result (under the conditions of the
    module's notes)::

        import dask
        array = warp_dask("scene.tif", model, shape, transform, tile_shape=(1024, 1024),
                          method="cubic")
        with dask.config.set(scheduler="processes", num_workers=2):
            corrected = array.compute()           # or dask.array.to_zarr, array.store(...)

    rsgeo's compiled kernels hold Python's lock (the GIL) while they run, so
    Dask's thread scheduler runs one tile's kernel at a time; its process
    scheduler (or a ``distributed.LocalCluster`` of processes) warps tiles
    in parallel.

    Parameters
    ----------
    source_path : str or path
        The source raster file (GeoTIFF or anything GDAL reads); a one-band
        raster gives a 2-D array, several bands a 3-D one (bands first).
    mapping : callable or affine.Affine
        Map (x, y) -> source (col, row), as in :func:`rsgeo.resample.warp`;
        it must pickle for a process scheduler (rsgeo's models and
        ``affine.Affine`` do; a lambda does not).
    dst_shape : (rows, cols)
        The whole output grid's size.
    dst_transform : affine.Affine, optional
        Its geotransform; identity if omitted.
    tile_shape : (rows, cols)
        Size of a tile: Dask's chunks along rows and columns.
    method : {"nearest", "bilinear", "cubic", "average"}
        As in :func:`rsgeo.resample.warp`.
    dst_nodata : number or None
        As in :func:`rsgeo.resample.warp`.
    error_threshold : float
        GDAL's approximation, along each row of a tile (see :func:`warp_tiled`).
    scale : float or (float, float), optional
        The kernel scale; the whole grid's if omitted.
    src_nodata : number or None
        The source's nodata, as in :func:`warp_tiled`.

    Returns
    -------
    dask.array.Array
        ``shape`` (bands first when several), the source's dtype, chunks of
        ``tile_shape``; not computed.

    Raises
    ------
    ImportError
        If Dask is not installed (``pip install rsgeo[tiles]``).
    ValueError
        As :func:`warp_tiled`, checked before any block is computed; a grid
        none of whose cells on a 65 x 65 lattice (edges included) falls
        near the source is refused as :func:`rsgeo.resample.warp` refuses it.
        A block whose cells all fall outside the source is nodata.
    TypeError
        As :func:`warp_tiled`.

    Examples
    --------
    >>> import tempfile, rasterio, dask
    >>> image = np.arange(300 * 400, dtype=np.float32).reshape(300, 400)
    >>> path = tempfile.mkdtemp() + "/source.tif"
    >>> with rasterio.open(path, "w", driver="GTiff", width=400, height=300, count=1,
    ...                    dtype="float32") as dataset:
    ...     dataset.write(image, 1)
    >>> mapping = affine.Affine.rotation(3) @ affine.Affine.scale(0.9)
    >>> array = warp_dask(path, mapping, (250, 350), tile_shape=(64, 100), method="cubic")
    >>> array.chunks
    ((64, 64, 64, 58), (100, 100, 100, 50))
    >>> with dask.config.set(scheduler="threads", num_workers=2):
    ...     tiled = array.compute()
    >>> int(np.count_nonzero(tiled != warp(image, mapping, (250, 350), method="cubic")))
    0
    >>> import shutil; shutil.rmtree(os.path.dirname(path))
    """
    shape, transform, nodata = dst_shape, dst_transform, dst_nodata
    try:
        import dask.array as da
    except ImportError as error:
        raise ImportError(_(
            "warp_dask needs Dask: pip install 'rsgeo[tiles]' (or dask[array]); warp_tiled "
            "makes the same tiles without it")) from error
    shape = as_shape(shape)
    tile_rows, tile_cols = as_shape(tile_shape, "tile_shape")
    to_map = as_affine(transform) if transform is not None else affine.Affine.identity()
    check_choice(method, "method", WARP_METHODS)
    check_mapping(mapping)
    error_threshold = as_number(error_threshold, "error_threshold", low=0.0,
                                why=N_("source pixels; 0 for exact positions"))
    if not isinstance(source_path, (str, os.PathLike)):
        raise TypeError(_(
            "source_path must be the path of a raster file (each block opens it), got "
            "{kind}; for an array in memory use warp_tiled").format(
                kind=type(source_path).__name__))
    source = _RasterSource(source_path)
    source.close()
    nodata = as_nodata(nodata, source.dtype)
    scale = (as_scale(scale) if scale is not None
             else grid_scale(mapping, shape, to_map, source.shape))
    _check_grid_meets_source(mapping, shape, to_map, source.shape)
    rows, cols = shape
    chunks = (tuple(min(tile_rows, rows - row) for row in range(0, rows, tile_rows)),
              tuple(min(tile_cols, cols - col) for col in range(0, cols, tile_cols)))
    if source.ndim == 3:
        chunks = ((source.bands,),) + chunks
    block = functools.partial(_dask_block, path=os.fspath(source_path), mapping=mapping,
                              transform=to_map, method=method, nodata=nodata, scale=scale,
                              error_threshold=error_threshold, src_nodata=src_nodata)
    return da.map_blocks(block, chunks=chunks, dtype=source.dtype,
                         meta=np.empty((0,) * len(chunks), dtype=source.dtype))
