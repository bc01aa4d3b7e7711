"""PROJ through pyproj, with the grids rsgeo ships, found without touching PROJ's global state.

rsgeo ships three PROJ grids in ``rsgeo/data/proj`` (provenance and licences in
``rsgeo/data/README.md``): IBGE's SAD69 -> SIRGAS 2000 and SAD69(96) -> SIRGAS 2000 shift
grids and EGM96 over Brazil. PROJ finds a grid by its file name in a search path that is the
whole process's (``pyproj.datadir``): a library that put its folder there would change every
transformation its user makes afterwards (SAD69 -> SIRGAS 2000 by IBGE's grid instead of
EPSG:15485, metres apart). So rsgeo names its grids by their absolute path inside each
operation it builds (the operation PROJ describes, its grid parameter a path), and chooses
between the operations point by point as PROJ's ``proj_trans`` does; nothing downloads at run
time whatever ``PROJ_NETWORK`` says (grids that are not on this disk are not used), and neither
pyproj's search path, its network switch nor the environment is changed.

A broken PROJ install (``PROJ_DATA`` pointing where there is no ``proj.db``) is named
(``rsgeo._proj_database``), rather than left to surface as "not a CRS that PROJ knows".
"""

import json
import math
import os
import re
import sqlite3
import warnings
from contextlib import closing
from functools import lru_cache
from pathlib import Path

import numpy as np

from ._proj_database import check_database
from .errors import CRSError
from .language import _

__all__ = ["GRIDS", "Alternatives", "transformer", "operations"]

GRIDS = Path(__file__).resolve().parent / "data" / "proj"

# PROJ's "no value" (HUGE_VAL) reaches Python as infinity
_DBL_MAX = float(np.finfo(np.float64).max)


# -- The grids rsgeo ships, by every name PROJ gives them -----------------------------------------

@lru_cache(maxsize=1)
def _shipped_grids():
    """{name PROJ may ask for: absolute path} of the shipped grids.

    A grid's file name, and the names PROJ's database gives the same grid (its
    ``grid_alternatives`` table: EGM96 is ``us_nga_egm96_15.tif`` in PROJ's catalogue and
    ``egm96_15.gtx`` here).
    """
    import pyproj.datadir

    found = {path.name: str(path) for path in GRIDS.iterdir() if path.is_file()
             and path.suffix.lower() in (".tif", ".tiff", ".gtx", ".gsb")}
    folders = pyproj.datadir.get_data_dir().split(os.pathsep)
    database = Path(folders[0]) / "proj.db"
    try:
        with closing(sqlite3.connect(f"{database.resolve().as_uri()}?mode=ro", uri=True)) as db:
            rows = db.execute("SELECT proj_grid_name, old_proj_grid_name, original_grid_name "
                              "FROM grid_alternatives").fetchall()
    except (sqlite3.Error, OSError, ValueError):
        rows = []
    for names in rows:
        path = next((found[name] for name in names if name in found), None)
        if path is not None:
            found.update({name: path for name in names if name})
    return found


def _grid_is_here(grid):
    """Whether a pyproj Grid is a file on this disk (not one PROJ would download)."""
    return bool(grid.full_name) and Path(grid.full_name).is_file()


def _grids(operation):
    return [grid for step in (operation.operations or [operation])
            for grid in getattr(step, "grids", [])]


# -- PROJ's operations between two CRSs, the shipped grids by path --------------------------------

def _swapped(crs):
    """Whether PROJ shows ``crs`` with its first two axes swapped (latitude first, northing
    first), as pyproj's always_xy does (PROJ's mustAxisOrderBeSwitchedForVisualization)."""
    axes = crs.axis_info
    return (len(axes) >= 2 and axes[0].direction.lower() in ("north", "south")
            and axes[1].direction.lower() in ("east", "west"))


def _replace_grids(value, paths):
    """``value`` (PROJJSON) with every grid name of ``paths`` replaced by its absolute path."""
    if isinstance(value, dict):
        return {key: _replace_grids(item, paths) for key, item in value.items()}
    if isinstance(value, list):
        return [_replace_grids(item, paths) for item in value]
    if isinstance(value, str) and value in paths:
        return paths[value]
    if isinstance(value, str) and "+grids=" in value:
        # an operation PROJ describes by a PROJ string (EGM96's): the names in +grids=
        return re.sub(r"(?<=[=,@])([^\s,@=]+)",
                      lambda match: paths.get(match.group(1), match.group(1)), value)
    return value


def _as_step(operation_json):
    """A PROJJSON operation as a step of a concatenated one (its usage is the whole's)."""
    step = {key: item for key, item in operation_json.items()
            if key not in ("$schema", "scope", "area", "bbox", "usages")}
    return step


def _with_shipped_grids(operation, reference):
    """A pyproj Transformer of ``operation`` (whose grids are shipped) reading them by path,
    axes in pyproj's always_xy order; None if it cannot be built.

    ``reference`` is a Transformer of the same group (always_xy), whose concatenated form
    gives the normalised CRSs and the axis swaps PROJ puts around every operation.
    """
    from pyproj import Transformer

    paths = _shipped_grids()
    # a Transformer of pyproj's group (a grid PROJ would download) is in always_xy order
    # already; a CoordinateOperation is in the CRSs' own and is framed as PROJ frames it
    normalised = isinstance(operation, Transformer)
    if normalised:
        reference = None
    own = _replace_grids(operation.to_json_dict(), paths)
    inner = own["steps"] if own.get("type") == "ConcatenatedOperation" else [_as_step(own)]
    inner = [_as_step(step) for step in inner]
    built = own
    if reference is not None:
        frame = reference.to_json_dict()
        steps = frame.get("steps", []) if frame.get("type") == "ConcatenatedOperation" else []

        def is_swap(step):
            return step.get("type") == "Conversion" and step.get("name", "").startswith(
                "axis order change")

        lead = [steps[0]] if steps and is_swap(steps[0]) else []
        trail = [steps[-1]] if len(steps) > 1 and is_swap(steps[-1]) else []
        if lead or trail:
            everything = lead + inner + trail
            built = {"$schema": own.get("$schema"), "type": "ConcatenatedOperation",
                     "name": " + ".join(step.get("name", "") for step in everything),
                     "source_crs": frame["source_crs"], "target_crs": frame["target_crs"],
                     "steps": everything}
            if operation.accuracy >= 0:
                built["accuracy"] = format(operation.accuracy, "g")
            area = operation.area_of_use
            if area is not None:
                built["area"] = area.name
                built["bbox"] = {"south_latitude": area.south, "west_longitude": area.west,
                                 "north_latitude": area.north, "east_longitude": area.east}
    try:
        return Transformer.from_pipeline(json.dumps(built))
    except Exception:                 # pyproj's ProjError: PROJJSON cannot say it
        pass
    # an operation PROJ holds as a PROJ string (EGM96's), which PROJJSON does not carry: its
    # pipeline with the grids by path, named and placed as PROJ's own would be
    try:
        pipeline = _replace_grids(operation.to_proj4(), paths)
        applied = Transformer.from_pipeline(pipeline)
    except Exception:                 # pyproj's ProjError
        return None
    frame = reference.to_json_dict() if reference is not None else {}
    steps = frame.get("steps", []) if frame.get("type") == "ConcatenatedOperation" else []
    names = [step.get("name", "") for step in steps]
    lead = names[:1] if names and names[0].startswith("axis order change") else []
    trail = names[-1:] if len(names) > 1 and names[-1].startswith("axis order change") else []
    name = operation.description if normalised else operation.name
    return _ByPath(applied, operation, " + ".join(lead + [name] + trail),
                   swap_source=bool(lead), swap_target=bool(trail),
                   grid_paths={grid.short_name: paths[grid.short_name]
                               for grid in _grids(operation) if grid.short_name in paths})


class _ByPath:
    """An operation PROJ holds as a PROJ string, applied with the shipped grids by path.

    Its ``transform`` takes and gives pyproj's always_xy order (the pipeline has the CRSs'
    own, latitude first: swapped here); ``description``, ``accuracy``, ``area_of_use`` and
    ``operations`` are PROJ's for the operation; ``grid_paths`` names the grids read.
    """

    def __init__(self, applied, operation, description, swap_source, swap_target,
                 grid_paths):
        self._applied = applied
        self._operation = operation
        self.description = description
        self.name = description
        self.accuracy = operation.accuracy
        self.area_of_use = operation.area_of_use
        self.operations = tuple(getattr(operation, "operations", None) or (operation,))
        self.grid_paths = grid_paths
        self._swap_source = swap_source
        self._swap_target = swap_target

    def transform(self, xx, yy, zz=None, errcheck=False):
        """Points through the operation, always_xy order.

        Parameters
        ----------
        xx, yy : array_like
            Longitude (easting), latitude (northing).
        zz : array_like, optional
            Heights.
        errcheck : bool
            Unused; for pyproj's signature.

        Returns
        -------
        tuple
            (x, y) or (x, y, z).
        """
        first, second = (yy, xx) if self._swap_source else (xx, yy)
        args = (first, second) if zz is None else (first, second, zz)
        result = self._applied.transform(*args)
        if self._swap_target:
            result = (result[1], result[0], *result[2:])
        return tuple(result)

    def to_proj4(self):
        """The pipeline in always_xy order, the grids by their path.

        Returns
        -------
        str
        """
        pipeline = self._applied.to_proj4()
        swap = "+step +proj=axisswap +order=2,1"
        if self._swap_source and pipeline.startswith(f"+proj=pipeline {swap} "):
            pipeline = pipeline.replace(f"+proj=pipeline {swap} ", "+proj=pipeline ", 1)
        if self._swap_target and pipeline.endswith(f" {swap}"):
            pipeline = pipeline[:-len(f" {swap}")]
        return pipeline

    def get_last_used_operation(self):
        """This operation, as a pyproj Transformer's method gives it.

        Returns
        -------
        _ByPath
        """
        return self


class _Group:
    """PROJ's operations between two CRSs: ``transformers`` usable here (the shipped grids
    by path; PROJ's order), ``unavailable_operations`` whose grids are not on this disk."""

    def __init__(self, transformers, unavailable_operations):
        self.transformers = transformers
        self.unavailable_operations = unavailable_operations


def _sort_key(operation):
    """An approximation of PROJ's order of operations (its SortFunction), to place the
    operations rsgeo makes available among those PROJ lists: ballpark last, known accuracy
    first, larger area first, then more accurate, fewer grids, fewer steps, shorter name."""
    accuracy = operation.accuracy
    name = getattr(operation, "description", None) or operation.name
    area = operation.area_of_use
    size = 0.0 if area is None else _pseudo_area(area.west, area.south, area.east, area.north)
    return ("Ballpark" in name, accuracy < 0, -size, accuracy if accuracy >= 0 else 0.0,
            bool(_grids(operation)), len(operation.operations or [operation]), len(name))


@lru_cache(maxsize=64)
def operations(src_wkt, dst_wkt):
    """Every operation PROJ knows from one CRS to another, in PROJ's order of preference.

    Parameters
    ----------
    src_wkt, dst_wkt : str
        The CRSs (WKT, or anything pyproj reads).

    Returns
    -------
    object
        ``transformers``: pyproj Transformers (always_xy) PROJ can apply here, the shipped
        grids read by their path; ``unavailable_operations``: pyproj CoordinateOperations whose
        grids are not on this disk (rsgeo.crs.transformations reports which).
    """
    from pyproj.transformer import TransformerGroup

    with warnings.catch_warnings():
        # pyproj's warning that the best operation's grid is missing: rsgeo supplies it
        warnings.filterwarnings("ignore", "Best transformation is not available",
                                UserWarning)
        group = TransformerGroup(src_wkt, dst_wkt, always_xy=True)
    usable = [t for t in group.transformers if all(_grid_is_here(g) for g in _grids(t))]
    missing = [op for op in group.transformers if op not in usable]
    missing += list(group.unavailable_operations)
    shipped = _shipped_grids()
    reference = group.transformers[0] if group.transformers else None
    still_missing = []
    for operation in missing:
        names = [grid.short_name for grid in _grids(operation)]
        built = None
        if names and all(name in shipped or _grid_is_here(grid)
                         for name, grid in zip(names, _grids(operation))):
            built = _with_shipped_grids(operation, reference)
        if built is None:
            still_missing.append(operation)
            continue
        # placed before the first operation PROJ would sort after it
        key = _sort_key(built)
        place = next((k for k, other in enumerate(usable) if key < _sort_key(other)),
                     len(usable))
        usable.insert(place, built)
    return _Group(usable, still_missing)


# -- PROJ's choice among operations, point by point ----------------------------------------------

def _pseudo_area(west, south, east, north):
    """PROJ's measure of an area of use: its longitude span times the span of sin(latitude)."""
    w, s, e, n = (math.radians(v) for v in (west, south, east, north))
    if w > e:
        e += 2 * math.pi
    return (e - w) * (math.sin(n) - math.sin(s))


def _box_in(to_crs, west, south, east, north):
    """PROJ's reproject_bbox: a lon-lat box's bounds in a CRS, 21 points along each edge."""
    if (west, south, east, north) == (-180.0, -90.0, 180.0, 90.0) or to_crs is None:
        return -_DBL_MAX, -_DBL_MAX, _DBL_MAX, _DBL_MAX
    steps = np.arange(21)
    lon = west + steps * ((east - west) / 20)
    lat = south + steps * ((north - south) / 20)
    x = np.concatenate([lon, lon, np.full(21, west), np.full(21, east)])
    y = np.concatenate([np.full(21, south), np.full(21, north), lat, lat])
    with np.errstate(all="ignore"):
        x, y = (np.asarray(v, dtype=np.float64) for v in to_crs.transform(x, y))
    good = np.isfinite(x) & np.isfinite(y)
    if not good.any():
        return _DBL_MAX, _DBL_MAX, -_DBL_MAX, -_DBL_MAX
    return float(x[good].min()), float(y[good].min()), float(x[good].max()), float(y[good].max())


def _from_lon_lat(crs):
    """A Transformer from longitude, latitude on ``crs``'s own datum to ``crs`` (always_xy)."""
    from pyproj import CRS, Transformer

    geodetic = crs.geodetic_crs
    if geodetic is None:
        return None
    if crs.is_compound:
        crs = CRS(crs.sub_crs_list[0])
    try:
        return Transformer.from_crs(geodetic, crs, always_xy=True)
    except Exception:                 # pyproj's ProjError
        return None


def _is_lon_lat_degree(crs):
    axes = crs.axis_info
    return (crs.is_geographic and len(axes) >= 2 and axes[0].direction.lower() == "east"
            and axes[0].unit_name == "degree")


class _Alternative:
    """One operation as PROJ's ``proj_trans`` sees it: its box in the source CRS and rank."""

    def __init__(self, transformer, box, accuracy, pseudo_area, area_name):
        self.transformer = transformer
        self.box = box
        self.accuracy = accuracy
        self.pseudo_area = pseudo_area
        self.offshore = "- offshore" in area_name
        self.unknown_area = area_name in ("", "unknown")
        self.needs_grids = bool(_grids(transformer))


class Alternatives:
    """A pyproj-like Transformer over several operations, chosen point by point as PROJ does.

    PROJ's ``proj_trans`` over the operations of ``proj_create_crs_to_crs``: at each point the
    most accurate operation whose area of use (its box in the source CRS) holds the point (of
    equal accuracy, the smaller area; offshore areas last); if it gives no value (a point
    outside its grid), the next, at most three tries; then the first operation without a grid.
    """

    def __init__(self, alternatives, lon_lat_source):
        self._alternatives = alternatives
        self._lon_lat_source = lon_lat_source
        self._last = None

    def _suggested(self, x, y, excluded):
        """Per point, the index PROJ's pj_get_suggested_operation picks, -1 for none.

        ``excluded`` is (n, 2): the operations already tried at each point (-1: none).
        """
        best = np.full(x.shape, -1)
        best_accuracy = np.full(x.shape, np.finfo(np.float64).max)
        areas = np.array([a.pseudo_area for a in self._alternatives])
        unknown = np.array([a.unknown_area for a in self._alternatives])
        with np.errstate(invalid="ignore"):
            # PROJ's normalizeLongitude, for a point given a turn away from the box
            wrapped = np.where(x > 180.0, x - 360.0, np.where(x < -180.0, x + 360.0, x))
            wrapped = np.where(np.abs(wrapped) > 180.0,
                               np.fmod(wrapped + 180.0, 360.0) - 180.0, wrapped)
        for k, alternative in enumerate(self._alternatives):
            minx, miny, maxx, maxy = alternative.box
            with np.errstate(invalid="ignore"):
                inside = (x >= minx) & (y >= miny) & (x <= maxx) & (y <= maxy)
                if self._lon_lat_source:
                    inside |= ((y >= miny) & (y <= maxy) & (wrapped >= minx)
                               & (wrapped <= maxx))
            inside &= (excluded[:, 0] != k) & (excluded[:, 1] != k)
            if not inside.any():
                continue
            accuracy = alternative.accuracy
            current = np.clip(best, 0, None)
            better = (((accuracy >= 0) & (accuracy < best_accuracy))
                      | ((accuracy == best_accuracy) & (alternative.pseudo_area < areas[current])
                         & ~(alternative.unknown_area & ~unknown[current])))
            take = inside & ((best < 0) | (better & (not alternative.offshore)))
            best[take] = k
            best_accuracy[take] = accuracy
        return best

    def _apply(self, k, rows, x, y, z, out):
        """Operation ``k`` at points ``rows``, written into ``out``; which gave a value."""
        args = (x[rows], y[rows]) if z is None else (x[rows], y[rows], z[rows])
        with np.errstate(all="ignore"):
            result = self._alternatives[k].transformer.transform(*args)
        values = [np.asarray(v, dtype=np.float64) for v in result]
        for target, value in zip(out, values):
            target[rows] = value
        return values[0] != np.inf

    def transform(self, xx, yy, zz=None, errcheck=False):
        """Points through the operation PROJ would choose at each; infinity where none gives
        a value.

        Parameters
        ----------
        xx, yy : array_like
            Easting or longitude, northing or latitude (always_xy order).
        zz : array_like, optional
            Heights.
        errcheck : bool
            Unused; for pyproj's signature.

        Returns
        -------
        tuple
            (x, y) or (x, y, z), of the input's shape (floats for a scalar point).
        """
        shape = np.shape(xx)
        x = np.array(xx, dtype=np.float64).ravel()
        y = np.array(yy, dtype=np.float64).ravel()
        z = None if zz is None else np.broadcast_to(
            np.asarray(zz, dtype=np.float64), shape).ravel().copy()
        out = [np.full(x.shape, np.inf) for _axis in range(2 if z is None else 3)]
        used = np.full(x.shape, -1)
        excluded = np.full((len(x), 2), -1)
        pending = np.arange(len(x))
        fallback = []
        for attempt in range(3):
            if not len(pending):
                break
            best = self._suggested(x[pending], y[pending], excluded[pending])
            fallback.append(pending[best < 0])
            again = []
            for k in np.unique(best[best >= 0]):
                rows = pending[best == k]
                good = self._apply(k, rows, x, y, z, out)
                used[rows] = k
                if attempt < 2:
                    excluded[rows[~good], attempt] = k
                again.append(rows[~good])
            pending = np.concatenate(again) if again else np.empty(0, dtype=np.intp)
        fallback.append(pending)
        left = np.sort(np.concatenate(fallback))
        first_without_grid = next(
            (k for k, a in enumerate(self._alternatives) if not a.needs_grids), None)
        if len(left):
            if first_without_grid is None:
                for target in out:
                    target[left] = np.inf
                used[left] = -1
            else:
                self._apply(first_without_grid, left, x, y, z, out)
                used[left] = first_without_grid
        if len(used) and used[-1] >= 0:
            self._last = int(used[-1])
        out = tuple(v.reshape(shape) for v in out)
        return tuple(float(v) for v in out) if not shape else out

    def get_last_used_operation(self):
        """The operation applied to the last point of the last call.

        Returns
        -------
        pyproj.Transformer
            Its Transformer (its ``description``, ``operations``...).

        Raises
        ------
        CRSError
            If no point was transformed yet.
        """
        if self._last is None:
            raise CRSError(_("no point has been transformed yet"))
        return self._alternatives[self._last].transformer


def _alternatives(src_wkt, dst_wkt, transformers):
    """PROJ's prepared operations (boxes in both CRSs) for :class:`Alternatives`."""
    from pyproj import CRS

    src, dst = CRS(src_wkt), CRS(dst_wkt)
    to_src, to_dst = _from_lon_lat(src), _from_lon_lat(dst)
    prepared = []
    for operation in transformers:
        area = operation.area_of_use
        west, south, east, north = ((-180.0, -90.0, 180.0, 90.0) if area is None
                                    else (area.west, area.south, area.east, area.north))
        name = "" if area is None else (area.name or "")
        pieces = ([(west, south, east, north)] if west <= east
                  else [(west, south, 180.0, north), (-180.0, south, east, north)])
        for piece in pieces:
            box = _box_in(to_src, *piece)
            dst_box = _box_in(to_dst, *piece)
            if box[0] <= box[2] and dst_box[0] <= dst_box[2]:
                prepared.append(_Alternative(operation, box, operation.accuracy,
                                             _pseudo_area(*piece), name))
    return prepared, _is_lon_lat_degree(src)


@lru_cache(maxsize=64)
def transformer(src_wkt, dst_wkt):
    """A Transformer from one CRS (as WKT) to another, longitude/easting first.

    PROJ's own multi-operation Transformer when no operation needs a shipped grid and the
    network is off (then it is exactly what PROJ would do); else :class:`Alternatives`, the
    same choice over the operations :func:`operations` makes usable. Either has
    ``transform(x, y[, z])`` and ``get_last_used_operation()``.

    Parameters
    ----------
    src_wkt, dst_wkt : str
        The CRSs (WKT, or anything pyproj reads).

    Returns
    -------
    pyproj.Transformer or Alternatives

    Raises
    ------
    CRSError
        If PROJ's database is not found (a broken install).
    """
    import pyproj.network
    from pyproj import Transformer

    check_database()
    group = operations(src_wkt, dst_wkt)
    built_here = any(_is_built_here(t) for t in group.transformers)
    if not built_here and not pyproj.network.is_network_enabled():
        return Transformer.from_crs(src_wkt, dst_wkt, always_xy=True)
    if len(group.transformers) == 1:
        return group.transformers[0]
    if not group.transformers:
        return Transformer.from_crs(src_wkt, dst_wkt, always_xy=True)
    prepared, lon_lat = _alternatives(src_wkt, dst_wkt, group.transformers)
    return Alternatives(prepared, lon_lat)


def _is_built_here(operation):
    """Whether an operation reads a shipped grid by its path (built by rsgeo)."""
    if isinstance(operation, _ByPath):
        return True
    return any(grid.full_name and Path(grid.full_name).parent == GRIDS
               for grid in _grids(operation))
