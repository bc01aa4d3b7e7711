"""Whole-raster verbs on top of :func:`rsgeo.resample.warp`: reprojecting a raster between CRSs
(through PROJ, as ``gdalwarp -t_srs`` does) and a complete georeferencing run (fit a model to
the GCPs, choose gdalwarp's suggested output grid, warp), the correction a user makes in QGIS's
Georeferencer or with ``gdalwarp``.
"""

import os
import warnings

import numpy as np

from .. import transforms as _transforms
from .._kernels.resampling import METHODS
from ..crs import transform_points, transformation_at
from ..data import Raster
from ..errors import CRSError, DataError, ExtrapolationWarning, GCPError
from ..gcp import GCPSet
from ..language import _
from ..validation import as_crs, as_output_shape, check_choice
from ._warp import suggested_grid, warp

__all__ = ["CRSMapping", "reproject", "georeference"]


class CRSMapping:
    """Output map (x, y) in ``dst_crs`` -> source (col, row), through PROJ then a model.

    Parameters
    ----------
    to_source : callable or affine.Affine
        Source map (x, y) in ``src_crs`` -> source image (col, row).
    src_crs, dst_crs : rasterio.crs.CRS
    transformation : optional
        The datum transformation to apply (:func:`~rsgeo.crs.transform_points`); PROJ's
        choice, point by point, by default.
    """

    def __init__(self, to_source, src_crs, dst_crs, transformation=None):
        self.to_source = to_source
        self.src_crs, self.dst_crs = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
        self.transformation = transformation

    def __call__(self, points):
        # every output cell, as gdalwarp does: cells beyond the CRS's area of use get nodata
        moved = transform_points(points, self.dst_crs, self.src_crs, check_area=False,
                                 transformation=self.transformation)
        if callable(self.to_source):
            return self.to_source(moved)
        cols, rows = self.to_source @ (moved[:, 0], moved[:, 1])
        return np.column_stack([cols, rows])


def _as_raster(raster_or_path):

    import rasterio

    if isinstance(raster_or_path, Raster):
        return raster_or_path
    if not isinstance(raster_or_path, (str, os.PathLike)):
        shape = getattr(raster_or_path, "shape", None)
        raise TypeError(_(
            "raster_or_path must be an rsgeo.data.Raster or the path of a GeoTIFF, got "
            "{kind}{shape}; wrap an array as rsgeo.data.Raster(array, transform, crs, nodata, "
            "description)").format(kind=type(raster_or_path).__name__,
                                   shape="" if shape is None else f" of shape {shape}"))
    try:
        with rasterio.open(raster_or_path) as dataset:
            array = dataset.read()
            return Raster(array[0] if dataset.count == 1 else array, dataset.transform,
                          dataset.crs, dataset.nodata, "", str(raster_or_path))
    except rasterio.errors.RasterioIOError as error:
        raise DataError(_("cannot read {raster_or_path!r} as a raster ({error}); give "
                          "an rsgeo.data.Raster or the path of a GeoTIFF").format(
                raster_or_path=raster_or_path, error=error)) from None


def reproject(raster, dst_crs, resolution=None, method="nearest", nodata=0,
              transformation=None):
    """A raster resampled into another CRS with rsgeo's GDAL-exact warp.

    Every output pixel centre is taken to the source CRS by PROJ (exactly,
    like ``gdalwarp -et 0``) and then to the source pixel by the inverse
    geotransform. The output grid is north-up over the transformed footprint,
    with the source's pixel size unless ``resolution`` is given. The datum
    transformation is :func:`~rsgeo.crs.transform_points`' (IBGE's grid from SAD69 to
    SIRGAS 2000 where it applies), named in the result's description;
    ``gdalwarp -ct`` with its ``pipeline`` (:func:`~rsgeo.crs.transformations`) gives GDAL
    the same one.

    Parameters
    ----------
    raster : rsgeo.data.Raster
        With a CRS and a geotransform.
    dst_crs : str, int or rasterio.crs.CRS
    resolution : float, optional
        Output pixel size in ``dst_crs`` units.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Destination nodata (``gdalwarp -dstnodata``).
    transformation : str, int, sequence or Transformation, optional
        The datum transformation to apply instead of PROJ's choice (see
        :func:`~rsgeo.crs.transform_points`), e.g. ``"EPSG:15485"``.

    Returns
    -------
    rsgeo.data.Raster
        In ``dst_crs``, with its transform and nodata; its description names the
        transformation applied at the raster's centre.

    Raises
    ------
    ValueError
        For a raster without a CRS, a CRS PROJ does not know, a resolution
        that is not positive, or an unknown method.

    Examples
    --------
    >>> import affine
    >>> image = np.arange(100, dtype=np.uint8).reshape(10, 10)
    >>> raster = Raster(image, affine.Affine(20, 0, 500000, 0, -20, 7400000), as_crs(29193),
    ...                 None, "", "ramp")
    >>> reproject(raster, "EPSG:31983").crs.to_epsg()
    31983
    """
    check_choice(method, "method", METHODS)
    if raster.crs is None:
        raise CRSError(_("raster {raster_name!r} has no CRS; reprojecting needs to know "
                         "which CRS its coordinates are in").format(raster_name=raster.name))
    src_crs, dst = as_crs(raster.crs, "raster.crs"), as_crs(dst_crs, "dst_crs")
    size = abs(raster.transform.a) if resolution is None else resolution

    def pixel_to_dst(points):
        xs, ys = raster.transform @ (points[:, 0], points[:, 1])
        return transform_points(np.column_stack([xs, ys]), src_crs, dst, check_area=False,
                                transformation=transformation)

    transform, shape = suggested_grid(raster.array.shape[-2:], pixel_to_dst, resolution=size)
    as_output_shape(shape, raster.array.dtype, _bands(raster.array), "shape")
    mapping = CRSMapping(~raster.transform, src_crs, dst, transformation)
    array = warp(raster.array, mapping, shape, transform, method=method, dst_nodata=nodata)
    rows, cols = raster.array.shape[-2:]
    named = transformation_at(np.array([raster.transform @ (cols / 2, rows / 2)]), src_crs, dst,
                          transformation)
    return Raster(array, transform, dst, nodata,
                  f"{raster.description} reprojected to {dst}"
                  f"{f' by {named}' if named is not None else ''}", raster.name)


def _bands(array):
    """Bands of an image: its first axis when 3-D, else 1."""
    return array.shape[0] if array.ndim == 3 else 1


def _then_transform(pixel_to_map, src_crs, dst_crs):
    """Source pixel -> map in ``src_crs`` -> map in ``dst_crs``."""
    return lambda points: transform_points(pixel_to_map(points), src_crs, dst_crs,
                                           check_area=False)


# How far the output may reach beyond the GCPs' hull, in GCP extents (transforms.outside_hull),
# before georeference warns, and before it refuses
_REACH_WARNING = 0.1
_REACH_LIMIT = 1.0


def _edge_points(shape, per_side=21):
    """(col, row) points along the four edges of an image of ``shape``, at pixel corners."""
    height, width = shape
    ratio = np.linspace(0.0, 1.0, per_side)
    cols = np.concatenate([ratio * width, ratio * width, np.zeros(per_side),
                           np.full(per_side, float(width))])
    rows = np.concatenate([np.zeros(per_side), np.full(per_side, float(height)),
                           ratio * height, ratio * height])
    return np.column_stack([cols, rows])


def _check_extrapolation(model, reverse, image_shape):
    """Warn or refuse when the image's edges land far beyond the GCPs of an exploding model.

    A polynomial of degree 2 or 3, or a projective model, is controlled by its GCPs
    only inside them: beyond, it grows like a power of the distance (degree 3 on GCPs
    clustered in 500 m of a 10 km scene: 0.14 px RMS on the GCPs, thousands of pixels off at the
    corners, an output of 450 m pixels with 100 valid cells). The output grid is the
    footprint of the image's edges taken to the map by ``reverse``; its reach is measured
    by ``model.outside_gcps``. Order 1, linear, Helmert and TPS (affine outside its GCPs)
    extrapolate linearly and are not checked.
    """
    kind = getattr(model, "kind", None)     # the fitted kind, also for kind=2 (a polynomial)
    if kind == "polynomial" and model.order >= 2:
        what = _("a polynomial of degree {order}").format(order=model.order)
        remedy = _("use order=1, which extrapolates linearly")
    elif kind == "projective":
        what = _("a projective model")
        remedy = _("use kind='polynomial' with order=1")
    else:
        return
    edges = _edge_points(image_shape)
    footprint = np.asarray(reverse(edges), dtype=np.float64)
    reach = np.full(len(edges), np.inf)
    finite = np.isfinite(footprint).all(axis=1)
    if finite.any():
        reach[finite] = model.outside_gcps(footprint[finite])
    farthest = int(np.argmax(reach))
    if reach[farthest] <= _REACH_WARNING:
        return
    gcps_extent = float(np.ptp(model.src, axis=0).max())
    where = _(
        "the output grid reaches {reach:.3g} GCP extents ({distance:.6g} map units) beyond the "
        "GCPs' hull (image point (col, row) {edge} lands at map {point})").format(
            reach=reach[farthest], distance=reach[farthest] * gcps_extent,
            edge=edges[farthest].round(1).tolist(),
            point=footprint[farthest].round(1).tolist())
    if reach[farthest] > _REACH_LIMIT:
        raise GCPError(_(
            "{where}: {what} explodes outside its GCPs, so the output's size, pixel size "
            "and most of its cells would come from extrapolation, not from the GCPs; add GCPs "
            "near the image's edges and corners, or {remedy}").format(
                where=where, what=what, remedy=remedy))
    warnings.warn(_(
        "{where}: {what} is not controlled by its GCPs there and its error grows fast with "
        "the distance (see rsgeo.accuracy.predicted_error_map); add GCPs near the image's edges "
        "and corners, or {remedy}").format(where=where, what=what, remedy=remedy),
        ExtrapolationWarning, stacklevel=3)


#: georeference's default ``order``, the polynomial's; other kinds read it as not given.
_DEFAULT_ORDER = 1


def _fit(gcps, kind, order):
    """Map -> image model of the enabled GCPs."""
    if kind == "polynomial":
        # the order checked as an order (order="2" is a wrong order, not a wrong kind)
        return gcps.fit(1 if order is None else order, kind="polynomial")
    fit_transform = getattr(_transforms, "fit_transform", None)   # the other model kinds
    if fit_transform is None:
        raise GCPError(_("kind {kind!r} is not available; use kind='polynomial' with an "
                         "order").format(kind=kind))
    if order == _DEFAULT_ORDER and not isinstance(order, bool):
        # georeference's default order is the polynomial's: a kind without an order (or a
        # polynomial's order given as the kind) has not been given one
        order = None
    image_xy, map_xy = gcps.image_xy[gcps.enabled], gcps.map_xy[gcps.enabled]
    if kind == "tps":
        # GDAL's TPS transformer: the image -> map spline, inverted point by point (its
        # GDALGenericInverse2D steps), not a second spline fitted the other way
        return fit_transform(image_xy, map_xy, kind, order).inverse()
    return fit_transform(map_xy, image_xy, kind, order)


def georeference(raster_or_path, gcps, kind="polynomial", order=1, resolution=None,
                 method="nearest", nodata=0, dst_crs=None):
    """The corrected image a user makes: fit the GCPs, choose the grid, warp.

    The same run as ``gdalwarp -order N -et 0 -r METHOD -dstnodata NODATA``
    on an image carrying GCPs: the model maps output map (x, y) to source
    (col, row) (through PROJ first when ``dst_crs`` differs from the GCPs'
    CRS, as GDAL chains them), and the output grid is GDAL's suggestion
    (footprint extent, diagonal-preserving pixel size) or ``resolution``.

    Parameters
    ----------
    raster_or_path : rsgeo.data.Raster or path
        The uncorrected image (its own transform and CRS are ignored).
    gcps : rsgeo.gcp.GCPSet
        With the map coordinates' CRS in ``gcps.crs`` when ``dst_crs`` is given.
    kind : str
        ``"polynomial"``, or another kind that ``rsgeo.transforms.fit_transform`` knows.
    order : {1, 2, 3} or None
        Polynomial degree. Kinds without one (e.g. "helmert") take the default
        (1) as not given; 2 or 3 with such a kind is refused.
    resolution : float, optional
        Output pixel size in map units (``gdalwarp -tr``).
    method : {"nearest", "bilinear", "cubic"}
    nodata : number
        Destination nodata.
    dst_crs : str, int or rasterio.crs.CRS, optional
        Output CRS; the GCPs' CRS by default.

    Returns
    -------
    rsgeo.data.Raster
        With transform, CRS and nodata; save it with :func:`rsgeo.data.save`.

    Raises
    ------
    ValueError
        Too few or collinear GCPs, a GCP set without a CRS when ``dst_crs`` is
        given, a CRS PROJ does not know, a resolution that is not positive, or
        an unknown method. ``GCPError`` when a polynomial of order 2 or 3 or a
        projective model puts the image's edges more than one GCP extent (the
        larger side of the GCPs' bounding box) beyond the GCPs' convex hull
        (:meth:`rsgeo.transforms.GeometricModel.outside_gcps`): such a model
        explodes outside its GCPs, and the output grid would be its
        extrapolation.

    Warns
    -----
    UserWarning
        When such a model puts the image's edges more than 0.1 GCP extent
        beyond the GCPs' hull: the corrected image's edges are extrapolated.
        Order 1, linear, Helmert and TPS models extrapolate linearly and are
        not checked.

    Examples
    --------
    >>> from rsgeo import data
    >>> corrected = georeference(data.load("cbers2b_rgb342"), data.load_gcps("cbers2b_ccd_hrc"),
    ...                          order=1, resolution=20.0)
    >>> corrected.transform.a, corrected.crs.to_epsg()
    (20.0, 29191)
    """
    check_choice(method, "method", METHODS)
    if not isinstance(gcps, GCPSet):
        raise TypeError(_("gcps must be an rsgeo.gcp.GCPSet, got {kind}").format(
                kind=type(gcps).__name__))
    raster = _as_raster(raster_or_path)
    model = _fit(gcps, kind, order)
    label = getattr(model, "kind", None) or kind           # "polynomial" also for kind=2
    order = getattr(model, "order", None) if label == "polynomial" else None
    reverse = (model.reverse() if hasattr(model, "reverse") else model.inverse())
    _check_extrapolation(model, reverse, raster.array.shape[-2:])
    pixel_to_map = reverse
    src_crs = None if gcps.crs is None else as_crs(gcps.crs, "gcps.crs")
    mapping = model
    if dst_crs is not None:
        dst = as_crs(dst_crs, "dst_crs")
        if src_crs is None:
            raise CRSError(_("the GCPs have no CRS (gcps.crs is None); set it to reproject into "
                             "dst_crs"))
        if dst != src_crs:
            pixel_to_map = _then_transform(reverse, src_crs, dst)
            mapping = CRSMapping(model, src_crs, dst)
        src_crs = dst
    # gdalwarp's suggested output grid (GDALSuggestedWarpOutput2; -tr when a resolution is given)
    transform, shape = suggested_grid(raster.array.shape[-2:], pixel_to_map, resolution=resolution)
    as_output_shape(shape, raster.array.dtype, _bands(raster.array), "shape")
    array = warp(raster.array, mapping, shape, transform, method=method, dst_nodata=nodata)
    return Raster(array, transform, src_crs, nodata,
                  f"{raster.name or 'image'} georeferenced: {label}"
                  f"{f' order {order}' if order is not None else ''}, {method}",
                  raster.name)
