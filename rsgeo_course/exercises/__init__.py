"""Checks for the course's exercises: a verdict that teaches, not a bare assert.

Every task in ``exercises/`` ends with a call such as ``check_rms(rms, ...)``. The check
recomputes the right answer with rsgeo and returns a :class:`Verdict`: "Correct", or "Not yet"
with which way and roughly how far the answer is off (never the expected value) and the hint for
the mistake it recognises.

One module per chapter's exercise notebook holds its checks; each check has a
:class:`Declaration` (``check.declaration``, :func:`declarations`): the task's inputs, the right
answer computed from them, and the mistakes it recognises, each a :class:`Mistake` (the wrong
answer it produces and its hint). The verdict engine, shared by all, is
``rsgeo_course.exercises.engine``; :func:`recognised_mistakes` lists a check's hints for the
teaching guide.
"""

from .engine import (
                     Declaration,
                     ExerciseNotSolved,
                     Mistake,
                     Verdict,
                     declaration,
                     declarations,
                     recognised_mistakes,
)
from .ex01_distortions import check_pixel_growth, check_skew, check_swath
from .ex02_georeferencing import (
                     check_blunder,
                     check_degree_choice,
                     check_design_matrix,
                     check_pec_class,
                     check_rms,
)
from .ex02b_datums import check_datum_shift_pixels, check_grid_vs_parameters
from .ex03b_models import check_helmert, check_model_choice, check_projective_matrix
from .ex04_resampling import (
                     check_bilinear,
                     check_grid_extent,
                     check_method_for_classes,
                     check_output_pixel_size,
                     check_overshoot,
)
from .ex04b_terrain import (
                     check_displacement,
                     check_geoid_shift,
                     check_height_budget,
                     check_rpc_position,
)
from .ex04c_sensors import check_bias_shift, check_compensated_rms
from .ex05_regression import check_filter_size, check_gain_offset, check_truncation_levels
from .ex06_matching import check_decode, check_fitness, check_suboptimal_segment
from .ex06c_registration import (
                     check_check_point_error,
                     check_composed_tiepoint,
                     check_keypoint_position,
)

__all__ = [
    "ExerciseNotSolved", "Verdict", "check_skew", "check_pixel_growth", "check_swath",
    "check_design_matrix", "check_rms", "check_blunder", "check_degree_choice",
    "check_pec_class",
    "check_bilinear", "check_method_for_classes", "check_overshoot", "check_gain_offset",
    "check_truncation_levels", "check_filter_size", "check_fitness", "check_decode",
    "check_suboptimal_segment", "check_datum_shift_pixels", "check_grid_vs_parameters",
    "check_helmert", "check_projective_matrix", "check_model_choice",
    "check_output_pixel_size", "check_grid_extent",
    "recognised_mistakes",
    "check_displacement", "check_height_budget", "check_rpc_position", "check_geoid_shift",
    "check_bias_shift", "check_compensated_rms",
    "check_keypoint_position", "check_composed_tiepoint", "check_check_point_error",
    "Declaration", "Mistake", "declaration", "declarations",
]
