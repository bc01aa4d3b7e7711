"""Rational polynomial camera models (RPC00B), GDAL's reading of them, their fit and their bias
compensation.

A rational polynomial camera (RPC, the RPC00B convention of image vendors and
of GDAL's ``RPC`` metadata) maps (longitude, latitude, height) to (sample,
line) with ratios of cubic polynomials of the normalised coordinates
(:class:`RPCModel`). :func:`fit_rpc` fits one to a physical sensor model, as
vendors do ("terrain independent": a 3-D grid of the sensor model, no GCPs),
and :func:`rsgeo.ortho.orthorectify` builds the orthoimage: for every output cell its
height from a DEM (bilinear), the RPC gives the source position, and
:func:`rsgeo.resample.interpolate` the value. An RPC takes heights above the
ellipsoid; a DEM's are often above the geoid (SRTM: EGM96), so
:func:`rsgeo.ortho.orthorectify` asks which (``dem_vertical``) and adds the geoid
undulation N (:mod:`rsgeo.heights`) when they are. :func:`rsgeo.relief.occluded` finds the
ground that buildings and trees hide from an oblique view.

Conventions follow GDAL's ``alg/gdal_rpc.cpp`` operation by operation, so
that the numbers agree with GDAL's RPC transformer and ``gdalwarp -rpc -to
RPC_DEM=...``:

* RPC line and sample are 0 at the *centre* of the first pixel; GDAL (and
  rsgeo) put 0 at its top-left *corner*, so
  :meth:`RPCModel.project` adds 0.5 to both, as ``RPCTransformPoint`` does;
* the 20 terms are GDAL's order (1, L, P, H, LP, LH, PH, L², P², H², PLH, L³,
  LP², LH², L²P, P³, PH², L²H, P²H, H³), with L the normalised longitude,
  P the latitude, H the height; the sums add even and odd terms separately
  and then the two (GDAL's SSE2 evaluation);
* the DEM is sampled as GDAL 3.10's ``GDALRPCGetDEMHeight`` does it with
  bilinear interpolation: at (x − 0.5, y − 0.5) in DEM pixels, the window's
  indices clamped to the DEM, so that within its outer half cell the height
  is still interpolated along the edge (GDAL 3.9 and earlier took the nearest
  cell there); a point is on the DEM for 0 ≤ x ≤ columns, 0 ≤ y ≤ rows.
"""

import numpy as np

from .._kernels.rpc import PACKED_SCALARS, project_points
from ..errors import DataError, GCPError, ModelError, RsgeoError
from ..language import _, prose_number
from ..validation import (
    as_broadcast,
    as_finite,
    as_integer,
    as_lon_lat_height,
    as_number,
    check_choice,
    few_values,
)

__all__ = [
    "RPC_TERMS", "RPCModel", "simple_rpc_dict", "fit_rpc", "BIAS_KINDS", "RefinedRPC",
    "refine_rpc",
]



RPC_TERMS = ("1", "L", "P", "H", "LP", "LH", "PH", "LL", "PP", "HH",
             "PLH", "LLL", "LPP", "LHH", "LLP", "PPP", "PHH", "LLH", "PPH", "HHH")

_SCALARS = ("LINE_OFF", "SAMP_OFF", "LAT_OFF", "LONG_OFF", "HEIGHT_OFF",
            "LINE_SCALE", "SAMP_SCALE", "LAT_SCALE", "LONG_SCALE", "HEIGHT_SCALE")
_COEFFS = ("LINE_NUM_COEFF", "LINE_DEN_COEFF", "SAMP_NUM_COEFF", "SAMP_DEN_COEFF")
_OPTIONAL = ("MIN_LONG", "MIN_LAT", "MAX_LONG", "MAX_LAT", "ERR_BIAS", "ERR_RAND")


# -- RPC model ---------------------------------------------------------------

def _terms(L, P, H):
    """GDAL's RPCComputeTerms for arrays: a (20,) + shape stack."""
    return np.stack([np.ones_like(L), L, P, H, L * P, L * H, P * H, L * L, P * P, H * H,
                     L * P * H, L * L * L, L * P * P, L * H * H, L * L * P, P * P * P,
                     P * H * H, L * L * H, P * P * H, H * H * H])


# The packed RPC the compiled code reads (RPCModel._packed): 10 scalars, then 4 x 20
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
        self.offsets = _rpc_numbers(offsets, "offsets")
        self.scales = _rpc_numbers(scales, "scales")
        zero = [kind for kind, value in self.scales.items() if value == 0]
        if zero:
            raise ModelError(_("scales {zero} are 0; an RPC divides by its scales, so every "
                               "scale must be a nonzero number").format(zero=", ".join(zero)))
        coefficients = []
        for name, values in zip(("line_num", "line_den", "samp_num", "samp_den"),
                                (line_num, line_den, samp_num, samp_den)):
            array = as_finite(values, name, error=ModelError)
            if array.shape != (20,):
                raise ModelError(_("{name} must be the 20 coefficients of an RPC00B cubic, in "
                                   "GDAL's term order (RPC_TERMS), got shape {shape}").format(
                                       name=name, shape=array.shape))
            coefficients.append(array.copy())
        for name, array in (("line_den", coefficients[1]), ("samp_den", coefficients[3])):
            if not array.any():
                raise ModelError(_("{name} is all zeros; a denominator needs a nonzero "
                                   "coefficient (usually its first, 1)").format(name=name))
        self.line_num, self.line_den, self.samp_num, self.samp_den = coefficients
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
            [-360, 360], or a value is not finite.
        """
        lon, lat, height = as_lon_lat_height(lon, lat, height, west=-360.0)
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
            [-360, 360], or a value is not finite.

        Examples
        --------
        >>> rpc = RPCModel.from_dict(simple_rpc_dict())
        >>> col, row = rpc.project(-34.9, -8.0, 0.0)
        >>> float(col), float(row)
        (500.5, 500.5)
        """
        # RPCTransformPoint folds a longitude 270 degrees or more from LONG_OFF by 360, so an
        # RPC over the antimeridian sees ground a little west of -180 (GDAL autotest
        # transformer.py, test_transformer_15)
        lon, lat, height = as_lon_lat_height(lon, lat, height, west=-360.0)
        shape = lon.shape
        cols, rows = np.empty(lon.size), np.empty(lon.size)
        # one compiled pass, point by point (no array per term), GDAL's operations in order
        project_points(self._packed(), np.ravel(lon), np.ravel(lat), np.ravel(height), cols,
                        rows)
        if not shape:
            return cols[0], rows[0]           # NumPy scalars for scalars, as before
        return cols.reshape(shape), rows.reshape(shape)

    def _packed(self):
        """The model as the float64 array that the compiled code reads (RPC_PACKED_SIZE)."""
        scalars = [(self.offsets if part == "OFF" else self.scales)[kind]
                   for kind, part in PACKED_SCALARS]
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
        col, row, height = as_broadcast(
            [as_finite(col, "col"), as_finite(row, "row"), as_finite(height, "height")],
            ["col", "row", "height"])
        if as_number(tolerance, "tolerance") <= 0:
            raise RsgeoError(_("tolerance must be > 0 pixels, got {tolerance!r}").format(
                    tolerance=tolerance))
        max_iterations = as_integer(max_iterations, "max_iterations", low=0)
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
            # longitude free to cross the antimeridian, as in GDAL's inverse (RPCInverseTransform)
            lon = np.clip(lon - (d * dc - b * dr) / det, -360.0, 360.0)
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


_RPC_KINDS = ("LINE", "SAMP", "LAT", "LONG", "HEIGHT")


def _rpc_numbers(values, name):
    """An RPC's offsets or scales: one finite number for each of its five coordinates."""
    if not hasattr(values, "items"):
        raise TypeError(_("{name} must be a dict with keys {keys}, got {kind}").format(
            name=name, keys=", ".join(_RPC_KINDS), kind=type(values).__name__))
    values = {str(key).upper(): value for key, value in values.items()}
    missing = [kind for kind in _RPC_KINDS if kind not in values]
    if missing:
        raise ModelError(_("{name} lacks {missing}; an RPC needs {keys}").format(
            name=name, missing=", ".join(missing), keys=", ".join(_RPC_KINDS)))
    return {kind: as_number(values[kind], f"{name}[{kind!r}]") for kind in _RPC_KINDS}


#: Largest |normalised longitude or latitude| of a GCP that refine_rpc takes: an RPC is fitted
#: over its normalised cube [-1, 1] (the scene, with a margin), and its cubic ratios are
#: meaningless far outside it; a GCP beyond 1.5 is not in the scene (or its lon and lat are
#: swapped, or it is in projected metres).
RPC_CUBE_LIMIT = 1.5


def _check_in_cube(rpc, lon, lat, height):
    """Refuse GCPs far outside the RPC's normalised cube, naming a lon/lat swap when it fits."""
    L, P, _H = rpc.normalise(lon, lat, height)
    outside = (np.abs(L) > RPC_CUBE_LIMIT) | (np.abs(P) > RPC_CUBE_LIMIT)
    if not outside.any():
        return
    swapped_L, swapped_P = (np.abs(lat - rpc.offsets["LONG"]) / abs(rpc.scales["LONG"]),
                            np.abs(lon - rpc.offsets["LAT"]) / abs(rpc.scales["LAT"]))
    swap = bool(((swapped_L <= RPC_CUBE_LIMIT) & (swapped_P <= RPC_CUBE_LIMIT))[outside].all())
    rows = np.flatnonzero(outside)
    raise GCPError(_(
        "GCPs {rows} lie far outside the scene the RPC describes: normalised longitude "
        "{L} and latitude {P}, where the RPC holds within [-1, 1] and rsgeo takes up to "
        "+/-{limit:g} (the RPC's centre is lon {lon0:.6g}, lat {lat0:.6g}){hint}").format(
            rows=rows[:5].tolist(), L=few_values(L[rows]), P=few_values(P[rows]),
            limit=RPC_CUBE_LIMIT, lon0=rpc.offsets["LONG"], lat0=rpc.offsets["LAT"],
            hint=_("; longitude and latitude look swapped: give lon first, then lat")
            if swap else _("; check that lon and lat are degrees (WGS 84) of points in the "
                           "image")))


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
    lon, lat, height = (np.ravel(a) for a in as_lon_lat_height(lon, lat, height))
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
        if getattr(np.asarray(values), "dtype", np.dtype("O")).kind in "bcUS":
            raise TypeError(_("gcps[{key!r}] must be numbers, got {values!r}").format(
                key=key, values=values))
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
    :func:`~rsgeo.ortho.orthorectify` or GDAL.

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
        col, row = as_broadcast([as_finite(col, "col"), as_finite(row, "row")],
                                ["col", "row"])
        p = self.parameters
        a, b, c, d = 1 + p["a1"], p["a2"], p["b1"], 1 + p["b2"]
        det = a * d - b * c
        u, v = col - p["a0"], row - p["b0"]
        return self.rpc.localize((d * u - b * v) / det, (a * v - c * u) / det, height,
                                 tolerance, max_iterations)

    def to_rpc(self, n=11):
        """The compensated model as a plain :class:`RPCModel` (for GDAL, and for
        :func:`~rsgeo.ortho.orthorectify`).

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
    _check_in_cube(rpc, lon, lat, height)
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


