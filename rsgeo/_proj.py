"""PROJ through pyproj, with the grids rsgeo ships on PROJ's search path.

rsgeo ships three PROJ grids in ``rsgeo/data/proj`` (provenance and licences in
``rsgeo/data/README.md``): IBGE's SAD69 -> SIRGAS 2000 and SAD69(96) -> SIRGAS 2000 shift
grids and EGM96 over Brazil. PROJ finds a grid by its file name in its search path; pyproj can
search several folders (rasterio's GDAL only one, its wheel's), so every transformation that
needs a grid goes through :func:`transformer` here, never through the network
(``PROJ_NETWORK`` stays off: nothing downloads at run time).
"""

from functools import lru_cache
from pathlib import Path

__all__ = ["GRIDS", "transformer", "operations"]

GRIDS = Path(__file__).resolve().parent / "data" / "proj"


@lru_cache(maxsize=1)
def _search_shipped_grids():
    """Append rsgeo's grid folder to pyproj's PROJ search path, once, network off."""
    import pyproj.datadir
    import pyproj.network

    pyproj.network.set_network_enabled(False)
    if str(GRIDS) not in pyproj.datadir.get_data_dir().split(":"):
        pyproj.datadir.append_data_dir(str(GRIDS))


@lru_cache(maxsize=64)
def transformer(src_wkt, dst_wkt):
    """A pyproj Transformer from one CRS (as WKT) to another, longitude/easting first.

    PROJ picks, point by point, the most accurate operation whose area of use (its bounding
    box) holds the point and whose grids it finds, and falls back to the next where a grid
    has no value; the one it used is ``transformer(...).get_last_used_operation()`` after a
    call. pyproj's Transformer is thread-safe (one PROJ context per thread).
    """
    from pyproj import Transformer

    _search_shipped_grids()
    return Transformer.from_crs(src_wkt, dst_wkt, always_xy=True)


def operations(src_wkt, dst_wkt):
    """Every operation PROJ knows from one CRS to another, as a pyproj TransformerGroup.

    Its ``transformers`` are those PROJ can apply here, its ``unavailable_operations`` those
    whose grids it does not find (rsgeo.crs.transformations reports which; pyproj's
    warning that the best one is missing is left out).
    """
    import warnings

    from pyproj.transformer import TransformerGroup

    _search_shipped_grids()
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "Best transformation is not available",
                                UserWarning)
        return TransformerGroup(src_wkt, dst_wkt, always_xy=True)
