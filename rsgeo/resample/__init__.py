"""Resampling and warping, as GDAL does them: the output grid, the kernels, whole rasters.

- :func:`interpolate` - an image's values at continuous (col, row) positions, by GDAL's
  nearest, bilinear and cubic convolution (the lecture's "Reamostragem");
- :func:`warp` - a whole output grid: for every cell, where in the source (a model or a
  mapping evaluated inside the kernel, as GDAL's transformers are), then interpolate;
  :func:`grid_positions`, :func:`grid_scale` and :func:`suggested_grid` are its grid;
- :func:`reproject` and :func:`georeference` - a raster moved to another CRS, or corrected with
  its GCPs, as ``gdalwarp`` does;
- :func:`warp_tiled` and :func:`warp_dask` - the same warp tile by tile, for scenes larger
  than memory.

What "bit for bit with GDAL" covers, and where gdalwarp's defaults differ, is said in
``rsgeo.resample._warp``'s notes, repeated on :func:`warp`.
"""

from .._kernels.resampling import (
    METHODS,
    WARP_METHODS,
    bilinear_weights,
    cubic_kernel,
    keys_weights,
)
from ._georeference import CRSMapping, georeference, reproject
from ._tiling import SourceWindow, Tile, source_window, tiles, warp_dask, warp_tiled
from ._warp import grid_positions, grid_scale, interpolate, suggested_grid, warp

__all__ = [
    "METHODS", "WARP_METHODS", "keys_weights", "cubic_kernel", "bilinear_weights", "interpolate",
    "grid_positions", "warp", "grid_scale", "suggested_grid",
    "CRSMapping", "reproject", "georeference",
    "Tile", "SourceWindow", "tiles", "source_window", "warp_tiled", "warp_dask",
]
