"""rsgeo.registration and rsgeo.registration: the GA paper's fitness, search and registration."""

import itertools
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsgeo import registration, synthetic
from rsgeo.registration import _genetic as genetic


def test_fitness_by_hand_on_three_segments():
    reference = registration.Mesh([[0, 0], [300, 0], [0, 400]], [100, 200, 300])
    adjustment = registration.Mesh([[10, 5], [5, 395], [305, 10]], [110, 290, 190])
    # solution [1, 3, 2]: sizes |100-110| + |200-190| + |300-290| = 30 over 600 -> FS = 0.95
    # distances: D_R = 300, 400, 500; D_A(1,2) = |(10,5)-(305,10)| etc.
    d12 = np.hypot(295, 5)        # reference 1-2 <- adjustment 1-3
    d13 = np.hypot(5, 390)        # reference 1-3 <- adjustment 1-2
    d23 = np.hypot(300, 385)      # reference 2-3 <- adjustment 3-2
    fe = 1 - (abs(300 - d12) + abs(400 - d13) + abs(500 - d23)) / 1200
    assert registration.fitness([1, 3, 2], reference, adjustment) == pytest.approx(
        0.5 * 0.95 + 0.5 * fe)
    assert registration.fitness([1, 3, 2], reference, adjustment, alpha=1.0) == pytest.approx(0.95)


def test_fitness_of_many_to_one_and_unmatched_segments():
    reference = registration.Mesh([[0, 0], [100, 0], [0, 100]], [100, 100, 100])
    split = registration.Mesh([[-10, 0], [10, 0], [100, 0], [0, 100]], [50, 50, 100, 100])
    assert registration.fitness([1, 1, 2, 3], reference, split) == pytest.approx(1.0)
    # leaving a reference segment unmatched costs its whole area: FS = 1 - 100/300
    assert registration.fitness([1, 1, 2, 0], reference, split, alpha=1.0) == pytest.approx(2 / 3)


def test_chromosome_round_trip():
    solution = np.array([3, 1, 1, 2, 4, 5])
    assert registration.encode(solution).size == 48
    np.testing.assert_array_equal(registration.decode(registration.encode(solution)), solution)


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 16).flatmap(
    lambda bits: st.tuples(st.just(bits),
                           st.lists(st.integers(0, 2**bits - 1), min_size=1, max_size=20))))
def test_decode_undoes_encode(bits_and_labels):
    bits, labels = bits_and_labels
    chromosome = registration.encode(labels, bits=bits)
    assert chromosome.shape == (len(labels) * bits,) and set(np.unique(chromosome)) <= {0, 1}
    np.testing.assert_array_equal(registration.decode(chromosome, bits=bits), labels)


@settings(max_examples=200, deadline=None)
@given(st.integers(1, 16).flatmap(
    lambda bits: st.tuples(st.just(bits),
                           st.lists(st.integers(0, 1), min_size=bits, max_size=bits * 12)
                           .filter(lambda chromosome: len(chromosome) % bits == 0))))
def test_encode_undoes_decode(bits_and_chromosome):
    bits, chromosome = bits_and_chromosome
    labels = registration.decode(chromosome, bits=bits)
    np.testing.assert_array_equal(registration.encode(labels, bits=bits), chromosome)
    # the most significant bit first: the first bit of a gene is worth 2^(bits - 1)
    assert labels[0] == int("".join(map(str, chromosome[:bits])), 2)


def test_encode_and_decode_refuse_what_they_cannot_code():
    with pytest.raises(ValueError, match="fit in 8 bits"):
        registration.encode([256])
    with pytest.raises(ValueError, match="not a multiple"):
        registration.decode([0, 1, 1])
    with pytest.raises(ValueError, match="only 0 and 1"):
        registration.decode([0, 2, 1, 0, 0, 0, 0, 0])


# -- the optimum, certified, and the GA reaching it --------------------------------------------

def test_compiled_fitness_agrees_with_the_numpy_one_term_by_term():
    rng = np.random.default_rng(0)
    for n, shrink in ((6, None), (8, (2, 0.31)), (12, None)):
        reference, adjustment, truth = synthetic.synthetic_meshes(n, seed=n, shrink=shrink)
        solutions = np.vstack([rng.integers(0, n + 1, (300, n)), truth, np.zeros(n, int)])
        for variant in registration.VARIANTS:
            for alpha in (0.0, 0.3, 1.0):
                np.testing.assert_allclose(
                    registration.fitness_batch(solutions, reference, adjustment, alpha, variant),
                    genetic._fitness_numpy(solutions, reference, adjustment, alpha, variant),
                    rtol=0, atol=1e-12)


def test_exhaustive_search_is_the_maximum_over_every_solution():
    # against a plain loop over itertools.product, not against the truth (the optimum need not
    # be it)
    reference, adjustment, _ = synthetic.synthetic_meshes(4, seed=3, shrink=(1, 0.31))
    every = list(itertools.product(range(5), repeat=4))
    for variant in registration.VARIANTS:
        scores = [registration.fitness(s, reference, adjustment, 0.7, variant) for s in every]
        best = registration.exhaustive_match(reference, adjustment, 0.7, one_to_one=False,
                                         variant=variant, batch=37)
        assert best.evaluations == 5**4 and best.optimal
        assert best.fitness == pytest.approx(max(scores), abs=1e-12)
        np.testing.assert_array_equal(best.solution, every[int(np.argmax(scores))])
    one_to_one = registration.exhaustive_match(reference, adjustment, 0.7, one_to_one=True)
    assert one_to_one.evaluations == 24 and not one_to_one.optimal


@pytest.mark.parametrize("n, shrink", [(4, None), (5, None), (5, (2, 0.31)), (6, (0, 0.31))])
def test_branch_and_bound_finds_the_exhaustive_optimum(n, shrink):
    for seed in range(6):
        reference, adjustment, truth = synthetic.synthetic_meshes(n, seed=seed, shrink=shrink)
        for variant, alpha in itertools.product(registration.VARIANTS, (0.3, 0.5, 0.9)):
            every = registration.exhaustive_match(reference, adjustment, alpha, one_to_one=False,
                                              variant=variant)
            for incumbent in (None, truth):
                bound = registration.optimum_match(reference, adjustment, alpha, variant,
                                               incumbent=incumbent)
                assert bound.optimal
                assert bound.fitness == pytest.approx(every.fitness, abs=1e-12), (
                    seed, variant, alpha)
                assert bound.evaluations < (n + 1) ** n          # it cut branches


def test_branch_and_bound_at_twelve_segments_and_its_node_limit():
    reference, adjustment, truth = synthetic.synthetic_meshes(12, seed=0)
    best = registration.optimum_match(reference, adjustment, incumbent=truth)
    assert best.optimal and best.fitness >= registration.fitness(truth, reference,
                                                                 adjustment) - 1e-12
    # a random solution is never better than the certified optimum
    rng = np.random.default_rng(1)
    assert (registration.fitness_batch(rng.integers(0, 13, (5000, 12)), reference,
                                       adjustment).max()
            <= best.fitness)
    cut = registration.optimum_match(reference, adjustment, node_limit=50)
    assert not cut.optimal and cut.evaluations == 50


def ga_optimum_rate(n, seeds, **options):
    """Share of seeds where the GA's solution reaches the certified optimum's FA.

    Both solutions are scored by the plain NumPy fitness, so a planted bug in
    the compiled one (which the GA uses) cannot hide itself.
    """
    reached = 0
    for seed in seeds:
        reference, adjustment, truth = synthetic.synthetic_meshes(n, seed=seed)
        optimum = registration.optimum_match(reference, adjustment, incumbent=truth)
        assert optimum.optimal
        result = registration.genetic_match(reference, adjustment, seed=seed, **options)
        found, best = genetic._fitness_numpy([result.solution, optimum.solution], reference,
                                              adjustment)
        reached += found >= best - 1e-9
    return reached / len(seeds)


@pytest.mark.parametrize("n, encoding", [(8, "binary"), (12, "integer")])
def test_ga_reaches_the_certified_optimum_on_fixed_seeds(n, encoding):
    # the 100-seed rates and the seconds per run are measured by benchmarks/matching.py
    assert ga_optimum_rate(n, range(100, 110), encoding=encoding) == 1.0


def test_the_success_check_fails_on_a_planted_bug(monkeypatch):
    # the fitness's sign flipped: the GA now minimises FA, and the check above must notice
    compiled = genetic._fitness_kernel
    monkeypatch.setattr(genetic, "_fitness_kernel", lambda *arguments: -compiled(*arguments))
    assert ga_optimum_rate(8, range(100, 105)) == 0


@pytest.mark.parametrize("encoding", ["binary", "integer"])
def test_mutation_changes_each_gene_at_its_rate(encoding):
    # (mutation off does not show in the success rate: 1000 individuals and crossover alone
    # reach the optimum at n = 8; so the operator is checked on its own)
    rng = np.random.default_rng(0)
    parents = (rng.integers(0, 2, (400, 64), dtype=np.uint8) if encoding == "binary"
               else rng.integers(0, 9, (400, 8)))
    for rate in (0.0, 0.04, 0.3):
        children = genetic._mutate(rng, parents, rate, encoding, m=8)
        assert children.shape == parents.shape and children.dtype == parents.dtype
        changed = np.mean(children != parents)
        # an integer gene reset to a random label keeps its value 1 time in 9
        expected = rate if encoding == "binary" else rate * 8 / 9
        assert (abs(changed - expected)
                < 4 * np.sqrt(expected * (1 - expected) / parents.size) + 1e-12)
        if encoding == "integer":
            assert children.min() >= 0 and children.max() <= 8


def test_elitism_keeps_each_generation_best_and_without_it_the_best_falls():
    reference, adjustment, _ = synthetic.synthetic_meshes(8, seed=1)
    kept = registration.genetic_match(reference, adjustment, seed=4, generations=60,
                                  selection="roulette")
    best = np.array([h["generation_best"] for h in kept.history])
    assert len(best) == 60 and (np.diff(best) >= 0).all()
    assert kept.fitness == best[-1] == max(h["best"] for h in kept.history)
    lost = registration.genetic_match(reference, adjustment, seed=4, generations=60,
                                  selection="roulette", elite_fraction=0.0)
    assert (np.diff([h["generation_best"] for h in lost.history]) < 0).any()


def test_ga_is_seeded_and_seeds_differ():
    reference, adjustment, _ = synthetic.synthetic_meshes(6, seed=1)
    runs = [registration.genetic_match(reference, adjustment, seed=seed, generations=5)
            for seed in (4, 4, 5)]
    np.testing.assert_array_equal(runs[0].history[0]["best_solution"],
                                  runs[1].history[0]["best_solution"])
    assert [h["mean"] for h in runs[0].history] == [h["mean"] for h in runs[1].history]
    assert [h["mean"] for h in runs[0].history] != [h["mean"] for h in runs[2].history]


def test_ga_stops_when_the_best_stalls():
    reference, adjustment, _ = synthetic.synthetic_meshes(5, seed=0)
    run = registration.genetic_match(reference, adjustment, seed=0, generations=1000,
                                 stall_generations=25)
    best = [h["best"] for h in run.history]
    last_improvement = int(np.argmax(np.array(best) >= best[-1]))
    assert len(run.history) == last_improvement + 26 < 1000
    assert run.evaluations == len(run.history) * 1000       # the default population


def test_matching_does_not_import_the_synthetic_data_or_the_harness():
    code = ("import sys, rsgeo.registration; "
            "print(sorted(m for m in sys.modules if m.startswith('rsgeo.')))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True)
    assert "rsgeo.synthetic" not in loaded.stdout and "rsgeo.experiments" not in loaded.stdout


def test_registration_of_the_synthetic_two_date_pair():
    land = synthetic.two_date_landscape()
    reference = registration.forest_segments(land.reference, threshold=185)
    adjustment = registration.forest_segments(land.adjustment, threshold=185)
    result = registration.register_by_regions(reference, adjustment, land.reference_transform,
                                              reference_pixel=20, adjustment_pixel=30, seed=1,
                                              tolerance=1.0)
    assert result.rms_kept < 1.0
    # and against the truth we built in, not just the GCPs' own residuals
    map_xy = result.map_xy
    truth = np.column_stack((~land.adjustment_transform) @ (map_xy[:, 0], map_xy[:, 1]))
    assert result.model.rms(map_xy, truth) < 1.0


@pytest.mark.parametrize("call, message", [
    (lambda: registration.Mesh([[0, 0], [1, 1]], [1, 2]), "at least 3 segments"),
    (lambda: registration.Mesh([[0, 0], [1, 1], [2, 0]], [1, 2]), "same segments"),
    (lambda: registration.Mesh([[0, 0], [1, 1], [2, 0]], [1, 0, 2]), "positive"),
    (lambda: registration.fitness([1, 2, 3], MESH, MESH, alpha=1.5), "alpha must be"),
    (lambda: registration.fitness([1, 2], MESH, MESH), "one label per adjustment segment"),
    (lambda: registration.fitness([1, 2, 7], MESH, MESH), "labels must be 0"),
    (lambda: registration.genetic_match(MESH, MESH, selection="rank"), "unknown selection"),
    (lambda: registration.fitness([1, 2, 3], MESH, MESH, variant="tight"), "unknown variant"),
    (lambda: registration.exhaustive_match(MESH, MESH, variant="tight"), "unknown variant"),
    (lambda: registration.true_matching([[0, 0]], [[1, 1]], tolerance=-1), "tolerance must be"),
    (lambda: registration.optimum_match(MESH, MESH, variant="tight"), "unknown variant"),
    (lambda: registration.optimum_match(MESH, MESH, incumbent=[1, 2]), "one label per adjustment"),
])
def test_bad_input_is_a_clear_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


MESH = registration.Mesh([[0, 0], [100, 0], [0, 100]], [10, 20, 30])


def test_grouping_segments_into_regions():
    land = synthetic.two_date_landscape()
    segments = registration.forest_segments(land.reference, threshold=185)
    grouped = registration.group_segments(segments, 5)
    assert len(grouped) == 5
    assert grouped.areas.sum() == segments.areas.sum()           # regions are unions of segments
    assert set(np.unique(grouped.labels)) == set(range(6))
    largest = registration.keep_largest(segments, 3)
    np.testing.assert_array_equal(largest.areas, np.sort(segments.areas)[::-1][:3])


# -- the paper's fitness rewards piling far-apart segments; the compact variant does not ----------

REFERENCE3 = registration.Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
# adjustment segment 4 is a separate forest 100 m from segment 3, which is short of area
PILED = registration.Mesh([[0, 0], [100, 0], [0, 100], [100, 100]], [50, 80, 60, 60])


def test_paper_fitness_prefers_piling_a_far_segment_onto_one_short_of_area():
    piled = registration.fitness([1, 2, 3, 3], REFERENCE3, PILED)
    honest = registration.fitness([1, 2, 3, 0], REFERENCE3, PILED)
    assert piled > honest + 0.05       # the flaw: 0.939 against 0.880
    best = registration.exhaustive_match(REFERENCE3, PILED, one_to_one=False)
    np.testing.assert_array_equal(best.solution, [1, 2, 3, 3])


def test_compact_fitness_leaves_a_far_segment_unmatched():
    piled = registration.fitness([1, 2, 3, 3], REFERENCE3, PILED, variant="compact")
    honest = registration.fitness([1, 2, 3, 0], REFERENCE3, PILED, variant="compact")
    assert honest == pytest.approx(registration.fitness([1, 2, 3, 0], REFERENCE3, PILED))
    # a non-compact group costs S_R + S_G = 240 of 250 in DMS and leaves the layout term
    assert piled == pytest.approx(0.5 * (1 - 240 / 250) + 0.5 * 1.0)
    best = registration.exhaustive_match(REFERENCE3, PILED, one_to_one=False, variant="compact")
    np.testing.assert_array_equal(best.solution, [1, 2, 3, 0])
    ga = registration.genetic_match(REFERENCE3, PILED, seed=0, generations=60, variant="compact")
    np.testing.assert_array_equal(ga.solution, [1, 2, 3, 0])


def test_compact_fitness_keeps_a_forest_split_in_two():
    # reference segment 1 seen as its two halves: centroids 4r/(3π) from its centre
    radius = np.sqrt(400 / np.pi)
    half = 4 * radius / (3 * np.pi)
    split = registration.Mesh([[-half, 0], [half, 0], [100, 0], [0, 100]], [200, 200, 80, 120])
    reference = registration.Mesh([[0, 0], [100, 0], [0, 100]], [400, 80, 120])
    spread = registration.group_spread([1, 1, 2, 3], split)
    assert spread[0] == pytest.approx(0.86, abs=0.01)
    np.testing.assert_allclose(spread[1:], 1.0)
    for variant in registration.VARIANTS:
        assert (registration.fitness([1, 1, 2, 3], reference, split, variant=variant)
                == pytest.approx(1.0))


def test_group_spread_of_two_touching_disks_is_one_and_a_half():
    radius = np.sqrt(100 / np.pi)
    touching = registration.Mesh([[0, 0], [2 * radius, 0], [0, 500]], [100, 100, 100])
    assert registration.group_spread([1, 1, 2], touching)[0] == pytest.approx(1.5)
    assert np.isnan(registration.group_spread([1, 1, 0], touching, m=3)[1])


def test_both_variants_agree_without_many_to_one_groups():
    reference, adjustment, truth = synthetic.synthetic_meshes(6, seed=2)
    rng = np.random.default_rng(0)
    solutions = np.array([rng.permutation(6) + 1 for _ in range(50)] + [truth])
    np.testing.assert_allclose(registration.fitness_batch(solutions, reference, adjustment),
                               registration.fitness_batch(solutions, reference, adjustment,
                                                      variant="compact"))


def test_compact_fitness_finds_the_truth_where_the_paper_piles_onto_a_shrunk_segment():
    # the chapter's 31 % case at a = 0.7: the paper's optimum piles two segments onto one
    reference, shrunk, truth = synthetic.synthetic_meshes(5, seed=0, shrink=(2, 0.31))
    paper = registration.exhaustive_match(reference, shrunk, 0.7, one_to_one=False)
    compact = registration.exhaustive_match(reference, shrunk, 0.7, one_to_one=False,
                                        variant="compact")
    assert not np.array_equal(paper.solution, truth)
    assert len(np.unique(paper.solution)) < len(truth)         # a many-to-one group
    np.testing.assert_array_equal(compact.solution, truth)


def test_exhaustive_search_tries_every_solution_in_order():
    reference = registration.Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    # all 4^3 solutions score the same on a degenerate alpha: the first, [0, 0, 0], is kept
    flat = registration.exhaustive_match(reference, reference, alpha=0.0, one_to_one=False,
                                         batch=7)
    assert flat.evaluations == 4**3
    best = registration.exhaustive_match(reference, reference, one_to_one=False, batch=7)
    np.testing.assert_array_equal(best.solution, [1, 2, 3])
    one_to_one = registration.exhaustive_match(reference, reference, one_to_one=True, batch=4)
    assert one_to_one.evaluations == 6
    np.testing.assert_array_equal(one_to_one.solution, [1, 2, 3])


def test_true_matching_by_the_known_transform():
    solution, distance = registration.true_matching([[0, 0], [10, 0], [0, 10]],
                                                [[0.5, 9], [10, 1], [40, 40]], tolerance=2)
    np.testing.assert_array_equal(solution, [3, 2, 0])
    np.testing.assert_allclose(distance, [np.hypot(0.5, 1), 1, np.hypot(40, 30)])


def real_scene():
    """Chapter 6's real scene (as benchmarks/matching.py builds it)."""
    import affine

    from rsgeo import data, resample

    ccd = data.load("cbers2b_rgb342")
    vegetation = registration.ndvi(ccd.array[0], ccd.array[1])
    centre = ccd.transform @ (ccd.shape[1] / 2, ccd.shape[0] / 2)
    moved = (affine.Affine.translation(centre[0] + 150, centre[1] - 90) @ affine.Affine.rotation(5)
             @ affine.Affine(30, 0, -106 * 30, 0, -30, 106 * 30))
    image = resample.warp(vegetation, ~ccd.transform, (212, 212), moved, method="bilinear",
                          dst_nodata=-1.0)
    reference = registration.keep_largest(
        registration.forest_segments(vegetation, threshold=0.55, min_area=25), 8)
    adjustment = registration.keep_largest(
        registration.forest_segments(image, threshold=0.55, min_area=11), 8)
    to_reference = ~ccd.transform @ moved
    mapped = np.column_stack(
        to_reference @ (adjustment.centroids[:, 0], adjustment.centroids[:, 1]))
    return ccd, reference, adjustment, mapped


def test_real_scene_the_paper_piles_and_the_compact_fitness_does_not():
    ccd, reference, adjustment, mapped = real_scene()
    truth, distance = registration.true_matching(reference.centroids, mapped, tolerance=10)
    np.testing.assert_array_equal(truth, [1, 2, 3, 4, 5, 8, 0, 0])
    assert distance[6] > 25 and distance[7] > 50
    reference_mesh = registration.Mesh(reference.centroids, reference.areas, pixel_size=20)
    adjustment_mesh = registration.Mesh(adjustment.centroids, adjustment.areas, pixel_size=30)
    piled = [1, 2, 3, 4, 5, 8, 1, 1]
    assert registration.fitness(piled, reference_mesh, adjustment_mesh) > registration.fitness(
        truth, reference_mesh, adjustment_mesh)
    assert (registration.fitness(piled, reference_mesh, adjustment_mesh, variant="compact")
            < registration.fitness(truth, reference_mesh, adjustment_mesh,
                               variant="compact"))
    paper = registration.register_by_regions(reference, adjustment, ccd.transform, 20, 30, seed=0)
    compact = registration.register_by_regions(reference, adjustment, ccd.transform, 20, 30,
                                               seed=0,
                                           variant="compact")
    np.testing.assert_array_equal(paper.match.solution, piled)
    np.testing.assert_array_equal(compact.match.solution, truth)
    assert compact.kept.sum() >= 5 and compact.rms_kept < 1.0


def test_evolution_frame_spans_the_whole_run_from_the_first_generation():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rsgeo.widgets import draw_evolution_frame

    from figure_audit import figure_problems

    reference, adjustment, truth = synthetic.synthetic_meshes(5, seed=1)
    run = registration.genetic_match(reference, adjustment, seed=0, generations=20)
    figure = draw_evolution_frame(reference, adjustment, truth, run.history[:1], generations=20)
    evolution = figure.axes[1]
    assert evolution.get_xlim()[1] >= 19 and evolution.get_xlim()[0] <= 0
    assert figure_problems(figure) == []
    with pytest.raises(ValueError, match="at least one generation"):
        draw_evolution_frame(reference, adjustment, truth, [])
    plt.close(figure)


def test_binary_coding_refuses_more_labels_than_8_bits_hold():
    # 256+ reference segments gave an OverflowError from NumPy
    rng = np.random.default_rng(0)
    adjustment = registration.Mesh(rng.uniform(0, 1000, (4, 2)), rng.uniform(1, 10, 4))
    big = registration.Mesh(rng.uniform(0, 1000, (300, 2)), rng.uniform(1, 10, 300))
    with pytest.raises(ValueError, match='use the integer coding \\(encoding="integer"\\)'):
        registration.genetic_match(big, adjustment, seed=0, generations=2, population_size=10)
    result = registration.genetic_match(big, adjustment, seed=0, generations=2, population_size=10,
                                    encoding="integer")
    assert result.solution.max() <= 300
    # 255 labels still fit in 8 bits: the binary coding runs
    most = registration.Mesh(rng.uniform(0, 1000, (255, 2)), rng.uniform(1, 10, 255))
    result = registration.genetic_match(most, adjustment, seed=0, generations=2,
                                        population_size=10)
    assert 0 <= result.solution.min() and result.solution.max() <= 255


@pytest.mark.parametrize("call, name", [
    (lambda mesh: registration.genetic_match([[0, 0], [1, 0], [0, 1]], mesh), "reference"),
    (lambda mesh: registration.genetic_match(mesh, None), "adjustment"),
    (lambda mesh: registration.fitness([1, 2, 3], mesh, "mesh"), "adjustment"),
    (lambda mesh: registration.exhaustive_match({}, mesh), "reference"),
    (lambda mesh: registration.optimum_match(mesh, 3), "adjustment"),
    (lambda mesh: registration.qap_match(np.zeros((3, 2)), mesh), "reference"),
    (lambda mesh: registration.matched_centroids([1, 2, 3], mesh, [1]), "adjustment"),
    (lambda mesh: registration.group_spread([1, 2, 3], "mesh"), "adjustment"),
])
def test_what_is_not_a_mesh_is_a_type_error_naming_the_argument(call, name):
    mesh = registration.Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    with pytest.raises(TypeError,
                       match=f"{name} must be a rsgeo.registration.Mesh.*Mesh\\(centroids"):
        call(mesh)


@pytest.mark.parametrize("kwargs, error, message", [
    ({"seed": np.nan}, ValueError, "seed must be a finite number"),
    ({"seed": 2.5}, ValueError, "seed must be a whole number"),
    ({"population_size": np.nan}, ValueError, "population_size must be a finite number"),
    ({"generations": True}, TypeError, "generations must be a number"),
    ({"stall_generations": 0.5}, ValueError, "stall_generations must be a whole number"),
])
def test_genetic_match_counts_and_seed_are_whole_numbers(kwargs, error, message):
    mesh = registration.Mesh([[0, 0], [100, 0], [0, 100]], [50, 80, 120])
    with pytest.raises(error, match=message):
        registration.genetic_match(mesh, mesh, **kwargs)
