"""GDAL as the reference, for the tests: the warps themselves are rsgeo_course.gdal_reference's
(written once, for the book, the tests and the benchmarks); here, what only the tests ask of
GDAL: its map -> image prediction on a grid and its suggested output grid.
"""

import os
import tempfile

import numpy as np
import rasterio

from rsgeo_course import gdal_reference
from rsgeo_course.gdal_reference import affine_source, gcp_source, gdal_warp

__all__ = ["affine_source", "gcp_source", "gdal_warp", "gdal_map_to_image", "gdalwarp_reproject",
           "gdal_suggested_grid"]


def gdal_map_to_image(image_xy, map_xy, order, dst_transform, shape, refine=None):
    """GDAL's map -> image prediction at the centres of an output grid.

    Warps two ramps whose pixel values are their own centre coordinates; bilinear
    interpolation is exact on a ramp, so each output pixel holds the (col, row)
    GDAL computed for it. Positions within one pixel of the source edge are NaN.
    """
    width = int(np.ceil(np.max(image_xy[:, 0]))) + 2
    height = int(np.ceil(np.max(image_xy[:, 1]))) + 2
    cols, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    ramps = np.stack([cols, rows])
    out = gdal_warp(ramps, gcp_source(image_xy, map_xy, order, refine), dst_transform, shape,
                    "bilinear", -1e9, plain_kernels=True)
    inside = ((out[0] > 1) & (out[0] < width - 1) & (out[1] > 1) & (out[1] < height - 1))
    return np.where(inside, out[0], np.nan), np.where(inside, out[1], np.nan)


def gdalwarp_reproject(image, src_transform, dst_transform, shape, method, nodata,
                       crs="EPSG:29191", **warp_options):
    """What gdalwarp itself gives (rsgeo_course.gdal_reference.gdalwarp_reproject), for an
    image placed by ``src_transform`` in ``crs``; ``warp_options``, e.g. ``XSCALE="0.5"``, are
    passed to GDAL."""
    return gdal_reference.gdalwarp_reproject(image, dst_transform, shape, method, nodata, crs,
                                             src_transform=src_transform, **warp_options)


def gdal_suggested_grid(shape, transform=None, gcps=None, crs="EPSG:29191"):
    """GDAL's GDALSuggestedWarpOutput2 for a source of ``shape`` (rows, cols).

    The source is placed by its geotransform or by ``gcps`` ((col, row, x, y)
    rows, for GDAL's GCP polynomial); a WarpedVRT into the same CRS with no
    grid given takes GDAL's suggested transform and size.
    """
    from rasterio.control import GroundControlPoint
    from rasterio.vrt import WarpedVRT

    rows, cols = shape
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "source.tif")
        options = dict(driver="GTiff", width=cols, height=rows, count=1, dtype="uint8", crs=crs)
        if gcps is None:
            options["transform"] = transform
        with rasterio.open(path, "w", **options) as dataset:
            if gcps is not None:
                dataset.gcps = ([GroundControlPoint(row=r, col=c, x=x, y=y, z=0.0)
                                 for c, r, x, y in gcps], rasterio.crs.CRS.from_user_input(crs))
        with rasterio.open(path) as source, WarpedVRT(source, crs=source.crs) as vrt:
            return vrt.transform, (vrt.height, vrt.width)
