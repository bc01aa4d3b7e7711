"""The step every automatic method shares with the GA paper's: tie points -> GCPSet -> model ->
refinement (``gdalwarp -refine_gcps``) -> check points; and the synthetic misregistrations it is
measured on.
"""

from dataclasses import dataclass

import numpy as np

from .. import accuracy, gcp, transforms
from ..errors import GridError, ImageError, ModelError
from ..language import _
from ..validation import (
    as_image,
    as_invertible_affine,
    as_shape,
)
from ._tiepoints import apply_model, to_map

__all__ = [
    "Registration", "register", "grid_error", "coarsen", "perturb_transform",
]





@dataclass
class Registration:
    """A registration's result: :func:`register`'s or
    :func:`~rsgeo.registration.register_by_regions`'s.

    Attributes
    ----------
    model : GeometricModel
        Map -> image, fitted on the kept GCPs.
    kept : ndarray of bool
        GCPs (of the enabled ones) that survived refinement.
    rms_all, rms_kept : float
        Lecture's RMS (pixels) of the model fitted on all enabled GCPs, and of
        the refined model on the kept ones.
    map_xy, image_xy : ndarray, shape (k, 2), or None
        The GCPs the model was fitted on (before refinement); with
        :func:`rsgeo.registration.register_by_regions`, the matched reference
        centroids (map units) and adjustment centroids (adjustment pixels).
    match : rsgeo.registration.MatchResult or None
        The GA's matching of adjustment segments to reference labels, when
        the GCPs come from :func:`rsgeo.registration.register_by_regions`.
    """

    model: object
    kept: np.ndarray
    rms_all: float
    rms_kept: float
    map_xy: np.ndarray = None
    image_xy: np.ndarray = None
    match: object = None


def register(gcps, kind="polynomial", order=1, tolerance=1.0, min_gcps=None):
    """The shared pipeline's last steps: GCPSet -> model -> refinement (``gdalwarp -refine_gcps``).

    Whatever found the GCPs (a human, the GA paper's matched regions,
    correlation, features), the model is fitted the same way: on the enabled
    GCPs, then the worst GCP is dropped while its residual is over
    ``tolerance`` (:func:`rsgeo.accuracy.refine_gcps`, for any kind).

    Parameters
    ----------
    gcps : GCPSet
        Map (x, y) and image (col, row); disabled GCPs are left out.
    kind, order
        As :func:`rsgeo.transforms.fit_transform`.
    tolerance : float
        Refinement tolerance, image pixels.
    min_gcps : int, optional
        Fewest GCPs refinement keeps; default the model's minimum.

    Returns
    -------
    Registration
        ``kept`` has one flag per enabled GCP.

    Raises
    ------
    ValueError
        As :func:`rsgeo.transforms.fit_transform` and
        :func:`rsgeo.accuracy.refine_gcps` (too few GCPs, a negative tolerance).
    TypeError
        If ``gcps`` is not a GCPSet.

    Examples
    --------
    >>> map_xy = np.array([[0, 0], [100, 0], [0, 100], [100, 100], [50, 50]], dtype=float)
    >>> image_xy = map_xy / 10
    >>> image_xy[4] += 3                                   # one bad GCP
    >>> result = register(gcp.GCPSet(map_xy, image_xy), tolerance=1.0)
    >>> result.kept.tolist(), round(result.rms_kept, 6)
    ([True, True, True, True, False], 0.0)
    """
    if not isinstance(gcps, gcp.GCPSet):
        raise TypeError(_("gcps must be a rsgeo.gcp.GCPSet, got {kind}").format(
                kind=type(gcps).__name__))
    map_xy, image_xy = gcps.map_xy[gcps.enabled], gcps.image_xy[gcps.enabled]
    order = order if kind == "polynomial" else None
    rms_all = transforms.fit_transform(map_xy, image_xy, kind, order).rms(map_xy, image_xy)
    model, kept = accuracy.refine_gcps(map_xy, image_xy, order, tolerance, min_gcps, kind)
    return Registration(model, kept, rms_all, model.rms(map_xy[kept], image_xy[kept]),
                        map_xy, image_xy)


def grid_error(model, truth, transform, shape, step=10):
    """Check points on a grid: RMS distance between two map -> image models over an image's area.

    The independent check of an automatic registration: on synthetic data
    ``truth`` is the known mapping (``~moving_transform``); on real data it
    can be another model (the hand-made GCPs'), and the result is how far
    the two agree.

    Parameters
    ----------
    model, truth : callable or affine.Affine
        Map (x, y) -> image (col, row).
    transform : affine.Affine
        Pixel -> map of the grid the check points are taken on (usually the
        reference's).
    shape : (rows, cols)
        That grid's size.
    step : int
        Every ``step``-th cell centre is a check point.

    Returns
    -------
    float
        RMS distance, in image pixels.

    Raises
    ------
    ValueError
        For a step that is not a positive whole number, a bad shape, or a
        model that gives NaN.

    Examples
    --------
    >>> import affine
    >>> truth = affine.Affine.identity()
    >>> model = affine.Affine.translation(0.3, 0.4)
    >>> round(grid_error(model, truth, affine.Affine.identity(), (20, 20)), 6)
    0.5
    """
    rows, cols = as_shape(shape)
    if int(step) != step or step < 1:
        raise GridError(_("step must be a positive whole number of pixels, got {step!r}").format(
                step=step))
    grid_rows, grid_cols = np.mgrid[0:rows:int(step), 0:cols:int(step)] + 0.5
    map_xy = to_map(transform, np.column_stack([grid_cols.ravel(), grid_rows.ravel()]))
    difference = apply_model(model, map_xy) - apply_model(truth, map_xy)
    if not np.isfinite(difference).all():
        raise ModelError(_("a model gave NaN or infinite positions on the check grid"))
    return float(np.sqrt(np.mean(np.sum(difference**2, axis=1))))


def coarsen(image, transform, factor):
    """Average ``factor`` × ``factor`` blocks: a finer image seen at a coarser pixel size.

    How the 2.5 m HRC is compared with the 20 m CCD (``factor=8``): each
    block's mean approximates what the coarser sensor integrates over its
    pixel. Rows and columns that do not fill a block are dropped.

    Parameters
    ----------
    image : (rows, cols) array_like
    transform : affine.Affine
        The image's pixel -> map geotransform.
    factor : int
        Block side, pixels.

    Returns
    -------
    blocks : ndarray, shape (rows // factor, cols // factor)
    block_transform : affine.Affine
        Pixel -> map of the blocks.

    Raises
    ------
    ValueError
        If the image is not 2-D or the factor is not a whole number from 1
        to the image's smaller side.

    Examples
    --------
    >>> import affine
    >>> transform = affine.Affine(2.5, 0, 0, 0, -2.5, 10)
    >>> blocks, t = coarsen(np.arange(16.0).reshape(4, 4), transform, 2)
    >>> blocks.tolist(), t.a
    ([[2.5, 4.5], [10.5, 12.5]], 5.0)
    """
    import affine

    image = as_image(image, "image").astype(np.float64)
    if image.ndim != 2:
        raise ImageError(_("image must be one band (2-D), got shape {image_shape}").format(
                image_shape=image.shape))
    if int(factor) != factor or not 1 <= factor <= min(image.shape):
        raise GridError(_("factor must be a whole number from 1 to {min}, got {factor!r}").format(
                min=min(image.shape), factor=factor))
    factor = int(factor)
    rows, cols = (n // factor * factor for n in image.shape)
    blocks = image[:rows, :cols].reshape(rows // factor, factor, cols // factor, factor)
    return blocks.mean(axis=(1, 3)), transform @ affine.Affine.scale(factor)


def perturb_transform(transform, shift=(0.0, 0.0), degrees=0.0, centre=None):
    """A geotransform moved by ``shift`` and turned by ``degrees`` about ``centre``: an approximate
    georeferencing, as a first estimate for :func:`~rsgeo.registration.correlation_tiepoints`.

    Parameters
    ----------
    transform : affine.Affine
        Pixel -> map.
    shift : (float, float)
        Map units added to every mapped point.
    degrees : float
        Rotation, counter-clockwise on the map.
    centre : (float, float), optional
        Map point the rotation turns about; default the map position of
        pixel (0, 0).

    Returns
    -------
    affine.Affine
        Pixel -> map, perturbed.

    Raises
    ------
    ValueError
        If the transform is not an invertible affine.Affine, or a value is
        not finite.

    Examples
    --------
    >>> import affine
    >>> moved = perturb_transform(affine.Affine.identity(), (3, 4), 90, centre=(0, 0))
    >>> [round(v, 6) + 0.0 for v in moved @ (1, 0)]
    [3.0, 5.0]
    """
    import affine

    as_invertible_affine(transform, "transform")
    values = [*np.ravel(shift), degrees] + ([] if centre is None else list(np.ravel(centre)))
    if not np.isfinite(np.asarray(values, dtype=float)).all():
        raise GridError(_("shift, degrees and centre must be finite numbers, got "
                          "{values}").format(values=values))
    cx, cy = transform @ (0, 0) if centre is None else centre
    return (affine.Affine.translation(*shift) @ affine.Affine.translation(cx, cy)
            @ affine.Affine.rotation(degrees) @ affine.Affine.translation(-cx, -cy) @ transform)
