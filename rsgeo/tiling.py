"""Deprecated: this module's names moved to tiled warps (:mod:`rsgeo.resample`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("SourceWindow", "Tile", "source_window", "tiles", "warp_dask", "warp_tiled"),
                    "rsgeo.resample"),
})
