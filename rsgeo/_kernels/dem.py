"""A DEM sampled inside compiled code as GDALRPCGetDEMHeight samples it (bilinear).
"""

import numpy as np
from numba import njit

from .._numba_cache import CACHE

__all__ = ["dem_height_at", "dem_heights"]


@njit(cache=CACHE, inline="always")
def dem_height_at(dem, inverse, x, y):
    """GDALRPCGetDEMHeight, bilinear with the nearest fallback, at one map point: (height,
    whether the point is outside the DEM). NaN for a point outside or over a hole."""
    rows, cols = dem.shape
    px = inverse[0] + x * inverse[1] + y * inverse[2]
    py = inverse[3] + x * inverse[4] + y * inverse[5]
    # GDAL's test for the nearest fallback, px > -1, py > -1, int(px) < cols and int(py) <
    # rows, asked before any conversion to int (the same for finite values; NaN, infinity and
    # huge values then never reach an index)
    if not (px > -1.0 and py > -1.0 and px < cols and py < rows):
        return np.nan, True
    fx = px - 0.5
    fy = py - 0.5
    ix = int(fx)                      # C's static_cast<int>: toward zero
    iy = int(fy)
    if ix >= 0 and iy >= 0 and ix + 2 <= cols and iy + 2 <= rows:
        dx = fx - ix
        dy = fy - iy
        dx1 = 1.0 - dx
        dy1 = 1.0 - dy
        z1 = dem[iy, ix] * dx1 + dem[iy, ix + 1] * dx
        z2 = dem[iy + 1, ix] * dx1 + dem[iy + 1, ix + 1] * dx
        return z1 * dy1 + z2 * dy, False
    return dem[int(py), int(px)], False


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


