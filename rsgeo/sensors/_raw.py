"""The geometry of a raw (level 1A) pushbroom scene: chapter 1's sensor model placed on a map,
over a DEM.
"""

from dataclasses import replace

import numpy as np

from ..distortion import EARTH_RADIUS_KM
from ..errors import ModelError
from ..language import _
from ..validation import as_finite, as_integer, as_number
from ._systematic import SystematicDistortion

__all__ = ["RawSensor"]


# -- Raw (level 1A) geometry: chapter 1's sensor model over the Olinda DEM ------

class RawSensor:
    """The geometry of a raw pushbroom scene: chapter 1's sensor model placed on a map.

    A :class:`rsgeo.sensors.SystematicDistortion` with view geometry maps
    its true grid (the ground in the orbit's frame: columns across track,
    rows along it, in nadir pixels, nadir at the grid's centre column) to the
    raw image, with the Earth-rotation skew, the attitude and the
    curved-Earth view angles of chapter 1. This class adds what a map needs:

    * the orbit's frame on the map: the track heads ``heading_deg`` west of
      south (a descending pass; the angle of
      :func:`rsgeo.distortion.track_angle`), columns run across it towards
      the east, and ``centre_xy`` lies ``offset_km`` across the track from
      nadir, on the grid's middle row;
    * relief: a point at height h is seen along the line of sight that meets
      the sphere of radius R + h there; the model receives the point of the
      datum (radius R) on the same line of sight, so a high point lands
      farther from nadir, by about h·tan z (z its view zenith angle,
      :func:`rsgeo.relief.relief_displacement`).

    Heights are ellipsoidal, on a sphere of radius
    ``rsgeo.distortion.EARTH_RADIUS_KM`` (6371 km); the map's metres are taken as
    ground metres (a UTM scale factor near 1).

    Parameters
    ----------
    distortion : rsgeo.sensors.SystematicDistortion
        With ``view_altitude_km``, ``nadir_pixel_km`` and ``shape`` (the raw
        image's rows and columns) set; a negative ``roll_deg`` points the
        camera towards the east.
    centre_xy : (float, float)
        Map point (m) at ``offset_km`` from the nadir track on the grid's middle row.
    heading_deg : float
        Angle of the track west of south (degrees).
    offset_km : float
        Ground distance across the track from nadir to ``centre_xy`` (km),
        positive to the east; the ground's, whatever the model's roll says.

    Raises
    ------
    ValueError
        If the distortion has no view geometry or no shape.

    Examples
    --------
    >>> from rsgeo.distortion import ground_distance
    >>> from rsgeo.sensors import SystematicDistortion
    >>> model = SystematicDistortion(roll_deg=-20.0, view_altitude_km=778.0,
    ...                              nadir_pixel_km=0.01, shape=(100, 100))
    >>> sensor = RawSensor(model, (5000.0, 9000.0), 8.6, ground_distance(20.0, 778.0))
    >>> col, row = sensor.project(5000.0, 9000.0, 0.0)
    >>> round(float(col), 6), round(float(row), 6)
    (50.0, 50.0)
    """

    def __init__(self, distortion, centre_xy, heading_deg, offset_km):
        if not isinstance(distortion, SystematicDistortion):
            raise TypeError(_("distortion must be a SystematicDistortion, got {kind}").format(
                kind=type(distortion).__name__))
        if distortion.view_altitude_km is None or distortion.shape is None:
            raise ModelError(_("a raw scene's distortion needs view geometry and a shape: give "
                               "view_altitude_km, nadir_pixel_km and shape=(rows, cols)"))
        self.distortion = distortion
        self.centre_xy = (as_number(centre_xy[0], "centre_xy[0]"),
                          as_number(centre_xy[1], "centre_xy[1]"))
        self.heading_deg = as_number(heading_deg, "heading_deg", -90, 90)
        self.offset_km = as_number(offset_km, "offset_km")

    def __repr__(self):
        return (f"RawSensor(heading {self.heading_deg:.2f}° west of south, "
                f"{self.offset_km:.1f} km across track, image {self.distortion.shape})")

    @property
    def shape(self):
        """(rows, cols) of the raw image.

        Returns
        -------
        tuple of int
        """
        return tuple(self.distortion.shape)

    def _frame(self):
        angle = np.radians(self.heading_deg)
        return np.cos(angle), np.sin(angle)

    def project(self, x, y, h):
        """Raw-image (col, row) of map points (x, y) at ellipsoidal height h.

        Parameters
        ----------
        x, y : array_like
            Map coordinates (m).
        h : array_like
            Ellipsoidal height (m); broadcast with x and y.

        Returns
        -------
        col, row : ndarray
            GDAL's pixel coordinates of the raw image.

        Raises
        ------
        ValueError
            If a value is not finite or a point is beyond the horizon.
        """
        x, y, h = np.broadcast_arrays(*(as_finite(v, name, error=ModelError)
                                        for v, name in ((x, "x"), (y, "y"), (h, "h"))))
        cos, sin = self._frame()
        dx, dy = x - self.centre_xy[0], y - self.centre_xy[1]
        across, along = dx * cos - dy * sin, -dx * sin - dy * cos        # metres
        radius = EARTH_RADIUS_KM
        orbit = radius + self.distortion.view_altitude_km
        alpha = (self.offset_km + across / 1000) / radius
        raised = radius + h / 1000
        look = np.arctan2(raised * np.sin(alpha), orbit - raised * np.cos(alpha))
        sine = orbit / radius * np.sin(look)
        if np.any(np.abs(sine) >= 1):
            raise ModelError(_("a point is beyond the horizon of the sensor"))
        datum = np.arcsin(sine) - look                  # the datum point on the same ray
        rows, cols = self.shape
        pixel = self.distortion.nadir_pixel_km
        true = np.column_stack([(datum * radius / pixel + cols / 2).ravel(),
                                (along / 1000 / pixel + rows / 2).ravel()])
        image = self.distortion(true)
        return image[:, 0].reshape(x.shape), image[:, 1].reshape(x.shape)

    def ground(self, col, row, h):
        """Map (x, y) seen at raw-image (col, row) if the ground there is at height h.

        Parameters
        ----------
        col, row : array_like
            GDAL pixel coordinates of the raw image.
        h : array_like
            Ellipsoidal height (m).

        Returns
        -------
        x, y : ndarray

        Raises
        ------
        ValueError
            If a value is not finite, or as the distortion's inverse.
        """
        col, row, h = np.broadcast_arrays(*(as_finite(v, name, error=ModelError)
                                            for v, name in ((col, "col"), (row, "row"), (h, "h"))))
        x, y = self._on_sphere(self._true_grid(col, row), h.ravel())
        return x.reshape(col.shape), y.reshape(col.shape)

    def _true_grid(self, col, row):
        """The distortion's true grid (datum) positions of image points: (n, 2)."""
        return self.distortion.inverse()(np.column_stack([np.ravel(col), np.ravel(row)]))

    def _on_sphere(self, true, h):
        """Map (x, y) of true-grid positions raised to heights h (1-D arrays)."""
        rows, cols = self.shape
        pixel = self.distortion.nadir_pixel_km
        radius = EARTH_RADIUS_KM
        orbit = radius + self.distortion.view_altitude_km
        datum = (true[:, 0] - cols / 2) * pixel / radius
        along = (true[:, 1] - rows / 2) * pixel * 1000
        look = np.arctan2(radius * np.sin(datum), orbit - radius * np.cos(datum))
        raised = radius + h / 1000
        reach = raised ** 2 - (orbit * np.sin(look)) ** 2
        if np.any(reach < 0):
            raise ModelError(_("a line of sight misses the sphere of the given height"))
        distance = orbit * np.cos(look) - np.sqrt(reach)
        alpha = np.arctan2(distance * np.sin(look), orbit - distance * np.cos(look))
        across = (alpha * radius - self.offset_km) * 1000
        cos, sin = self._frame()
        return (self.centre_xy[0] + across * cos - along * sin,
                self.centre_xy[1] - across * sin - along * cos)

    def ground_on_dem(self, col, row, dem, dem_transform, iterations=10):
        """Where the lines of sight of (col, row) meet a DEM (fixed-point iteration).

        Parameters
        ----------
        col, row : array_like
        dem : 2-D array
            Ellipsoidal heights (m).
        dem_transform : affine.Affine
            In the sensor's map coordinates.
        iterations : int
            Steps of h -> (x, y) -> h; each shrinks the error by the terrain's
            slope times tan z, so a few suffice on gentle terrain.

        Returns
        -------
        x, y, h : ndarray

        Raises
        ------
        ValueError
            If a line of sight leaves the DEM.
        """
        from ..dem import line_of_sight_on_dem

        iterations = as_integer(iterations, "iterations", low=1)
        col, row = np.broadcast_arrays(as_finite(col, "col", error=ModelError),
                                       as_finite(row, "row", error=ModelError))
        true = self._true_grid(col, row)          # the line of sight: once, whatever the height
        x, y, h = line_of_sight_on_dem(lambda h: self._on_sphere(true, h), (col.size,), dem,
                                       dem_transform, iterations)
        return x.reshape(col.shape), y.reshape(col.shape), h.reshape(col.shape)

    def with_knowledge_errors(self, roll_deg=0.0, pitch_deg=0.0, yaw_deg=0.0,
                              yaw_rate_deg_per_line=0.0, across_km=0.0, along_km=0.0,
                              radial_km=0.0):
        """The sensor a ground station believes in: its attitude and position off by these.

        The ground does not move (``centre_xy``, ``heading_deg`` and
        ``offset_km`` are kept); the model's platform data change as in
        :meth:`rsgeo.sensors.SystematicDistortion.with_knowledge_errors`,
        and ``yaw_rate_deg_per_line`` adds a drift of the yaw during the scene.

        Parameters
        ----------
        roll_deg, pitch_deg, yaw_deg, yaw_rate_deg_per_line : float
            Attitude knowledge errors (degrees; degrees per line).
        across_km, along_km, radial_km : float
            Ephemeris knowledge errors (km).

        Returns
        -------
        RawSensor

        Raises
        ------
        ValueError
            If a value is not a finite number.
        """
        known = self.distortion.with_knowledge_errors(roll_deg, pitch_deg, yaw_deg, across_km,
                                                      along_km, radial_km)
        rate = known.yaw_rate_deg_per_line + as_number(yaw_rate_deg_per_line,
                                                       "yaw_rate_deg_per_line")
        known = replace(known, yaw_rate_deg_per_line=float(rate))
        return RawSensor(known, self.centre_xy, self.heading_deg, self.offset_km)
