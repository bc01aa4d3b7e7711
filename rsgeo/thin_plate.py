"""Deprecated: this module's names moved to rsgeo's compiled internals
(``rsgeo._kernels.thin_plate``, not an API).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("FULL", "GDAL_FAST_LOG", "GDAL_INVERSE", "GDAL_STEPS", "ONE_DIMENSIONAL",
                     "evaluate", "evaluate_many", "invert_many", "pack_inverse", "solve"),
                    "rsgeo._kernels.thin_plate"),
})
