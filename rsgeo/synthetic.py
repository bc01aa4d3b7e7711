"""Synthetic data with a known answer, seeded and deterministic.

Real scenes show what a method does; synthetic ones built from them, with a
distortion, a gain and offset or a segment matching that we chose, tell
whether it found the right answer.
"""

from dataclasses import dataclass

import affine
import numpy as np
from rasterio.warp import transform as warp_transform

from . import data
from ._deprecated import moved_names
from .errors import GridError
from .gcp import GCPSet
from .language import _
from .registration import Mesh
from .resample import interpolate
from .sensors import RawSensor as _RawSensor
from .validation import as_integer, as_number, as_points, as_shape

__all__ = [
    "ContrastPair", "contrast_pair", "DistortedPair", "distorted_pair", "Landscape",
    "two_date_landscape", "synthetic_meshes", "ControlPoints", "RawScene", "raw_scene",
]

# moved to rsgeo.sensors: importable from here for one release, with a warning (the module
# keeps its own dir())
__getattr__ = moved_names(__name__, {"RawSensor": "rsgeo.sensors"})[0]


# -- The regression paper's case ---------------------------------------------

@dataclass
class ContrastPair:
    """Two images of the same ground with a known radiometric relation.

    y_image ≈ gain · x_true + offset, where x_image = x_true + noise, both
    8-bit, and y_image is also shifted by ``shift`` pixels (misregistration).
    """

    x_image: np.ndarray
    y_image: np.ndarray
    gain: float
    offset: float
    noise: float
    shift: tuple


def contrast_pair(gain=0.885, offset=27.107, size=100, noise=45.0, shift=(0.7, 0.5), seed=0):
    """A pair like the regression paper's: one 100 × 100 ground, another contrast, noise, a shift.

    The ground is a crop of the real CBERS scene ``cbers_b2_A`` stretched to
    a wide range of DNs; X is it plus noise; Y is gain·ground + offset, resampled
    ``shift`` pixels away, plus noise (of the same relative size). With the
    defaults the raw correlation is 0.43 (the paper's 0.45) and a 3 × 3 mean
    filter raises it to 0.87 (the paper's 0.80).

    Parameters
    ----------
    gain, offset : float
        The true relation y = gain · x + offset (DN); the defaults are the
        paper's fitted values.
    size : int
        Side of the two square images (pixels).
    noise : float
        Standard deviation of the noise added to X (DN); Y's is ``noise · gain``.
    shift : (float, float)
        Misregistration of Y against X, (cols, rows) in pixels.
    seed : int
        Seed of the noise; the same seed gives the same pair.

    Returns
    -------
    ContrastPair
        The two uint8 images and the parameters that made them.

    Raises
    ------
    ValueError
        For a negative ``noise`` (NumPy's "scale < 0"). Nothing else is
        checked: ``shift`` needs two numbers, and ``rsgeo.data.load`` raises
        if the scene ``cbers_b2_A`` is missing.

    References
    ----------
    The regression paper: *Linear regression to match the contrast of
    overlapping aerial photographs* (seed document 000 of this course).

    Examples
    --------
    >>> pair = contrast_pair(seed=0)
    >>> pair.x_image.shape, pair.y_image.dtype.name
    ((100, 100), 'uint8')
    """
    rng = np.random.default_rng(seed)
    scene = data.load("cbers_b2_A").array.astype(np.float64)
    top, left = 180, 150
    ground = scene[top:top + size // 4 + 4, left:left + size // 4 + 4]
    ground = 40 + 160 * (ground - ground.min()) / (np.ptp(ground) or 1.0)
    # Aerial photos at 1:30,000 resolve ground features over many pixels: sample the 20 m
    # scene four times finer, so the ground varies smoothly and the noise does not.
    rows, cols = (np.mgrid[0:size, 0:size] + 0.5) / 4 + 2
    x_true = interpolate(ground, cols, rows, "cubic")
    y_true = interpolate(ground, cols + shift[0] / 4, rows + shift[1] / 4, "cubic")
    noisy = np.round(x_true + rng.normal(0, noise, x_true.shape))
    x_image = np.clip(noisy, 0, 255).astype(np.uint8)
    y_values = gain * y_true + offset + rng.normal(0, noise * gain, y_true.shape)
    y_image = np.clip(np.round(y_values), 0, 255).astype(np.uint8)
    return ContrastPair(x_image, y_image, gain, offset, noise, tuple(shift))


# -- Georeferencing: a distorted image with GCPs of known error -------------

@dataclass
class DistortedPair:
    """A reference map, an image distorted by a known polynomial, and GCPs with known errors.

    Attributes
    ----------
    reference : rsgeo.data.Raster
        The "map": a real scene with its geotransform.
    image : ndarray
        The distorted image (what the sensor recorded).
    image_to_map : callable
        The true mapping: (n, 2) image (col, row) -> (n, 2) map (x, y).
    gcps : GCPSet
        GCPs as a student would collect them: map coordinates exact, image
        coordinates with the hand's error (``gcp_errors``) and one blunder.
    gcp_errors : ndarray, shape (n, 2)
        The error added to each GCP's image coordinates.
    blunder : int
        Index of the GCP with the planted blunder (its id is ``gcps.ids[blunder]``).
    """

    reference: object
    image: np.ndarray
    image_to_map: object
    gcps: GCPSet
    gcp_errors: np.ndarray
    blunder: int


def distorted_pair(n_gcps=16, gcp_error=0.4, blunder_size=9.0, shape=(360, 360), seed=0):
    """A reference map and an image distorted from it by a known second-degree mapping.

    The reference is the real ``nat1`` scene (25 m). The distorted image's
    pixel (col, row) sees the map point given by a polynomial of degree 2: a
    rotation of 6°, pixels of 27.5 m, a shear and a gentle curvature, the kind
    of residual distortion georeferencing removes. GCPs are spread over the
    image on a jittered grid; their image coordinates carry Gaussian errors of
    ``gcp_error`` pixels ("a mão treme") and one of them a blunder of
    ``blunder_size`` pixels.

    Parameters
    ----------
    n_gcps : int
        Number of GCPs (at least 1).
    gcp_error : float
        Standard deviation of each GCP's image-coordinate error (pixels).
    blunder_size : float
        Length of the blunder added to one GCP (pixels).
    shape : (int, int)
        Size (rows, cols) of the distorted image.
    seed : int
        Seed of the GCP layout, errors and blunder.

    Returns
    -------
    DistortedPair
        The reference, the distorted image, the true mapping and the GCPs.

    Raises
    ------
    ValueError
        For ``n_gcps`` below 1 or a negative ``gcp_error`` (NumPy's errors).
        Nothing else is checked: ``shape`` needs two numbers, and
        ``rsgeo.data.load`` raises if the scene ``nat1`` is missing.

    Examples
    --------
    >>> pair = distorted_pair(seed=0)
    >>> pair.image.shape, len(pair.gcps.ids), pair.gcps.ids[pair.blunder] in pair.gcps.ids
    ((360, 360), 16, True)
    """
    rng = np.random.default_rng(seed)
    reference = data.load("nat1")
    west, north = reference.transform.c + 3000.0, reference.transform.f - 3500.0
    angle = np.radians(6.0)

    def image_to_map(points):
        points = np.asarray(points, dtype=np.float64)
        c, r = points[..., 0], points[..., 1]
        u, v = c - shape[1] / 2, r - shape[0] / 2
        x = (west + 27.5 * (np.cos(angle) * c + np.sin(angle) * r) + 0.04 * u * v / 10
             + 0.0009 * u * u)
        y = (north + 27.5 * (np.sin(angle) * c - np.cos(angle) * r) + 1.5 * c / 10
             - 0.0012 * v * v)
        return np.stack([x, y], axis=-1)

    rows, cols = np.mgrid[0:shape[0], 0:shape[1]] + 0.5
    map_xy = image_to_map(np.stack([cols, rows], axis=-1))
    ref_cols, ref_rows = ~reference.transform @ (map_xy[..., 0], map_xy[..., 1])
    image = interpolate(reference.array, ref_cols, ref_rows, "cubic")

    side = int(np.ceil(np.sqrt(n_gcps)))
    cells = np.stack(np.meshgrid(np.arange(side), np.arange(side)), axis=-1).reshape(-1, 2)
    grid = cells[:n_gcps] + 0.5
    image_xy = grid / side * np.array([shape[1], shape[0]])
    image_xy = (image_xy + rng.uniform(-0.3, 0.3, image_xy.shape)
                * np.array([shape[1], shape[0]]) / side)
    gcp_map = image_to_map(image_xy)
    errors = rng.normal(0, gcp_error, image_xy.shape)
    blunder = int(rng.integers(0, n_gcps))
    direction = rng.uniform(0, 2 * np.pi)
    errors[blunder] += blunder_size * np.array([np.cos(direction), np.sin(direction)])
    gcps = GCPSet(gcp_map, image_xy + errors,
                  crs=reference.crs.to_wkt() if reference.crs else None,
                  ids=[f"P{i + 1:02d}" for i in range(n_gcps)])
    return DistortedPair(reference, image, image_to_map, gcps, errors, blunder)


# -- The genetic-algorithm paper: two dates of a landscape -------------------

@dataclass
class Landscape:
    """Two dates of a landscape: crop fields change, forest remnants stay.

    Attributes
    ----------
    reference, adjustment : ndarray (uint8)
        Vegetation images: the reference (date 1) on a north-up grid of
        ``reference_transform``; the adjustment (date 2) at another pixel size,
        rotated and shifted (``adjustment_transform``, its true geotransform).
    reference_transform, adjustment_transform : affine.Affine
    forest_truth : ndarray of int
        Forest remnant k (1..n) on the reference grid, 0 elsewhere.
    forest_centroids_map : ndarray, shape (n, 2)
        True centroid of each remnant in map coordinates.
    """

    reference: np.ndarray
    adjustment: np.ndarray
    reference_transform: object
    adjustment_transform: object
    forest_truth: np.ndarray
    forest_centroids_map: np.ndarray


def two_date_landscape(n_forest=8, reference_pixel=20.0, adjustment_pixel=30.0, rotation_deg=4.0,
                       shift=(170.0, -110.0), size_m=8000.0, seed=0):
    """A synthetic landscape of fields and stable forest remnants, at two dates and resolutions.

    Fields are Voronoi parcels whose vegetation signal is redrawn for each
    date (crops grow and are harvested); forest remnants are irregular blobs
    with a high, stable signal. The adjustment image sees the same ground at
    another pixel size, rotated by ``rotation_deg`` and shifted by ``shift``
    metres: the misregistration the paper's method must find. Each image
    averages a fine 10 m scene over its own pixel's footprint, centred on the
    pixel, so both images sit where their geotransforms say.

    Parameters
    ----------
    n_forest : int
        Number of forest remnants.
    reference_pixel, adjustment_pixel : float
        Pixel sizes of the reference and adjustment images (metres).
    rotation_deg : float
        Rotation of the adjustment grid against the reference (degrees).
    shift : (float, float)
        Shift of the adjustment grid's centre, (x, y) in metres.
    size_m : float
        Side of the square landscape (metres).
    seed : int
        Seed of the fields, remnants and both dates' signals.

    Returns
    -------
    Landscape
        Both images, their geotransforms and the true forest remnants.

    Raises
    ------
    ZeroDivisionError
        Nothing is checked: pixel sizes must be positive (a zero divides by
        zero), and the remnants, kept 1400 m apart and 1100 m from the edge,
        must fit in ``size_m`` (with too many, placing them never ends).

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme).
    """
    from scipy import ndimage
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(seed)
    fine = 10.0
    n_fine = int(size_m / fine)
    rows, cols = np.mgrid[0:n_fine, 0:n_fine] + 0.5
    x, y = cols * fine, size_m - rows * fine
    seeds = rng.uniform(0, size_m, (90, 2))
    parcel = cKDTree(seeds).query(np.column_stack([x.ravel(), y.ravel()]))[1].reshape(x.shape)

    forest = np.zeros(x.shape, dtype=np.int32)
    margin = 1100.0
    centres = []
    while len(centres) < n_forest:
        candidate = rng.uniform(margin, size_m - margin, 2)
        if all(np.hypot(*(candidate - c)) > 1400 for c in centres):
            centres.append(candidate)
    for k, (cx, cy) in enumerate(centres, start=1):
        radius = rng.uniform(200, 420)
        stretch = rng.uniform(0.6, 1.0)
        theta = rng.uniform(0, np.pi)
        dx, dy = x - cx, y - cy
        u = (dx * np.cos(theta) + dy * np.sin(theta)) / radius
        v = (-dx * np.sin(theta) + dy * np.cos(theta)) / (radius * stretch)
        wobble = 1 + 0.25 * np.sin(3 * np.arctan2(v, u) + k)
        forest[(u * u + v * v) < wobble**2] = k

    def date_image(date_rng):
        field_signal = date_rng.uniform(0.1, 0.62, len(seeds))[parcel]
        texture = ndimage.gaussian_filter(date_rng.normal(0, 0.05, x.shape), 2)
        signal = np.where(forest > 0, 0.82, field_signal) + texture
        return np.clip(signal * 255, 0, 255)

    date1 = date_image(np.random.default_rng(seed + 1))
    date2 = date_image(np.random.default_rng(seed + 2))
    fine_transform = affine.Affine(fine, 0, 0, 0, -fine, size_m)

    n_ref = int(size_m / reference_pixel)
    reference_transform = affine.Affine(reference_pixel, 0, 0, 0, -reference_pixel, size_m)
    n_adj = int(0.8 * size_m / adjustment_pixel)
    centre = np.array([size_m / 2, size_m / 2])
    adjustment_transform = (affine.Affine.translation(*(centre + np.asarray(shift)))
                            @ affine.Affine.rotation(rotation_deg)
                            @ affine.Affine(adjustment_pixel, 0, -n_adj * adjustment_pixel / 2,
                                            0, -adjustment_pixel, n_adj * adjustment_pixel / 2))

    def fine_positions(transform, count):
        # (col, row) on the fine scene of the centres of a count × count grid
        r, c = np.mgrid[0:count, 0:count] + 0.5
        return ~fine_transform @ (transform @ (c, r))

    def sample(image, positions, pixel):
        # the sensor integrates over its pixel: smooth the fine scene to its footprint first.
        # scipy's box of even size k covers cells i - k/2 .. i + k/2 - 1: its mean belongs
        # to the corner (i, i) of cell i, half a cell before the cell's centre (i + 0.5),
        # so an even box is read half a cell further to stay centred on each position.
        size = max(1, int(round(pixel / fine)))
        blurred = ndimage.uniform_filter(image, size=size)
        half = 0.5 if size % 2 == 0 else 0.0
        return interpolate(blurred, positions[0] + half, positions[1] + half, "bilinear")

    on_reference = fine_positions(reference_transform, n_ref)
    reference = np.round(sample(date1, on_reference, reference_pixel)).astype(np.uint8)
    adjustment = np.round(sample(date2, fine_positions(adjustment_transform, n_adj),
                                 adjustment_pixel)).astype(np.uint8)
    forest_truth = interpolate(forest, *on_reference, "nearest")
    centroids = np.array([[x[forest == k].mean(), y[forest == k].mean()]
                          for k in range(1, n_forest + 1)])
    return Landscape(reference, adjustment, reference_transform, adjustment_transform,
                     forest_truth, centroids)


def synthetic_meshes(n=8, centroid_noise=1.0, area_noise=0.10, seed=0, shrink=None):
    """A reference mesh and a shuffled, noisy copy with a known true matching.

    The reference has n segments scattered over 400 × 400 pixels with areas
    from 50 to 600 pixels; the adjustment sees them in a random order, with
    Gaussian centroid noise of ``centroid_noise`` pixels and areas changed by
    up to ±``area_noise``. ``shrink=(k, share)`` makes reference segment k
    (0-based) keep only ``share`` of its area in the adjustment image, its
    centroid moving towards one side, as the paper's Landsat 2002 segment that
    kept 31 % of its reference area.

    Parameters
    ----------
    n : int
        Number of segments (at least 3).
    centroid_noise : float
        Standard deviation of the centroid noise (pixels).
    area_noise : float
        Largest relative change of an area (0.10 is ±10 %).
    seed : int
        Seed of the meshes, the order and the noise.
    shrink : (int, float), optional
        (k, share): reference segment k (0-based, below n) keeps ``share``
        (above 0) of its area in the adjustment.

    Returns
    -------
    reference, adjustment : rsgeo.registration.Mesh
    truth : ndarray
        truth[k] = reference label (1-based) of adjustment segment k.

    Raises
    ------
    ValueError
        From :class:`rsgeo.registration.Mesh`: fewer than 3 segments, or an area
        that is not positive (``area_noise`` above 1, a ``share`` of 0);
        from NumPy for a negative ``centroid_noise``. A ``shrink`` index
        outside 0..n-1 raises IndexError.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme).

    Examples
    --------
    >>> reference, adjustment, truth = synthetic_meshes(5, seed=0)
    >>> len(reference), sorted(truth.tolist())
    (5, [1, 2, 3, 4, 5])
    """
    rng = np.random.default_rng(seed)
    centroids = rng.uniform(0, 400, (n, 2))
    areas = rng.uniform(50, 600, n)
    order = rng.permutation(n)
    adjustment_centroids = centroids[order] + rng.normal(0, centroid_noise, (n, 2))
    adjustment_areas = areas[order] * (1 + rng.uniform(-area_noise, area_noise, n))
    if shrink is not None:
        index, share = shrink
        where = int(np.flatnonzero(order == index)[0])
        adjustment_areas[where] = areas[index] * share
        # what is left of a round segment of this area sits off its old centre
        radius = np.sqrt(areas[index] / np.pi)
        adjustment_centroids[where] += radius * (1 - share) * np.array([1.0, 0.0])
    return Mesh(centroids, areas), Mesh(adjustment_centroids, adjustment_areas), order + 1




@dataclass
class ControlPoints:
    """Points of a raw scene with their ground and image positions (GCPs or check points).

    Attributes
    ----------
    map_xy : ndarray, shape (n, 2)
        Map coordinates (m) in the scene's CRS.
    lon, lat : ndarray, shape (n,)
        WGS 84 degrees.
    height : ndarray, shape (n,)
        Ellipsoidal heights (m), from the scene's DEM.
    image_xy : ndarray, shape (n, 2)
        Measured (col, row): the true position plus the measurement noise.
    true_image_xy : ndarray, shape (n, 2)
        Where the sensor really records them.
    """

    map_xy: np.ndarray
    lon: np.ndarray
    lat: np.ndarray
    height: np.ndarray
    image_xy: np.ndarray
    true_image_xy: np.ndarray

    def __len__(self):
        return len(self.map_xy)

    @property
    def rpc_gcps(self):
        """The points as :func:`rsgeo.sensors.refine_rpc` takes them (measured positions).

        Returns
        -------
        dict of ndarray
            ``lon``, ``lat``, ``height``, ``col``, ``row``.
        """
        return {"lon": self.lon, "lat": self.lat, "height": self.height,
                "col": self.image_xy[:, 0], "row": self.image_xy[:, 1]}


@dataclass
class RawScene:
    """A raw (level 1A) scene with its true geometry, a DEM and control points on demand.

    Attributes
    ----------
    image : ndarray or None
        The raw image (uint8, rows along track), None when not simulated.
    sensor : rsgeo.sensors.RawSensor
        The true geometry.
    dem : ndarray
        Ellipsoidal heights (m) of the Olinda DEM (EGM96 heights plus the geoid undulation).
    dem_transform : affine.Affine
    crs : str
        The map's CRS (SIRGAS 2000 / UTM 25S).
    latitude_deg : float
        Latitude of the scene's centre.
    skew_per_line : float
        Earth-rotation skew in nadir pixels per line (:func:`rsgeo.distortion.skew_per_line`).
    off_nadir_deg : float
        The camera's pointing (roll) across the track.
    bounds : tuple of float
        (west, south, east, north) of the ground the image sees (m).
    height_range : (float, float)
        The DEM's lowest and highest ellipsoidal height (m).
    """

    image: np.ndarray
    sensor: _RawSensor
    dem: np.ndarray
    dem_transform: affine.Affine
    crs: str
    latitude_deg: float
    skew_per_line: float
    off_nadir_deg: float
    bounds: tuple
    height_range: tuple

    def control_points(self, points, noise_px=0.0, seed=0, margin=0.05):
        """Points of the scene: their ground on the DEM and their measured image positions.

        Parameters
        ----------
        points : int or (n, 2) array_like
            How many, drawn uniformly over the image inside ``margin``, or
            their true image (col, row).
        noise_px : float
            Standard deviation of the measurement error added to each image
            coordinate (pixels), >= 0.
        seed : int
            Seed of the positions and the noise.
        margin : float
            Share of the image's size left out at each edge, in [0, 0.5).

        Returns
        -------
        ControlPoints

        Raises
        ------
        ValueError
            For a count below 1, points that are not (n, 2) finite numbers,
            a negative noise or a margin outside [0, 0.5).
        """
        rng = np.random.default_rng(seed)
        rows, cols = self.sensor.shape
        margin = as_number(margin, "margin", 0, 0.4999)
        noise_px = as_number(noise_px, "noise_px", low=0)
        if np.ndim(points) == 0:
            count = as_integer(points, "points", low=1)
            true = np.column_stack([rng.uniform(margin * cols, (1 - margin) * cols, count),
                                    rng.uniform(margin * rows, (1 - margin) * rows, count)])
        else:
            true = as_points(points, "points").copy()
        x, y, h = self.sensor.ground_on_dem(true[:, 0], true[:, 1], self.dem,
                                            self.dem_transform)
        lon, lat = (np.asarray(v, dtype=np.float64)
                    for v in warp_transform(self.crs, "EPSG:4326", x, y))
        measured = true + rng.normal(0.0, noise_px, true.shape)
        return ControlPoints(np.column_stack([x, y]), lon, lat, h, measured, true)


def raw_scene(shape=(600, 560), nadir_pixel_m=10.0, off_nadir_deg=30.0, altitude_km=778.0,
              inclination_deg=98.5, simulate=True):
    """A raw pushbroom scene of Olinda: heading, Earth-rotation skew, view angles, relief.

    Chapter 1's sensor model (:class:`rsgeo.sensors.SystematicDistortion`,
    curved Earth) at CBERS's altitude and inclination, on a descending pass
    over the shipped Olinda DEM, pointed ``off_nadir_deg`` east of the track:
    the track heads :func:`rsgeo.distortion.track_angle` west of south, each
    line is shifted west by the Earth's rotation
    (:func:`rsgeo.distortion.skew_per_line`), pixels grow away from nadir, and
    the DEM's relief moves every point by about h·tan z (:class:`rsgeo.sensors.RawSensor`).
    The DEM's heights (EGM96) are made ellipsoidal with the shipped geoid
    (:func:`rsgeo.heights.to_ellipsoidal`), as an RPC takes them. The image,
    when simulated, samples the Landsat 7 band of Olinda (28.5 m, bilinear)
    where each pixel's line of sight meets the DEM. The scene's centre looks
    at the DEM's centre.

    Parameters
    ----------
    shape : (int, int)
        Rows and columns of the raw image; its footprint must stay inside the
        DEM (10 km × 10 km).
    nadir_pixel_m : float
        Ground size of a pixel at nadir (m).
    off_nadir_deg : float
        Pointing across the track (degrees, 0 to 45).
    altitude_km, inclination_deg : float
        The orbit (CBERS: 778 km, 98.5°).
    simulate : bool
        Simulate the image (a few seconds), or only the geometry.

    Returns
    -------
    RawScene

    Raises
    ------
    ValueError
        For a shape, pixel size or angle out of range, or a footprint that
        leaves the DEM.

    Examples
    --------
    >>> scene = raw_scene(shape=(60, 50), nadir_pixel_m=100.0, simulate=False)
    >>> round(scene.sensor.heading_deg, 1), scene.image is None
    (8.6, True)
    """
    from rasterio.crs import CRS

    from . import distortion, heights, sensors

    shape = as_shape(shape)
    pixel_km = as_number(nadir_pixel_m, "nadir_pixel_m", low=1e-3, high=1e4) / 1000
    off_nadir_deg = as_number(off_nadir_deg, "off_nadir_deg", 0, 45)
    dem = data.load("olinda_dem")
    ground = data.load("olinda_l7_b4")
    crs = CRS.from_user_input(ground.crs).to_string()
    west, south, east, north = dem.bounds
    centre = ((west + east) / 2, (south + north) / 2)
    (lon,), (lat,) = warp_transform(crs, "EPSG:4326", [centre[0]], [centre[1]])
    cols, rows = np.meshgrid(np.arange(dem.array.shape[1]) + 0.5,
                             np.arange(dem.array.shape[0]) + 0.5)
    dem_x, dem_y = dem.transform @ (cols, rows)
    dem_lon, dem_lat = (np.asarray(v).reshape(dem_x.shape) for v in warp_transform(
        crs, "EPSG:4326", dem_x.ravel(), dem_y.ravel()))
    ellipsoidal = heights.to_ellipsoidal(dem.array, dem_lon, dem_lat, "EGM96")
    skew = distortion.skew_per_line(lat, shape[0], pixel_km, altitude_km, inclination_deg)
    model = sensors.SystematicDistortion(skew_per_line=skew, roll_deg=-off_nadir_deg,
                                            view_altitude_km=altitude_km,
                                            nadir_pixel_km=pixel_km, shape=shape)
    heading = distortion.track_angle(lat, inclination_deg)
    offset = float(distortion.ground_distance(off_nadir_deg, altitude_km))
    sensor = _RawSensor(model, centre, heading, offset)
    for _iteration in range(3):              # move the ground so that the image centre sees it
        seen = sensor.ground(shape[1] / 2, shape[0] / 2, 0.0)
        sensor = _RawSensor(model, (sensor.centre_xy[0] + centre[0] - float(seen[0]),
                                   sensor.centre_xy[1] + centre[1] - float(seen[1])),
                           heading, offset)
    low, high = float(ellipsoidal.min()), float(ellipsoidal.max())
    edge = np.linspace(0, 1, 9)
    border_c = np.concatenate([edge, np.ones(9), edge[::-1], np.zeros(9)]) * shape[1]
    border_r = np.concatenate([np.zeros(9), edge, np.ones(9), edge[::-1]]) * shape[0]
    corners = [sensor.ground(border_c, border_r, level) for level in (low, high)]
    xs = np.concatenate([c[0] for c in corners])
    ys = np.concatenate([c[1] for c in corners])
    bounds = (float(xs.min()), float(ys.min()), float(xs.max()), float(ys.max()))
    if bounds[0] < west or bounds[2] > east or bounds[1] < south or bounds[3] > north:
        raise GridError(_("the raw image's footprint ({w:.0f} to {e:.0f} m east, {s:.0f} to "
                          "{n:.0f} m north) leaves the DEM; use fewer rows and columns or "
                          "smaller pixels").format(w=bounds[0], e=bounds[2], s=bounds[1],
                                                   n=bounds[3]))
    image = None
    if simulate:
        r, c = np.mgrid[0:shape[0], 0:shape[1]] + 0.5
        x, y, _h = sensor.ground_on_dem(c, r, ellipsoidal, dem.transform)
        gc, gr = ~ground.transform @ (x, y)
        image = interpolate(ground.array, gc, gr, "bilinear", nodata=None)
    return RawScene(image, sensor, ellipsoidal, dem.transform, crs, float(lat), float(skew),
                    float(off_nadir_deg), bounds, (low, high))
