"""Checks of exercises 2b (chapter 2b, CRSs and datums): a datum shift in pixels."""

import numpy as np

from .. import georef
from .._checks import as_points
from .._i18n import N_
from ..errors import GridError
from .engine import Declaration, Mistake, declare

__all__ = ["check_datum_shift_pixels"]


def _datum_derived(task):
    size = float(task.pixel_size)
    if not np.isfinite(size) or size <= 0:
        raise GridError(f"pixel_size must be a positive number of metres, got {task.pixel_size!r}")
    dx, dy, distance = georef.datum_shift(as_points(task.map_xy, "map_xy"), task.src_crs,
                                          task.dst_crs)
    return {"size": size, "dx": dx, "dy": dy, "distance": distance}


DATUM_SHIFT_PIXELS = Declaration(
    check="check_datum_shift_pixels", answer="shift_px",
    inputs=("map_xy", "src_crs", "dst_crs", "pixel_size"),
    derive=_datum_derived,
    right=lambda task: float(np.mean(task.distance)) / task.size,
    general=N_("Transform the points with rsgeo.georef.transform_points, take each point's "
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
