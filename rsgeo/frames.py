"""Reference frames and coordinate epochs: how far SIRGAS 2000 coordinates are from today's.

SIRGAS 2000 is a static frame: its coordinates are ITRF2000 coordinates at the epoch 2000.4
(EPSG:9052, "ITRF2000 to SIRGAS 2000 (1)": zero parameters at that epoch, in PROJ's database).
The ground does not stand still: the South American plate carries every point on it by a
centimetre or two a year in the International Terrestrial Reference Frame (ITRF). A GNSS
receiver that positions itself from the broadcast orbits gets coordinates in WGS 84, in its
latest realization (G2296, which EPSG takes as ITRF2020 to a centimetre, EPSG:10608), at the
epoch of the observation: the point where it is that day, not where it was in 2000.4.

:func:`sirgas2000_shift` measures that difference with PROJ's own operations, from the files
of PROJ's data folder (its ``ITRF2014`` and ``ITRF2020`` init files): the change of frame,
ITRF2000 to ``frame`` at the epoch 2000.4 (the time-dependent Helmert transformation), then the
plate's motion from 2000.4 to the epoch asked, from ``frame``'s plate motion model (a rotation
of the rigid plate about a pole; local deformation is left out).

Examples
--------
>>> from rsgeo import frames
>>> shift = frames.sirgas2000_shift(-34.85, -8.0, 2026.0)            # Olinda
>>> bool(0.25 < shift.horizontal < 0.45)                             # decimetres
True
"""

import os
from pathlib import Path
from typing import NamedTuple

import numpy as np

from .errors import CRSError, DataError
from .language import N_, _
from .validation import as_lon_lat_height, as_number

__all__ = ["SIRGAS2000_EPOCH", "FRAMES", "EpochShift", "plates", "sirgas2000_shift"]

#: The reference epoch of SIRGAS 2000 (decimal year): its coordinates are ITRF2000's then.
SIRGAS2000_EPOCH = 2000.4

#: The frames whose transformation from ITRF2000 and plate motion model PROJ ships, as init
#: files of its data folder (Altamimi et al. 2017 for ITRF2014, 2023 for ITRF2020).
FRAMES = ("ITRF2014", "ITRF2020")

# decimal years accepted as an epoch: a mistake such as 26 for 2026 is refused, not computed
_EPOCHS = (1900.0, 2200.0)


class EpochShift(NamedTuple):
    """Where ``frame`` puts a point at ``epoch``, from its SIRGAS 2000 coordinates.

    ``east``, ``north`` and ``up`` (metres, the shape of the points given) are the whole
    difference in the local horizon at each point, ``horizontal`` its length across the
    ground; ``frame_change`` and ``plate_motion`` (metres, 3-D lengths) are its two parts; the
    ``pipeline`` is the PROJ operation applied, to be run again or read.
    """

    east: np.ndarray
    north: np.ndarray
    up: np.ndarray
    horizontal: np.ndarray
    frame_change: np.ndarray
    plate_motion: np.ndarray
    pipeline: str


def _init_file(frame):
    """The path of PROJ's init file ``frame`` (e.g. ITRF2020) in PROJ's data folders."""
    import pyproj.datadir

    if frame not in FRAMES:
        raise CRSError(_("unknown frame {frame!r}; rsgeo computes the epoch shift in {known}, "
                         "whose plate motion models PROJ ships").format(
                             frame=frame, known=", ".join(FRAMES)))
    for folder in pyproj.datadir.get_data_dir().split(os.pathsep):
        path = Path(folder) / frame
        if path.is_file():
            return path
    raise DataError(_("PROJ's data folder ({folder}) has no init file {frame}, which holds "
                      "the frame's transformations and plate motion model; reinstall pyproj, "
                      "whose data folder ships it").format(
                          folder=pyproj.datadir.get_data_dir(), frame=frame))


def plates(frame="ITRF2020"):
    """The tectonic plates of ``frame``'s plate motion model, as PROJ's init file names them.

    Parameters
    ----------
    frame : {"ITRF2020", "ITRF2014"}
        The frame.

    Returns
    -------
    tuple of str
        Plate names, such as ``"SOAM"`` (South America) and ``"NOAM"`` (North America).

    Raises
    ------
    CRSError
        If ``frame`` is not one of :data:`FRAMES`.
    DataError
        If PROJ's data folder lacks the frame's init file.

    Examples
    --------
    >>> "SOAM" in plates("ITRF2020") and "SOAM" in plates("ITRF2014")
    True
    """
    names = []
    for line in _init_file(frame).read_text(encoding="utf-8").splitlines():
        # a plate is a rotation rate alone: "<SOAM> +proj=helmert +drx=... +dry=... +drz=..."
        if line.startswith("<") and "+drx=" in line and " +x=" not in line and "_T>" not in line:
            names.append(line[1:line.index(">")])
    return tuple(names)


def _pipeline(frame, plate):
    """PROJ's pipeline: SIRGAS 2000 (lon, lat, h, epoch) -> ``frame`` geocentric at epoch."""
    return " ".join([
        "+proj=pipeline",
        "+step +proj=unitconvert +xy_in=deg +xy_out=rad",
        "+step +proj=cart +ellps=GRS80",
        # ITRF2000 -> frame at the epoch 2000.4 (the 4th coordinate set there, then restored)
        "+step +proj=push +v_4",
        f"+step +proj=set +v_4={SIRGAS2000_EPOCH}",
        f"+step +inv +init={frame}:ITRF2000",
        "+step +proj=pop +v_4",
        # the plate's rotation from 2000.4 to the point's epoch (its 4th coordinate)
        f"+step +init={frame}:{plate} +t_epoch={SIRGAS2000_EPOCH}",
    ])


def _geocentric(lon, lat, height):
    """GRS80 geocentric X, Y, Z (m) of geographic coordinates, by PROJ."""
    from pyproj import Transformer

    cart = Transformer.from_pipeline(
        "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
        "+step +proj=cart +ellps=GRS80")
    return np.array(cart.transform(lon, lat, height), dtype=np.float64)


def _local(dxyz, lon, lat):
    """East, north and up components of geocentric differences at (lon, lat) in degrees."""
    lam, phi = np.radians(lon), np.radians(lat)
    dx, dy, dz = dxyz
    east = -np.sin(lam) * dx + np.cos(lam) * dy
    north = (-np.sin(phi) * np.cos(lam) * dx - np.sin(phi) * np.sin(lam) * dy
             + np.cos(phi) * dz)
    up = np.cos(phi) * np.cos(lam) * dx + np.cos(phi) * np.sin(lam) * dy + np.sin(phi) * dz
    return east, north, up


def sirgas2000_shift(lon, lat, epoch, height=0.0, frame="ITRF2020", plate="SOAM"):
    """How far a point's ITRF coordinates at ``epoch`` are from its SIRGAS 2000 coordinates.

    The point is taken as fixed on ``plate``: its SIRGAS 2000 coordinates (ITRF2000 at
    2000.4) are carried into ``frame`` at 2000.4 by PROJ's time-dependent Helmert
    transformation, then moved with the plate from 2000.4 to ``epoch`` by ``frame``'s plate
    motion model, as PROJ applies it (``+init=ITRF2020:SOAM``). The difference is what
    separates a survey in SIRGAS 2000 from a GNSS position of the same mark at ``epoch``
    (WGS 84 (G2296) is ITRF2020 to a centimetre).

    Parameters
    ----------
    lon, lat : array_like
        SIRGAS 2000 longitude and latitude, degrees, of one shape (or single values).
    epoch : float
        The epoch of the ITRF coordinates, a decimal year (2026.0 is the first of January).
    height : array_like
        Ellipsoidal height (m); it changes the result by less than a millimetre per
        kilometre.
    frame : {"ITRF2020", "ITRF2014"}
        The ITRF realization and its plate motion model.
    plate : str
        The plate the point sits on, one of :func:`plates` (``"SOAM"``, South America).

    Returns
    -------
    EpochShift
        East, north and up differences (m), their horizontal length, the frame change's and
        the plate motion's parts, and PROJ's pipeline.

    Raises
    ------
    CRSError
        If ``frame`` or ``plate`` is unknown, or a latitude or longitude is out of range.
    DataError
        If PROJ's data folder lacks the frame's init file.
    RsgeoError
        If ``epoch`` is not a decimal year between 1900 and 2200, or a value is not finite.
    TypeError
        If a value is text or a boolean, not a number.

    References
    ----------
    Altamimi, Z., Métivier, L., Rebischung, P., Collilieux, X., Chanard, K. and Barnéoud, J.
    (2023), ITRF2020 plate motion model, *Geophysical Research Letters* 50, e2023GL106373.
    Altamimi, Z., Métivier, L., Rebischung, P., Rouby, H. and Collilieux, X. (2017), ITRF2014
    plate motion model, *Geophysical Journal International* 209(3), 1906-1912.

    Examples
    --------
    >>> shift = sirgas2000_shift([-34.85, -47.93], [-8.0, -15.78], 2026.0)   # Olinda, Brasília
    >>> [bool(0.25 < d < 0.45) for d in shift.horizontal]
    [True, True]
    >>> float(sirgas2000_shift(-34.85, -8.0, 2000.4).plate_motion)           # at 2000.4
    0.0
    """
    from pyproj import Transformer
    from pyproj.exceptions import ProjError

    epoch = as_number(epoch, "epoch", *_EPOCHS, why=N_("a decimal year such as 2026.0"))
    known = plates(frame)
    if plate not in known:
        raise CRSError(_("unknown plate {plate!r} in {frame}'s plate motion model; choose one "
                         "of {known}").format(plate=plate, frame=frame,
                                              known=", ".join(known)))
    lon, lat, height = as_lon_lat_height(lon, lat, height)
    shape = lon.shape
    lon, lat, height = (np.ravel(v).astype(np.float64) for v in (lon, lat, height))
    pipeline = _pipeline(frame, plate)
    try:
        proj = Transformer.from_pipeline(pipeline)
        times = np.full(lon.shape, epoch)
        moved = np.array(proj.transform(lon, lat, height, times)[:3], dtype=np.float64)
        # the frame change alone: the same pipeline at the epoch 2000.4, where the plate rests
        changed = np.array(proj.transform(lon, lat, height, np.full(lon.shape,
                                                                    SIRGAS2000_EPOCH))[:3],
                           dtype=np.float64)
    except ProjError as error:
        raise CRSError(_("PROJ could not apply {pipeline!r}: {error}").format(
            pipeline=pipeline, error=error)) from None
    if not (np.isfinite(moved).all() and np.isfinite(changed).all()):
        raise CRSError(_("PROJ gave no coordinates (inf or nan) for the pipeline {pipeline!r}; "
                         "its init file {frame} could not be read").format(
                             pipeline=pipeline, frame=frame))
    start = _geocentric(lon, lat, height)
    east, north, up = _local(moved - start, lon, lat)
    frame_change = np.linalg.norm(changed - start, axis=0)
    plate_motion = np.linalg.norm(moved - changed, axis=0)
    return EpochShift(*(np.reshape(v, shape) for v in (
        east, north, up, np.hypot(east, north), frame_change, plate_motion)), pipeline)
