"""How good is a model fitted to GCPs: residuals, RMS, leave-one-out, check points, refinement.

Every function that fits takes any kind of :data:`rsgeo.transforms.REGISTRY`, named as the
chapters name it: ``order`` a polynomial's degree (``refine_gcps(src, dst, 1, tolerance)``,
GDAL's case) or a kind's name (``refine_gcps(src, dst, "helmert", tolerance)``), or
``kind="polynomial"`` with ``order`` its degree.

- per-GCP residuals and the lecture's RMS (chapter 3), QGIS's "mean error";
- leave-one-out errors and check points: errors of GCPs the model was not fitted to;
- ``gdalwarp -refine_gcps``: bad GCPs dropped one by one;
- the polynomial's standard errors, its design's condition number, the GCPs' hull and the
  predicted error between them;
- one table of every model (chapter 3b) and comparisons with an image's own geotransform;
- accuracy standards (chapter 3): the class of the Brazilian PEC-PCD a set of check-point errors
  meets at a map scale; ASPRS Edition 2's (2023) RMSE_H and RMSE_V, the checkpoints' own accuracy
  included, and its accuracy classes (30 checkpoints at least); ASPRS 2014's RMSE_r and 95 %
  accuracy as history; CE90 and LE90.
"""

from ._residuals import (
    GeotransformCheck,
    coefficient_standard_errors,
    compare_models,
    compare_with_geotransform,
    condition_number,
    fit_with_check_points,
    hull_coverage,
    leave_one_out_errors,
    leave_one_out_residuals,
    mean_error,
    predicted_error_map,
    refine_gcps,
    residuals,
    rms_error,
)
from ._standards import (
    ASPRS_CHECKPOINT_RATIO,
    ASPRS_MIN_CHECKPOINTS,
    CE90_FACTOR,
    CE90_RADIAL_FACTOR,
    LE90_FACTOR,
    MAP_SCALES,
    NSSDA_95_FACTOR,
    NSSDA_95_RADIAL_FACTOR,
    PEC_CLASSES,
    VERTICAL_95_FACTOR,
    HorizontalAccuracy,
    HorizontalAccuracy2023,
    PECResult,
    VerticalAccuracy,
    VerticalAccuracy2023,
    asprs_horizontal,
    asprs_horizontal_2023,
    asprs_vertical,
    asprs_vertical_2023,
    classify,
    largest_scale,
    pec_thresholds,
)

__all__ = [
    "ASPRS_CHECKPOINT_RATIO",
    "ASPRS_MIN_CHECKPOINTS",
    "CE90_FACTOR",
    "CE90_RADIAL_FACTOR",
    "GeotransformCheck",
    "HorizontalAccuracy",
    "HorizontalAccuracy2023",
    "LE90_FACTOR",
    "MAP_SCALES",
    "NSSDA_95_FACTOR",
    "NSSDA_95_RADIAL_FACTOR",
    "PECResult",
    "PEC_CLASSES",
    "VERTICAL_95_FACTOR",
    "VerticalAccuracy",
    "VerticalAccuracy2023",
    "asprs_horizontal",
    "asprs_horizontal_2023",
    "asprs_vertical",
    "asprs_vertical_2023",
    "classify",
    "coefficient_standard_errors",
    "compare_models",
    "compare_with_geotransform",
    "condition_number",
    "fit_with_check_points",
    "hull_coverage",
    "largest_scale",
    "leave_one_out_errors",
    "leave_one_out_residuals",
    "mean_error",
    "pec_thresholds",
    "predicted_error_map",
    "refine_gcps",
    "residuals",
    "rms_error",
]


