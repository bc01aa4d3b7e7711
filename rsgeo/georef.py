"""Deprecated: this module's names moved to CRSs and datums (:mod:`rsgeo.crs`); reproject and
georeference (:mod:`rsgeo.resample`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("DatumShift", "SHIFT_GRIDS", "ShiftGrid", "Transformation", "as_crs",
                     "datum_shift", "geocentric_translation", "grid_shift", "read_shift_grid",
                     "transform_points", "transformations"), "rsgeo.crs"),
    **dict.fromkeys(("CRSMapping", "georeference", "reproject"), "rsgeo.resample"),
})
