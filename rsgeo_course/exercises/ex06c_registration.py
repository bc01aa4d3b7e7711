"""Checks of exercises 6c (chapter 6c, automatic registration): keypoints, tie points, check
points."""

import numpy as np

from rsgeo import registration
from rsgeo.validation import as_shape

from .._i18n import N_, _
from .engine import Declaration, Mistake, WrongForm, declare, position_verdict, two_numbers

__all__ = ["check_keypoint_position", "check_composed_tiepoint", "check_check_point_error"]


KEYPOINT_POSITION = Declaration(
    check="check_keypoint_position", answer="position", inputs=("keypoint",),
    right=lambda task: np.array([float(v) for v in np.ravel(task.keypoint)[:2]])[::-1] + 0.5,
    general=N_("scikit-image gives (row, col) with the first pixel's centre at (0, 0); GDAL's "
               "(col, row) has the first pixel's corner at (0, 0)."),
    mistakes=(
        Mistake(N_("Half a pixel is missing: a pixel's centre is 0.5 from its corner, so add 0.5 "
                   "to both coordinates."), lambda task: task.right - 0.5),
        Mistake(N_("The half pixel goes the other way: GDAL's coordinates are 0.5 larger than "
                   "scikit-image's at the same pixel centre."), lambda task: task.right - 1.0),
        Mistake(N_("The order is swapped: scikit-image gives (row, col), the check wants (col, "
                   "row)."), lambda task: task.right[::-1]),
        Mistake(N_("The order is swapped (scikit-image gives (row, col)), and half a pixel is "
                   "missing: add 0.5 to both."), lambda task: task.right[::-1] - 0.5),
    ))


@declare(KEYPOINT_POSITION)
def check_keypoint_position(position, keypoint):
    """A scikit-image keypoint, (row, col) with pixel centres at whole numbers, in GDAL's
    (col, row).

    Parameters
    ----------
    position : (float, float)
        The student's (col, row), with (0, 0) at the image's top-left corner.
    keypoint : (float, float)
        The keypoint as scikit-image gives it (``SIFT().keypoints[k]``): (row, col).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``position`` is still ``...``.

    Examples
    --------
    >>> check_keypoint_position((20.5, 10.5), (10.0, 20.0))
    Correct: (col, row) is the keypoint in GDAL's convention.
    """
    try:
        value = two_numbers(position, "position")
    except WrongForm as form:
        return form.verdict(_(KEYPOINT_POSITION.general))
    task = KEYPOINT_POSITION.task(keypoint=keypoint)
    return position_verdict(KEYPOINT_POSITION, value, task, 1e-6,
                             _("(col, row) is the keypoint in GDAL's convention."))


def _apply_affine(transform, point):
    return np.array(transform @ (float(point[0]), float(point[1])))


def _tiepoint_derived(task):
    drow, dcol = (float(v) for v in np.ravel(task.shift)[:2])
    return {"centre": np.asarray(task.centre, dtype=float).ravel(), "drow": drow, "dcol": dcol}


def _composed(task, point, through_map=True):
    """``point`` on the reference grid taken to the moving image (through the map or not)."""
    return _apply_affine(task.estimate, _apply_affine(task.reference_transform, point)
                         if through_map else point)


COMPOSED_TIEPOINT = Declaration(
    check="check_composed_tiepoint", answer="position",
    inputs=("centre", "shift", "estimate", "reference_transform"),
    derive=_tiepoint_derived,
    right=lambda task: _composed(task, task.centre - [task.dcol, task.drow]),
    general=N_("Move the window centre by minus the shift, (col − dcol, row − drow), take that "
               "reference pixel to the map with the reference transform, then to the moving "
               "image with the estimate."),
    mistakes=(
        Mistake(N_("The shift registers the moving window onto the reference one: the feature "
                   "is at the centre minus the shift, not plus."),
                lambda task: _composed(task, task.centre + [task.dcol, task.drow])),
        Mistake(N_("scikit-image's shift is (drow, dcol), rows first; subtract dcol from the "
                   "column and drow from the row."),
                lambda task: _composed(task, task.centre - [task.drow, task.dcol])),
        Mistake(N_("That is the position on the reference grid; the tie point needs it in the "
                   "moving image: through the reference transform to the map, then through the "
                   "estimate."), lambda task: task.centre - [task.dcol, task.drow]),
        Mistake(N_("The reference transform is missing: a reference pixel must go to the map "
                   "first."),
                lambda task: _composed(task, task.centre - [task.dcol, task.drow],
                                       through_map=False)),
    ))


@declare(COMPOSED_TIEPOINT)
def check_composed_tiepoint(position, centre, shift, estimate, reference_transform):
    """A correlation tie point composed by hand: where the window's feature is in the moving image.

    The moving image was resampled onto the reference grid through ``estimate``
    (map -> moving (col, row)); ``phase_cross_correlation(reference_window,
    resampled_window)`` returned ``shift`` = (drow, dcol). The feature at the
    window centre p is at p - (dcol, drow) on the resampled grid, so in the
    moving image at ``estimate(reference_transform(p - (dcol, drow)))``.

    Parameters
    ----------
    position : (float, float)
        The student's (col, row) in the moving image.
    centre : (float, float)
        The window's centre (col, row) on the reference grid.
    shift : (float, float)
        (drow, dcol), as scikit-image returns it.
    estimate : affine.Affine
        Map (x, y) -> moving image (col, row).
    reference_transform : affine.Affine
        Reference pixel (col, row) -> map (x, y).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``position`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> to_map = affine.Affine(20, 0, 0, 0, -20, 0)
    >>> check_composed_tiepoint((10.0, 8.0), (12, 9), (1.0, 2.0), ~to_map, to_map)
    Correct: (col, row) is where the window's feature is in the moving image.
    """
    try:
        value = two_numbers(position, "position")
    except WrongForm as form:
        return form.verdict(_(COMPOSED_TIEPOINT.general))
    task = COMPOSED_TIEPOINT.task(centre=centre, shift=shift, estimate=estimate,
                                  reference_transform=reference_transform)
    return position_verdict(COMPOSED_TIEPOINT, value, task, 1e-6,
                             _("(col, row) is where the window's feature is in the moving "
                               "image."), N_("moving-image pixels"))


def _grid_distances(task):
    rows, cols = as_shape(task.shape)
    grid_rows, grid_cols = np.mgrid[0:rows:int(task.step), 0:cols:int(task.step)] + 0.5
    map_xy = np.column_stack(task.transform @ (grid_cols.ravel(), grid_rows.ravel()))

    def apply(mapping):
        if callable(mapping):
            return np.asarray(mapping(map_xy), dtype=float)
        return np.column_stack(mapping @ (map_xy[:, 0], map_xy[:, 1]))   # an affine.Affine

    return {"distance": np.hypot(*(apply(task.model) - apply(task.truth)).T)}


CHECK_POINT_ERROR = Declaration(
    check="check_check_point_error", answer="error_px",
    inputs=("model", "truth", "transform", "shape", "step", "pixel_size"),
    derive=_grid_distances,
    right=lambda task: registration.grid_error(task.model, task.truth, task.transform, task.shape,
                                            task.step),
    general=N_("At each check point take the two models' (col, row), the distance between them, "
               "then the lecture's RMS: square, average, root."),
    mistakes=(
        Mistake(N_("That is the mean distance; the lecture's RMS squares the distances before "
                   "averaging and takes the root after."),
                lambda task: float(task.distance.mean())),
        Mistake(N_("That divides by 2n: the squared distance of a point is dcol² + drow², one "
                   "number per point; average over the n points."),
                lambda task: task.right / np.sqrt(2)),
        Mistake(N_("That is the largest distance, not the RMS."),
                lambda task: float(task.distance.max())),
        Mistake(N_("That looks like map units; the check wants pixels of the image."),
                lambda task: task.right * task.pixel_size if task.pixel_size else None),
    ),
    rtol=1e-3, mistake_rtol=1e-3, units=" px")


@declare(CHECK_POINT_ERROR)
def check_check_point_error(error_px, model, truth, transform, shape, step=10, pixel_size=None):
    """The check-point error of a registration: RMS distance to the truth over a grid, in pixels.

    Parameters
    ----------
    error_px : float
        The student's RMS, in pixels of the image the models map to.
    model, truth : callable or affine.Affine
        Map (x, y) -> image (col, row): the fitted model and the known answer.
    transform : affine.Affine
        Pixel -> map of the grid of check points (every ``step``-th cell centre).
    shape : (rows, cols)
        That grid's size.
    step : int
        Spacing of the check points, cells.
    pixel_size : float, optional
        The image's pixel size (map units), to recognise an answer in metres.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``error_px`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> model = affine.Affine.translation(0.3, 0.4)
    >>> check_check_point_error(0.5, model, affine.Affine.identity(), affine.Affine.identity(),
    ...                         (20, 20))
    Correct: `error_px` = 0.5 px.
    """
    return CHECK_POINT_ERROR.judge(error_px, CHECK_POINT_ERROR.task(
        model=model, truth=truth, transform=transform, shape=shape, step=step,
        pixel_size=pixel_size))
