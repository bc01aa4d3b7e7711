"""GDAL's thin-plate spline transformer as the reference (rasterio 1.4, GDAL 3.10).

Three ways to GDAL's TPS transformer (``alg/gdal_tps.cpp``):

* :func:`tps_source`: the transformer XML of a VRTWarpedDataset, for
  :func:`gdal_reference.gdal_warp` (gdalwarp ``-tps -et 0``: the spline fitted
  image -> map, and for each output cell GDAL's DstToSrc: the spline fitted
  map -> image as a start, refined by GDALGenericInverse2D on the first);
* :func:`gdal_spline`: GDAL's spline src -> dst at points (its ``get_point``);
* :func:`gdal_spline_inverse`: GDAL's DstToSrc for the spline src -> dst at
  dst points (start from the spline dst -> src, refined by Newton's method).

rasterio's ``GCPTransformer(gcps, tps=True)`` builds GDAL's transformer with
the GCPs' (x, y) -> (col, row) as its forward spline (checked: ``rowcol``
equals that spline's ``get_point`` to the last bit, and ``xy`` is the
refined inverse of it), so the two point functions hand GDAL the GCPs with
src as (x, y) and dst as (col, row).
"""

from xml.sax.saxutils import quoteattr

import numpy as np
from rasterio.control import GroundControlPoint
from rasterio.transform import GCPTransformer


def tps_source(image_xy, map_xy):
    """Transformer XML for a source placed on the map by GDAL's thin-plate spline.

    Parameters
    ----------
    image_xy, map_xy : (n, 2) array_like
        The GCPs: (pixel, line) and (x, y).
    """
    points = "".join(
        f'<GCP Id="{i}" Pixel={quoteattr(repr(float(c)))} Line={quoteattr(repr(float(r)))} '
        f'X={quoteattr(repr(float(x)))} Y={quoteattr(repr(float(y)))}/>'
        for i, ((c, r), (x, y)) in enumerate(zip(image_xy, map_xy)))
    return (f"<SrcTPSTransformer><TPSTransformer><Reversed>0</Reversed>"
            f"<GCPList>{points}</GCPList></TPSTransformer></SrcTPSTransformer>")


def _transformer(src, dst):
    gcps = [GroundControlPoint(row=float(r), col=float(c), x=float(x), y=float(y))
            for (x, y), (c, r) in zip(np.asarray(src), np.asarray(dst))]
    return GCPTransformer(gcps, tps=True)


def gdal_spline(src, dst, points):
    """GDAL's thin-plate spline fitted src -> dst, at (n, 2) src ``points``: (n, 2)."""
    points = np.asarray(points, dtype=np.float64)
    with _transformer(src, dst) as transformer:
        rows, cols = transformer.rowcol(points[:, 0], points[:, 1], op=lambda v: v)
    return np.column_stack([cols, rows]).astype(np.float64)


def gdal_spline_inverse(src, dst, points):
    """GDAL's TPS DstToSrc for the spline fitted src -> dst, at (n, 2) dst ``points``: (n, 2).

    What gdalwarp computes for an output cell's map point when the spline is
    fitted image -> map (src = image, dst = map).
    """
    points = np.asarray(points, dtype=np.float64)
    with _transformer(src, dst) as transformer:
        xs, ys = transformer.xy(points[:, 1], points[:, 0], offset="ul")
    return np.column_stack([xs, ys]).astype(np.float64)
