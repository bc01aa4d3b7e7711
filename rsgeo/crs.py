"""Coordinate reference systems and datum shifts, through PROJ.

Map coordinates only mean something with their CRS: the CBERS scenes shipped
with rsgeo are in SAD69 / UTM, Brazil's datum since 2015 is SIRGAS 2000, and the
same point has UTM coordinates tens of metres apart in the two. This module
moves points and rasters between CRSs through PROJ (pyproj, with the datum grids
rsgeo ships on its search path and the network off: IBGE's SAD69 and SAD69(96)
grids), names the transformation PROJ applied, and reads a shift grid itself to check
PROJ. Rasters are reprojected and georeferenced by :func:`rsgeo.resample.reproject` and
:func:`rsgeo.resample.georeference`.

Examples
--------
>>> from rsgeo import crs
>>> x, y = crs.transform_points([[500000.0, 7400000.0]], "EPSG:29193", "EPSG:31983")[0]
>>> 30 < float(np.hypot(x - 500000.0, y - 7400000.0)) < 80     # SAD69 -> SIRGAS 2000
True
"""

import os
import re
import warnings
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from . import _proj
from .errors import CRSError, DataError, GridError
from .language import _
from .validation import as_crs, as_points

__all__ = ["as_crs", "transform_points", "datum_shift", "DatumShift", "transformations",
           "Transformation", "transformation_at", "SHIFT_GRIDS", "ShiftGrid", "read_shift_grid",
           "grid_shift", "geocentric_translation"]

def _network_hint():
    """A sentence naming PROJ_NETWORK when it is on: PROJ then fetches grids it lacks, and a
    grid it could not fetch gives no number (inf or nan)."""
    import pyproj.network

    if pyproj.network.is_network_enabled() or str(
            os.environ.get("PROJ_NETWORK", "")).upper() in ("ON", "YES", "TRUE", "1"):
        return _(" PROJ_NETWORK is ON: PROJ fetches the grids it lacks from the network, and "
                 "a grid it could not fetch gives no number; turn PROJ_NETWORK off (rsgeo "
                 "ships its grids) or install the grids PROJ needs (projsync).")
    return ""


# EPSG:15485, "SAD69 to SIRGAS 2000 (1)": geocentric translations in metres (accuracy 5 m)
SAD69_TO_SIRGAS2000 = (-67.35, 3.88, -38.22)


# No position on Earth has a coordinate 25 times the Earth's circumference (1e9 m) or 25 turns
# (9,000°) from its CRS's origin; PROJ wraps longitudes by a loop whose time grows with the value
# (a point at x = 1e18 m in EPSG:3857 takes minutes), so larger coordinates never reach PROJ.
_FARTHEST_METRES = 1e9
_FARTHEST_RADIANS = 50 * np.pi


def _refuse_far_coordinates(points, crs):
    """Refuse (n, 2) finite points with a coordinate no position on Earth has in ``crs``."""
    kind, unit, factor = _kind_and_unit(crs)
    farthest = _FARTHEST_RADIANS if kind == "geographic" else _FARTHEST_METRES
    limit = farthest / factor if np.isfinite(factor) and factor > 0 else _FARTHEST_METRES
    far = (np.abs(points) > limit).any(axis=1)
    if far.any():
        first = int(np.flatnonzero(far)[0])
        raise CRSError(_(
            "{count} of {n} points have a coordinate that no position on Earth has in {crs} "
            "(first: point {first} ({x:.6g}, {y:.6g}); its coordinates stay within ±{limit:.6g} "
            "{unit}, 25 times around the Earth): PROJ is not asked, it can take minutes on such "
            "values; give points in the CRS's own coordinates and units").format(
                count=int(far.sum()), n=len(points), crs=_crs_name(crs), first=first,
                x=points[first, 0], y=points[first, 1], limit=limit, unit=unit))


def _area_of_use(crs):
    """PROJ's area of use of ``crs``: (west, south, east, north) in degrees, or None.

    Read from the CRS's WKT2 ``USAGE[... BBOX[south, west, north, east]]``, which
    PROJ fills from its database (EPSG's area of use); a CRS read from a file
    carries no usage, so its EPSG code (if PROJ identifies one) is looked up.
    """
    from rasterio.crs import CRS
    from rasterio.errors import CRSError as RasterioCRSError

    def boxes(value):
        return re.findall(r"BBOX\[([-+.\deE]+),([-+.\deE]+),([-+.\deE]+),([-+.\deE]+)\]",
                          value.to_wkt(version="WKT2_2019"))

    try:
        found = boxes(crs)
        if not found:
            code = crs.to_epsg()
            found = boxes(CRS.from_epsg(code)) if code else []
    except RasterioCRSError:
        return None
    if not found:
        return None
    south, west, north, east = (float(v) for v in found[-1])
    return west, south, east, north


def _outside_area(lon, lat, area):
    """Mask of the points (degrees) outside an area of use; NaN and inf are outside."""
    west, south, east, north = area
    inside_lon = ((lon >= west) & (lon <= east) if west <= east
                  else (lon >= west) | (lon <= east))          # an area across 180°
    return ~(inside_lon & (lat >= south) & (lat <= north))


def _check_area(points, src, dst):
    """Refuse points outside the area of use of ``src`` or of ``dst`` (PROJ's, in degrees)."""
    areas = [(crs, _area_of_use(crs)) for crs in (src, dst)]
    areas = [(crs, area) for crs, area in areas if area is not None]
    if not areas:
        return
    lon, lat = _lon_lat(points, src)
    for crs, area in areas:
        outside = _outside_area(lon, lat, area)
        if outside.any():
            first = int(np.flatnonzero(outside)[0])
            if not (np.isfinite(lon[first]) and np.isfinite(lat[first])):
                raise CRSError(_(
                    "PROJ gave no longitude and latitude (inf or nan) for point {first} "
                    "({x:.6g}, {y:.6g}) in {src}, so rsgeo cannot check it against the CRSs' "
                    "areas of use; give points in src_crs's own coordinates and units.").format(
                        first=first, x=points[first, 0], y=points[first, 1],
                        src=_crs_name(src)) + _network_hint())
            raise CRSError(_(
                "{count} of {n} points are outside the area of use of {crs} (longitude "
                "{west:g} to {east:g}, latitude {south:g} to {north:g}; first: point {first} "
                "({x:.6g}, {y:.6g}) in {src}, at longitude {lon:.4f}, latitude {lat:.4f}): "
                "PROJ's answer there is not a position; give points in src_crs's own "
                "coordinates and units (longitude and latitude typed into a projected CRS?), "
                "or CRSs whose area covers them").format(
                    count=int(outside.sum()), n=len(points), crs=_crs_name(crs),
                    west=area[0], east=area[2], south=area[1], north=area[3], first=first,
                    x=points[first, 0], y=points[first, 1], src=_crs_name(src),
                    lon=lon[first], lat=lat[first]))


def _lon_lat(points, crs):
    """Longitude, latitude (EPSG:4326) of points in ``crs``; NaN where PROJ cannot say."""
    from rasterio.warp import transform

    _refuse_far_coordinates(points, crs)
    try:
        with np.errstate(all="ignore"):
            lon, lat = (np.asarray(v, dtype=np.float64)
                        for v in transform(crs, "EPSG:4326", points[:, 0], points[:, 1]))
    except Exception:                  # GDAL refuses the batch: point by point, failures NaN
        lon, lat = np.full(len(points), np.nan), np.full(len(points), np.nan)
        for k, (x, y) in enumerate(points):
            try:
                with np.errstate(all="ignore"):
                    (lon[k],), (lat[k],) = transform(crs, "EPSG:4326", [x], [y])
            except Exception:
                pass
    lost = ~(np.isfinite(lon) & np.isfinite(lat))
    if lost.any():
        # GDAL's PROJ gives no number where it wanted a grid it could not fetch (PROJ_NETWORK
        # on, no network): rsgeo's own PROJ, offline with its grids, is asked there
        try:
            with np.errstate(all="ignore"):
                again = _proj.transformer(_wkt(crs), _wkt(as_crs("EPSG:4326"))).transform(
                    points[lost, 0], points[lost, 1])
            lon[lost], lat[lost] = (np.asarray(v, dtype=np.float64) for v in again)
        except Exception:              # pyproj's ProjError: left NaN, refused by the caller
            pass
    return lon, lat


# PROJ parameters of the datum, not of the projection (a datum shift changes only these)
_DATUM_KEYS = {"ellps", "datum", "towgs84", "nadgrids", "a", "b", "rf", "f", "R", "pm",
               "no_defs", "wktext", "type", "units", "to_meter"}


def _projection(crs):
    """The projection of ``crs`` without its datum: PROJ's parameters (proj, zone, lon_0 ...)."""
    return {key: value for key, value in crs.to_dict().items() if key not in _DATUM_KEYS}


def _crs_name(crs):
    """'EPSG:31983' when PROJ identifies a code, else the CRS's name."""
    code = crs.to_epsg()
    if code:
        return f"EPSG:{code}"
    match = re.match(r'\w+\["([^"]*)"', crs.to_wkt())
    return match.group(1) if match else crs.to_string()[:60]


def _kind_and_unit(crs):
    """("geographic" or "projected" or another kind, unit name, metres or radians per unit)."""
    kind = ("geographic" if crs.is_geographic else "projected" if crs.is_projected
            else "other")
    try:
        unit, factor = crs.units_factor
    except Exception:                 # rasterio's CRSError for a CRS without one unit
        unit, factor = "unknown", float("nan")
    return kind, unit, factor


# -- Datum transformations: PROJ (pyproj) with the grids rsgeo ships --------------------------

class Transformation(NamedTuple):  # numpydoc ignore=PR02
    """A coordinate operation PROJ knows between two CRSs, as rsgeo names it.

    Parameters
    ----------
    name : str
        The datum steps' names in PROJ's database, e.g. "SAD69 to SIRGAS 2000 (2)"
        ("Inverse of ..." when PROJ runs one backwards; several joined by " + ").
    codes : tuple of str
        Their registry codes, e.g. ``("EPSG:5528",)``; empty for PROJ's "ballpark" offset,
        which is no published transformation.
    accuracy : float or None
        The accuracy the registry states, in metres; None when it states none.
    grids : tuple of str
        The grid files it needs (``"br_ibge_SAD69_003.tif"``); empty for parameters.
    available : bool
        Whether PROJ finds every grid here (rsgeo's shipped grids, PROJ's own folder).
    area : tuple or None
        Its area of use as PROJ checks it, a box (west, south, east, north) in degrees.
    pipeline : str
        The whole operation as a PROJ string, shipped grids by their absolute path: give it
        to GDAL as ``gdalwarp -ct "..."`` or the warp option ``COORDINATE_OPERATION`` to make
        GDAL apply the same operation.
    """

    name: str
    codes: tuple
    accuracy: float | None
    grids: tuple
    available: bool
    area: tuple | None
    pipeline: str

    def __str__(self):
        code = " + ".join(self.codes) or _("no registry code")
        accuracy = (_("accuracy unknown") if self.accuracy is None
                    else _("accuracy {metres:g} m").format(metres=self.accuracy))
        grids = (_(", grid {grids}").format(grids=", ".join(self.grids)) if self.grids
                 else "")
        return f"{self.name} ({code}; {accuracy}{grids})"


def _wkt(crs):
    """A rasterio CRS as WKT2, which keeps its EPSG identity for pyproj's PROJ."""
    return crs.to_wkt(version="WKT2_2019")


def _authority_code(identifier):
    """'EPSG:5528' from PROJ's id {'authority': 'INVERSE(DERIVED_FROM(EPSG))', 'code': 5528}."""
    if not identifier:
        return None
    authority = str(identifier.get("authority", ""))
    while (inner := re.fullmatch(r"[A-Z_]+\((.*)\)", authority)) is not None:
        authority = inner.group(1)          # INVERSE(...) and DERIVED_FROM(...) name the source
    return f"{authority}:{identifier.get('code')}"


def _describe(operation, available=True):
    """A :class:`Transformation` from a pyproj Transformer or CoordinateOperation."""
    steps = list(operation.operations or []) or [operation]
    datum_steps = [step for step in steps
                   if step.to_json_dict().get("type") != "Conversion"] or steps
    names = [step.name for step in datum_steps]
    codes = tuple(code for code in (_authority_code(step.to_json_dict().get("id"))
                                    for step in datum_steps) if code is not None)
    found = [grid for step in steps for grid in getattr(step, "grids", [])]
    # the shipped grids an operation built by rsgeo._proj reads by their path
    by_path = getattr(operation, "grid_paths", {})
    grids = tuple(dict.fromkeys(os.path.basename(grid.short_name) for grid in found))
    try:
        pipeline = operation.to_proj4() or ""
    except Exception:                 # pyproj's ProjError: an operation PROJ cannot write
        pipeline = ""
    for grid in found:
        if grid.available and grid.full_name:
            pipeline = pipeline.replace(f"={grid.short_name}", f"={grid.full_name}")
        elif grid.short_name in by_path:
            pipeline = pipeline.replace(f"={grid.short_name}", f"={by_path[grid.short_name]}")
    accuracy = float(operation.accuracy)
    box = operation.area_of_use
    area = None if box is None else (box.west, box.south, box.east, box.north)
    return Transformation(" + ".join(names), codes, accuracy if accuracy >= 0 else None, grids,
                          bool(available and all(grid.available or grid.short_name in by_path
                                                  for grid in found)), area,
                          pipeline)


@lru_cache(maxsize=64)
def _candidates(src_wkt, dst_wkt):
    """PROJ's operations between two CRSs: ([(Transformation, Transformer)] available, most
    accurate first, unknown accuracy last; [Transformation] whose grids are missing)."""
    try:
        group = _proj.operations(src_wkt, dst_wkt)
    except Exception as error:        # pyproj's ProjError
        raise CRSError(_("PROJ knows no operation between these CRSs ({error})").format(
            error=error)) from None
    usable = [(_describe(transformer), transformer) for transformer in group.transformers]
    usable.sort(key=lambda pair: (pair[0].accuracy is None, pair[0].accuracy or 0.0))
    missing = [_describe(operation, available=False)
               for operation in group.unavailable_operations]
    return usable, missing


def transformations(src_crs, dst_crs):
    """Every operation PROJ knows from ``src_crs`` to ``dst_crs``, most accurate first.

    PROJ's database (the EPSG registry's transformations and PROJ's own) searched with the
    grids rsgeo ships (``rsgeo/data/README.md``) and without the network: those whose grids
    are here first, by their stated accuracy, then those whose grids are not.

    Parameters
    ----------
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        See :func:`as_crs`.

    Returns
    -------
    list of Transformation
        Name, registry codes, stated accuracy (m), grid files, available here or not, and
        the PROJ pipeline; ``pandas.DataFrame(transformations(...))`` makes a table.

    Raises
    ------
    ValueError
        For a CRS that PROJ does not know.

    Examples
    --------
    >>> [t.codes for t in transformations("EPSG:4618", "EPSG:4674")][:2]    # SAD69 -> SIRGAS
    [('EPSG:5528',), ('EPSG:15485',)]
    >>> transformations("EPSG:4618", "EPSG:4674")[0].grids
    ('br_ibge_SAD69_003.tif',)
    """
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    usable, missing = _candidates(_wkt(src), _wkt(dst))
    missing = sorted(missing, key=lambda t: (t.accuracy is None, t.accuracy or 0.0))
    return [described for described, _transformer in usable] + missing


def _requested_codes(transformation):
    """The set of registry codes a ``transformation`` argument names."""
    if isinstance(transformation, Transformation):
        return frozenset(transformation.codes)
    items = ([transformation] if isinstance(transformation, (str, int, np.integer))
             else transformation)
    try:
        items = list(items)
    except TypeError:
        raise TypeError(_("transformation must be a code such as 'EPSG:15485', a sequence of "
                          "codes or a Transformation from georef.transformations, got "
                          "{kind}").format(kind=type(transformation).__name__)) from None
    codes = set()
    for item in items:
        if isinstance(item, (int, np.integer)) and not isinstance(item, bool):
            codes.add(f"EPSG:{int(item)}")
        elif isinstance(item, str) and (match := re.fullmatch(r"\s*([A-Za-z_]+):(\d+)\s*",
                                                              item)):
            codes.add(f"{match.group(1).upper()}:{int(match.group(2))}")
        else:
            raise CRSError(_("transformation {item!r} is not a registry code; give one such as "
                             "'EPSG:15485' (see georef.transformations)").format(item=item))
    if not codes:
        raise CRSError(_("transformation names no code; give one such as 'EPSG:15485'"))
    return frozenset(codes)


def _forced(src, dst, transformation):
    """(Transformation, pyproj Transformer) of the operation ``transformation`` names."""
    wanted = _requested_codes(transformation)
    usable, missing = _candidates(_wkt(src), _wkt(dst))
    for described, transformer in usable:
        if frozenset(described.codes) == wanted:
            return described, transformer
    for described in missing:
        if frozenset(described.codes) == wanted:
            raise CRSError(_(
                "{name} ({codes}) needs the grid {grids}, which PROJ does not find here; "
                "rsgeo ships {shipped}, and downloads nothing").format(
                    name=described.name, codes=" + ".join(described.codes),
                    grids=", ".join(described.grids),
                    shipped=", ".join(sorted(path.name for path in _proj.GRIDS.glob("*")))))
    known = "; ".join(f"{' + '.join(t.codes) or '-'} {t.name}"
                      for t in [d for d, _t in usable] + missing)
    raise CRSError(_(
        "PROJ knows no operation {wanted} from {src} to {dst}; it knows: {known}").format(
            wanted=" + ".join(sorted(wanted)), src=_crs_name(src), dst=_crs_name(dst),
            known=known or _("none")))


def _check_operation_area(points, src, described):
    """Refuse points outside the area of use of a transformation asked for by name."""
    if described.area is None:
        return
    lon, lat = _lon_lat(points, src)
    outside = _outside_area(lon, lat, described.area)
    if outside.any():
        first = int(np.flatnonzero(outside)[0])
        raise CRSError(_(
            "{count} of {n} points are outside the area of use of {name} ({codes}: longitude "
            "{west:g} to {east:g}, latitude {south:g} to {north:g}; first: point {first} at "
            "longitude {lon:.4f}, latitude {lat:.4f}); leave transformation=None for PROJ's "
            "choice there, or give points inside it").format(
                count=int(outside.sum()), n=len(points), name=described.name,
                codes=" + ".join(described.codes) or "-", west=described.area[0],
                east=described.area[2], south=described.area[1], north=described.area[3],
                first=first, lon=lon[first], lat=lat[first]))


def _apply(transformer, points, src, dst):
    """(n, 2) points through a pyproj Transformer; a CRSError where PROJ gives no number."""
    if not len(points):
        return points.copy()
    try:
        with np.errstate(all="ignore"):
            xs, ys = transformer.transform(points[:, 0], points[:, 1])
    except Exception as error:        # pyproj's ProjError
        raise CRSError(_("PROJ could not transform the points from {src} to {dst} ({error}); "
                         "give points inside both CRSs' areas of use").format(
                             src=_crs_name(src), dst=_crs_name(dst), error=error)) from None
    result = np.column_stack([xs, ys]).astype(np.float64)
    if not np.isfinite(result).all():
        raise CRSError(_("PROJ could not transform some points from {src} to {dst} "
                         "(outside the CRS's area of use, or outside a grid's coverage?)").format(
                             src=_crs_name(src), dst=_crs_name(dst)) + _network_hint())
    return result


def _transform(points, src, dst, transformation=None):
    """PROJ's transformation of finite (n, 2) points between two checked CRSs, unchecked area.

    PROJ picks, point by point, the most accurate operation whose area of use holds the point
    and whose grids it finds (``transformation=None``), as ``gdalwarp`` does with the same
    grids; or applies the one ``transformation`` names.
    """
    if src == dst:
        return points.copy()
    _refuse_far_coordinates(points, src)
    if transformation is not None:
        return _apply(_forced(src, dst, transformation)[1], points, src, dst)
    try:
        transformer = _proj.transformer(_wkt(src), _wkt(dst))
    except Exception as error:        # pyproj's ProjError
        raise CRSError(_("PROJ could not transform the points from {src} to {dst} ({error}); "
                         "give points inside both CRSs' areas of use").format(
                             src=_crs_name(src), dst=_crs_name(dst), error=error)) from None
    return _apply(transformer, points, src, dst)


def _used_operations(points, moved, src, dst):
    """Which operation PROJ applied at each point: (Transformations, (n,) index into them).

    Each operation PROJ could have picked is run on the points, most accurate first; a point
    is named by the first whose result is PROJ's (the same pipeline gives the same numbers).
    A point none reproduces is asked of PROJ itself, one by one.
    """
    usable, _missing = _candidates(_wkt(src), _wkt(dst))
    used = np.full(len(points), -1)
    for index, (_described, transformer) in enumerate(usable):
        todo = np.flatnonzero(used < 0)
        if not len(todo):
            break
        with np.errstate(all="ignore"):
            xs, ys = transformer.transform(points[todo, 0], points[todo, 1])
        same = np.isclose(np.column_stack([xs, ys]), moved[todo], rtol=1e-12,
                          atol=1e-9).all(axis=1)
        used[todo[same]] = index
    found = [described for described, _transformer in usable]
    if (used < 0).any():
        transformer = _proj.transformer(_wkt(src), _wkt(dst))
        for k in np.flatnonzero(used < 0):
            transformer.transform(points[k, 0], points[k, 1])
            described = _describe(transformer.get_last_used_operation())
            if described not in found:
                found.append(described)
            used[k] = found.index(described)
    kept = sorted(set(used.tolist()))
    return tuple(found[k] for k in kept), np.searchsorted(kept, used)


class DatumShift(tuple):
    """How far points move between two datums, and the transformation that moved them.

    A tuple ``(dx, dy, distance)``, so that ``dx, dy, distance = datum_shift(...)`` works, with
    more attributes than items (as ``os.stat_result`` has): ``dx``, ``dy`` and ``distance``
    per point in the CRSs' units (metres for UTM), and ``transformation``, the operation PROJ
    applied (at most points, when it needed several; None for no points or two equal CRSs).

    Attributes
    ----------
    transformations : tuple of Transformation
        Every operation applied, most points first.
    used : ndarray of int
        Per point, its operation's index in ``transformations``.
    """

    def __new__(cls, dx, dy, distance, transformations=(), used=None):
        shift = super().__new__(cls, (dx, dy, distance))
        shift.transformations = tuple(transformations)
        shift.used = (np.zeros(len(dx), dtype=np.intp) if used is None
                      else np.asarray(used, dtype=np.intp))
        return shift

    def __getnewargs__(self):
        return (*self, self.transformations, self.used)

    dx = property(lambda self: self[0], doc="Easting (or longitude) change per point.")
    dy = property(lambda self: self[1], doc="Northing (or latitude) change per point.")
    distance = property(lambda self: self[2], doc="sqrt(dx² + dy²) per point.")

    @property
    def transformation(self):
        """The operation applied at most points.

        Returns
        -------
        Transformation or None
            None for no points or two equal CRSs.
        """
        return self.transformations[0] if self.transformations else None

    def __repr__(self):
        if not self.transformations:
            named = "none"
        elif len(self.transformations) == 1:
            named = str(self.transformation)
        else:
            counts = np.bincount(self.used, minlength=len(self.transformations))
            named = "; ".join(f"{t} at {c} points"
                              for t, c in zip(self.transformations, counts))
        return (f"DatumShift({len(self.dx)} points, mean distance "
                f"{float(np.mean(self.distance)) if len(self.dx) else 0.0:.4g}; "
                f"transformation: {named})")


def transform_points(points, src_crs, dst_crs, check_area=True, transformation=None):
    """Map coordinates (x, y) moved from one CRS to another by PROJ.

    PROJ picks, point by point, the most accurate transformation (datum shift) whose area of
    use holds the point and whose grids it finds: rsgeo puts its shipped grids on PROJ's
    search path (offline: nothing is downloaded), so SAD69 -> SIRGAS 2000 is IBGE's grid
    (EPSG:5528, accuracy 1 m) inside its area and EPSG:15485 (three geocentric translations,
    5 m) elsewhere in Brazil. :func:`datum_shift` names the one used;
    :func:`transformations` lists what PROJ knows.

    Parameters
    ----------
    points : (n, 2) array_like
        Easting, northing (or longitude, latitude) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        See :func:`as_crs`.
    check_area : bool
        Refuse points outside the area of use (PROJ's, from the EPSG
        database) of ``src_crs`` or ``dst_crs``: there PROJ still returns
        numbers, but they are not the points' positions (longitude and
        latitude typed into a UTM CRS move 42.8 m from SAD69 to SIRGAS 2000).
        False transforms them as ``gdalwarp`` does, without a word.
    transformation : str, int, sequence or Transformation, optional
        Apply this operation instead of PROJ's choice, to compare: a registry code
        (``"EPSG:15485"``, ``15485``), the codes of a chain (``("EPSG:5528", "EPSG:5529")``),
        or an item of :func:`transformations`. With ``check_area``, points outside its own
        area of use are refused too.

    Returns
    -------
    ndarray
        (n, 2) float64 in ``dst_crs``.

    Raises
    ------
    ValueError
        For a CRS that PROJ does not know, points that are not (n, 2) finite,
        a coordinate no position on Earth has (beyond 1e9 m, or 9,000° in a
        geographic CRS: refused whatever ``check_area``, before PROJ sees it),
        (``check_area``) points outside a CRS's area of use, a transformation
        PROJ does not know between the CRSs or whose grid is missing, or points
        where PROJ gives no number (outside a grid).

    Examples
    --------
    >>> transform_points([[0.0, 0.0]], "EPSG:4326", "EPSG:4326")
    array([[0., 0.]])
    >>> p = [[775445.0, 7369105.0]]                     # a GCP in SAD69 / UTM 21S
    >>> grid = transform_points(p, "EPSG:29191", "EPSG:31981")
    >>> three = transform_points(p, "EPSG:29191", "EPSG:31981", transformation="EPSG:15485")
    >>> bool(1 < np.hypot(*(grid - three)[0]) < 10)      # metres between the two
    True
    """
    points = as_points(points, "points")
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    if check_area:
        _check_area(points, src, dst)
    if transformation is not None and src != dst:
        described, _transformer = _forced(src, dst, transformation)
        if check_area:
            _check_operation_area(points, src, described)
    return _transform(points, src, dst, transformation)


def datum_shift(points, src_crs, dst_crs, transformation=None):
    """How far each point's coordinates move from ``src_crs`` to ``dst_crs``, and by what.

    A shift is a difference of coordinates, so the two CRSs must be alike:
    the same projection in the same unit on two datums (SAD69 / UTM 21S and
    SIRGAS 2000 / UTM 21S), or both geographic; and the points must be inside both CRSs' areas of
    use (:func:`transform_points`). The result names the transformation PROJ applied.

    Parameters
    ----------
    points : (n, 2) array_like
        Map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        Two projected CRSs with the same units (e.g. SAD69 / UTM 21S and
        SIRGAS 2000 / UTM 21S), or two geographic CRSs.
    transformation : str, int, sequence or Transformation, optional
        The operation to apply instead of PROJ's choice, e.g. ``"EPSG:15485"`` to compare the
        three-parameter shift with the grid (see :func:`transform_points`).

    Returns
    -------
    DatumShift
        ``dx, dy, distance`` per point in the CRSs' units (metres for UTM), as a tuple that
        unpacks so; ``.transformation`` is the operation applied (name, EPSG codes, stated
        accuracy, grids), ``.transformations`` and ``.used`` say which point got which when
        PROJ needed more than one (points outside a grid's coverage).

    Raises
    ------
    ValueError
        As :func:`transform_points`; if one CRS is geographic and the other
        projected, their units differ (EPSG:4326 -> 31983 is a projection,
        not a shift), or their projections differ (UTM zones 22S and 23S,
        UTM and Web Mercator).

    Warns
    -----
    UserWarning
        When PROJ knew no transformation for some points and applied its "ballpark" offset
        (the ellipsoid change alone): the shift is not a datum shift there.

    Examples
    --------
    >>> shift = datum_shift([[775445.0, 7369105.0]], "EPSG:29191", "EPSG:31981")
    >>> dx, dy, distance = shift
    >>> bool(dx[0] < 0 and dy[0] < 0), shift.transformation.codes
    (True, ('EPSG:5528',))
    """
    points = as_points(points, "points")
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    (src_kind, src_unit, src_factor), (dst_kind, dst_unit, dst_factor) = (
        _kind_and_unit(src), _kind_and_unit(dst))
    if src_kind != dst_kind or src_kind == "other" or not np.isclose(src_factor, dst_factor,
                                                                     rtol=1e-12, atol=0):
        raise CRSError(_(
            "a datum shift needs two CRSs of the same kind and unit, got src_crs {src} "
            "({src_kind}, {src_unit}) and dst_crs {dst} ({dst_kind}, {dst_unit}): the "
            "difference of their coordinates is not a distance; give two projected CRSs in "
            "the same unit (e.g. EPSG:29193 and EPSG:31983) or two geographic CRSs, or use "
            "transform_points to convert between kinds").format(
                src=_crs_name(src), src_kind=src_kind, src_unit=src_unit, dst=_crs_name(dst),
                dst_kind=dst_kind, dst_unit=dst_unit))
    if _projection(src) != _projection(dst):
        raise CRSError(_(
            "a datum shift compares one projection on two datums, but src_crs {src} and dst_crs "
            "{dst} are different projections ({src_projection} and {dst_projection}): the "
            "difference of their coordinates is mostly the projection's; give the same "
            "projection (e.g. UTM zone 23S: EPSG:29193 and EPSG:31983), or use transform_points "
            "to change projection").format(
                src=_crs_name(src), dst=_crs_name(dst), src_projection=_proj_text(src),
                dst_projection=_proj_text(dst)))
    moved = transform_points(points, src, dst, transformation=transformation)
    dx, dy = (moved - points).T
    if src == dst or not len(points):
        return DatumShift(dx, dy, np.hypot(dx, dy))
    if transformation is not None:
        return DatumShift(dx, dy, np.hypot(dx, dy), [_forced(src, dst, transformation)[0]])
    found, used = _used_operations(points, moved, src, dst)
    order = np.argsort(-np.bincount(used, minlength=len(found)), kind="stable")
    found, used = tuple(found[k] for k in order), np.argsort(order)[used]
    ballpark = [t for t in found if not t.codes]
    if ballpark:
        warnings.warn(_(
            "PROJ knows no datum transformation from {src} to {dst} at {count} of {n} points "
            "and applied {name}: the ellipsoid change alone, not a datum shift; give points "
            "where a published transformation applies").format(
                src=_crs_name(src), dst=_crs_name(dst), name=ballpark[0].name, n=len(points),
                count=int(np.isin(used, [found.index(t) for t in ballpark]).sum())),
            UserWarning, stacklevel=2)
    return DatumShift(dx, dy, np.hypot(dx, dy), found, used)


def _proj_text(crs):
    """A CRS's projection as PROJ parameters, e.g. "+proj=utm +zone=23 +south"."""
    return " ".join(f"+{key}" if value is True else f"+{key}={value}"
                    for key, value in _projection(crs).items())


def _geographic(crs):
    """(geographic CRS, semi-major axis, flattening) of a CRS's datum, from its WKT1."""
    from rasterio.crs import CRS

    wkt = crs.to_wkt()
    start = wkt.find("GEOGCS[")
    depth, end = 0, start
    for end in range(start, len(wkt)):
        depth += {"[": 1, "]": -1}.get(wkt[end], 0)
        if depth == 0 and wkt[end] == "]":
            break
    geogcs = wkt[start:end + 1]
    spheroid = re.search(r'SPHEROID\["[^"]*",([-+.\deE]+),([-+.\deE]+)', geogcs)
    if start < 0 or spheroid is None:
        raise CRSError(_("cannot find the datum's ellipsoid in {crs}").format(crs=crs))
    inverse_flattening = float(spheroid.group(2))
    return (CRS.from_wkt(geogcs), float(spheroid.group(1)),
            1 / inverse_flattening if inverse_flattening else 0.0)


def _to_geocentric(lon, lat, a, f):
    """Longitude, latitude (degrees, height 0) -> Earth-centred X, Y, Z on an ellipsoid."""
    lon, lat = np.radians(lon), np.radians(lat)
    e2 = f * (2 - f)
    n = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
    return (n * np.cos(lat) * np.cos(lon), n * np.cos(lat) * np.sin(lon),
            n * (1 - e2) * np.sin(lat))


def _to_geographic(x, y, z, a, f):
    """Earth-centred X, Y, Z -> longitude, latitude in degrees (iterated, to 1e-12 rad)."""
    e2 = f * (2 - f)
    p = np.hypot(x, y)
    lat = np.arctan2(z, p * (1 - e2))
    for _iteration in range(10):
        n = a / np.sqrt(1 - e2 * np.sin(lat) ** 2)
        height = p / np.cos(lat) - n
        lat = np.arctan2(z, p * (1 - e2 * n / (n + height)))
    return np.degrees(np.arctan2(y, x)), np.degrees(lat)


def geocentric_translation(points, src_crs, dst_crs, translation=SAD69_TO_SIRGAS2000):
    """A datum shift by three geocentric translations, computed here without PROJ's choice.

    The EPSG method "Geocentric translations": geographic coordinates on the
    source ellipsoid -> Earth-centred X, Y, Z -> add (tx, ty, tz) -> back to
    geographic on the target ellipsoid (heights taken as 0). PROJ is used only
    for the projection steps (UTM <-> geographic, same datum). Comparing the
    result with :func:`transform_points` (``transformation="EPSG:15485"``) checks
    PROJ's computation of EPSG:15485 independently.

    Parameters
    ----------
    points : (n, 2) array_like
        Map (x, y) in ``src_crs``.
    src_crs, dst_crs : str, int or rasterio.crs.CRS
        Projected or geographic CRSs on two datums.
    translation : (tx, ty, tz)
        Metres; EPSG:15485's SAD69 -> SIRGAS 2000 values by default.

    Returns
    -------
    ndarray
        (n, 2) map (x, y) in ``dst_crs``.

    Raises
    ------
    ValueError
        As :func:`transform_points`; if ``translation`` is not three finite numbers.

    Examples
    --------
    >>> p = [[775445.0, 7369105.0]]
    >>> here = geocentric_translation(p, "EPSG:29191", "EPSG:31981")
    >>> by_name = transform_points(p, "EPSG:29191", "EPSG:31981", transformation="EPSG:15485")
    >>> bool(np.abs(here - by_name).max() < 0.01)
    True
    """
    shift = np.asarray(translation, dtype=np.float64)
    if shift.shape != (3,) or not np.isfinite(shift).all():
        raise CRSError(_("translation must be three finite numbers (tx, ty, tz) in "
                         "metres, got {translation!r}").format(translation=translation))
    src, dst = as_crs(src_crs, "src_crs"), as_crs(dst_crs, "dst_crs")
    (src_geo, *src_ellipsoid), (dst_geo, *dst_ellipsoid) = _geographic(src), _geographic(dst)
    lonlat = transform_points(points, src, src_geo)
    xyz = np.array(_to_geocentric(lonlat[:, 0], lonlat[:, 1], *src_ellipsoid))
    lon, lat = _to_geographic(*(xyz + shift[:, np.newaxis]), *dst_ellipsoid)
    return transform_points(np.column_stack([lon, lat]), dst_geo, dst)


# -- rsgeo's own reading of a horizontal shift grid (the check on PROJ's) ---------------------

#: The shift grids rsgeo ships (``rsgeo/data/README.md``), by the datum they shift from.
SHIFT_GRIDS = {"SAD69": "br_ibge_SAD69_003.tif", "SAD69(96)": "br_ibge_SAD96_003.tif"}

# The units a GeoTIFF shift grid may give its offsets in (PROJ's grids.cpp), in arc-seconds
_ARCSECONDS_PER = {"arc-second": 1.0, "degree": 3600.0, "radian": 180 / np.pi * 3600}

# PROJ's tolerance at a grid's edges, a fraction of a cell (REL_TOLERANCE_HGRIDSHIFT)
_EDGE_TOLERANCE = 1e-5


class ShiftGrid(NamedTuple):  # numpydoc ignore=PR02
    """A horizontal shift grid (NTv2 converted to GeoTIFF), read by rsgeo.

    Parameters
    ----------
    name : str
        The file's name.
    source_crs, target_crs : str
        The geographic CRSs it shifts from and to, e.g. "EPSG:4618" (SAD69) and "EPSG:4674".
    lon, lat : ndarray
        The nodes' longitudes (west to east) and latitudes (south to north), degrees.
    dlon, dlat : ndarray
        (rows, cols) shifts at the nodes in arc-seconds, longitude positive east; row 0 is the
        southernmost, as ``lat``.
    """

    name: str
    source_crs: str
    target_crs: str
    lon: np.ndarray
    lat: np.ndarray
    dlon: np.ndarray
    dlat: np.ndarray

    @property
    def bounds(self):
        """The box the nodes cover.

        Returns
        -------
        tuple of float
            (west, south, east, north) of the first and last nodes, degrees.
        """
        return (float(self.lon[0]), float(self.lat[0]), float(self.lon[-1]),
                float(self.lat[-1]))

    def covers(self, lon, lat):
        """Which points are inside the grid, within PROJ's tolerance at its edges.

        Parameters
        ----------
        lon, lat : array_like
            Longitude and latitude, degrees, in the grid's source CRS.

        Returns
        -------
        ndarray of bool
            True inside; NaN is outside.
        """
        west, south, east, north = self.bounds
        step_lon, step_lat = self.lon[1] - self.lon[0], self.lat[1] - self.lat[0]
        eps = (step_lon + step_lat) * _EDGE_TOLERANCE
        return ((lon >= west - eps) & (lon <= east + eps) & (lat >= south - eps)
                & (lat <= north + eps))

    def shift(self, lon, lat):
        """The shift at points inside the grid, bilinear between the four nodes around each.

        Parameters
        ----------
        lon, lat : ndarray
            Longitude and latitude, degrees, inside the grid (:meth:`covers`; not checked).

        Returns
        -------
        dlon, dlat : ndarray
            Arc-seconds, longitude positive east.
        """
        x = (lon - self.lon[0]) / (self.lon[1] - self.lon[0])
        y = (lat - self.lat[0]) / (self.lat[1] - self.lat[0])
        cols, rows = len(self.lon), len(self.lat)
        # the node to the south-west; on the east or north edge the last cell, at weight 1
        i = np.clip(np.floor(x).astype(np.intp), 0, cols - 2)
        j = np.clip(np.floor(y).astype(np.intp), 0, rows - 2)
        fx, fy = np.clip(x - i, 0.0, 1.0), np.clip(y - j, 0.0, 1.0)

        def bilinear(values):
            south_row = values[j, i] * (1 - fx) + values[j, i + 1] * fx
            north_row = values[j + 1, i] * (1 - fx) + values[j + 1, i + 1] * fx
            return south_row * (1 - fy) + north_row * fy

        return bilinear(self.dlon), bilinear(self.dlat)


def _grid_path(grid):
    from pathlib import Path

    name = SHIFT_GRIDS.get(grid, grid)
    if not isinstance(name, (str, os.PathLike)):
        raise TypeError(_("grid must be one of {known} or the path of a GeoTIFF shift grid, "
                          "got {kind}").format(known=", ".join(SHIFT_GRIDS),
                                               kind=type(grid).__name__))
    shipped = _proj.GRIDS / str(name)
    path = shipped if shipped.is_file() else Path(name)
    if not path.is_file():
        raise DataError(_("no shift grid {grid!r}: give one of {known} (shipped with rsgeo) "
                          "or the path of an NTv2-style GeoTIFF").format(
                              grid=grid, known=", ".join(SHIFT_GRIDS)))
    return path.resolve()


def read_shift_grid(grid="SAD69"):
    """Read a horizontal shift grid (PROJ's GeoTIFF form of an NTv2 grid) with rasterio.

    Everything is read from the file's metadata, as PROJ reads it (``grids.cpp``): the bands
    named ``latitude_offset`` and ``longitude_offset``, their unit (arc-second, degree or
    radian), the longitude's sign (``positive_value`` east or west: NTv2 counts west), the
    nodes at the pixel centres (GDAL's geotransform, whatever the file's AREA_OR_POINT), the
    source CRS (the file's) and the target (``target_crs_epsg_code``).

    Parameters
    ----------
    grid : str or path
        ``"SAD69"`` or ``"SAD69(96)"`` (IBGE's grids, shipped: :data:`SHIFT_GRIDS`), a
        shipped file's name, or the path of another such GeoTIFF.

    Returns
    -------
    ShiftGrid

    Raises
    ------
    rsgeo.errors.DataError
        For a file that is not a single-grid horizontal shift GeoTIFF PROJ could read.

    Examples
    --------
    >>> sad69 = read_shift_grid("SAD69")
    >>> sad69.source_crs, sad69.target_crs, sad69.dlon.shape
    ('EPSG:4618', 'EPSG:4674', (233, 181))
    """
    return _read_shift_grid(_grid_path(grid))


@lru_cache(maxsize=8)
def _read_shift_grid(path):
    import rasterio

    def refuse(why):
        return DataError(_("{name} is not a horizontal shift grid rsgeo can read: {why}").format(
            name=path.name, why=why))

    try:
        with rasterio.open(path) as dataset:
            tags, names = dataset.tags(), list(dataset.descriptions)
            units, subgrids = list(dataset.units), dataset.subdatasets
            transform, crs = dataset.transform, dataset.crs
            if tags.get("TYPE") != "HORIZONTAL_OFFSET":
                raise refuse(_("its TYPE is {kind!r}, not 'HORIZONTAL_OFFSET'").format(
                    kind=tags.get("TYPE")))
            if "latitude_offset" not in names or "longitude_offset" not in names:
                raise refuse(_("no bands named latitude_offset and longitude_offset (its "
                               "bands: {names})").format(names=names))
            lat_band = names.index("latitude_offset") + 1
            lon_band = names.index("longitude_offset") + 1
            dlat, dlon = (dataset.read(band).astype(np.float64)
                          for band in (lat_band, lon_band))
            positive = dataset.tags(lon_band).get("positive_value", "east")
    except rasterio.errors.RasterioIOError as error:
        raise DataError(_("cannot read {name} ({error})").format(
            name=path.name, error=error)) from None
    if subgrids:
        raise refuse(_("it holds {n} subgrids; rsgeo reads single-grid files").format(
            n=len(subgrids) + 1))
    unit = units[lat_band - 1] or "arc-second"
    if unit != (units[lon_band - 1] or "arc-second") or unit not in _ARCSECONDS_PER:
        raise refuse(_("offset units {units}, not one of {known} for both").format(
            units=units, known=", ".join(_ARCSECONDS_PER)))
    if positive not in ("east", "west"):
        raise refuse(_("positive_value {value!r}, not 'east' or 'west'").format(value=positive))
    if crs is None or not crs.is_geographic or transform.b or transform.d:
        raise refuse(_("it is not a north-up grid in a geographic CRS"))
    rows, cols = dlat.shape
    lon = transform.c + (np.arange(cols) + 0.5) * transform.a
    lat = transform.f + (np.arange(rows) + 0.5) * transform.e
    if transform.e < 0:                      # north-up file: make row 0 the southernmost
        lat, dlat, dlon = lat[::-1], dlat[::-1], dlon[::-1]
    factor = _ARCSECONDS_PER[unit] * (1.0 if positive == "east" else -1.0)
    target = tags.get("target_crs_epsg_code")
    arrays = [lon, lat, dlon * factor, dlat * _ARCSECONDS_PER[unit]]
    for array in arrays:
        array.flags.writeable = False
    source = crs.to_epsg()
    return ShiftGrid(path.name, f"EPSG:{source}" if source else crs.to_string(),
                     f"EPSG:{target}" if target else "", *arrays)


def grid_shift(points, grid="SAD69", inverse=False):
    """Longitude and latitude moved by a horizontal shift grid, computed by rsgeo itself.

    What PROJ's ``hgridshift`` does with the same file: the shift (dlon, dlat) at a point is
    the bilinear interpolation of the four nodes around it, added to its longitude and
    latitude; the inverse (target datum -> source) iterates ``p = q - shift(p)`` as PROJ does.
    It reads the grid with :func:`read_shift_grid`; its agreement with PROJ, to a few
    micrometres (PROJ keeps each node's shift, in radians, as a float32), is the check that
    the two read the file alike (``tests/test_datum_grids.py``).

    Parameters
    ----------
    points : (n, 2) array_like
        Longitude, latitude in degrees, in the grid's source CRS (SAD69, EPSG:4618, for
        ``"SAD69"``), or in its target CRS (SIRGAS 2000) with ``inverse``.
    grid : str or path
        See :func:`read_shift_grid`.
    inverse : bool
        From the target datum back to the source.

    Returns
    -------
    ndarray
        (n, 2) longitude, latitude in degrees in the target CRS (the source with
        ``inverse``).

    Raises
    ------
    rsgeo.errors.GridError
        If a point is outside the grid (PROJ has no number there; rsgeo says so rather than
        fall back to another transformation), or the inverse does not converge.
    rsgeo.errors.DataError
        For a grid file rsgeo cannot read (:func:`read_shift_grid`).

    Examples
    --------
    >>> lon, lat = grid_shift([[-57.0, -23.0]], "SAD69")[0]      # SAD69 -> SIRGAS 2000
    >>> print(f"{(lon + 57.0) * 3600:.3f}, {(lat + 23.0) * 3600:.3f}")      # arc-seconds
    -1.749, -1.457
    """
    points = as_points(points, "points")
    shift_grid = read_shift_grid(grid)
    lon, lat = points[:, 0], points[:, 1]
    outside = ~shift_grid.covers(lon, lat)
    if outside.any():
        west, south, east, north = shift_grid.bounds
        first = int(np.flatnonzero(outside)[0])
        raise GridError(_(
            "{count} of {n} points are outside the grid {name} (longitude {west:g} to {east:g}, "
            "latitude {south:g} to {north:g}; first: point {first} ({lon:.6g}, {lat:.6g})): "
            "the grid has no shift there; give longitude and latitude in degrees inside it, "
            "or use transform_points, which lets PROJ choose another transformation").format(
                count=int(outside.sum()), n=len(points), name=shift_grid.name, west=west,
                east=east, south=south, north=north, first=first, lon=lon[first],
                lat=lat[first]))
    if not inverse:
        dlon, dlat = shift_grid.shift(lon, lat)
        return np.column_stack([lon + dlon / 3600, lat + dlat / 3600])
    # PROJ's inverse: start from q - shift(q), correct by the mismatch, at most 10 times
    dlon, dlat = shift_grid.shift(lon, lat)
    guess_lon, guess_lat = lon - dlon / 3600, lat - dlat / 3600
    converged = np.zeros(len(points), dtype=bool)
    for _iteration in range(10):
        if not shift_grid.covers(guess_lon, guess_lat).all():
            break
        dlon, dlat = shift_grid.shift(guess_lon, guess_lat)
        miss_lon = guess_lon + dlon / 3600 - lon
        miss_lat = guess_lat + dlat / 3600 - lat
        guess_lon, guess_lat = guess_lon - miss_lon, guess_lat - miss_lat
        converged = np.radians(np.hypot(miss_lon, miss_lat)) <= 1e-12
        if converged.all():
            return np.column_stack([guess_lon, guess_lat])
    raise GridError(_("the inverse shift by {name} did not converge at {count} of {n} points "
                      "(at the grid's edge?); give points farther inside the grid").format(
                          name=shift_grid.name, n=len(points), count=int((~converged).sum())))

def transformation_at(points, src, dst, transformation=None):
    """The transformation PROJ applies at the first of ``points``.

    Parameters
    ----------
    points : ndarray
        (n, 2) finite map coordinates in ``src``; the first is asked about.
    src, dst : rasterio.crs.CRS
        Checked CRSs (:func:`as_crs`).
    transformation : optional
        A transformation forced, as :func:`transform_points` takes it.

    Returns
    -------
    Transformation or None
        The operation PROJ applies there; None when ``src`` and ``dst`` are the same CRS.
    """
    if src == dst:
        return None
    if transformation is not None:
        return _forced(src, dst, transformation)[0]
    found, used = _used_operations(points[:1], _transform(points[:1], src, dst), src, dst)
    return found[used[0]]


