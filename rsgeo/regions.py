"""Deprecated: this module's names moved to the GA paper's regions (:mod:`rsgeo.registration`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("Segments", "centroids_and_areas", "forest_segments", "group_segments",
                     "keep_largest", "ndvi"), "rsgeo.registration"),
})
