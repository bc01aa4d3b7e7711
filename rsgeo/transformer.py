"""Deprecated: this module's names moved to rsgeo's compiled internals
(``rsgeo._kernels.transformer``, not an API).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("AFFINE", "ARRAYS", "POLYNOMIAL", "PROJECTIVE", "TPS", "pack", "pixel_centre",
                     "polynomial_many", "polynomial_parameters", "polynomial_point", "positions",
                     "row_positions", "to_source"), "rsgeo._kernels.transformer"),
})
