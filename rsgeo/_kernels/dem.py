"""A DEM sampled inside compiled code as GDAL 3.10's GDALRPCGetDEMHeight samples it (bilinear).
"""

import numpy as np
from numba import njit

from .._numba_cache import CACHE

__all__ = ["dem_height_at", "dem_heights"]


@njit(cache=CACHE, inline="always")
def dem_height_at(dem, inverse, x, y):
    """GDAL 3.10's DEM height for the RPC transformer, bilinear, at one map point: (height,
    whether the point is outside the DEM). NaN for a point outside or over a hole.

    GDALRPCGetDEMHeight calls GDALInterpolateAtPoint (``alg/gdal_interpolateatpoint.cpp``):
    a point is inside for 0 <= px <= cols and 0 <= py <= rows; the 2 x 2 window starts at
    floor(px - 0.5), floor(py - 0.5) and, where it leaves the DEM, is moved back inside with
    its values dragged to the edge, which is bilinear interpolation with the indices clamped
    to the DEM: along an edge the height is still interpolated along that edge. (GDAL 3.9
    and earlier truncated the index toward zero and fell back to the nearest cell.) A DEM
    of one row or column is sampled at its nearest cell, as GDAL downgrades bilinear then.
    """
    rows, cols = dem.shape
    px = inverse[0] + x * inverse[1] + y * inverse[2]
    py = inverse[3] + x * inverse[4] + y * inverse[5]
    # asked before any conversion to int: NaN, infinity and huge values never reach an index
    if not (px >= 0.0 and py >= 0.0 and px <= cols and py <= rows):
        return np.nan, True
    if rows < 2 or cols < 2:
        ix = int(px)
        iy = int(py)
        if ix >= cols or iy >= rows:          # on the far edge: GDAL's read fails
            return np.nan, True
        return dem[iy, ix], False
    fx = px - 0.5
    fy = py - 0.5
    x0 = np.floor(fx)
    y0 = np.floor(fy)
    dx = fx - x0
    dy = fy - y0
    ix = int(x0)
    iy = int(y0)
    ix0 = min(max(ix, 0), cols - 1)
    ix1 = min(max(ix + 1, 0), cols - 1)
    iy0 = min(max(iy, 0), rows - 1)
    iy1 = min(max(iy + 1, 0), rows - 1)
    dx1 = 1.0 - dx
    dy1 = 1.0 - dy
    z1 = dem[iy0, ix0] * dx1 + dem[iy0, ix1] * dx
    z2 = dem[iy1, ix0] * dx1 + dem[iy1, ix1] * dx
    return z1 * dy1 + z2 * dy, False


@njit(cache=CACHE)
def dem_heights(dem, inverse, x, y, out):
    """dem_height_at at every point of 1-D arrays, into ``out``.

    Returns the number of points outside the DEM (their ``out`` is NaN).
    """
    outside = 0
    for k in range(x.size):
        out[k], is_outside = dem_height_at(dem, inverse, x[k], y[k])
        outside += is_outside
    return outside


