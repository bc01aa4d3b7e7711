"""Checks of exercises 2b (chapter 2b, CRSs and datums): a datum shift in pixels, and how far
apart IBGE's grid and the three-parameter transformation put the same points."""

import numpy as np

from rsgeo import crs
from rsgeo.errors import GridError
from rsgeo.validation import as_points

from .._i18n import N_, _
from .engine import Declaration, Mistake, declare

__all__ = ["check_datum_shift_pixels", "check_grid_vs_parameters"]


def _datum_derived(task):
    size = float(task.pixel_size)
    if not np.isfinite(size) or size <= 0:
        raise GridError(_("pixel_size must be a positive number of metres, got "
                          "{task_pixel_size!r}").format(task_pixel_size=task.pixel_size))
    dx, dy, distance = crs.datum_shift(as_points(task.map_xy, "map_xy"), task.src_crs,
                                          task.dst_crs)
    return {"size": size, "dx": dx, "dy": dy, "distance": distance}


DATUM_SHIFT_PIXELS = Declaration(
    check="check_datum_shift_pixels", answer="shift_px",
    inputs=("map_xy", "src_crs", "dst_crs", "pixel_size"),
    derive=_datum_derived,
    right=lambda task: float(np.mean(task.distance)) / task.size,
    general=N_("Transform the points with rsgeo.crs.transform_points, take each point's "
               "distance sqrt(dx² + dy²), average, and divide by the pixel size."),
    mistakes=(
        Mistake(N_("That is the shift in metres; divide by the pixel size to get pixels."),
                lambda task: np.mean(task.distance)),
        Mistake(N_("That is only the easting's change; the shift is the distance sqrt(dx² + "
                   "dy²)."), lambda task: np.mean(np.abs(task.dx)) / task.size),
        Mistake(N_("That is only the northing's change; the shift is the distance sqrt(dx² + "
                   "dy²)."), lambda task: np.mean(np.abs(task.dy)) / task.size),
        Mistake(N_("|dx| + |dy| overstates the distance; use sqrt(dx² + dy²)."),
                lambda task: np.mean(np.abs(task.dx) + np.abs(task.dy)) / task.size),
        Mistake(N_("Multiplying by the pixel size gives metres², not pixels: divide."),
                lambda task: np.mean(task.distance) * task.size),
        Mistake(N_("The shift's size is a distance, sqrt(dx² + dy²), not dx alone."),
                lambda task: np.mean(task.dx) / task.size),
    ),
    rtol=0.01, mistake_rtol=0.01, units=" px")


@declare(DATUM_SHIFT_PIXELS)
def check_datum_shift_pixels(shift_px, map_xy, src_crs, dst_crs, pixel_size, name="shift_px"):
    """The mean size of a datum shift at some points, in pixels of a given size.

    Parameters
    ----------
    shift_px : float
        The student's answer: the mean distance each point moves from
        ``src_crs`` to ``dst_crs``, divided by the pixel size.
    map_xy : (n, 2) array_like
        The points' map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio CRS
        E.g. SAD69 / UTM 21S and SIRGAS 2000 / UTM 21S.
    pixel_size : float
        Metres per pixel (20 for the CBERS CCD).
    name : str, optional
        The name of the student's variable, which the verdict quotes
        (``"hrc_shift_px"`` in exercise 2b.2).

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``shift_px`` is still ``...``.
    rsgeo.errors.GridError
        For a pixel size that is not positive.
    ValueError
        For a CRS that PROJ does not know.

    Examples
    --------
    >>> check_datum_shift_pixels(0.0, [[775445.0, 7369105.0]], 29191, 31981, 20.0).ok
    False
    >>> check_datum_shift_pixels(0.0, [[775445.0, 7369105.0]], 29191, 31981, 2.5,
    ...                          name="hrc_shift_px").message
    '`hrc_shift_px` is zero, and it should not be.'
    """
    task = DATUM_SHIFT_PIXELS.task(map_xy=map_xy, src_crs=src_crs, dst_crs=dst_crs,
                                   pixel_size=pixel_size)
    return DATUM_SHIFT_PIXELS.judge(shift_px, task, name=name)


def _gap_derived(task):
    size = float(task.pixel_size)
    if not np.isfinite(size) or size <= 0:
        raise GridError(_("pixel_size must be a positive number of metres, got "
                          "{task_pixel_size!r}").format(task_pixel_size=task.pixel_size))
    points = as_points(task.map_xy, "map_xy")
    grid = crs.datum_shift(points, task.src_crs, task.dst_crs, transformation=task.grid)
    three = crs.datum_shift(points, task.src_crs, task.dst_crs,
                               transformation=task.parameters)
    ddx, ddy = grid.dx - three.dx, grid.dy - three.dy
    return {"size": size, "grid_shift": grid.distance, "three_shift": three.distance,
            "ddx": ddx, "ddy": ddy, "gap": np.hypot(ddx, ddy)}


GRID_VS_PARAMETERS = Declaration(
    check="check_grid_vs_parameters", answer="gap_px",
    inputs=("map_xy", "src_crs", "dst_crs", "pixel_size", "grid", "parameters"),
    derive=_gap_derived,
    right=lambda task: float(np.max(task.gap)) / task.size,
    general=N_("Move the points twice with rsgeo.crs.transform_points, once with "
               "transformation='EPSG:5528' (the grid) and once with 'EPSG:15485' (the three "
               "parameters); take each point's distance between its two results, sqrt(dx² + "
               "dy²), keep the largest, and divide by the pixel size."),
    mistakes=(
        Mistake(N_("That is the difference in metres; divide by the pixel size to get pixels."),
                lambda task: np.max(task.gap)),
        Mistake(N_("That is the grid's shift itself, from SAD69 to SIRGAS 2000; the task asks how "
                   "far the two transformations' results are from each other."),
                lambda task: [np.max(task.grid_shift) / task.size,
                              np.mean(task.grid_shift) / task.size], many=True),
        Mistake(N_("That is the three-parameter shift itself; the task asks how far its result "
                   "is from the grid's."),
                lambda task: [np.max(task.three_shift) / task.size,
                              np.mean(task.three_shift) / task.size], many=True),
        Mistake(N_("You subtracted the lengths of the two shifts; subtract the two results "
                   "(the positions), then take the distance sqrt(dx² + dy²)."),
                lambda task: np.max(np.abs(task.grid_shift - task.three_shift)) / task.size),
        Mistake(N_("That is only the easting's difference; the distance is sqrt(dx² + dy²)."),
                lambda task: np.max(np.abs(task.ddx)) / task.size),
        Mistake(N_("That is only the northing's difference; the distance is sqrt(dx² + dy²)."),
                lambda task: np.max(np.abs(task.ddy)) / task.size),
        Mistake(N_("|dx| + |dy| overstates the distance; use sqrt(dx² + dy²)."),
                lambda task: np.max(np.abs(task.ddx) + np.abs(task.ddy)) / task.size),
        Mistake(N_("That is the mean distance over the points; the task asks for the largest."),
                lambda task: np.mean(task.gap) / task.size),
        Mistake(N_("That is the smallest distance over the points; the task asks for the "
                   "largest."), lambda task: np.min(task.gap) / task.size),
        Mistake(N_("Multiplying by the pixel size gives metres², not pixels: divide."),
                lambda task: np.max(task.gap) * task.size),
    ),
    rtol=0.001, mistake_rtol=0.001, units=" px")


@declare(GRID_VS_PARAMETERS)
def check_grid_vs_parameters(gap_px, map_xy, src_crs, dst_crs, pixel_size, grid="EPSG:5528",
                             parameters="EPSG:15485", name="gap_px"):
    """How far apart a grid and a parameter transformation put the same points, in pixels.

    Parameters
    ----------
    gap_px : float
        The student's answer: the largest distance, over the points, between the positions
        the two transformations give in ``dst_crs``, divided by the pixel size.
    map_xy : (n, 2) array_like
        The points' map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio CRS
        E.g. SAD69 / UTM 23S and SIRGAS 2000 / UTM 23S (the same projection).
    pixel_size : float
        Metres per pixel (25 for the nat1 scene).
    grid, parameters : str
        The two transformations, as :func:`rsgeo.crs.datum_shift` takes them: IBGE's
        grid (EPSG:5528) and the three geocentric translations (EPSG:15485) by default.
    name : str, optional
        The name of the student's variable, which the verdict quotes.

    Returns
    -------
    Verdict

    Raises
    ------
    ExerciseNotSolved
        If ``gap_px`` is still ``...``.
    rsgeo.errors.GridError
        For a pixel size that is not positive.
    ValueError
        For a CRS or transformation that PROJ does not know, or points outside the
        transformations' areas of use.

    Examples
    --------
    >>> check_grid_vs_parameters(0.0, [[775445.0, 7369105.0]], 29191, 31981, 20.0).ok
    False
    >>> check_grid_vs_parameters(0.0, [[775445.0, 7369105.0]], 29191, 31981, 20.0).message
    '`gap_px` is zero, and it should not be.'
    """
    task = GRID_VS_PARAMETERS.task(map_xy=map_xy, src_crs=src_crs, dst_crs=dst_crs,
                                   pixel_size=pixel_size, grid=grid, parameters=parameters)
    return GRID_VS_PARAMETERS.judge(gap_px, task, name=name)
