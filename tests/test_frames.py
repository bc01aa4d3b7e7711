"""rsgeo.frames: SIRGAS 2000 coordinates against ITRF coordinates at another epoch.

Each part of the shift is checked against a computation that does not use rsgeo's pipeline:
the frame change against PROJ's EPSG operation "ITRF2000 to ITRF2020 (1)" (and ITRF2014's),
the plate motion against the rotation v = ω × X computed by hand from the published poles.
"""

import numpy as np
import pytest
from pyproj import Transformer
from pyproj.crs import CoordinateOperation

from rsgeo import frames
from rsgeo.errors import CRSError, RsgeoError

OLINDA = (-34.85, -8.0)

# Euler poles of the South American plate (SOAM), milliarc-seconds a year, as published:
# Altamimi et al. (2023), ITRF2020 plate motion model, table 1; Altamimi et al. (2017),
# ITRF2014 plate motion model, table 1
SOAM_POLE = {"ITRF2020": (-0.261, -0.282, -0.157), "ITRF2014": (-0.270, -0.301, -0.140)}
# the EPSG geographic 3-D CRSs of the frames: ITRF2000, ITRF2014, ITRF2020
GEOGRAPHIC_3D = {"ITRF2000": 7909, "ITRF2014": 7912, "ITRF2020": 9989}


def geocentric(lon, lat, h):
    cart = Transformer.from_pipeline("+proj=pipeline +step +proj=unitconvert +xy_in=deg "
                                     "+xy_out=rad +step +proj=cart +ellps=GRS80")
    return np.array(cart.transform(lon, lat, h))


def east_north_up(d, lon, lat):
    """The local east, north and up unit vectors at (lon, lat), dotted with d (3, ...)."""
    lam, phi = np.radians(lon), np.radians(lat)
    east = (-np.sin(lam), np.cos(lam), 0.0)
    north = (-np.sin(phi) * np.cos(lam), -np.sin(phi) * np.sin(lam), np.cos(phi))
    up = (np.cos(phi) * np.cos(lam), np.cos(phi) * np.sin(lam), np.sin(phi))
    return tuple(sum(u * c for u, c in zip(unit, d)) for unit in (east, north, up))


def test_sirgas2000_is_itrf2000_at_its_epoch_in_projs_database():
    operation = CoordinateOperation.from_epsg(9052)           # ITRF2000 to SIRGAS 2000 (1)
    values = {p.name: p.value for p in operation.params}
    assert values.pop("Transformation reference epoch") == frames.SIRGAS2000_EPOCH
    assert all(value == 0 for value in values.values())       # seven zero parameters


@pytest.mark.parametrize("frame", frames.FRAMES)
def test_the_frame_change_is_projs_epsg_operation(frame):
    # at 2000.4 the plate has not moved: the shift is ITRF2000 -> frame alone, which PROJ's
    # EPSG database gives independently of the init file rsgeo's pipeline reads
    lon, lat, h = np.array([-34.85, -47.93, -60.0]), np.array([-8.0, -15.78, -30.0]), 50.0
    shift = frames.sirgas2000_shift(lon, lat, frames.SIRGAS2000_EPOCH, h, frame=frame)
    epsg = Transformer.from_crs(GEOGRAPHIC_3D["ITRF2000"], GEOGRAPHIC_3D[frame], always_xy=True)
    moved = epsg.transform(lon, lat, np.full(3, h), np.full(3, frames.SIRGAS2000_EPOCH))
    d = geocentric(*moved[:3]) - geocentric(lon, lat, np.full(3, h))
    for ours, theirs in zip((shift.east, shift.north, shift.up), east_north_up(d, lon, lat)):
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-4)   # a tenth of a mm
    np.testing.assert_allclose(shift.frame_change, np.linalg.norm(d, axis=0), atol=1e-4)
    assert (shift.plate_motion == 0).all() and (shift.frame_change < 0.05).all()   # cm


@pytest.mark.parametrize("frame", frames.FRAMES)
def test_the_plate_motion_is_the_published_poles_rotation(frame):
    lon, lat = OLINDA
    years = 2026.0 - frames.SIRGAS2000_EPOCH
    shift = frames.sirgas2000_shift(lon, lat, 2026.0, frame=frame)
    rest = frames.sirgas2000_shift(lon, lat, frames.SIRGAS2000_EPOCH, frame=frame)
    omega = np.radians(np.array(SOAM_POLE[frame]) / 3.6e6)        # mas/yr -> rad/yr
    by_hand = np.cross(omega, geocentric(lon, lat, 0.0)) * years    # v = ω × X, times Δt
    moved = np.subtract((shift.east, shift.north, shift.up), (rest.east, rest.north, rest.up))
    np.testing.assert_allclose(moved, east_north_up(by_hand, lon, lat), rtol=0, atol=1e-4)
    assert shift.plate_motion == pytest.approx(np.linalg.norm(by_hand), abs=1e-4)
    # the South American plate at Olinda: one to two centimetres a year, to the north
    assert 0.01 < np.linalg.norm(by_hand) / years < 0.02 and moved[1] > abs(moved[0])


def test_decimetres_at_olinda_today_and_the_shape_is_kept():
    shift = frames.sirgas2000_shift(*OLINDA, 2026.0)
    assert 0.25 < shift.horizontal < 0.45 and abs(shift.up) < 0.02
    assert shift.frame_change < 0.1 * shift.plate_motion             # the plate dominates
    assert "+init=ITRF2020:SOAM" in shift.pipeline
    grid = frames.sirgas2000_shift(np.full((2, 3), -40.0), np.full((2, 3), -10.0), 2026.0)
    assert all(np.shape(v) == (2, 3) for v in grid[:6])
    np.testing.assert_allclose(grid.horizontal, grid.horizontal[0, 0], rtol=1e-12)


@pytest.mark.parametrize("call, error, match", [
    (lambda: frames.sirgas2000_shift(*OLINDA, 2026.0, frame="ITRF2008"), CRSError,
     "unknown frame 'ITRF2008'"),
    (lambda: frames.sirgas2000_shift(*OLINDA, 2026.0, plate="XXXX"), CRSError,
     "unknown plate 'XXXX'.*SOAM"),
    (lambda: frames.sirgas2000_shift(*OLINDA, 26.0), RsgeoError, "epoch must be .*2026.0"),
    (lambda: frames.sirgas2000_shift(*OLINDA, float("nan")), RsgeoError, "finite"),
    (lambda: frames.sirgas2000_shift(-8.0, -134.85, 2026.0), CRSError, "swapped"),
    (lambda: frames.sirgas2000_shift([-34.85, -35.0], [-8.0, -8.1, -8.2], 2026.0), RsgeoError,
     "one shape"),
    (lambda: frames.sirgas2000_shift("-34.85", -8.0, 2026.0), TypeError, "lon must be"),
    (lambda: frames.sirgas2000_shift(*OLINDA, "2026"), TypeError, "epoch must be a number"),
    (lambda: frames.plates("WGS84"), CRSError, "unknown frame"),
])
def test_refusals_say_what_is_needed(call, error, match):
    with pytest.raises(error, match=match):
        call()
