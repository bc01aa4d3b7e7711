"""Geotransforms and grids as GDAL computes them, shared by the DEM, orthorectification and
sensor modules: a GDAL 6-tuple from an affine, GDAL's inverse of it, cell centres, bounds, and
points moved between CRSs by GDAL (rasterio.warp.transform).
"""

import numpy as np

from .errors import GridError
from .language import _
from .validation import as_affine

__all__ = [
    "gdal_inverse", "as_gdal", "outside_mask", "grid_bounds", "grid_centres", "to_crs",
    "is_lon_lat",
]


def gdal_inverse(gt):
    """GDALInvGeoTransform, operation for operation."""
    if gt[2] == 0.0 and gt[4] == 0.0 and gt[1] != 0.0 and gt[5] != 0.0:
        return np.array([-gt[0] / gt[1], 1.0 / gt[1], 0.0, -gt[3] / gt[5], 0.0, 1.0 / gt[5]])
    det = gt[1] * gt[5] - gt[2] * gt[4]
    magnitude = max(abs(gt[1]), abs(gt[2]), abs(gt[4]), abs(gt[5]))
    if abs(det) <= 1e-10 * magnitude * magnitude:
        raise GridError(_("the geotransform {gt} cannot be inverted (its pixels have no "
                          "area)").format(gt=tuple(gt)))
    inv = 1.0 / det
    return np.array([(gt[2] * gt[3] - gt[0] * gt[5]) * inv, gt[5] * inv, -gt[2] * inv,
                     (-gt[1] * gt[3] + gt[0] * gt[4]) * inv, -gt[4] * inv, gt[1] * inv])


def as_gdal(transform, name):
    """GDAL's 6 numbers of an affine.Affine (or, deprecated, a GDAL-ordered 6-sequence)."""
    if transform is None:
        raise GridError(_("{name} is None; give the grid's affine.Affine (pixel corner -> "
                          "map)").format(name=name))
    return np.array(as_affine(transform, name, gdal_tuple=True).to_gdal(), dtype=np.float64)


def outside_mask(shape, inverse, x, y):
    with np.errstate(invalid="ignore", over="ignore"):   # infinite points: NaN, outside
        px = inverse[0] + x * inverse[1] + y * inverse[2]
        py = inverse[3] + x * inverse[4] + y * inverse[5]
    # GDAL 3.10's GDALInterpolateAtPoint: inside for 0 <= px <= cols, 0 <= py <= rows
    return ~((px >= 0) & (py >= 0) & (px <= shape[1]) & (py <= shape[0]))


def grid_bounds(shape, transform):
    gt = as_gdal(transform, "transform")
    xs = [gt[0], gt[0] + shape[1] * gt[1] + shape[0] * gt[2]]
    ys = [gt[3], gt[3] + shape[1] * gt[4] + shape[0] * gt[5]]
    return f"x {min(xs):.6f} to {max(xs):.6f}, y {min(ys):.6f} to {max(ys):.6f}"


def grid_centres(gt, shape, start=0, stop=None):
    """Map coordinates of cell centres (rows start to stop) as GDAL's GenImgProjTransform does."""
    cols = np.arange(shape[1]) + 0.5
    rows = (np.arange(start, shape[0] if stop is None else stop) + 0.5)[:, None]
    x = gt[0] + cols * gt[1] + rows * gt[2]
    y = gt[3] + cols * gt[4] + rows * gt[5]
    return x, y


def to_crs(x, y, src, dst):
    """Points from CRS src to dst with GDAL's PROJ (rasterio.warp.transform); None = EPSG:4326.

    One call, single-threaded (GDAL's ``OCTTransform``, which rasterio reaches through
    Python objects, a coordinate at a time: most of a projected grid's time; a grid in
    EPSG:4326 needs no PROJ).
    """
    src = src or "EPSG:4326"
    dst = dst or "EPSG:4326"
    if str(src) == str(dst):
        return x, y
    from rasterio.warp import transform as warp_transform

    tx, ty = warp_transform(src, dst, np.ravel(x), np.ravel(y))
    return np.reshape(tx, np.shape(x)), np.reshape(ty, np.shape(y))


def is_lon_lat(crs):
    """Whether a CRS is the RPC's own, EPSG:4326 (rsgeo's rule in to_crs: no PROJ then)."""
    return crs is None or str(crs) == "EPSG:4326"


