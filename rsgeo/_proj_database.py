"""Is PROJ's database there? A broken install named as such, not as an unknown CRS.

rsgeo reaches PROJ twice, through pyproj and through rasterio's GDAL, each with its own copy of
PROJ's database (``proj.db``); either missing (``PROJ_DATA`` pointing where there is none) makes
every CRS unknown, which :func:`rsgeo.validation.as_crs` would otherwise report as "not a CRS
that PROJ knows".
"""

import os
import sqlite3
from contextlib import closing
from pathlib import Path

from .errors import CRSError
from .language import _

__all__ = ["check_database", "database_problem"]


def _opens(database):
    """The error reading PROJ's database at ``database``, or None when it opens."""
    try:
        with closing(sqlite3.connect(f"{database.resolve().as_uri()}?mode=ro", uri=True)) as db:
            db.execute("SELECT 1 FROM metadata LIMIT 1").fetchall()
    except (sqlite3.Error, OSError, ValueError) as error:
        return error
    return None


def _gdal_proj_folders():
    """The folders rasterio's GDAL looks in for PROJ's database (its own PROJ, not pyproj's)."""
    try:
        from rasterio._env import get_proj_data_search_paths
        return [folder for folder in get_proj_data_search_paths() if folder]
    except Exception:                  # another rasterio: what PROJ_DATA says, if anything
        value = os.environ.get("PROJ_DATA") or os.environ.get("PROJ_LIB")
        return value.split(os.pathsep) if value else []


def database_problem():
    """Why PROJ cannot work here, or None: its ``proj.db`` not found by pyproj or by GDAL.

    rsgeo reaches PROJ twice, through pyproj and through rasterio's GDAL, each with its own
    copy of PROJ's database; either missing (``PROJ_DATA`` pointing where there is none)
    makes every CRS unknown.

    Returns
    -------
    str or None
        The message (where PROJ looked, what to do), or None when both databases open.
    """
    import pyproj.datadir

    folders = [folder for folder in pyproj.datadir.get_data_dir().split(os.pathsep) if folder]
    places = [("pyproj", [Path(folders[0]) / "proj.db"] if folders else [])]
    gdal = [Path(folder) / "proj.db" for folder in _gdal_proj_folders()]
    if gdal:
        places.append(("rasterio's GDAL", gdal))
    for user, databases in places:
        errors = [_opens(database) for database in databases]
        if databases and all(error is not None for error in errors):
            return _(
                "PROJ's database is not found at {path} ({error}): {user} cannot read any CRS. "
                "PROJ_DATA (or PROJ_LIB) is {value!r}; unset it, or point it at a folder that "
                "holds proj.db, then restart Python").format(
                    path=", ".join(str(database) for database in databases), error=errors[0],
                    user=user,
                    value=os.environ.get("PROJ_DATA", os.environ.get("PROJ_LIB")))
    return None


def check_database():
    """Raise a CRSError naming a broken PROJ install; nothing when PROJ's database opens.

    Raises
    ------
    CRSError
        If pyproj's ``proj.db`` is not found or cannot be read.
    """
    problem = database_problem()
    if problem is not None:
        raise CRSError(problem)
