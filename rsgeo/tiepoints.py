"""Deprecated: this module's names moved to tie points and registration
(:mod:`rsgeo.registration`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("BAND_FEATURES", "DETECTORS", "MAX_EDGE_SHARE", "MIN_WINDOW", "Registration",
                     "band_misregistration", "coarsen", "correlation_tiepoints", "edge_share",
                     "feature_tiepoints", "grid_error", "measure_shifts",
                     "offsets_against_reference", "perturb_transform", "ransac_model", "register",
                     "robust_fit"), "rsgeo.registration"),
})
