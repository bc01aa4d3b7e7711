"""A pushbroom scanner over a flat map plane with a known geometry (for simulations), and an RPC
fitted to it as vendors fit theirs.
"""

import numpy as np

from .._grids import as_gdal, gdal_inverse, to_crs
from ..dem import line_of_sight_on_dem
from ..errors import ImageError, ModelError, RsgeoError
from ..language import _
from ..resample import interpolate
from ..validation import (
    as_image,
    as_shape,
)
from ._rpc import fit_rpc

__all__ = ["PushbroomSensor", "fit_rpc_to_sensor"]



# -- A physical sensor to fit RPCs to ----------------------------------------

class PushbroomSensor:
    """A pushbroom scanner over a flat map plane, with a known geometry (for simulations).

    The platform flies south along the map's y axis at ``altitude_m`` (a
    descending pass, as the daytime passes of Landsat and CBERS are): line
    ``row`` is acquired when it is at y = ``y0 - row * line_step_m``, so the
    first line is the northernmost and rows go south, as in a north-up map.
    The across-track detector array sees view angles from
    ``centre_angle_deg - half_fov`` to ``+ half_fov``, one angle per column,
    with columns running west to east: a positive angle looks east (to the
    platform's left, since it flies south). A ground point (x, y, h)
    is seen at ``tan(angle) = (x - x_nadir) / (altitude - h)``: its
    displacement from where a point at height 0 would be is h·tan(angle),
    :func:`~rsgeo.relief.relief_displacement`. Earth curvature and attitude changes are
    left out (chapter 1 has them).

    Parameters
    ----------
    x_nadir, y0 : float
        Map coordinates of the nadir track and of the first line's ground (m).
    altitude_m : float
        Platform altitude above the datum (m).
    centre_angle_deg : float
        View angle of the middle column (roll, off-nadir pointing).
    ifov_deg : float
        Angle between adjacent columns (degrees).
    columns : int
        Detectors per line.
    line_step_m : float
        Ground distance between lines (m).

    Examples
    --------
    >>> sensor = PushbroomSensor(0.0, 1000.0, 700e3, 0.0, 1e-3, 101, 10.0)
    >>> col, row = sensor.project(0.0, 900.0, 0.0)
    >>> float(col), float(row)
    (50.5, 10.0)
    """

    def __init__(self, x_nadir, y0, altitude_m, centre_angle_deg, ifov_deg, columns,
                 line_step_m):
        self.x_nadir, self.y0 = float(x_nadir), float(y0)
        self.altitude = float(altitude_m)
        self.centre = np.radians(float(centre_angle_deg))
        self.ifov = np.radians(float(ifov_deg))
        self.columns = int(columns)
        self.line_step = float(line_step_m)

    def view_angle(self, col):
        """View angle (degrees) of a column position.

        Parameters
        ----------
        col : array_like
            GDAL column position.

        Returns
        -------
        ndarray
            Degrees, positive to the east.

        Raises
        ------
        ValueError
            Never; NumPy rules apply.
        """
        return np.degrees(self.centre + (np.asarray(col, float) - self.columns / 2) * self.ifov)

    def project(self, x, y, h):
        """Image (col, row) of map points (x, y) at height h.

        Parameters
        ----------
        x, y, h : array_like
            Map metres and height (m).

        Returns
        -------
        col, row : ndarray

        Raises
        ------
        ValueError
            If a point is at or above the platform.
        """
        x, y, h = (np.asarray(a, dtype=float) for a in (x, y, h))
        if np.any(h >= self.altitude):
            raise ModelError(_("a ground point is at or above the platform's altitude"))
        angle = np.arctan((x - self.x_nadir) / (self.altitude - h))
        col = (angle - self.centre) / self.ifov + self.columns / 2
        row = (self.y0 - y) / self.line_step
        return col, row

    def ground(self, col, row, h):
        """Map (x, y) seen at image (col, row) if the ground there is at height h.

        Parameters
        ----------
        col, row, h : array_like

        Returns
        -------
        x, y : ndarray

        Raises
        ------
        ValueError
            Never; NumPy rules apply.
        """
        col, row, h = (np.asarray(a, dtype=float) for a in (col, row, h))
        angle = self.centre + (col - self.columns / 2) * self.ifov
        return self.x_nadir + (self.altitude - h) * np.tan(angle), self.y0 - row * self.line_step

    def ground_on_dem(self, col, row, dem, dem_transform, iterations=20):
        """Where the line of sight of (col, row) meets the DEM (fixed-point iteration).

        Parameters
        ----------
        col, row : array_like
        dem : 2-D array
        dem_transform : affine.Affine
            In the same map coordinates as the sensor.
        iterations : int

        Returns
        -------
        x, y, h : ndarray

        Raises
        ------
        ValueError
            If a line of sight leaves the DEM.
        """
        shape = np.broadcast(np.asarray(col), np.asarray(row)).shape
        return line_of_sight_on_dem(lambda h: self.ground(col, row, h), shape, dem,
                                    dem_transform, int(iterations))

    def simulate(self, shape, dem, dem_transform, ground, ground_transform):
        """The raw image this sensor records over a DEM, from an orthoimage of the ground.

        Each pixel's line of sight meets the DEM (:meth:`ground_on_dem`); the
        pixel takes the ground image's value there (bilinear, GDAL's rules).

        Parameters
        ----------
        shape : (rows, cols)
            Size of the raw image; ``cols`` at most the sensor's columns.
        dem, dem_transform
            Heights and their geotransform, in the sensor's map coordinates.
        ground : 2-D ndarray
            The ground's reflectance as a map (an orthoimage).
        ground_transform : affine.Affine
            Its geotransform, same coordinates.

        Returns
        -------
        image : ndarray
            ``ground``'s dtype, ``shape``.
        x, y, h : ndarray
            The ground point each pixel centre sees.

        Raises
        ------
        ValueError
            If a line of sight leaves the DEM, or the ground image is not 2-D.

        Examples
        --------
        >>> import affine
        >>> sensor = PushbroomSensor(0.0, 100.0, 700e3, 0.0, 1e-3, 10, 10.0)
        >>> dem_gt = affine.Affine(50, 0, -500, 0, -50, 500)
        >>> ground = np.arange(400, dtype=np.uint8).reshape(20, 20) % 200
        >>> image, *_ = sensor.simulate((10, 10), np.zeros((20, 20)), dem_gt, ground, dem_gt)
        >>> image.shape
        (10, 10)
        """
        rows, cols = as_shape(shape)
        ground = as_image(ground, "ground")
        if ground.ndim != 2:
            raise ImageError(_("ground must be a 2-D image, got shape {ground_shape}").format(
                    ground_shape=ground.shape))
        r, c = np.mgrid[0:rows, 0:cols] + 0.5
        x, y, h = self.ground_on_dem(c, r, dem, dem_transform)
        gt = gdal_inverse(as_gdal(ground_transform, "ground_transform"))
        gc = gt[0] + x * gt[1] + y * gt[2]
        gr = gt[3] + x * gt[4] + y * gt[5]
        return interpolate(ground, gc, gr, "bilinear", nodata=None), x, y, h


def fit_rpc_to_sensor(sensor, crs, bounds, heights, n=15):
    """Fit an RPC to a sensor model over a 3-D grid, as vendors do (terrain independent).

    Parameters
    ----------
    sensor : object with ``project(x, y, h) -> (col, row)``
        The physical model, in map coordinates of ``crs``.
    crs : str or rasterio CRS
        The sensor's map CRS (projected).
    bounds : (west, south, east, north)
        The ground the image covers, in ``crs``.
    heights : (low, high)
        Height range (m) of the grid's layers (5 layers).
    n : int
        Grid points along each horizontal axis.

    Returns
    -------
    RPCModel

    Raises
    ------
    ValueError
        If the heights do not span a range, or :func:`fit_rpc` refuses the grid.

    Examples
    --------
    >>> sensor = PushbroomSensor(200000.0, 9120000.0, 700e3, 0.0, 1e-3, 101, 10.0)
    >>> rpc = fit_rpc_to_sensor(sensor, "EPSG:31985", (199500, 9119000, 200500, 9120000),
    ...                         (0, 100))
    >>> rpc.offsets["HEIGHT"]
    50.0
    """
    low, high = (float(v) for v in heights)
    if not high > low:
        raise RsgeoError(_("heights must be (low, high) with high > low, got {heights!r}").format(
                heights=heights))
    west, south, east, north = (float(v) for v in bounds)
    x, y, h = np.meshgrid(np.linspace(west, east, n), np.linspace(south, north, n),
                          np.linspace(low, high, 5), indexing="ij")
    x, y, h = x.ravel(), y.ravel(), h.ravel()
    lon, lat = to_crs(x, y, crs, "EPSG:4326")
    col, row = sensor.project(x, y, h)
    return fit_rpc(lon, lat, h, col, row)


