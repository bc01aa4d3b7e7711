"""Registration: finding the same ground in two images, and the model between them.

- tie points by correlation (:func:`measure_shifts`, :func:`correlation_tiepoints`, as AROSICS
  does) and by features (:func:`feature_tiepoints`: SIFT or ORB, then RANSAC);
- :func:`register`: tie points -> GCPSet -> model -> refinement -> check points, the step
  every automatic method shares;
- :func:`band_misregistration`: band-to-band registration of a multispectral image;
- the GA paper: homologous regions (:func:`forest_segments`, :func:`group_segments`,
  :class:`Mesh`) matched by a genetic algorithm (:func:`genetic_match`, against the exhaustive
  optimum :func:`exhaustive_match`), then registration from their centroids
  (:func:`register_by_regions`).
"""

from ._bands import (
    BAND_FEATURES,
    band_misregistration,
)
from ._genetic import (
    BITS_PER_GENE,
    COMPACT_SPREAD,
    VARIANTS,
    MatchResult,
    Mesh,
    decode,
    encode,
    exhaustive_match,
    fitness,
    fitness_batch,
    genetic_match,
    group_spread,
    matched_centroids,
    optimum_match,
    qap_match,
    register_by_regions,
    true_matching,
)
from ._pipeline import (
    Registration,
    coarsen,
    grid_error,
    perturb_transform,
    register,
)
from ._regions import (
    Segments,
    centroids_and_areas,
    forest_segments,
    group_segments,
    keep_largest,
    ndvi,
)
from ._tiepoints import (
    DETECTORS,
    MAX_EDGE_SHARE,
    MIN_WINDOW,
    correlation_tiepoints,
    edge_share,
    feature_tiepoints,
    measure_shifts,
    offsets_against_reference,
    ransac_model,
    robust_fit,
)

__all__ = [
    "DETECTORS", "MIN_WINDOW", "MAX_EDGE_SHARE", "measure_shifts", "edge_share",
    "offsets_against_reference", "ransac_model", "robust_fit", "correlation_tiepoints",
    "feature_tiepoints", "Registration", "register", "grid_error", "coarsen",
    "perturb_transform", "BAND_FEATURES", "band_misregistration", "Segments",
    "centroids_and_areas", "forest_segments", "group_segments", "keep_largest", "ndvi",
    "BITS_PER_GENE", "COMPACT_SPREAD", "VARIANTS", "MatchResult", "Mesh", "decode", "encode",
    "exhaustive_match", "fitness", "fitness_batch", "genetic_match", "group_spread",
    "matched_centroids", "optimum_match", "qap_match", "register_by_regions", "true_matching",
]
