"""Relief displacement and orthorectification: RPCs and a DEM, as GDAL does them.

Every model of the georeferencing chapters maps a plane to a plane. The ground
has height: a point at elevation h seen at view zenith angle θ lands
h·tan θ away from where a point at the datum would (:func:`relief_displacement`);
on a vertical frame photograph a point r millimetres from the centre moves
r·h / H (:func:`relief_displacement_photo`). No polynomial in (x, y) removes
that, because the displacement depends on h, which (x, y) do not give.

A rational polynomial camera (RPC, the RPC00B convention of image vendors and
of GDAL's ``RPC`` metadata) maps (longitude, latitude, height) to (sample,
line) with ratios of cubic polynomials of the normalised coordinates
(:class:`RPCModel`). :func:`fit_rpc` fits one to a physical sensor model, as
vendors do ("terrain independent": a 3-D grid of the sensor model, no GCPs),
and :func:`orthorectify` builds the orthoimage: for every output cell its
height from a DEM (bilinear), the RPC gives the source position, and
:func:`rsgeo.resample.interpolate` the value. An RPC takes heights above the
ellipsoid; a DEM's are often above the geoid (SRTM: EGM96), so
:func:`orthorectify` asks which (``dem_vertical``) and adds the geoid
undulation N (:mod:`rsgeo.heights`) when they are. :func:`occluded` finds the
ground that buildings and trees hide from an oblique view.

Conventions follow GDAL's ``alg/gdal_rpc.cpp`` operation by operation, so
that the numbers agree with GDAL's RPC transformer and ``gdalwarp -rpc -to
RPC_DEM=...``:

* RPC line and sample are 0 at the *centre* of the first pixel; GDAL (and
  rsgeo, DESIGN.md) put 0 at its top-left *corner*, so
  :meth:`RPCModel.project` adds 0.5 to both, as ``RPCTransformPoint`` does;
* the 20 terms are GDAL's order (1, L, P, H, LP, LH, PH, L², P², H², PLH, L³,
  LP², LH², L²P, P³, PH², L²H, P²H, H³), with L the normalised longitude,
  P the latitude, H the height; the sums add even and odd terms separately
  and then the two (GDAL's SSE2 evaluation);
* the DEM is sampled as ``GDALRPCGetDEMHeight`` does it with bilinear
  interpolation: at (x − 0.5, y − 0.5) in DEM pixels, the index truncated
  toward zero, falling back to the nearest DEM cell where the 2 × 2 window
  leaves the DEM.

Measured agreement with GDAL 3.10 through rasterio (``tests/test_terrain.py``):
:meth:`RPCModel.project` is GDAL's ``RPCTransformer`` to the last bit at
random (lon, lat, h); :func:`orthorectify` gives ``reproject(...,
rpcs=..., RPC_DEM=..., tolerance=0)``'s pixels bit for bit for nearest,
bilinear and cubic, with the output grid in EPSG:4326 or UTM, with the DEM's
nearest fallback at its edge, and without a destination nodata or with
nodata 255. One difference remains: with nodata 0, a valid pixel whose cubic
value rounds to 0 (Keys' kernel overshoots below 0 beside dark pixels) is
moved to 1 by rsgeo (GDAL's "AvoidNoData", which rsgeo.resample applies as
GDAL's VRT warps do) and left at 0 by ``reproject``: about 0.5 % of the valid
pixels of a uniform-noise image, each by 1 DN. GDAL 3.10 replaces a valid value
that collides with the destination nodata inconsistently across its warp paths
(GDAL issue 11711; changed in 3.11 by pull request 11713).

How :func:`orthorectify` computes, strip of output rows by strip (GDAL's
warper asks its transformer row by row): one compiled pass (Numba) gives
each cell its longitude and latitude, its DEM height and its RPC position,
the RPC over a whole row at a time in vector instructions (several cells per
instruction, each cell's operations in GDAL's order, so the numbers do not
change); on a grid in EPSG:4326, the RPC's own CRS and the usual orthoimage
grid, the longitude and latitude come from the grid's geotransform, with no
PROJ. PROJ, which cannot run compiled, transforms a projected grid's cells
(and the DEM's, when the DEM is projected) strip by strip, through
``rasterio.warp.transform``. Then
:func:`rsgeo.resample.interpolate`. ``benchmarks/orthorectify.py`` times it
against GDAL. Note that gdalwarp does not approximate RPC + DEM by default:
given ``RPC_DEM`` its error threshold is 0 (exact) unless ``-et`` says
otherwise.
"""

import numpy as np
from numba import njit, prange

from ._checks import (
    as_bands_first,
    as_finite,
    as_image,
    as_integer,
    as_num_threads,
    as_output_shape,
    as_shape,
    check_choice,
)
from ._i18n import _, prose_number
from .data import _as_affine
from .errors import CRSError, DataError, GCPError, GridError, ImageError, ModelError, RsgeoError
from .resample import METHODS, interpolate
from .tiepoints import measure_shifts

__all__ = [
    "relief_displacement", "relief_displacement_photo", "height_error_budget", "occluded",
    "RPCModel", "RPC_TERMS", "simple_rpc_dict", "fit_rpc", "refine_rpc", "RefinedRPC",
    "BIAS_KINDS", "dem_height", "line_of_sight_on_dem", "orthorectify",
    "PushbroomSensor", "fit_rpc_to_sensor", "map_on_grid", "positional_error",
]

# GDAL's RPCComputeTerms, in its order (L = longitude, P = latitude, H = height)
RPC_TERMS = ("1", "L", "P", "H", "LP", "LH", "PH", "LL", "PP", "HH",
             "PLH", "LLL", "LPP", "LHH", "LLP", "PPP", "PHH", "LLH", "PPH", "HHH")

_SCALARS = ("LINE_OFF", "SAMP_OFF", "LAT_OFF", "LONG_OFF", "HEIGHT_OFF",
            "LINE_SCALE", "SAMP_SCALE", "LAT_SCALE", "LONG_SCALE", "HEIGHT_SCALE")
_COEFFS = ("LINE_NUM_COEFF", "LINE_DEN_COEFF", "SAMP_NUM_COEFF", "SAMP_DEN_COEFF")
_OPTIONAL = ("MIN_LONG", "MIN_LAT", "MAX_LONG", "MAX_LAT", "ERR_BIAS", "ERR_RAND")


def relief_displacement(height_m, view_zenith_deg):
    """Horizontal displacement of a point at height h seen at view zenith θ: h·tan θ.

    Parameters
    ----------
    height_m : float or array_like
        Height above the datum the image was mapped to (m); negative below it.
    view_zenith_deg : float or array_like
        Angle between the line of sight and the vertical at the ground, in
        degrees, from 0 (nadir) to below 90.

    Returns
    -------
    float or ndarray
        Displacement in metres, away from the nadir for a positive height.

    Raises
    ------
    ValueError
        If an angle is outside [0, 90) or a value is not finite.

    Examples
    --------
    >>> round(float(relief_displacement(500.0, 8.2)), 1)   # Landsat's swath edge
    72.1
    >>> round(float(relief_displacement(100.0, 45.0)), 6)
    100.0
    """
    height = as_finite(height_m, "height_m")
    angle = as_finite(view_zenith_deg, "view_zenith_deg")
    if np.any((angle < 0) | (angle >= 90)):
        raise RsgeoError(_("view_zenith_deg must be in [0, 90) degrees (0 = nadir), got "
                           "{few}").format(few=_few(angle[(angle < 0) | (angle >= 90)])))
    result = height * np.tan(np.radians(angle))
    return float(result) if result.ndim == 0 else result


def relief_displacement_photo(height_m, radial_distance_mm, flying_height_m):
    """Relief displacement on a vertical frame photograph: d = r·h / H.

    Parameters
    ----------
    height_m : float or array_like
        Height of the point above the datum (m).
    radial_distance_mm : float or array_like
        Distance of the point's image from the photo's principal point (mm).
    flying_height_m : float
        Flying height above the datum (m); must be above every height.

    Returns
    -------
    float or ndarray
        Displacement on the photo in mm, radial (outwards for h > 0). Times
        the scale number (H / focal length) it is metres on the ground.

    Raises
    ------
    ValueError
        If a value is not finite, the radial distance is negative, or the
        flying height is not above every height.

    Examples
    --------
    >>> relief_displacement_photo(50.0, 100.0, 4500.0)   # 1:30,000 with a 150 mm lens
    1.1111111111111112
    """
    height = as_finite(height_m, "height_m")
    radius = as_finite(radial_distance_mm, "radial_distance_mm")
    flying = float(as_finite(flying_height_m, "flying_height_m"))
    if np.any(radius < 0):
        raise RsgeoError(_("radial_distance_mm must be >= 0 (a distance from the "
                           "principal point), got {few}").format(few=_few(radius[radius < 0])))
    if np.any(height >= flying):
        raise RsgeoError(_("flying_height_m ({flying:g} m) must be above every height; "
                           "got heights up to {value:g} m").format(
                flying=prose_number(flying), value=prose_number(float(np.max(height)))))
    result = radius * height / flying
    return float(result) if result.ndim == 0 else result


def height_error_budget(position_error_m, view_zenith_deg):
    """The largest DEM height error a horizontal position budget allows: Δh = Δx / tan θ.

    Parameters
    ----------
    position_error_m : float
        Allowed horizontal error (m), > 0.
    view_zenith_deg : float
        View zenith angle (degrees), in (0, 90).

    Returns
    -------
    float
        Height error (m) that moves a point by ``position_error_m``.

    Raises
    ------
    ValueError
        If the budget is not positive or the angle is not in (0, 90).

    Examples
    --------
    >>> round(height_error_budget(10.0, 30.0), 2)
    17.32
    """
    budget = float(as_finite(position_error_m, "position_error_m"))
    angle = float(as_finite(view_zenith_deg, "view_zenith_deg"))
    if budget <= 0:
        raise RsgeoError(_("position_error_m must be > 0, got {budget:g}").format(
                budget=prose_number(budget)))
    if not 0 < angle < 90:
        raise RsgeoError(_("view_zenith_deg must be in (0, 90) degrees (at nadir any "
                           "height error is allowed), got {angle:g}").format(
                angle=prose_number(angle)))
    return float(budget / np.tan(np.radians(angle)))


def occluded(distance_m, height_m, view_zenith_deg):
    """Which points of a surface profile the sensor cannot see: hidden behind higher ground.

    The profile runs away from the sensor (its first point is the nearest), in the plane of
    the lines of sight, which are parallel (a satellite is far away) and lean
    ``view_zenith_deg`` from the vertical. A point is hidden when the line from it towards the
    sensor passes below the surface somewhere nearer the sensor: at a point j nearer than i,
    that line is (d_i - d_j) / tan θ above h_i, so i is hidden if h_j + d_j / tan θ >
    h_i + d_i / tan θ for some j < i, a running maximum. Between the samples the surface is
    taken as straight, for which testing the samples is exact. On a DSM (buildings, tree
    canopy) the hidden ground behind each building is what an orthoimage cannot show: a DTM
    orthoimage leans each roof over it by h·tan θ (:func:`relief_displacement`); a "true
    orthoimage" needs the DSM and another view for the hidden part.

    Parameters
    ----------
    distance_m : (n,) array_like
        Horizontal distance of each point along the profile (m), strictly increasing away
        from the sensor.
    height_m : (n,) array_like
        Surface height at each point (m).
    view_zenith_deg : float
        View zenith angle of the lines of sight, in [0, 90) degrees.

    Returns
    -------
    ndarray of bool
        True where the point is hidden (0 is seen at nadir: nothing hides).

    Raises
    ------
    ValueError
        If the arrays are not 1-D of the same length, hold NaN, the distances do not
        increase, or the angle is outside [0, 90).

    Examples
    --------
    A 10 m wall at 45°: it hides the next 10 m of ground behind it.

    >>> d = np.arange(0.0, 30.0, 2.0)
    >>> h = np.where(d == 10.0, 10.0, 0.0)
    >>> d[occluded(d, h, 45.0)].tolist()
    [12.0, 14.0, 16.0, 18.0]
    """
    distance = as_finite(distance_m, "distance_m")
    height = as_finite(height_m, "height_m")
    angle = float(as_finite(view_zenith_deg, "view_zenith_deg"))
    if distance.ndim != 1 or distance.shape != height.shape:
        raise RsgeoError(_("distance_m and height_m must be 1-D of the same length, got "
                           "shapes {a} and {b}").format(a=distance.shape, b=height.shape))
    if distance.size > 1 and not (np.diff(distance) > 0).all():
        raise RsgeoError(_("distance_m must increase strictly, away from the sensor; reverse "
                           "both arrays if the sensor is at the profile's other end"))
    if not 0 <= angle < 90:
        raise RsgeoError(_("view_zenith_deg must be in [0, 90) degrees, got {angle:g}").format(
            angle=angle))
    if angle == 0 or distance.size < 2:
        return np.zeros(distance.shape, dtype=bool)
    # a line of sight's height above its point, measured back at distance 0: what is in front
    # of a point hides it if it reaches above the point's line
    reach = height + distance / np.tan(np.radians(angle))
    in_front = np.maximum.accumulate(np.concatenate([[-np.inf], reach[:-1]]))
    return in_front > reach


def _few(values):
    values = np.ravel(values)
    shown = ", ".join(f"{v:g}" for v in values[:5])
    return shown + (f" ... ({values.size} values)" if values.size > 5 else "")


# -- RPC model ---------------------------------------------------------------

def _terms(L, P, H):
    """GDAL's RPCComputeTerms for arrays: a (20,) + shape stack."""
    return np.stack([np.ones_like(L), L, P, H, L * P, L * H, P * H, L * L, P * P, H * H,
                     L * P * H, L * L * L, L * P * P, L * H * H, L * L * P, P * P * P,
                     P * H * H, L * L * H, P * P * H, H * H * H])


# The packed RPC the compiled code reads (RPCModel._packed): 10 scalars, then 4 x 20
# coefficients in GDAL's padfCoeffs order (LINE_NUM, LINE_DEN, SAMP_NUM, SAMP_DEN)
_PACKED_SCALARS = (("LONG", "OFF"), ("LONG", "SCALE"), ("LAT", "OFF"), ("LAT", "SCALE"),
                   ("HEIGHT", "OFF"), ("HEIGHT", "SCALE"), ("SAMP", "OFF"), ("SAMP", "SCALE"),
                   ("LINE", "OFF"), ("LINE", "SCALE"))
_RPC_PACKED_SIZE = 10 + 4 * 20


@njit(cache=True, inline="always")
def _rpc_sum(p, o, L, P, H, LP, LH, PH, LL, PP, HH):
    """GDAL's RPCEvaluate of one cubic (coefficients p[o:o + 20]): the even terms and the odd
    terms summed apart, in index order, then added (GDAL's two SSE2 lanes)."""
    even = 0.0
    odd = 0.0
    even += 1.0 * p[o]
    odd += L * p[o + 1]
    even += P * p[o + 2]
    odd += H * p[o + 3]
    even += LP * p[o + 4]
    odd += LH * p[o + 5]
    even += PH * p[o + 6]
    odd += LL * p[o + 7]
    even += PP * p[o + 8]
    odd += HH * p[o + 9]
    # the cubic terms as RPCComputeTerms multiplies them, left to right: L * P * H is
    # (L * P) * H = LP * H, and so on
    even += LP * H * p[o + 10]
    odd += LL * L * p[o + 11]
    even += LP * P * p[o + 12]
    odd += LH * H * p[o + 13]
    even += LL * P * p[o + 14]
    odd += PP * P * p[o + 15]
    even += PH * H * p[o + 16]
    odd += LL * H * p[o + 17]
    even += PP * H * p[o + 18]
    odd += HH * H * p[o + 19]
    return even + odd


@njit(cache=True, inline="always")
def _rpc_point(p, o, lon, lat, height):
    """GDAL's RPCTransformPoint: (col, row) of one ground point, the packed RPC at p[o:]."""
    diff = lon - p[o]
    if diff < -270:                   # GDAL's dateline fold
        diff += 360
    elif diff > 270:
        diff -= 360
    L = diff / p[o + 1]
    P = (lat - p[o + 2]) / p[o + 3]
    H = (height - p[o + 4]) / p[o + 5]
    LP = L * P
    LH = L * H
    PH = P * H
    LL = L * L
    PP = P * P
    HH = H * H
    line_num = _rpc_sum(p, o + 10, L, P, H, LP, LH, PH, LL, PP, HH)
    line_den = _rpc_sum(p, o + 30, L, P, H, LP, LH, PH, LL, PP, HH)
    samp_num = _rpc_sum(p, o + 50, L, P, H, LP, LH, PH, LL, PP, HH)
    samp_den = _rpc_sum(p, o + 70, L, P, H, LP, LH, PH, LL, PP, HH)
    # RPC line and sample count from the first pixel's centre, GDAL from its corner: + 0.5
    col = samp_num / samp_den * p[o + 7] + p[o + 6] + 0.5
    row = line_num / line_den * p[o + 9] + p[o + 8] + 0.5
    return col, row


@njit(cache=True, error_model="numpy")
def _project_points(p, lon, lat, height, cols, rows):
    """_rpc_point for every point of 1-D arrays, into cols and rows (in vector instructions:
    error_model="numpy" lets a division by zero give infinity, as in GDAL's C)."""
    for k in range(lon.size):
        cols[k], rows[k] = _rpc_point(p, 0, lon[k], lat[k], height[k])


class RPCModel:
    """A rational polynomial camera model (RPC00B), GDAL's reading of it.

    Normalised coordinates L = (lon − LONG_OFF) / LONG_SCALE, P = (lat −
    LAT_OFF) / LAT_SCALE, H = (h − HEIGHT_OFF) / HEIGHT_SCALE give

        sample = SAMP_NUM(L, P, H) / SAMP_DEN(L, P, H) · SAMP_SCALE + SAMP_OFF
        line   = LINE_NUM(L, P, H) / LINE_DEN(L, P, H) · LINE_SCALE + LINE_OFF

    with 0 at the centre of the first pixel; :meth:`project` returns GDAL's
    (col, row) = (sample + 0.5, line + 0.5).

    Parameters
    ----------
    offsets, scales : dict
        ``{"LINE": ..., "SAMP": ..., "LAT": ..., "LONG": ..., "HEIGHT": ...}``.
    line_num, line_den, samp_num, samp_den : array_like, shape (20,)
        Coefficients in GDAL's term order (``RPC_TERMS``).
    extra : dict, optional
        MIN_LONG, MAX_LAT, ERR_BIAS ... when given.

    Attributes
    ----------
    offsets, scales : dict
        As given, values as floats.
    line_num, line_den, samp_num, samp_den : ndarray, shape (20,)
        The coefficients, float64.
    extra : dict
        As given (empty when None).
    """

    def __init__(self, offsets, scales, line_num, line_den, samp_num, samp_den, extra=None):
        self.offsets = {k: float(v) for k, v in offsets.items()}
        self.scales = {k: float(v) for k, v in scales.items()}
        self.line_num, self.line_den, self.samp_num, self.samp_den = (
            np.array(c, dtype=np.float64) for c in (line_num, line_den, samp_num, samp_den))
        self.extra = dict(extra or {})

    @classmethod
    def from_dict(cls, mapping):
        """An RPC model from GDAL's RPC metadata or rasterio's ``RPC``.

        Parameters
        ----------
        mapping : mapping or rasterio.rpc.RPC
            Keys as GDAL's RPC metadata domain (``LINE_OFF``, ``SAMP_SCALE``,
            ``LINE_NUM_COEFF`` ...; any case); values numbers or strings,
            the four coefficient entries 20 numbers each, as a sequence or a
            space-separated string. A rasterio ``RPC`` (``dataset.rpcs``) is
            read through its ``to_gdal()``.

        Returns
        -------
        RPCModel

        Raises
        ------
        ValueError
            If a key is missing (the message names every missing key), a
            value is not a number, a coefficient entry does not hold 20
            numbers, or a scale is 0.

        Examples
        --------
        >>> rpc = RPCModel.from_dict(simple_rpc_dict())
        >>> rpc.scales["LINE"]
        500.0
        """
        if hasattr(mapping, "to_gdal"):
            mapping = mapping.to_gdal()
        try:
            upper = {str(key).upper(): value for key, value in dict(mapping).items()}
        except (TypeError, ValueError):
            raise TypeError(_("mapping must be a dict of RPC metadata (LINE_OFF, "
                              "SAMP_OFF, ..., LINE_NUM_COEFF, ...), got {kind}").format(
                    kind=type(mapping).__name__)) from None
        missing = [key for key in _SCALARS + _COEFFS if key not in upper]
        if missing:
            raise DataError(_("the RPC mapping lacks {listed}; an RPC00B model needs "
                              "{listed2}").format(
                    listed=', '.join(missing), listed2=', '.join(_SCALARS + _COEFFS)))
        numbers = {}
        for key in _SCALARS + tuple(k for k in _OPTIONAL if k in upper):
            try:
                numbers[key] = float(upper[key])
            except (TypeError, ValueError):
                raise DataError(_("RPC entry {key} must be a number, got {value!r}").format(
                        key=key, value=upper[key])) from None
            if not np.isfinite(numbers[key]):
                raise DataError(_("RPC entry {key} must be finite, got {value!r}").format(
                        key=key, value=upper[key]))
        coeffs = []
        for key in _COEFFS:
            value = upper[key]
            if isinstance(value, str):
                value = value.split()
            try:
                array = np.asarray(value, dtype=np.float64).ravel()
            except (TypeError, ValueError):
                raise DataError(_("RPC entry {key} must be 20 numbers, got {value!r}").format(
                        key=key, value=value)) from None
            if array.size != 20 or not np.isfinite(array).all():
                raise DataError(_("RPC entry {key} must be 20 finite numbers, got "
                                  "{array_size}").format(key=key, array_size=array.size))
            coeffs.append(array)
        for kind in ("LINE", "SAMP", "LAT", "LONG", "HEIGHT"):
            if numbers[f"{kind}_SCALE"] == 0:
                raise DataError(_("RPC entry {kind}_SCALE is 0; scales divide, so they "
                                  "must not be 0").format(kind=kind))
        offsets = {k: numbers[f"{k}_OFF"] for k in ("LINE", "SAMP", "LAT", "LONG", "HEIGHT")}
        scales = {k: numbers[f"{k}_SCALE"] for k in ("LINE", "SAMP", "LAT", "LONG", "HEIGHT")}
        extra = {k: numbers[k] for k in _OPTIONAL if k in numbers}
        return cls(offsets, scales, *coeffs, extra=extra)

    def to_dict(self):
        """GDAL's RPC metadata: every value a string that GDAL reads back exactly.

        Returns
        -------
        dict of str
            For ``rasterio.rpc.RPC(**...)`` use lower-case keys; for GDAL
            metadata (``dataset.update_tags(ns="RPC", ...)``) use these.

        Raises
        ------
        ValueError
            Never for a model built by :meth:`from_dict` or :func:`fit_rpc`.

        Examples
        --------
        >>> RPCModel.from_dict(simple_rpc_dict()).to_dict()["LINE_SCALE"]
        '500.0'
        """
        out = {}
        for kind in ("LINE", "SAMP", "LAT", "LONG", "HEIGHT"):
            out[f"{kind}_OFF"] = repr(self.offsets[kind])
            out[f"{kind}_SCALE"] = repr(self.scales[kind])
        for key, coeffs in zip(_COEFFS, (self.line_num, self.line_den, self.samp_num,
                                         self.samp_den)):
            out[key] = " ".join(repr(float(c)) for c in coeffs)
        out.update({k: repr(float(v)) for k, v in self.extra.items()})
        return out

    def to_rasterio(self):
        """The same model as a ``rasterio.rpc.RPC``, for GDAL through rasterio.

        Returns
        -------
        rasterio.rpc.RPC

        Raises
        ------
        ValueError
            Never for a valid model.
        """
        from rasterio.rpc import RPC

        o, s = self.offsets, self.scales
        return RPC(height_off=o["HEIGHT"], height_scale=s["HEIGHT"], lat_off=o["LAT"],
                   lat_scale=s["LAT"], line_den_coeff=list(self.line_den),
                   line_num_coeff=list(self.line_num), line_off=o["LINE"],
                   line_scale=s["LINE"], long_off=o["LONG"], long_scale=s["LONG"],
                   samp_den_coeff=list(self.samp_den), samp_num_coeff=list(self.samp_num),
                   samp_off=o["SAMP"], samp_scale=s["SAMP"])

    def __repr__(self):
        o = self.offsets
        return (f"RPCModel(centre lon {o['LONG']:.5f}°, lat {o['LAT']:.5f}°, height "
                f"{o['HEIGHT']:g} m; image centre col {o['SAMP'] + 0.5:g}, "
                f"row {o['LINE'] + 0.5:g})")

    def normalise(self, lon, lat, height):
        """Normalised (L, P, H) as GDAL computes them (with its ±270° dateline fold).

        Parameters
        ----------
        lon, lat, height : array_like
            Degrees, degrees, metres.

        Returns
        -------
        L, P, H : ndarray

        Raises
        ------
        ValueError
            If a latitude is outside [-90, 90], a longitude outside
            [-180, 360], or a value is not finite.
        """
        lon, lat, height = _lon_lat_height(lon, lat, height)
        diff = lon - self.offsets["LONG"]
        diff = np.where(diff < -270, diff + 360, np.where(diff > 270, diff - 360, diff))
        return (diff / self.scales["LONG"], (lat - self.offsets["LAT"]) / self.scales["LAT"],
                (height - self.offsets["HEIGHT"]) / self.scales["HEIGHT"])

    def project(self, lon, lat, height):
        """Image position (col, row) of ground points, GDAL's ``RPCTransformPoint``.

        Parameters
        ----------
        lon, lat : float or array_like
            Longitude and latitude (degrees, WGS 84 as RPCs are).
        height : float or array_like
            Ellipsoidal height (m); broadcast with lon and lat.

        Returns
        -------
        col, row : ndarray
            GDAL's continuous pixel coordinates, (0, 0) at the image's
            top-left corner (the RPC's line and sample plus 0.5).

        Raises
        ------
        ValueError
            If a latitude is outside [-90, 90], a longitude outside
            [-180, 360], or a value is not finite.

        Examples
        --------
        >>> rpc = RPCModel.from_dict(simple_rpc_dict())
        >>> col, row = rpc.project(-34.9, -8.0, 0.0)
        >>> float(col), float(row)
        (500.5, 500.5)
        """
        lon, lat, height = _lon_lat_height(lon, lat, height)
        shape = lon.shape
        cols, rows = np.empty(lon.size), np.empty(lon.size)
        # one compiled pass, point by point (no array per term), GDAL's operations in order
        _project_points(self._packed(), np.ravel(lon), np.ravel(lat), np.ravel(height), cols,
                        rows)
        if not shape:
            return cols[0], rows[0]           # NumPy scalars for scalars, as before
        return cols.reshape(shape), rows.reshape(shape)

    def _packed(self):
        """The model as the float64 array that the compiled code reads (_RPC_PACKED_SIZE)."""
        scalars = [(self.offsets if part == "OFF" else self.scales)[kind]
                   for kind, part in _PACKED_SCALARS]
        return np.concatenate([scalars, self.line_num, self.line_den, self.samp_num,
                               self.samp_den]).astype(np.float64)

    def localize(self, col, row, height, tolerance=1e-8, max_iterations=30):
        """Ground position (lon, lat) of image points at a given height: the RPC's inverse.

        Newton's method on :meth:`project` with a finite-difference Jacobian,
        started at the offsets, until every point's position reprojects
        within ``tolerance`` pixels (GDAL's own inverse stops at 0.1 pixel by
        default, ``RPC_PIXEL_ERROR_THRESHOLD``).

        Parameters
        ----------
        col, row : float or array_like
            GDAL pixel coordinates, (0, 0) at the top-left corner.
        height : float or array_like
            Height of the ground there (m).
        tolerance : float
            Largest error accepted in col and in row (pixels), > 0.
        max_iterations : int
            Newton steps before giving up.

        Returns
        -------
        lon, lat : ndarray
            Degrees.

        Raises
        ------
        ValueError
            If a value is not finite, or some point did not converge (the
            message says how many and where).

        Examples
        --------
        >>> rpc = RPCModel.from_dict(simple_rpc_dict())
        >>> lon, lat = rpc.localize(500.5, 500.5, 0.0)
        >>> round(float(lon), 9), round(float(lat), 9)
        (-34.9, -8.0)
        """
        col = as_finite(col, "col")
        row = as_finite(row, "row")
        height = as_finite(height, "height")
        col, row, height = np.broadcast_arrays(col, row, height)
        if not tolerance > 0:
            raise RsgeoError(_("tolerance must be > 0 pixels, got {tolerance!r}").format(
                    tolerance=tolerance))
        lon = np.full(col.shape, self.offsets["LONG"])
        lat = np.full(col.shape, self.offsets["LAT"])
        step_lon = 1e-7 * self.scales["LONG"]
        step_lat = 1e-7 * self.scales["LAT"]
        for _iteration in range(int(max_iterations)):
            c0, r0 = self.project(lon, lat, height)
            dc, dr = c0 - col, r0 - row
            if np.all(np.maximum(np.abs(dc), np.abs(dr)) < tolerance):
                return lon, lat
            c1, r1 = self.project(lon + step_lon, lat, height)
            c2, r2 = self.project(lon, lat + step_lat, height)
            a, b = (c1 - c0) / step_lon, (c2 - c0) / step_lat
            c, d = (r1 - r0) / step_lon, (r2 - r0) / step_lat
            det = a * d - b * c
            lon = np.clip(lon - (d * dc - b * dr) / det, -180.0, 360.0)
            lat = np.clip(lat - (-c * dc + a * dr) / det, -90.0, 90.0)
        c0, r0 = self.project(lon, lat, height)
        bad = np.maximum(np.abs(c0 - col), np.abs(r0 - row)) >= tolerance
        if bad.any():
            where = np.flatnonzero(bad.ravel())[:5].tolist()
            raise ModelError(_("localize did not converge to {tolerance:g} px for {sum} "
                               "point(s) (flat indices {where}); are they inside the "
                               "image the RPC describes?").format(
                    tolerance=prose_number(tolerance), sum=bad.sum(), where=where))
        return lon, lat


def simple_rpc_dict():
    """A small, valid RPC metadata dict (a nadir view of Olinda, 10 m pixels) for examples.

    Returns
    -------
    dict
        GDAL RPC metadata keys; lon −34.9°, lat −8.0° projects to (500.5, 500.5).

    Raises
    ------
    ValueError
        Never.

    Examples
    --------
    >>> sorted(simple_rpc_dict())[:3]
    ['HEIGHT_OFF', 'HEIGHT_SCALE', 'LAT_OFF']
    """
    zeros = [0.0] * 20
    samp_num, line_num, den = list(zeros), list(zeros), list(zeros)
    samp_num[1], line_num[2], den[0] = 1.0, -1.0, 1.0
    return {"LINE_OFF": 500.0, "SAMP_OFF": 500.0, "LAT_OFF": -8.0, "LONG_OFF": -34.9,
            "HEIGHT_OFF": 0.0, "LINE_SCALE": 500.0, "SAMP_SCALE": 500.0, "LAT_SCALE": 0.045,
            "LONG_SCALE": 0.045, "HEIGHT_SCALE": 500.0, "LINE_NUM_COEFF": line_num,
            "LINE_DEN_COEFF": den, "SAMP_NUM_COEFF": samp_num, "SAMP_DEN_COEFF": list(den)}


def _lon_lat_height(lon, lat, height):
    lon = as_finite(lon, "lon")
    lat = as_finite(lat, "lat")
    height = as_finite(height, "height")
    if np.any(np.abs(lat) > 90):
        raise CRSError(_("lat must be in [-90, 90] degrees, got {few} (longitude and "
                         "latitude swapped?)").format(few=_few(lat[np.abs(lat) > 90])))
    if np.any((lon < -180) | (lon > 360)):
        raise CRSError(_("lon must be in [-180, 360] degrees, got {few} (projected "
                         "metres given instead of degrees?)").format(
                few=_few(lon[(lon < -180) | (lon > 360)])))
    return np.broadcast_arrays(lon, lat, height)


def fit_rpc(lon, lat, height, col, row, regularization=1e-10):
    """Fit an RPC to ground points and their image positions, as image vendors do.

    The terrain-independent fit: the points are a 3-D grid of a physical
    sensor model (several height layers), not GCPs. Offsets are the middles
    and scales the half-ranges of the data; for line and sample separately,
    the 39 unknowns (20 numerator coefficients, 19 denominator ones, the
    first fixed to 1) solve the linearised equations
    NUM(L, P, H) − x·DEN(L, P, H) = 0 by least squares, reweighted once by
    1/DEN² (Tao and Hu 2001), with a small ridge term against the
    near-collinearity of the cubic terms.

    Parameters
    ----------
    lon, lat, height : array_like
        Ground points (degrees, degrees, metres), same size, at least 39.
    col, row : array_like
        Their image positions, GDAL pixel coordinates.
    regularization : float
        Ridge weight, relative to the normal matrix's diagonal.

    Returns
    -------
    RPCModel
        With MIN/MAX_LONG/LAT set to the data's range.

    Raises
    ------
    ValueError
        If the arrays differ in size, hold fewer than 39 points or
        non-finite values, latitudes or longitudes are out of range, or the
        heights do not vary (a single layer cannot fix the height terms).

    References
    ----------
    Tao, C. V. and Hu, Y. (2001), "A comprehensive study of the rational
    function model for photogrammetric processing", Photogrammetric
    Engineering & Remote Sensing 67(12), 1347-1357.

    Examples
    --------
    >>> rpc = RPCModel.from_dict(simple_rpc_dict())
    >>> g = np.meshgrid(np.linspace(-34.92, -34.88, 6), np.linspace(-8.02, -7.98, 6),
    ...                 [0.0, 100.0, 200.0], indexing="ij")
    >>> lon, lat, h = (a.ravel() for a in g)
    >>> fitted = fit_rpc(lon, lat, h, *rpc.project(lon, lat, h))
    >>> bool(np.allclose(fitted.project(-34.9, -8.0, 50.0), rpc.project(-34.9, -8.0, 50.0)))
    True
    """
    lon, lat, height = (np.ravel(a) for a in _lon_lat_height(lon, lat, height))
    col = np.ravel(as_finite(col, "col"))
    row = np.ravel(as_finite(row, "row"))
    if not (lon.size == lat.size == height.size == col.size == row.size):
        raise GCPError(_("lon, lat, height, col and row must have one size, got "
                         "{lon_size}, {lat_size}, {height_size}, {col_size}, {row_size}").format(
                lon_size=lon.size, lat_size=lat.size, height_size=height.size,
                col_size=col.size, row_size=row.size))
    if lon.size < 39:
        raise GCPError(_("fit_rpc needs at least 39 points (39 unknowns per "
                         "coordinate), got {lon_size}").format(lon_size=lon.size))
    if np.ptp(height) == 0:
        raise GCPError(_("the heights do not vary; fit the RPC to a 3-D grid (several height "
                         "layers), as the height terms need"))

    def middle_half(values, least=1e-9):
        low, high = float(values.min()), float(values.max())
        return (low + high) / 2, max((high - low) / 2, least)

    offsets, scales = {}, {}
    for kind, values in (("LONG", lon), ("LAT", lat), ("HEIGHT", height),
                         ("SAMP", col - 0.5), ("LINE", row - 0.5)):
        offsets[kind], scales[kind] = middle_half(values)
    L = (lon - offsets["LONG"]) / scales["LONG"]
    P = (lat - offsets["LAT"]) / scales["LAT"]
    H = (height - offsets["HEIGHT"]) / scales["HEIGHT"]
    terms = _terms(L, P, H).T                          # (n, 20)
    fitted = {}
    for kind, values in (("SAMP", col - 0.5), ("LINE", row - 0.5)):
        x = (values - offsets[kind]) / scales[kind]
        design = np.hstack([terms, -x[:, None] * terms[:, 1:]])
        weights = np.ones_like(x)
        for _iteration in range(2):
            a = design * weights[:, None]
            normal = a.T @ a
            normal += regularization * np.trace(normal) / normal.shape[0] * np.eye(normal.shape[0])
            solution = np.linalg.solve(normal, a.T @ (x * weights))
            den = np.concatenate([[1.0], solution[20:]])
            weights = 1.0 / np.abs(terms @ den)
        fitted[kind] = (solution[:20], den)
    extra = {"MIN_LONG": float(lon.min()), "MAX_LONG": float(lon.max()),
             "MIN_LAT": float(lat.min()), "MAX_LAT": float(lat.max())}
    return RPCModel(offsets, scales, fitted["LINE"][0], fitted["LINE"][1], fitted["SAMP"][0],
                    fitted["SAMP"][1], extra)


# -- RPC bias compensation with GCPs -------------------------------------------

#: The image-space bias compensations :func:`refine_rpc` fits.
BIAS_KINDS = ("shift", "affine")
_BIAS_MINIMUM = {"shift": 1, "affine": 3}
_GCP_COLUMNS = ("lon", "lat", "height", "col", "row")


def _rpc_gcps(gcps):
    """(lon, lat, height, col, row) 1-D float arrays from a mapping or an (n, 5) array."""
    if hasattr(gcps, "keys"):
        missing = [key for key in _GCP_COLUMNS if key not in gcps.keys()]
        if missing:
            raise GCPError(_("gcps lacks {missing}; give lon, lat, height (ellipsoidal, m), col "
                             "and row for every GCP").format(missing=", ".join(missing)))
        columns = [gcps[key] for key in _GCP_COLUMNS]
    else:
        try:
            kind = np.asarray(gcps).dtype.kind
        except (TypeError, ValueError):
            kind = "O"
        if kind in "cbUS":
            raise TypeError(_("gcps must hold real numbers, got a {kind} array").format(
                kind={"c": "complex", "b": "bool"}.get(kind, "text")))
        try:
            array = np.asarray(gcps, dtype=np.float64)
        except (TypeError, ValueError):
            raise GCPError(_("gcps must be an (n, 5) array of lon, lat, height, col, row (or a "
                             "mapping of those five names), got {got!r}").format(
                                 got=type(gcps).__name__)) from None
        if array.ndim == 1 and array.size == 5:
            array = array[np.newaxis]
        if array.ndim != 2 or array.shape[1] != 5:
            raise GCPError(_("gcps must be an (n, 5) array of lon, lat, height, col, row, got "
                             "shape {shape}").format(shape=array.shape))
        columns = list(array.T)
    arrays = []
    for key, values in zip(_GCP_COLUMNS, columns):
        try:
            values = np.asarray(values, dtype=np.float64).ravel()
        except (TypeError, ValueError):
            raise GCPError(_("gcps[{key!r}] must be numbers").format(key=key)) from None
        arrays.append(values)
    sizes = [values.size for values in arrays]
    if len(set(sizes)) != 1:
        raise GCPError(_("lon, lat, height, col and row of the GCPs must have one size, got "
                         "{sizes}").format(sizes=", ".join(map(str, sizes))))
    bad = ~np.isfinite(np.column_stack(arrays)).all(axis=1)
    if bad.any():
        raise GCPError(_("GCPs {rows} hold NaN or infinite values; every lon, lat, height, col "
                         "and row must be a finite number").format(
                             rows=np.flatnonzero(bad)[:5].tolist()))
    return arrays


class RefinedRPC:
    """An RPC with an image-space bias compensation fitted to GCPs (:func:`refine_rpc`).

    The vendor's RPC gives (col, row); the compensation adds

        Δcol = a0 + a1·col + a2·row,    Δrow = b0 + b1·col + b2·row

    (``kind="shift"``: a1 = a2 = b1 = b2 = 0). It has the interface of
    :class:`RPCModel` that places points (:meth:`project`, :meth:`localize`);
    :meth:`to_rpc` turns it into a plain :class:`RPCModel` for
    :func:`orthorectify` or GDAL.

    Parameters
    ----------
    rpc : RPCModel
        The delivered model.
    kind : {"shift", "affine"}
        The compensation.
    parameters : dict of float
        ``a0, a1, a2, b0, b1, b2``.
    residuals, residuals_before : ndarray, shape (n, 2)
        The GCPs' residuals with and without the compensation (pixels).

    Attributes
    ----------
    rpc : RPCModel
        The model that was compensated (not modified).
    kind : {"shift", "affine"}
    parameters : dict of float
        ``a0, a1, a2`` (columns) and ``b0, b1, b2`` (rows); a0, b0 in pixels.
    residuals : ndarray, shape (n, 2)
        Each GCP's measured (col, row) minus the compensated model's, pixels.
    residuals_before : ndarray, shape (n, 2)
        The same for the RPC as delivered.
    rms, rms_before : float
        The lecture's RMS of those residuals, sqrt(Σ(dcol² + drow²) / n), pixels:
        fitting errors, not check points.
    """

    def __init__(self, rpc, kind, parameters, residuals, residuals_before):
        self.rpc = rpc
        self.kind = kind
        self.parameters = dict(parameters)
        self.residuals = residuals
        self.residuals_before = residuals_before
        self.rms = float(np.sqrt(np.mean(np.sum(residuals ** 2, axis=1))))
        self.rms_before = float(np.sqrt(np.mean(np.sum(residuals_before ** 2, axis=1))))

    def __repr__(self):
        p = self.parameters
        return (f"RefinedRPC({self.kind}, {len(self.residuals)} GCPs: Δcol = {p['a0']:+.3f} px, "
                f"Δrow = {p['b0']:+.3f} px at (0, 0); GCP RMS {self.rms_before:.3f} -> "
                f"{self.rms:.3f} px)")

    def _apply(self, col, row):
        p = self.parameters
        return (col + p["a0"] + p["a1"] * col + p["a2"] * row,
                row + p["b0"] + p["b1"] * col + p["b2"] * row)

    def project(self, lon, lat, height):
        """Image position (col, row) of ground points: the RPC's, compensated.

        Parameters
        ----------
        lon, lat : float or array_like
            Degrees (WGS 84).
        height : float or array_like
            Ellipsoidal height (m).

        Returns
        -------
        col, row : ndarray
            GDAL's pixel coordinates, (0, 0) at the top-left corner.

        Raises
        ------
        ValueError
            As :meth:`RPCModel.project`.
        """
        return self._apply(*self.rpc.project(lon, lat, height))

    def localize(self, col, row, height, tolerance=1e-8, max_iterations=30):
        """Ground position (lon, lat) of image points at a given height: :meth:`project`'s inverse.

        The compensation is undone exactly (a 2 × 2 linear system), then
        :meth:`RPCModel.localize` inverts the RPC.

        Parameters
        ----------
        col, row : float or array_like
            GDAL pixel coordinates.
        height : float or array_like
            Ellipsoidal height (m).
        tolerance, max_iterations
            As :meth:`RPCModel.localize`.

        Returns
        -------
        lon, lat : ndarray

        Raises
        ------
        ValueError
            As :meth:`RPCModel.localize`.
        """
        col = as_finite(col, "col")
        row = as_finite(row, "row")
        p = self.parameters
        a, b, c, d = 1 + p["a1"], p["a2"], p["b1"], 1 + p["b2"]
        det = a * d - b * c
        u, v = col - p["a0"], row - p["b0"]
        return self.rpc.localize((d * u - b * v) / det, (a * v - c * u) / det, height,
                                 tolerance, max_iterations)

    def to_rpc(self, n=11):
        """The compensated model as a plain :class:`RPCModel` (for :func:`orthorectify`, GDAL).

        A shift is exact: it moves ``SAMP_OFF`` and ``LINE_OFF``. An affine
        mixes the sample's and the line's ratios, which have different
        denominators, so no RPC holds it exactly; it is refitted
        (:func:`fit_rpc`) to this model on an n × n × 5 grid spanning the
        RPC's normalised cube (offset ± scale in longitude, latitude and
        height), as vendors fit RPCs to their sensor models.

        Parameters
        ----------
        n : int
            Grid points along longitude and latitude for the affine's refit, >= 3.

        Returns
        -------
        RPCModel

        Raises
        ------
        ValueError
            If ``n`` is not a whole number >= 3.
        """
        n = as_integer(n, "n", low=3)
        if self.kind == "shift":
            offsets = dict(self.rpc.offsets)
            offsets["SAMP"] += self.parameters["a0"]
            offsets["LINE"] += self.parameters["b0"]
            return RPCModel(offsets, self.rpc.scales, self.rpc.line_num, self.rpc.line_den,
                            self.rpc.samp_num, self.rpc.samp_den, self.rpc.extra)
        o, s = self.rpc.offsets, self.rpc.scales
        L, P, H = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n),
                              np.linspace(-1, 1, 5), indexing="ij")
        lon = o["LONG"] + L.ravel() * s["LONG"]
        lat = np.clip(o["LAT"] + P.ravel() * s["LAT"], -90.0, 90.0)
        height = o["HEIGHT"] + H.ravel() * s["HEIGHT"]
        return fit_rpc(lon, lat, height, *self.project(lon, lat, height))


def refine_rpc(rpc, gcps, kind="shift"):
    """Compensate an RPC's bias with GCPs: an image-space shift or affine, by least squares.

    A delivered RPC places points as well as the satellite knew its position
    and attitude: off by a bias of a few metres to tens of metres, nearly the
    same everywhere in a scene. Grodecki and Dial (2003) and Fraser and Hanley
    (2003) remove it in image space, with the RPC untouched:

        col' = col + a0 + a1·col + a2·row,    row' = row + b0 + b1·col + b2·row

    with (col, row) the RPC's position of a GCP's ground point and (col',
    row') its measured position. ``kind="shift"`` fits a0 and b0 only (the
    mean residual; 1 GCP at least), ``"affine"`` all six (3 GCPs at least,
    not on one line). Both are least squares; their fitting residuals come
    with the result, but only check points (GCPs left out) measure the
    compensated model's error.

    Parameters
    ----------
    rpc : RPCModel or mapping
        The delivered RPC (a mapping is read by :meth:`RPCModel.from_dict`).
    gcps : mapping or (n, 5) array_like
        The GCPs: a mapping (a dict of arrays, a pandas DataFrame) with keys
        ``lon``, ``lat``, ``height``, ``col``, ``row``, or an array whose
        columns are those five. lon, lat in degrees (WGS 84), height
        **ellipsoidal** in metres (as RPCs take it: add the geoid undulation
        to a height above sea level, :func:`rsgeo.heights.to_ellipsoidal`),
        col, row the measured GDAL pixel position.
    kind : {"shift", "affine"}
        The compensation.

    Returns
    -------
    RefinedRPC
        With ``project`` and ``localize`` as an RPC has, the fitted
        ``parameters`` and the GCPs' ``residuals`` before and after.

    Raises
    ------
    GCPError
        Too few GCPs for ``kind`` (1 for a shift, 3 for an affine), GCPs whose
        image positions are on one line (affine), NaN or infinite values, a
        missing column, columns of different sizes.
    RsgeoError
        An unknown ``kind``.
    TypeError
        If ``rpc`` is neither an RPCModel nor a mapping, or ``gcps`` holds text.

    References
    ----------
    Grodecki, J. and Dial, G. (2003), "Block adjustment of high-resolution
    satellite images described by rational polynomials", Photogrammetric
    Engineering & Remote Sensing 69(1), 59-68.

    Fraser, C. S. and Hanley, H. B. (2003), "Bias compensation in rational
    functions for IKONOS satellite imagery", Photogrammetric Engineering &
    Remote Sensing 69(1), 53-58.

    Examples
    --------
    >>> rpc = RPCModel.from_dict(simple_rpc_dict())
    >>> lon, lat, h = np.array([-34.91, -34.89, -34.90]), np.array([-8.01, -8.0, -7.99]), 0.0
    >>> col, row = rpc.project(lon, lat, h)
    >>> refined = refine_rpc(rpc, {"lon": lon, "lat": lat, "height": [h] * 3,
    ...                            "col": col + 2.0, "row": row - 1.0})
    >>> round(refined.parameters["a0"], 6), round(refined.parameters["b0"], 6)
    (2.0, -1.0)
    """
    kind = check_choice(kind, "kind", BIAS_KINDS)
    if not isinstance(rpc, RPCModel):
        rpc = RPCModel.from_dict(rpc)
    lon, lat, height, col, row = _rpc_gcps(gcps)
    needed = _BIAS_MINIMUM[kind]
    if lon.size < needed:
        raise GCPError(_("a {kind} compensation needs at least {needed} GCP(s), got {got}")
                       .format(kind=kind, needed=needed, got=lon.size))
    rpc_col, rpc_row = (np.asarray(v, dtype=np.float64) for v in rpc.project(lon, lat, height))
    before = np.column_stack([col - rpc_col, row - rpc_row])
    parameters = dict.fromkeys(("a0", "a1", "a2", "b0", "b1", "b2"), 0.0)
    if kind == "shift":
        parameters["a0"], parameters["b0"] = (float(v) for v in before.mean(axis=0))
    else:
        # centred and scaled for the conditioning, then back to the raw coefficients
        centre = np.array([rpc_col.mean(), rpc_row.mean()])
        spread = np.column_stack([rpc_col, rpc_row]) - centre
        scale = max(float(np.abs(spread).max()), 1e-300)
        singular = np.linalg.svd(spread / scale, compute_uv=False)
        if singular[-1] <= 1e-9 * max(singular[0], 1e-300) * np.sqrt(lon.size):
            raise GCPError(_("the GCPs' image positions are on one line (or coincide): an "
                             "affine compensation needs 3 GCPs that span an area; use a shift "
                             "or spread the GCPs"))
        design = np.column_stack([np.ones(lon.size), spread / scale])
        solution = np.linalg.lstsq(design, before, rcond=None)[0]       # (3, 2)
        for axis, names in enumerate((("a0", "a1", "a2"), ("b0", "b1", "b2"))):
            linear = solution[1:, axis] / scale
            parameters[names[1]], parameters[names[2]] = (float(v) for v in linear)
            parameters[names[0]] = float(solution[0, axis] - linear @ centre)
    refined = RefinedRPC(rpc, kind, parameters, before, before)
    after = np.column_stack([col, row]) - np.column_stack(refined._apply(rpc_col, rpc_row))
    return RefinedRPC(rpc, kind, parameters, after, before)


# -- DEM and orthorectification ---------------------------------------------

def _gdal_inverse(gt):
    """GDALInvGeoTransform, operation for operation."""
    if gt[2] == 0.0 and gt[4] == 0.0 and gt[1] != 0.0 and gt[5] != 0.0:
        return np.array([-gt[0] / gt[1], 1.0 / gt[1], 0.0, -gt[3] / gt[5], 0.0, 1.0 / gt[5]])
    det = gt[1] * gt[5] - gt[2] * gt[4]
    magnitude = max(abs(gt[1]), abs(gt[2]), abs(gt[4]), abs(gt[5]))
    if abs(det) <= 1e-10 * magnitude * magnitude:
        raise GridError(_("the geotransform {gt} cannot be inverted (its pixels have no "
                          "area)").format(gt=tuple(gt)))
    inv = 1.0 / det
    return np.array([(gt[2] * gt[3] - gt[0] * gt[5]) * inv, gt[5] * inv, -gt[2] * inv,
                     (-gt[1] * gt[3] + gt[0] * gt[4]) * inv, -gt[4] * inv, gt[1] * inv])


def _as_gdal(transform, name):
    """GDAL's 6 numbers of an affine.Affine or a GDAL-ordered 6-sequence (rsgeo.data's rule)."""
    if transform is None:
        raise GridError(_("{name} is None; give the grid's affine.Affine (pixel corner -> "
                          "map)").format(name=name))
    return np.array(_as_affine(transform, name).to_gdal(), dtype=np.float64)


@njit(cache=True, inline="always")
def _dem_height_at(dem, inverse, x, y):
    """GDALRPCGetDEMHeight, bilinear with the nearest fallback, at one map point: (height,
    whether the point is outside the DEM). NaN for a point outside or over a hole."""
    rows, cols = dem.shape
    px = inverse[0] + x * inverse[1] + y * inverse[2]
    py = inverse[3] + x * inverse[4] + y * inverse[5]
    # GDAL's test for the nearest fallback, px > -1, py > -1, int(px) < cols and int(py) <
    # rows, asked before any conversion to int (the same for finite values; NaN, infinity and
    # huge values then never reach an index)
    if not (px > -1.0 and py > -1.0 and px < cols and py < rows):
        return np.nan, True
    fx = px - 0.5
    fy = py - 0.5
    ix = int(fx)                      # C's static_cast<int>: toward zero
    iy = int(fy)
    if ix >= 0 and iy >= 0 and ix + 2 <= cols and iy + 2 <= rows:
        dx = fx - ix
        dy = fy - iy
        dx1 = 1.0 - dx
        dy1 = 1.0 - dy
        z1 = dem[iy, ix] * dx1 + dem[iy, ix + 1] * dx
        z2 = dem[iy + 1, ix] * dx1 + dem[iy + 1, ix + 1] * dx
        return z1 * dy1 + z2 * dy, False
    return dem[int(py), int(px)], False


@njit(cache=True)
def _dem_heights(dem, inverse, x, y, out):
    """_dem_height_at at every point of 1-D arrays, into ``out``.

    Returns the number of points outside the DEM (their ``out`` is NaN).
    """
    outside = 0
    for k in range(x.size):
        out[k], is_outside = _dem_height_at(dem, inverse, x[k], y[k])
        outside += is_outside
    return outside


# the columns of _ortho_positions' per-row counts
_OUTSIDE_DEM, _OVER_HOLE, _BAD_LON_LAT, _SEES_IMAGE = range(4)


@njit(cache=True, parallel=True, error_model="numpy")
def _ortho_positions(dst_gt, first_row, width, lon, lat, dem_x, dem_y, dem, inverse, rpc,
                     image_width, image_height, cols, rows, counts):
    """One strip of orthorectify in one compiled pass: each cell's DEM height and RPC position.

    Cell (i, j) of the strip (output row ``first_row + i``) is at flat index
    ``i * width + j``. Its longitude and latitude are ``lon``, ``lat`` (PROJ's, for a
    projected grid) or, when they are empty, its centre through ``dst_gt`` (a grid in
    EPSG:4326, as GDAL's GenImgProjTransform computes it); the DEM is sampled at ``dem_x``,
    ``dem_y`` (a DEM in another CRS) or, when empty, at the longitude and latitude. The RPC's
    (col, row) go to ``cols``, ``rows``. ``counts[i]`` gets row i's cells outside the DEM,
    over a DEM hole, with a longitude or latitude out of range (their position is set to
    (-1, -1), outside the image), and whose position falls inside the image.

    Each row goes in passes: coordinates, heights (the DEM's branches), then the RPC over the
    whole row, a loop without branches that the compiler turns into vector instructions
    (several cells per instruction, each cell's operations unchanged: error_model="numpy"
    lets a division by zero give infinity, as in C, instead of testing every division).
    """
    n_rows = counts.shape[0]
    geographic_grid = lon.size == 0
    dem_on_lon_lat = dem_x.size == 0
    for i in prange(n_rows):
        # the row's views, indexed from 0 (an index known not to be negative spares Numba's
        # wrap-around test, which kept the RPC's loop from vector instructions)
        first, stop = i * width, (i + 1) * width
        row_cols = cols[first:stop]
        row_rows = rows[first:stop]
        heights = np.empty(width)
        # the cells' longitude and latitude, held in cols and rows until the RPC replaces them
        if geographic_grid:
            centre_row = first_row + i + 0.5
            for j in range(width):
                centre_col = j + 0.5
                row_cols[j] = dst_gt[0] + centre_col * dst_gt[1] + centre_row * dst_gt[2]
                row_rows[j] = dst_gt[3] + centre_col * dst_gt[4] + centre_row * dst_gt[5]
        else:
            row_cols[:] = lon[first:stop]
            row_rows[:] = lat[first:stop]
        row_x = row_cols if dem_on_lon_lat else dem_x[first:stop]
        row_y = row_rows if dem_on_lon_lat else dem_y[first:stop]
        outside = 0
        holed = 0
        bad = 0
        for j in range(width):
            height, is_outside = _dem_height_at(dem, inverse, row_x[j], row_y[j])
            if is_outside:
                outside += 1
            elif np.isnan(height):
                holed += 1
            elif not (-180.0 <= row_cols[j] <= 360.0 and -90.0 <= row_rows[j] <= 90.0):
                bad += 1
                height = np.nan
            heights[j] = height
        for j in range(width):
            row_cols[j], row_rows[j] = _rpc_point(rpc, 0, row_cols[j], row_rows[j], heights[j])
        seen = 0
        for j in range(width):
            if np.isnan(heights[j]):
                row_cols[j] = -1.0
                row_rows[j] = -1.0
            elif 0.0 <= row_cols[j] < image_width and 0.0 <= row_rows[j] < image_height:
                seen += 1
        counts[i, _OUTSIDE_DEM] = outside
        counts[i, _OVER_HOLE] = holed
        counts[i, _BAD_LON_LAT] = bad
        counts[i, _SEES_IMAGE] = seen


def line_of_sight_on_dem(ground, shape, dem, dem_transform, iterations):
    """Where lines of sight meet a DEM, by the fixed-point iteration h -> (x, y) -> h.

    One idea for every sensor model of the course (:class:`PushbroomSensor`,
    :class:`rsgeo.synthetic.RawSensor`): start on the datum (h = 0), find where each line of
    sight is at that height, read the DEM there, repeat. Each step shrinks the error by the
    terrain's slope times tan θ, so a few steps suffice on gentle terrain.

    Parameters
    ----------
    ground : callable
        ``ground(h) -> (x, y)``: where the lines of sight are at heights ``h`` (an array of
        ``shape``), in the DEM's map coordinates.
    shape : tuple of int
        The shape of the lines of sight's array.
    dem : 2-D array
        Heights (m) on the sensor model's datum.
    dem_transform : affine.Affine
        The DEM's geotransform.
    iterations : int
        How many steps.

    Returns
    -------
    x, y, h : ndarray
        The ground points, of ``shape``.

    Raises
    ------
    ValueError
        If a line of sight leaves the DEM (:func:`dem_height`).

    Examples
    --------
    >>> import affine
    >>> dem = np.full((10, 10), 50.0)
    >>> x, y, h = line_of_sight_on_dem(lambda h: (2.0 + 0.1 * h, 5.0 - 0 * h), (1,), dem,
    ...                                affine.Affine(1, 0, 0, 0, -1, 10), 3)
    >>> float(x[0]), float(h[0])                        # 50 m up, 0.1 m east per metre
    (7.0, 50.0)
    """
    h = np.zeros(shape)
    for _iteration in range(iterations):
        x, y = ground(h)
        h = dem_height(dem, dem_transform, x, y)
    x, y = ground(h)
    return x, y, h


def dem_height(dem, dem_transform, x, y, dem_nodata=None):
    """DEM heights at map points, bilinear, exactly as GDAL's RPC transformer samples its DEM.

    Parameters
    ----------
    dem : (rows, cols) array_like
        Heights (m). NaN (or ``dem_nodata``) marks a hole.
    dem_transform : affine.Affine
        The DEM's geotransform (pixel corner -> map).
    x, y : array_like
        Points in the DEM's coordinates, same shape.
    dem_nodata : float, optional
        Value marking holes, besides NaN.

    Returns
    -------
    ndarray
        Heights, shape of ``x``.

    Raises
    ------
    ValueError
        If the DEM is not 2-D, a point falls outside the DEM, or a point
        needs a DEM cell that is a hole; the message says how many and the
        first such point.

    References
    ----------
    GDAL, ``alg/gdal_rpc.cpp``: ``GDALRPCGetDEMHeight``.

    Examples
    --------
    >>> import affine
    >>> dem = np.array([[0.0, 10.0], [20.0, 30.0]])
    >>> float(dem_height(dem, affine.Affine(1, 0, 0, 0, -1, 2), 1.0, 1.0))
    15.0
    """
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if x.shape != y.shape:
        raise RsgeoError(_("x and y must have the same shape, got {x_shape} and "
                           "{y_shape}").format(x_shape=x.shape, y_shape=y.shape))
    prepared = _prepare_dem(dem, dem_transform, dem_nodata)
    heights, outside, holed = _sample_dem(prepared, x, y)
    _raise_dem_problems(prepared, outside, holed, x.size)
    return heights


def _prepare_dem(dem, dem_transform, dem_nodata):
    """(DEM with NaN holes, its inverse geotransform, its holes, its transform) for sampling."""
    kind = np.asarray(dem).dtype.kind
    if kind not in "uif":
        raise ImageError(_(
            "dem must hold real heights in metres (integers or floats), got dtype {dtype}; a "
            "complex DEM has no height: give its real part (dem.real) if that is one").format(
                dtype=np.asarray(dem).dtype))
    dem = np.asarray(dem, dtype=np.float64)
    if dem.ndim != 2 or min(dem.shape) < 1:
        raise ImageError(_("dem must be a 2-D (rows, cols) array of heights, got shape "
                           "{dem_shape}").format(dem_shape=dem.shape))
    inverse = _gdal_inverse(_as_gdal(dem_transform, "dem_transform"))
    holes = ~np.isfinite(dem)
    if dem_nodata is not None:
        holes |= dem == dem_nodata
    work = np.ascontiguousarray(np.where(holes, np.nan, dem))
    return work, inverse, holes, dem_transform


def _sample_dem(prepared, x, y):
    """Heights at points (shape of ``x``); with (count, first x, first y) of the points outside
    the DEM and of those on a hole (count 0: none)."""
    work, inverse, _holes, _transform = prepared
    flat_x, flat_y = np.ravel(x), np.ravel(y)
    out = np.empty(flat_x.size)
    outside = _dem_heights(work, inverse, flat_x, flat_y, out)
    outside_first = holed_first = (0, 0.0, 0.0)
    if outside:
        first = int(np.flatnonzero(np.isnan(out) & _outside_mask(work.shape, inverse, flat_x,
                                                                     flat_y))[0])
        outside_first = (outside, flat_x[first], flat_y[first])
    else:
        missing = np.isnan(out)
        if missing.any():
            first = int(np.flatnonzero(missing)[0])
            holed_first = (int(missing.sum()), flat_x[first], flat_y[first])
    return out.reshape(np.shape(x)), outside_first, holed_first


def _raise_dem_problems(prepared, outside, holed, n):
    """The errors of points outside the DEM or over its holes (counts over ``n`` points)."""
    work, _inverse, holes, dem_transform = prepared
    if outside[0]:
        raise GridError(_("the DEM does not cover {value} of {n} points (first at "
                          "x={value2:.6f}, y={value3:.6f}; DEM bounds {bounds}); give a "
                          "DEM that covers the output grid").format(
                value=outside[0], n=n, value2=prose_number(outside[1]),
                value3=prose_number(outside[2]), bounds=_bounds(work.shape, dem_transform)))
    if holed[0]:
        rows, cols = np.nonzero(holes)
        raise ImageError(_("the DEM has nodata holes ({sum} cells, e.g. row {value}, "
                           "col {value2}) under {value3} points (first at "
                           "x={value4:.6f}, y={value5:.6f}); fill them first").format(
                sum=holes.sum(), value=rows[0], value2=cols[0], value3=holed[0],
                value4=prose_number(holed[1]), value5=prose_number(holed[2])))


def _outside_mask(shape, inverse, x, y):
    with np.errstate(invalid="ignore", over="ignore"):   # infinite points: NaN, outside
        px = inverse[0] + x * inverse[1] + y * inverse[2]
        py = inverse[3] + x * inverse[4] + y * inverse[5]
    return ~((px > -1) & (py > -1) & (np.trunc(px) < shape[1]) & (np.trunc(py) < shape[0]))


def _bounds(shape, transform):
    gt = _as_gdal(transform, "transform")
    xs = [gt[0], gt[0] + shape[1] * gt[1] + shape[0] * gt[2]]
    ys = [gt[3], gt[3] + shape[1] * gt[4] + shape[0] * gt[5]]
    return f"x {min(xs):.6f} to {max(xs):.6f}, y {min(ys):.6f} to {max(ys):.6f}"


def _grid_centres(gt, shape, start=0, stop=None):
    """Map coordinates of cell centres (rows start to stop) as GDAL's GenImgProjTransform does."""
    cols = np.arange(shape[1]) + 0.5
    rows = (np.arange(start, shape[0] if stop is None else stop) + 0.5)[:, None]
    x = gt[0] + cols * gt[1] + rows * gt[2]
    y = gt[3] + cols * gt[4] + rows * gt[5]
    return x, y


def _to_crs(x, y, src, dst):
    """Points from CRS src to dst with GDAL's PROJ (rasterio.warp.transform); None = EPSG:4326.

    One call, single-threaded (GDAL's ``OCTTransform``, which rasterio reaches through
    Python objects, a coordinate at a time: most of a projected grid's time; a grid in
    EPSG:4326 needs no PROJ).
    """
    src = src or "EPSG:4326"
    dst = dst or "EPSG:4326"
    if str(src) == str(dst):
        return x, y
    from rasterio.warp import transform as warp_transform

    tx, ty = warp_transform(src, dst, np.ravel(x), np.ravel(y))
    return np.reshape(tx, np.shape(x)), np.reshape(ty, np.shape(y))


def _is_lon_lat(crs):
    """Whether a CRS is the RPC's own, EPSG:4326 (rsgeo's rule in _to_crs: no PROJ then)."""
    return crs is None or str(crs) == "EPSG:4326"


def _strip_coordinates(dst_gt, shape, start, stop, dst_crs, dem_crs, every=False):
    """Flat (lon, lat, dem_x, dem_y) of the cell centres of output rows start to stop.

    lon and lat come from PROJ for a projected grid, dem_x and dem_y for a DEM outside
    EPSG:4326; the others are empty (the compiled pass computes them from the grid), unless
    ``every``: then all four are computed, in NumPy, as GDAL does.
    """
    geographic, dem_geographic = _is_lon_lat(dst_crs), _is_lon_lat(dem_crs)
    lon = lat = dem_x = dem_y = _EMPTY
    if every or not geographic or not dem_geographic:
        x, y = (np.ravel(a) for a in np.broadcast_arrays(*_grid_centres(dst_gt, shape, start,
                                                                         stop)))
        lon, lat = _to_crs(x, y, dst_crs, "EPSG:4326")
    if every or not dem_geographic:
        dem_x, dem_y = _to_crs(lon, lat, "EPSG:4326", dem_crs)
    if not every and geographic:
        lon = lat = _EMPTY
    return lon, lat, dem_x, dem_y


_EMPTY = np.empty(0)


class _numba_threads:
    """``with _numba_threads(n):`` Numba's parallel loops use n threads inside, as before after."""

    def __init__(self, count):
        self.count = count

    def __enter__(self):
        import numba

        self.previous = numba.get_num_threads()
        numba.set_num_threads(self.count)

    def __exit__(self, *exc):
        import numba

        numba.set_num_threads(self.previous)


# cells of one strip of orthorectify: 16 bytes each while it is computed (its source positions)
# on a grid in EPSG:4326, up to about 100 with PROJ's coordinates for a projected grid and DEM
_STRIP_CELLS = 2 ** 19


def orthorectify(image, rpc, dem, dem_transform, dst_transform, dst_shape, method="bilinear",
                 nodata=0, dst_crs=None, dem_crs=None, dem_nodata=None, num_threads=1,
                 strip_rows=None, dem_vertical=None):
    """The orthoimage on an output grid: DEM height, RPC, interpolation, cell by cell.

    For each output cell centre: its longitude and latitude (through
    ``dst_crs`` when the grid is projected), its height from the DEM
    (bilinear, GDAL's :func:`dem_height`), the RPC's image position
    (:meth:`RPCModel.project`), and the value there by
    :func:`rsgeo.resample.interpolate` (GDAL's kernels, plain 2 × 2 and 4 × 4:
    GDAL's XSCALE = YSCALE = 1). This is ``gdalwarp -rpc -to RPC_DEM=dem.tif
    -to RPC_DEMINTERPOLATION=bilinear -et 0``.

    Parameters
    ----------
    image : ndarray
        The raw image the RPC describes, (rows, cols) or (bands, rows, cols).
    rpc : RPCModel or mapping
        Its RPC (a mapping is read with :meth:`RPCModel.from_dict`).
    dem : (rows, cols) array_like
        Heights (m) above what ``dem_vertical`` says; NaN marks holes.
    dem_transform : affine.Affine or sequence of 6 numbers
        The DEM's geotransform, in ``dem_crs``: an affine.Affine, or 6 numbers
        in GDAL's order (x0, pixel width, row rotation, y0, column rotation,
        pixel height), as :func:`rsgeo.data.save` reads them (a tuple in
        affine.Affine's order, pixel width first, is refused).
    dst_transform : affine.Affine or sequence of 6 numbers
        The output grid's geotransform, in ``dst_crs``; as ``dem_transform``.
    dst_shape : (rows, cols)
        Output grid size (refused if the output alone would not fit in
        this machine's memory).
    method : {"nearest", "bilinear", "cubic"}
        Interpolator for the image.
    nodata : number or None
        Value of output cells that see no pixel of the image.
    dst_crs, dem_crs : str, int or rasterio CRS, optional
        CRS of the output grid and of the DEM (see :func:`rsgeo.georef.as_crs`);
        None is EPSG:4326 (longitude, latitude in degrees).
    dem_nodata : float, optional
        DEM value marking holes, besides NaN.
    num_threads : int
        Threads for the compiled passes (DEM heights and RPC, interpolation)
        and for PROJ. The result does not depend on it.
    strip_rows : int, optional
        Output rows computed at a time (as :func:`rsgeo.resample.warp`):
        memory is the output plus one strip's working arrays, about 16
        bytes per cell with the grid and the DEM in EPSG:4326 (the source
        positions) and up to about 100 with PROJ's coordinates of a
        projected grid and DEM. By default about 2**19 cells a strip (256
        rows of a 2048-wide grid: 8 to 50 MB). The result does not depend
        on it.
    dem_vertical : {"ellipsoidal", "EGM96"}
        What the DEM's heights are above; required. An RPC takes heights
        above the WGS 84 ellipsoid, h = H + N; SRTM and Copernicus DEMs give
        H above a geoid (EGM96, EGM2008). "EGM96" adds the geoid undulation N
        (:func:`rsgeo.heights.geoid_on_grid`, at the DEM's cells) before the
        RPC, as ``gdalwarp`` does for a DEM whose CRS has the EGM96 height
        (``RPC_DEM_APPLY_VDATUM_SHIFT``); "ellipsoidal" takes the heights as
        they are (a DEM without a vertical CRS, in GDAL). Forgetting N moves
        every point N·tan θ.

    Returns
    -------
    ndarray
        ``image``'s dtype, ``dst_shape`` (with bands first when several).

    Raises
    ------
    TypeError
        If a transform is neither an affine.Affine nor a sequence of numbers.
    ValueError
        If the image is not 2-D or 3-D, the method is unknown, the RPC
        mapping lacks keys, a transform is a 6-tuple in affine.Affine's order
        or its pixels have no area, a CRS is not one PROJ knows, the output
        would not fit in memory, ``strip_rows`` is not a positive whole
        number, the DEM does not cover the output grid (how
        many cells, the first one), the DEM has holes under the grid, the
        grid's longitudes or latitudes are out of range, or no output cell
        sees the image (a grid in the wrong place or CRS); if ``dem_vertical``
        is missing or unknown, or a DEM cell is outside the shipped geoid grid.

    References
    ----------
    GDAL, ``alg/gdal_rpc.cpp`` (``GDALRPCTransform``, ``GDALRPCGetDEMHeight``)
    and ``alg/gdalwarpkernel.cpp``.

    Examples
    --------
    >>> import affine
    >>> rpc = RPCModel.from_dict(simple_rpc_dict())
    >>> image = np.arange(1000 * 1000, dtype=np.float32).reshape(1000, 1000)
    >>> dem = np.zeros((10, 10))
    >>> dem_gt = affine.Affine(0.01, 0, -34.95, 0, -0.01, -7.95)
    >>> grid = affine.Affine(0.001, 0, -34.91, 0, -0.001, -7.99)
    >>> ortho = orthorectify(image, rpc, dem, dem_gt, grid, (20, 20), "nearest",
    ...                      dem_vertical="EGM96")
    >>> ortho.shape
    (20, 20)
    """
    from .georef import as_crs
    from .heights import _add_geoid, check_vertical

    image = as_bands_first(as_image(image))
    check_choice(method, "method", METHODS)
    rpc = rpc if isinstance(rpc, RPCModel) else RPCModel.from_dict(rpc)
    bands = image.shape[0] if image.ndim == 3 else 1
    shape = as_output_shape(dst_shape, image.dtype, bands, "dst_shape")
    strip_rows = (max(1, _STRIP_CELLS // shape[1]) if strip_rows is None
                  else as_integer(strip_rows, "strip_rows", low=1))
    dst_gt = _as_gdal(dst_transform, "dst_transform")
    dst_crs = as_crs("EPSG:4326" if dst_crs is None else dst_crs, "dst_crs")
    dem_crs = as_crs("EPSG:4326" if dem_crs is None else dem_crs, "dem_crs")
    check_vertical(dem_vertical, "dem_vertical")
    prepared = _prepare_dem(dem, dem_transform, dem_nodata)
    if dem_vertical != "ellipsoidal":
        # The RPC takes h = H + N. N is added once at the DEM's own cells and then interpolated
        # with the DEM, not looked up at every output cell as GDAL does: EGM96 is a 15' (28 km)
        # grid, bilinear inside each of its cells, so the two agree exactly where a DEM cell lies
        # inside one EGM96 cell and within 2 mm for a 90 m DEM where it straddles two (measured
        # over Brazil), N·tan θ of that is nothing, and it costs one lookup per DEM cell, not
        # one per output cell. Holes stay NaN. (rsgeo.heights.geoid_on_grid, added in place.)
        _add_geoid(prepared[0], dem_transform, dem_crs, dem_vertical)
    height, width = image.shape[-2:]
    num_threads = as_num_threads(num_threads)
    out = np.empty((bands,) + shape, dtype=image.dtype)
    outside, holed = [0, 0.0, 0.0], [0, 0.0, 0.0]
    seen = False
    packed = rpc._packed()
    dem_work, dem_inverse = prepared[:2]
    strip_cells = min(strip_rows, shape[0]) * shape[1]
    cols, rows = np.empty(strip_cells), np.empty(strip_cells)
    counts = np.empty((min(strip_rows, shape[0]), 4), dtype=np.int64)
    # in strips of rows, as rsgeo.resample.warp: memory is the output plus one strip's
    # positions (each cell is computed alone, so the pixels do not depend on the strips)
    for start in range(0, shape[0], strip_rows):
        stop = min(start + strip_rows, shape[0])
        cells = (stop - start) * shape[1]
        # PROJ where a CRS is not the RPC's (it cannot run compiled), vectorised over the strip;
        # empty arrays tell the compiled pass to take the grid's or the DEM's own coordinates
        lon, lat, dem_x, dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                    dem_crs)
        with _numba_threads(num_threads):
            _ortho_positions(dst_gt, start, shape[1], lon, lat, dem_x, dem_y, dem_work,
                             dem_inverse, packed, width, height, cols, rows,
                             counts[:stop - start])
        found = counts[:stop - start].sum(axis=0)
        if found[_OUTSIDE_DEM] or found[_OVER_HOLE]:
            # the NumPy path of dem_height over this strip, for the messages' counts and
            # first points
            lon, lat, dem_x, dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                        dem_crs, every=True)
            _heights, strip_outside, strip_holed = _sample_dem(prepared, dem_x, dem_y)
            for total, strip in ((outside, strip_outside), (holed, strip_holed)):
                if strip[0] and not total[0]:
                    total[1:] = strip[1:]
                total[0] += strip[0]
        if outside[0] or holed[0]:
            continue                      # counted over the whole grid, then refused below
        if found[_BAD_LON_LAT]:
            lon, lat, _dem_x, _dem_y = _strip_coordinates(dst_gt, shape, start, stop, dst_crs,
                                                          dem_crs, every=True)
            _lon_lat_height(lon, lat, 0.0)        # raises, naming the values out of range
        seen = seen or bool(found[_SEES_IMAGE])
        strip_shape = (stop - start, shape[1])
        out[:, start:stop] = interpolate(
            image, cols[:cells].reshape(strip_shape), rows[:cells].reshape(strip_shape),
            method, nodata=nodata, num_threads=num_threads).reshape((bands,) + strip_shape)
    _raise_dem_problems(prepared, outside, holed, shape[0] * shape[1])
    if not seen:
        raise GridError(_("no output cell sees the image ({height} x {width} px): the "
                          "grid is elsewhere; check dst_transform and dst_crs against "
                          "the RPC's area (lon {value:.4f}, lat {value2:.4f})").format(
                height=height, width=width, value=prose_number(rpc.offsets['LONG']),
                value2=prose_number(rpc.offsets['LAT'])))
    return out if image.ndim == 3 else out[0]


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
    :func:`relief_displacement`. Earth curvature and attitude changes are
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
        gt = _gdal_inverse(_as_gdal(ground_transform, "ground_transform"))
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
    lon, lat = _to_crs(x, y, crs, "EPSG:4326")
    col, row = sensor.project(x, y, h)
    return fit_rpc(lon, lat, h, col, row)


# -- Checking an orthoimage on the image itself --------------------------------

def map_on_grid(image, transform, dst_transform, dst_shape, method="bilinear", nodata=None):
    """A map image resampled onto another grid of the same CRS (GDAL's kernels).

    Each output cell centre is sent through ``~transform`` into ``image``
    and interpolated there by :func:`rsgeo.resample.interpolate`: the true
    ground on an orthoimage's grid, for :func:`positional_error`.

    Parameters
    ----------
    image : 2-D ndarray
        The map (e.g. the ground a simulation was made from).
    transform, dst_transform : affine.Affine
        Geotransforms of ``image`` and of the output grid, same CRS.
    dst_shape : (rows, cols)
        Output grid size.
    method : {"nearest", "bilinear", "cubic"}
    nodata : number or None
        Value of cells outside ``image``.

    Returns
    -------
    ndarray
        ``image``'s dtype, ``dst_shape``.

    Raises
    ------
    ValueError
        If the image is not 2-D or the method is unknown.

    Examples
    --------
    >>> import affine
    >>> image = np.arange(16, dtype=np.float64).reshape(4, 4)
    >>> gt = affine.Affine(10, 0, 0, 0, -10, 40)
    >>> map_on_grid(image, gt, affine.Affine(20, 0, 0, 0, -20, 40), (2, 2)).tolist()
    [[2.5, 4.5], [10.5, 12.5]]
    """
    image = as_image(image)
    if image.ndim != 2:
        raise ImageError(_("image must be 2-D, got shape {image_shape}").format(
                image_shape=image.shape))
    check_choice(method, "method", METHODS)
    x, y = np.broadcast_arrays(*_grid_centres(_as_gdal(dst_transform, "dst_transform"),
                                              as_shape(dst_shape, "dst_shape")))
    inverse = _gdal_inverse(_as_gdal(transform, "transform"))
    cols = inverse[0] + x * inverse[1] + y * inverse[2]
    rows = inverse[3] + x * inverse[4] + y * inverse[5]
    return interpolate(image, cols, rows, method, nodata=nodata)


def positional_error(image, truth, step=64, window=64, nodata=0, upsample=100, taper=True):
    """Where a corrected image puts the ground, measured on the image against the truth.

    ``truth`` is the true ground on the same grid (:func:`map_on_grid` of
    the map a simulation was made from, or a reference orthoimage); at the
    check points of a regular grid the local shift between the two images'
    windows is measured by correlation (:func:`rsgeo.tiepoints.measure_shifts`;
    Hann-tapered by default, which smooth images need), skipping windows that touch a ``nodata``
    pixel of ``image``. This measures
    the image itself (its DEM, model and resampling together), not the
    model's fit at points.

    Parameters
    ----------
    image, truth : (rows, cols) array_like
        The corrected image and the truth, same grid.
    step, window : int
        Spacing of the check points and size of their windows, pixels.
    nodata : number or None
        ``image``'s value outside its footprint.
    upsample : int
        Sub-pixel precision: 1 / upsample pixel.
    taper : bool
        Hann-tapered cross-correlation (True) or phase correlation.

    Returns
    -------
    pandas.DataFrame
        One row per check point: ``col``, ``row`` (its position),
        ``dcol``, ``drow`` (the shift that moves ``image`` onto ``truth``,
        pixels) and ``error`` (its length, pixels).

    Raises
    ------
    ValueError
        As :func:`rsgeo.tiepoints.measure_shifts`, or if no window lies wholly
        inside the image's footprint.

    Examples
    --------
    >>> truth = np.random.default_rng(0).random((128, 128))
    >>> table = positional_error(np.roll(truth, 2, axis=1), truth, nodata=None)
    >>> table["dcol"].round(1).tolist(), table["drow"].round(1).tolist()
    ([-2.0, -2.0, -2.0, -2.0], [0.0, 0.0, 0.0, 0.0])
    """
    import pandas as pd

    image = np.asarray(image)
    valid = None if nodata is None else image != nodata
    points, shifts = measure_shifts(truth, image, step, window, upsample=upsample, taper=taper,
                                    valid=valid)
    if len(points) == 0:
        raise GridError(_("no check-point window lies wholly inside the image's footprint; use "
                          "a smaller window or step"))
    return pd.DataFrame({"col": points[:, 0], "row": points[:, 1], "dcol": shifts[:, 0],
                         "drow": shifts[:, 1], "error": np.hypot(shifts[:, 0], shifts[:, 1])})
