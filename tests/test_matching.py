"""rsgeo.matching and rsgeo.regions: the GA paper's fitness, search and registration."""

import numpy as np
import pytest

from rsgeo import gcp, matching, regions, synthetic


def test_fitness_by_hand_on_three_segments():
    reference = matching.Mesh([[0, 0], [300, 0], [0, 400]], [100, 200, 300])
    adjustment = matching.Mesh([[10, 5], [5, 395], [305, 10]], [110, 290, 190])
    # solution [1, 3, 2]: sizes |100-110| + |200-190| + |300-290| = 30 over 600 -> FS = 0.95
    # distances: D_R = 300, 400, 500; D_A(1,2) = |(10,5)-(305,10)| etc.
    d12 = np.hypot(295, 5)        # reference 1-2 <- adjustment 1-3
    d13 = np.hypot(5, 390)        # reference 1-3 <- adjustment 1-2
    d23 = np.hypot(300, 385)      # reference 2-3 <- adjustment 3-2
    fe = 1 - (abs(300 - d12) + abs(400 - d13) + abs(500 - d23)) / 1200
    assert matching.fitness([1, 3, 2], reference, adjustment) == pytest.approx(0.5 * 0.95 + 0.5 * fe)
    assert matching.fitness([1, 3, 2], reference, adjustment, alpha=1.0) == pytest.approx(0.95)


def test_fitness_of_many_to_one_and_unmatched_segments():
    reference = matching.Mesh([[0, 0], [100, 0], [0, 100]], [100, 100, 100])
    split = matching.Mesh([[-10, 0], [10, 0], [100, 0], [0, 100]], [50, 50, 100, 100])
    assert matching.fitness([1, 1, 2, 3], reference, split) == pytest.approx(1.0)
    # leaving a reference segment unmatched costs its whole area: FS = 1 - 100/300
    assert matching.fitness([1, 1, 2, 0], reference, split, alpha=1.0) == pytest.approx(2 / 3)


def test_chromosome_round_trip():
    solution = np.array([3, 1, 1, 2, 4, 5])
    assert matching.encode(solution).size == 48
    np.testing.assert_array_equal(matching.decode(matching.encode(solution)), solution)


@pytest.mark.parametrize("n", [5, 8])
def test_ga_finds_the_exhaustive_optimum_in_95_percent_of_30_runs(n):
    # (its speed, under a second per run here, is measured by benchmarks/matching.py, not asserted)
    found = 0
    for seed in range(30):
        reference, adjustment, truth = synthetic.synthetic_meshes(n, centroid_noise=1.0, area_noise=0.1, seed=seed)
        optimum = matching.exhaustive_match(reference, adjustment, one_to_one=n > 5)
        result = matching.genetic_match(reference, adjustment, seed=seed)
        found += np.array_equal(result.solution, optimum.solution)
    assert found >= 29              # 95 % of 30 is 28.5


def test_exhaustive_over_all_solutions_agrees_with_one_to_one_here():
    reference, adjustment, truth = synthetic.synthetic_meshes(5, seed=11)
    everything = matching.exhaustive_match(reference, adjustment, one_to_one=False)
    assert everything.evaluations == 6**5
    np.testing.assert_array_equal(everything.solution, truth)


def test_ga_history_is_monotone_and_seeded():
    reference, adjustment, _ = synthetic.synthetic_meshes(6, seed=1)
    first = matching.genetic_match(reference, adjustment, seed=4, generations=30, selection="roulette")
    again = matching.genetic_match(reference, adjustment, seed=4, generations=30, selection="roulette")
    best = [h["best"] for h in first.history]
    assert best == sorted(best) and len(best) == 30
    np.testing.assert_array_equal(first.solution, again.solution)


def test_registration_of_the_synthetic_two_date_pair():
    land = synthetic.two_date_landscape()
    reference = regions.forest_segments(land.reference, threshold=185)
    adjustment = regions.forest_segments(land.adjustment, threshold=185)
    registration = matching.register_by_regions(reference, adjustment, land.reference_transform,
                                                reference_pixel=20, adjustment_pixel=30, seed=1, tolerance=1.0)
    assert registration.rms_kept < 1.0
    # and against the truth we built in, not just the GCPs' own residuals
    map_xy = registration.map_xy
    truth = np.column_stack((~land.adjustment_transform) @ (map_xy[:, 0], map_xy[:, 1]))
    assert gcp.rms_error(registration.model(map_xy), truth) < 1.0


@pytest.mark.parametrize("call, message", [
    (lambda: matching.Mesh([[0, 0], [1, 1]], [1, 2]), "at least 3 segments"),
    (lambda: matching.Mesh([[0, 0], [1, 1], [2, 0]], [1, 2]), "same segments"),
    (lambda: matching.Mesh([[0, 0], [1, 1], [2, 0]], [1, 0, 2]), "positive"),
    (lambda: matching.fitness([1, 2, 3], MESH, MESH, alpha=1.5), "alpha must be"),
    (lambda: matching.fitness([1, 2], MESH, MESH), "one label per adjustment segment"),
    (lambda: matching.fitness([1, 2, 7], MESH, MESH), "labels must be 0"),
    (lambda: matching.genetic_match(MESH, MESH, selection="rank"), "unknown selection"),
])
def test_bad_input_is_a_clear_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


MESH = matching.Mesh([[0, 0], [100, 0], [0, 100]], [10, 20, 30])


def test_grouping_segments_into_regions():
    land = synthetic.two_date_landscape()
    segments = regions.forest_segments(land.reference, threshold=185)
    grouped = regions.group_segments(segments, 5)
    assert len(grouped) == 5
    assert grouped.areas.sum() == segments.areas.sum()           # regions are unions of segments
    assert set(np.unique(grouped.labels)) == set(range(6))
    largest = regions.keep_largest(segments, 3)
    np.testing.assert_array_equal(largest.areas, np.sort(segments.areas)[::-1][:3])
