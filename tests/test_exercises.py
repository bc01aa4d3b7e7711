"""The exercise checks: right answers pass, wrong ones get a hint, placeholders stop the notebook."""

import numpy as np
import pytest

from rsgeo import exercises, synthetic


def test_placeholder_raises_exercise_not_solved():
    with pytest.raises(exercises.ExerciseNotSolved, match="`skew_km` is still `...`"):
        exercises.check_skew(..., 0.0, 185.0, 705.0, 98.2)


def test_wrong_answers_get_a_verdict_with_a_hint():
    verdict = exercises.check_swath(2014.0, 55.0, 705.0)          # the flat-Earth answer
    assert not verdict and "should be about 2330" in verdict.message and "2·R·γ" in verdict.hint
    assert "Not yet" in verdict._repr_html_()


def test_rms_hint_names_the_common_mistake():
    predicted, observed = np.array([[3.0, 4.0], [0.0, 0.0]]), np.zeros((2, 2))
    verdict = exercises.check_rms(np.sqrt(25 / 4), predicted, observed)   # divided by 2n
    assert not verdict and "divide by n" in verdict.hint
    assert exercises.check_rms(np.sqrt(25 / 2), predicted, observed)


def test_design_matrix_names_the_wrong_column():
    points = np.array([[1.0, 2.0], [3.0, 5.0], [4.0, 1.0]])
    wrong = np.column_stack([np.ones(3), points[:, 1], points[:, 0]])
    verdict = exercises.check_design_matrix(wrong, points)
    assert not verdict and "x, y" in verdict.message


def test_blunder_check_knows_the_planted_blunder():
    pair = synthetic.distorted_pair(seed=2)
    assert exercises.check_blunder(pair.gcps.ids[pair.blunder], pair.gcps, order=2)
    other = pair.gcps.ids[(pair.blunder + 1) % len(pair.gcps)]
    assert not exercises.check_blunder(other, pair.gcps, order=2)


def test_method_for_classes():
    assert exercises.check_method_for_classes("nearest")
    assert not exercises.check_method_for_classes("cubic")
