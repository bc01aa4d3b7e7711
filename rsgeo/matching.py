"""Deprecated: this module's names moved to the GA paper's matching (:mod:`rsgeo.registration`).

Each name still works from here for one release, with a ``DeprecationWarning`` naming its new
home; this module goes in rsgeo 0.3.
"""

from ._deprecated import moved_names

__getattr__, __dir__ = moved_names(__name__, {
    **dict.fromkeys(("BITS_PER_GENE", "COMPACT_SPREAD", "MatchResult", "Mesh", "VARIANTS",
                     "decode",
                     "encode", "exhaustive_match", "fitness", "fitness_batch", "genetic_match",
                     "group_spread", "matched_centroids", "optimum_match", "qap_match",
                     "register_by_regions", "true_matching"), "rsgeo.registration"),
})
