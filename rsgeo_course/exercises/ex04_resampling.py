"""Checks of exercises 4 (chapter 4, resampling): kernels by hand, methods, output grids."""

import affine
import numpy as np

from rsgeo import resample
from rsgeo.validation import as_resolution, as_shape

from .._i18n import N_, _, prose_number
from .engine import Declaration, Mistake, Verdict, WrongForm, declare, require

__all__ = ["check_bilinear", "check_method_for_classes", "check_overshoot",
           "check_output_pixel_size", "check_grid_extent"]


def _bilinear_by_hand(task, wx, wy):
    return float(resample.bilinear_weights(wy) @ task.window @ resample.bilinear_weights(wx))


_SWAP = N_("dx and dy are swapped: dx moves to the right, along a line (between columns), dy "
           "down.")

BILINEAR = Declaration(
    check="check_bilinear", answer="value", inputs=("window", "dx", "dy"),
    derive=lambda task: {"window": np.asarray(task.window, dtype=float)},
    right=lambda task: _bilinear_by_hand(task, task.dx, task.dy),
    general=N_("First interpolate along each of the two lines with weights (1 − dx, dx), then "
               "between the two results with (1 − dy, dy)."),
    mistakes=(
        Mistake(_SWAP, lambda task: _bilinear_by_hand(task, task.dy, task.dx)),
        Mistake(_SWAP, lambda task: float(resample.bilinear_weights(task.dx) @ task.window
                                          @ resample.bilinear_weights(task.dy))),
        Mistake(N_("The weights are reversed: the pixel nearer the point weighs more, so the left "
                   "pixel gets 1 − dx and the right one dx."),
                lambda task: _bilinear_by_hand(task, 1 - task.dx, 1 - task.dy)),
        Mistake(N_("The weights along the line are reversed: the left pixel gets 1 − dx."),
                lambda task: _bilinear_by_hand(task, 1 - task.dx, task.dy)),
        Mistake(N_("The weights between the lines are reversed: the upper line gets 1 − dy."),
                lambda task: _bilinear_by_hand(task, task.dx, 1 - task.dy)),
        Mistake(N_("That is the plain mean of the four pixels; bilinear weights them by "
                   "closeness."), lambda task: task.window.mean()),
        Mistake(N_("That is the nearest pixel's value; bilinear weights all four."),
                lambda task: task.window[int(task.dy >= 0.5), int(task.dx >= 0.5)]),
        Mistake(N_("You interpolated along the upper line only; do the lower line too, then "
                   "between the two."),
                lambda task: float(task.window[0] @ resample.bilinear_weights(task.dx))),
    ),
    rtol=1e-9)


@declare(BILINEAR)
def check_bilinear(value, window, dx, dy):
    """Bilinear interpolation by hand in a 2 × 2 window at fractional offsets (dx, dy).

    Parameters
    ----------
    value : float
        The student's answer.
    window : (2, 2) array_like
        The window, upper-left pixel centre at (0, 0).
    dx, dy : float
        Offsets to the right and down, in [0, 1).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``value`` is still ``...``.

    References
    ----------
    GDAL, ``alg/gdalwarpkernel.cpp``: ``GWKBilinearResample4Sample``.

    Examples
    --------
    >>> check_bilinear(15.0, [[10, 20], [10, 20]], 0.5, 0.5)
    Correct: `value` = 15.
    """
    return BILINEAR.judge(value, BILINEAR.task(window=window, dx=dx, dy=dy))


METHOD_FOR_CLASSES = Declaration(
    check="check_method_for_classes", answer="method", inputs=(),
    right=lambda task: "nearest",
    general=N_("Which method only ever copies existing values?"),
    mistakes=(
        Mistake(N_("Bilinear averages the four neighbouring values: between class 3 and class 5 "
                   "it invents class 4."), lambda task: "bilinear"),
        Mistake(N_("Cubic convolution averages sixteen neighbours with weights that can be "
                   "negative: it invents classes, even values outside the legend."),
                lambda task: "cubic"),
    ))


@declare(METHOD_FOR_CLASSES)
def check_method_for_classes(method):
    """The interpolator for a classified (thematic) map: one of ``resample.METHODS``.

    Parameters
    ----------
    method : str
        The student's answer.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``method`` is still ``...``.

    Examples
    --------
    >>> check_method_for_classes("Nearest")
    Not yet: 'Nearest' is not written as in resample.METHODS: 'nearest', 'bilinear', 'cubic' (lower case, no spaces).
    Hint: Which method only ever copies existing values?
    """  # noqa: E501  (a doctest's expected line)
    generic = _(METHOD_FOR_CLASSES.general)
    listed = ", ".join(map(repr, resample.METHODS))
    try:
        method = require(method, "method")
    except WrongForm as form:
        return form.verdict(generic)
    if not isinstance(method, str):
        return Verdict(False, _("`method` is not a string (`{kind}`); the check needs a name from "
                                "resample.METHODS, a string: {listed}.").format(
                                    kind=type(method).__name__, listed=listed), generic)
    task = METHOD_FOR_CLASSES.task()
    if method == task.right:
        return Verdict(True, _("nearest neighbour: class 3 next to class 5 must not become "
                               "class 4."))
    hints = METHOD_FOR_CLASSES.hints(method, task, lambda answer, wrong: answer == wrong)
    if hints:
        return Verdict(False, _("{value!r} changes a classified map's values.").format(
            value=method), hints[0] + " " + generic)
    if method.strip().lower() in resample.METHODS:
        return Verdict(False, _("{value!r} is not written as in resample.METHODS: {listed} "
                                "(lower case, no spaces).").format(value=method, listed=listed),
                       generic)
    return Verdict(False, _("{value!r} is not one of resample.METHODS: choose one of {listed}, "
                            "written exactly so.").format(value=method, listed=listed), generic)


def _overshoot_derived(task):
    image = np.asarray(task.image)
    values = resample.interpolate(image.astype(np.float64), task.cols, task.rows, "cubic")
    height = float(image.max()) - float(image.min())
    return {"image": image, "values": values, "scale": height if height > 0 else 1.0}


def _scipy_spline(task):
    try:
        from scipy.ndimage import map_coordinates
    except ImportError:                          # pragma: no cover - scipy is a dependency
        return None
    spline = map_coordinates(task.image.astype(np.float64),
                             [np.asarray(task.rows) - 0.5, np.asarray(task.cols) - 0.5],
                             order=3, mode="nearest")
    return float(spline.max() - task.image.max())


OVERSHOOT = Declaration(
    check="check_overshoot", answer="overshoot", inputs=("image", "cols", "rows"),
    derive=_overshoot_derived,
    right=lambda task: float(task.values.max() - task.image.max()),
    general=N_("Interpolate with method='cubic' on a float copy (so nothing is clipped) and "
               "subtract the image's maximum from the interpolated maximum."),
    mistakes=(
        Mistake(N_("Your interpolated values are whole numbers: you interpolated the integer "
                   "image, which GDAL's rules round (and clip); interpolate "
                   "image.astype(np.float64)."),
                lambda task: float(resample.interpolate(task.image, task.cols, task.rows,
                                                        "cubic").max())
                - float(task.image.max())),
        Mistake(N_("That is the largest interpolated value; subtract the image's own maximum."),
                lambda task: float(task.values.max())),
        Mistake(N_("Subtract the image's maximum FROM the interpolated maximum (the excess is "
                   "positive)."), lambda task: -task.right),
        Mistake(N_("That is the undershoot below the minimum, negative; the task asks how far "
                   "the values go ABOVE the maximum."),
                lambda task: float(task.values.min() - task.image.min())),
        Mistake(N_("That is a fraction of the step's height; the check wants DN."),
                lambda task: task.right / task.scale),
        Mistake(N_("That is a percentage of the step's height; the check wants DN."),
                lambda task: 100 * task.right / task.scale),
        Mistake(N_("Zero: nearest and bilinear never leave the range of their neighbours, cubic "
                   "convolution does (negative lobes); interpolate a float copy with "
                   "method='cubic'."), lambda task: 0.0),
        Mistake(N_("That is scipy's cubic spline, not Keys' cubic convolution (a = −0.5, GDAL's "
                   "'cubic'): use rsgeo.resample.interpolate with method='cubic'."),
                _scipy_spline),
    ),
    rtol=1e-6, units=" DN", scale=lambda task: task.scale,
    scale_name=N_("the image's range (its step height)"))


@declare(OVERSHOOT)
def check_overshoot(overshoot, image, cols, rows):
    """Largest amount by which cubic convolution exceeds the image's own maximum.

    Parameters
    ----------
    overshoot : float
        The student's answer, in DN.
    image : 2-D ndarray
        The task's image.
    cols, rows : array_like
        The positions to interpolate at.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``overshoot`` is still ``...``.

    Examples
    --------
    >>> check_overshoot(0.0, np.full((6, 6), 9, np.uint8), [2.5, 3.1], [3.0, 3.0])
    Correct: `overshoot` = 0 DN.
    """
    return OVERSHOOT.judge(overshoot, OVERSHOOT.task(image=image, cols=cols, rows=rows))


def _pixel_size_derived(task):
    rows, cols = as_shape(task.src_shape, "src_shape")
    transform = task.transform
    corners_x, corners_y = transform @ (np.array([0.0, cols, 0.0, cols]),
                                        np.array([0.0, rows, rows, 0.0]))
    return {"rows": rows, "cols": cols,
            "box": np.hypot(np.ptp(corners_x), np.ptp(corners_y)),
            "diagonal": np.hypot(corners_x[1] - corners_x[0], corners_y[1] - corners_y[0]),
            "x_size": np.hypot(transform.a, transform.d),
            "y_size": np.hypot(transform.b, transform.e)}


OUTPUT_PIXEL_SIZE = Declaration(
    check="check_output_pixel_size", answer="pixel_size", inputs=("src_shape", "transform"),
    derive=_pixel_size_derived,
    right=lambda task: float(resample.suggested_grid((task.rows, task.cols),
                                                     task.transform)[0].a),
    general=N_("Take the top-left (0, 0) and bottom-right (cols, rows) corners to the map with "
               "the transform, and divide the distance between them by sqrt(rows² + cols²)."),
    mistakes=(
        Mistake(N_("That is the source's pixel width alone; gdalwarp keeps the number of pixels "
                   "along the diagonal, which mixes width and height."),
                lambda task: task.x_size),
        Mistake(N_("That is the source's pixel height alone; gdalwarp keeps the number of pixels "
                   "along the diagonal, which mixes width and height."),
                lambda task: task.y_size),
        Mistake(N_("The mean of width and height is not the rule: divide the diagonal's length "
                   "on the map by its length in pixels."),
                lambda task: (task.x_size + task.y_size) / 2),
        Mistake(N_("That is the diagonal of the bounding box; the rule uses the top-left to "
                   "bottom-right corner of the image itself."),
                lambda task: task.box / np.hypot(task.rows, task.cols)),
        Mistake(N_("Divide by the diagonal in pixels, sqrt(rows² + cols²), not rows + cols."),
                lambda task: task.diagonal / (task.rows + task.cols)),
        Mistake(N_("Upside down: map length over pixel count."),
                lambda task: np.hypot(task.rows, task.cols) / task.diagonal),
    ),
    rtol=1e-6, mistake_rtol=1e-4, units=" m")


@declare(OUTPUT_PIXEL_SIZE)
def check_output_pixel_size(pixel_size, src_shape, transform):
    """The pixel size gdalwarp chooses for a source: its diagonal rule.

    Parameters
    ----------
    pixel_size : float
        The student's answer, in map units (metres).
    src_shape : (rows, cols)
        The source image's size.
    transform : affine.Affine
        The source's geotransform (pixel -> map).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``pixel_size`` is still ``...``.

    Examples
    --------
    >>> import affine
    >>> check_output_pixel_size(20.0, (100, 100), affine.Affine(20, 0, 0, 0, -20, 0))
    Correct: `pixel_size` = 20 m.
    """
    return OUTPUT_PIXEL_SIZE.judge(pixel_size, OUTPUT_PIXEL_SIZE.task(src_shape=src_shape,
                                                                      transform=transform))


#: The grids chapter 4's table prints (book/04_resampling): the HRC scene's shape and
#: geotransform (GDAL order), and the resolutions (``-tr``) it is warped to, with and without -tap.
_CHAPTER_4_GRIDS = (((2810, 2954), (770595.0, 2.5, 0.0, 7370115.0, 0.0, -2.5), (20.0,)),)


def _chapter_4_grids():
    """(west, north, rows, cols) of each grid chapter 4's table prints."""
    grids = []
    for shape, geotransform, resolutions in _CHAPTER_4_GRIDS:
        transform = affine.Affine.from_gdal(*geotransform)
        options = [dict()] + [dict(resolution=size, tap=tap) for size in resolutions
                              for tap in (False, True)]
        for option in options:
            grid, (rows, cols) = resample.suggested_grid(shape, transform, **option)
            grids.append((grid.c, grid.f, rows, cols))
    return grids


def _grid_derived(task):
    size = as_resolution(task.resolution)[0]
    natural, (n_rows, n_cols) = resample.suggested_grid(task.src_shape, task.transform)
    own = [(natural.c, natural.f, n_rows, n_cols)] + [
        (g.c, g.f, *shape) for g, shape in (resample.suggested_grid(
            task.src_shape, task.transform, resolution=size, tap=tap) for tap in (False, True))]
    return {"size": size, "natural": natural, "natural_shape": (n_rows, n_cols), "own": own}


def _grid(task):
    grid, (rows, cols) = resample.suggested_grid(task.src_shape, task.transform,
                                                 resolution=task.size, tap=True)
    return (grid.c, grid.f, rows, cols)


def _copied_from_chapter_4(answer, task):
    return tuple(answer) in set(_chapter_4_grids()) - set(task.own)


def _footprint_edges(answer, task):
    return tuple(answer[:2]) == (task.natural.c, task.natural.f)


def _edges_inwards(answer, task):
    west, north = answer[:2]
    return (west == np.ceil(task.natural.c / task.size) * task.size
            or north == np.floor(task.natural.f / task.size) * task.size)


def _size_without_tap(answer, task):
    n_rows, n_cols = task.natural_shape
    return tuple(answer[2:]) == (round(n_rows * task.natural.a / task.size),
                                 round(n_cols * task.natural.a / task.size))


GRID_EXTENT = Declaration(
    check="check_grid_extent", answer="extent",
    inputs=("src_shape", "transform", "resolution"),
    derive=_grid_derived,
    right=_grid,
    general=N_("Find the footprint's edges (the corners through the transform), move them out "
               "to multiples of the resolution, then count pixels between them."),
    mistakes=(          # the first that matches gives its hint
        Mistake(N_("Those are the numbers of chapter 4's table, made for the chapter's own "
                   "resolution; this task asks for another one: move the edges to multiples of "
                   "this task's resolution and count its pixels."),
                recognise=_copied_from_chapter_4),
        Mistake(N_("Those are the footprint's own edges; -tap moves them outwards to multiples of "
                   "the resolution: floor(west / res) * res, ceil(north / res) * res."),
                recognise=_footprint_edges),
        Mistake(N_("Outwards: the west edge goes down (floor), the north edge up (ceil), so the "
                   "whole scene stays inside the grid."), recognise=_edges_inwards),
        Mistake(N_("That is the size without -tap; after moving the edges outwards, count the "
                   "pixels between them: (east - west) / res and (north - south) / res."),
                recognise=_size_without_tap),
        Mistake(N_("Rows come first, then columns: (west, north, rows, cols)."),
                recognise=lambda answer, task: tuple(answer[2:]) == (task.right[3],
                                                                      task.right[2])),
    ))


@declare(GRID_EXTENT)
def check_grid_extent(extent, src_shape, transform, resolution):
    """West, north, rows and cols of gdalwarp's grid with ``-tr resolution -tap``.

    Parameters
    ----------
    extent : sequence of four numbers
        The student's answer: (west, north, rows, cols).
    src_shape : (rows, cols)
        The source image's size.
    transform : affine.Affine
        The source's geotransform (pixel -> map).
    resolution : float
        The output pixel size (``-tr``).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``extent`` is still ``...``.
    rsgeo.errors.GridError
        If ``resolution`` is not a positive number.

    Examples
    --------
    >>> import affine
    >>> check_grid_extent((0.0, 40.0, 2, 2), (4, 4), affine.Affine(10, 0, 0, 0, -10, 40), 20)
    Correct: `extent` = (west 0, north 40, 2 rows, 2 cols).
    """
    task = GRID_EXTENT.task(src_shape=src_shape, transform=transform, resolution=resolution)
    west_, north_, rows, cols = task.right
    try:
        answer = require(extent, "extent")
    except WrongForm as wrong:                 # None: the message about a missing return
        return wrong.verdict(_(GRID_EXTENT.general))
    form = _("`extent` must be four numbers, (west, north, rows, cols): the grid's left edge "
             "and top edge in metres, then its size in pixels.")
    try:
        values = [float(v) for v in np.asarray(answer, dtype=object).ravel()]
    except (TypeError, ValueError):
        return Verdict(False, form)
    if len(values) != 4 or not np.isfinite(values).all():
        return Verdict(False, form)
    west, north, n_r, n_c = values
    if [west, north, n_r, n_c] == [west_, north_, rows, cols]:
        return Verdict(True, _("`extent` = (west {west:.10g}, north {north:.10g}, {rows} rows, "
                               "{cols} cols).").format(west=prose_number(west),
                                                       north=prose_number(north),
                                                       rows=int(n_r), cols=int(n_c)))
    # which parts are off and which way, never by how much (that would give the answer away)
    problems = []
    if west != west_:
        problems.append(_("the west edge lies too far west") if west < west_
                        else _("the west edge lies too far east"))
    if north != north_:
        problems.append(_("the north edge lies too far north") if north > north_
                        else _("the north edge lies too far south"))
    if n_r != rows:
        problems.append(_("there are too many rows") if n_r > rows
                        else _("there are too few rows"))
    if n_c != cols:
        problems.append(_("there are too many columns") if n_c > cols
                        else _("there are too few columns"))
    message = _("in `extent`, {problems}.").format(problems="; ".join(problems))
    hints = GRID_EXTENT.hints((west, north, n_r, n_c), task,
                              lambda answer, wrong: tuple(answer) == tuple(wrong),
                              exclude_right=False, first=True)
    return Verdict(False, message, hints[0] if hints else _(GRID_EXTENT.general))
