"""Experiments on the matchers of :mod:`rsgeo.registration` (chapter 6's tables; beyond the paper).

The harness behind ``python benchmarks/matching.py`` and chapter 6's live run (course tooling,
not part of rsgeo; the chapter imports it from this folder): seeded synthetic meshes
(:func:`rsgeo.synthetic.synthetic_meshes`) and the real CBERS scene, each searched by the
paper's GA and its peers, each answer compared with the true matching and with the certified
optimum of the fitness (:func:`rsgeo.registration.optimum_match`).
"""

import time

import affine
import numpy as np
import pandas as pd

from rsgeo import data, registration, resample
from rsgeo.registration import (
    VARIANTS,
    Mesh,
    exhaustive_match,
    fitness,
    genetic_match,
    optimum_match,
    qap_match,
    true_matching,
)
from rsgeo.synthetic import synthetic_meshes

__all__ = ["MATCHERS", "success_table", "fitness_comparison", "real_scene", "real_table"]

#: The matchers compared by :func:`success_table`:
#: name -> matcher(reference, adjustment, alpha, seed).
MATCHERS = {
    "GA, binary (the paper)": lambda ref, adj, alpha, seed: genetic_match(ref, adj, alpha,
                                                                          seed=seed),
    "GA, integer": lambda ref, adj, alpha, seed: genetic_match(ref, adj, alpha, seed=seed,
                                                               encoding="integer"),
    "QAP (SciPy FAQ, 20 restarts)": lambda ref, adj, alpha, seed: qap_match(ref, adj, alpha,
                                                                            seed=seed),
}


def success_table(sizes=(5, 8), seeds=range(30), alpha=0.5, shrink=None, matchers=None):
    """How often each matcher reaches the optimum and the truth, and how fast, on seeded meshes.

    For every size n and seed, :func:`rsgeo.synthetic.synthetic_meshes` makes
    a reference mesh and a noisy, shuffled copy with a known true matching.
    The optimum of the paper's fitness over all (n + 1)^n solutions (0 and
    many-to-one included) is found by :func:`rsgeo.registration.optimum_match`
    (branch and bound, certified); each matcher then searches the same
    meshes with the same seed. A run reaches the optimum when its FA is the
    optimum's (within 1e-9), and finds the truth when it returns the true
    matching.

    Parameters
    ----------
    sizes : sequence of int
        Segments per mesh (3 or more).
    seeds : iterable of int
        One mesh, and one run of each matcher, per seed.
    alpha : float
        Weight of size against layout in FA.
    shrink : (int, float), optional
        Passed to ``synthetic_meshes``: one segment keeps only this share of its area.
    matchers : dict, optional
        name -> matcher(reference, adjustment, alpha, seed) returning a
        :class:`rsgeo.registration.MatchResult`; default :data:`MATCHERS`.

    Returns
    -------
    pandas.DataFrame
        Indexed by (n, matcher): "runs", "optimum reached (%)", "exact matches (%)"
        (the truth), "segments right (%)", "mean s/run", "worst s/run", and
        "optimum", which says what the optimum is: certified by branch and
        bound over all (n + 1)^n solutions in so many of the seeds (where the
        search gave up, the best FA known: the search's, the truth's, every
        matcher's), and how often it is the truth.

    Raises
    ------
    ValueError
        For a size under 3 or no seeds.

    Examples
    --------
    >>> table = success_table(sizes=(5,), seeds=range(2))
    >>> table.loc[(5, "GA, binary (the paper)"), "optimum reached (%)"]
    np.float64(100.0)
    """
    sizes, seeds = [int(n) for n in sizes], list(seeds)
    if not seeds or any(n < 3 for n in sizes):
        raise ValueError(f"success_table needs sizes of 3 or more segments and at least one seed, "
                         f"got sizes {sizes} and {len(seeds)} seeds")
    matchers = MATCHERS if matchers is None else matchers
    rows = []
    for n in sizes:
        cases = [synthetic_meshes(n, seed=seed, shrink=shrink) for seed in seeds]
        optima = [optimum_match(reference, adjustment, alpha, incumbent=truth)
                  for reference, adjustment, truth in cases]
        best = [optimum.fitness for optimum in optima]
        results = {}
        for name, matcher in matchers.items():
            runs = []
            for seed, (reference, adjustment, _) in zip(seeds, cases):
                start = time.perf_counter()
                result = matcher(reference, adjustment, alpha, seed)
                runs.append((result, time.perf_counter() - start))
            results[name] = runs
            # an uncertified optimum is the best FA anyone found
            best = [max(b, result.fitness) for b, (result, _) in zip(best, runs)]
        certified = sum(optimum.optimal for optimum in optima)
        is_truth = sum(np.array_equal(optimum.solution, truth) and optimum.fitness >= b - 1e-9
                       for optimum, b, (_, _, truth) in zip(optima, best, cases))
        meaning = (f"max FA over all {n + 1}^{n} solutions by branch and bound: certified in "
                   f"{certified} of {len(seeds)} seeds"
                   + ("" if certified == len(seeds) else ", else the best FA found by any search")
                   + f"; it is the truth in {is_truth}")
        for name, runs in results.items():
            seconds = [s for _, s in runs]
            answers = [(result, truth) for (result, _), (_, _, truth) in zip(runs, cases)]
            rows.append({
                "n": n, "matcher": name, "runs": len(seeds),
                "optimum reached (%)": 100 * np.mean([r.fitness >= b - 1e-9
                                                      for (r, _), b in zip(runs, best)]),
                "exact matches (%)": 100 * np.mean([np.array_equal(r.solution, truth)
                                                    for r, truth in answers]),
                "segments right (%)": 100 * np.mean([np.mean(r.solution == truth)
                                                     for r, truth in answers]),
                "mean s/run": np.mean(seconds), "worst s/run": np.max(seconds),
                "optimum": meaning})
    return pd.DataFrame(rows).set_index(["n", "matcher"])


def fitness_comparison(sizes=(5, 6), seeds=range(30), alphas=(0.5, 0.7), shrink_share=0.31,
                       variants=VARIANTS):
    """How often each fitness's optimum, and the GA searching it, is the true matching.

    For every size n, seed and weight a, :func:`rsgeo.synthetic.synthetic_meshes`
    makes a reference mesh and a noisy, shuffled copy with a known true
    matching, once as it is ("one-to-one") and once with reference segment 3
    keeping only ``shrink_share`` of its area (the paper's Landsat 2002 case).
    Each variant of :func:`rsgeo.registration.fitness` is maximised by exhaustive
    search over all (n + 1)^n solutions (0 and many-to-one included) and by
    the paper's GA (same seed).

    Parameters
    ----------
    sizes : sequence of int
        Segments per mesh; (n + 1)^n solutions each, so keep n <= 7.
    seeds : iterable of int
    alphas : sequence of float
        Weights a of size against layout.
    shrink_share : float
        Share of its area the shrunk segment keeps.
    variants : sequence of str
        Fitness variants to compare.

    Returns
    -------
    pandas.DataFrame
        One row per (case, n, a, variant): runs, "optimum is the truth (%)",
        "GA finds the truth (%)", "GA finds the optimum (%)" (the GA's FA equals
        the optimum's, within 1e-9).

    Raises
    ------
    ValueError
        For a size under 3 or over 7, or an unknown variant.

    Examples
    --------
    >>> table = fitness_comparison(sizes=(4,), seeds=range(2), alphas=(0.5,))
    >>> table["GA finds the optimum (%)"].tolist()
    [100.0, 100.0, 100.0, 100.0]
    """
    for variant in variants:
        if variant not in VARIANTS:
            raise ValueError(f"unknown variant {variant!r}; choose one of "
                             f"{', '.join(map(repr, VARIANTS))}")
    if any(not 3 <= int(n) <= 7 for n in sizes):
        raise ValueError(f"sizes must be 3 to 7 segments (exhaustive search over (n + 1)^n), got "
                         f"{list(sizes)}")
    seeds = list(seeds)
    rows = []
    cases = (("one-to-one", None), (f"one segment at {shrink_share:.0%}", (2, shrink_share)))
    for case, shrink in cases:
        for n in sizes:
            for alpha in alphas:
                counts = {variant: [0, 0, 0] for variant in variants}
                for seed in seeds:
                    reference, adjustment, truth = synthetic_meshes(n, seed=seed, shrink=shrink)
                    for variant in variants:
                        best = exhaustive_match(reference, adjustment, alpha, one_to_one=False,
                                                variant=variant)
                        ga = genetic_match(reference, adjustment, alpha, seed=seed,
                                           variant=variant)
                        counts[variant][0] += np.array_equal(best.solution, truth)
                        counts[variant][1] += np.array_equal(ga.solution, truth)
                        counts[variant][2] += ga.fitness >= best.fitness - 1e-9
                for variant, (optimum, ga_truth, ga_optimum) in counts.items():
                    rows.append({"case": case, "n": n, "a": alpha, "fitness": variant,
                                 "runs": len(seeds),
                                 "optimum is the truth (%)": 100 * optimum / len(seeds),
                                 "GA finds the truth (%)": 100 * ga_truth / len(seeds),
                                 "GA finds the optimum (%)": 100 * ga_optimum / len(seeds)})
    return pd.DataFrame(rows)


def real_scene():
    """Chapter 6's real scene: CBERS-2B CCD NDVI (20 m) against a 30 m copy, rotated and shifted.

    The reference keeps the 8 largest forest segments (NDVI above 0.55) of the
    scene; the adjustment, the same ground resampled to 30 m pixels, rotated
    by 5° and shifted by (150, −90) m, its own 8 largest. The true matching
    comes from the known transform (:func:`rsgeo.registration.true_matching`, 10
    reference pixels).

    Returns
    -------
    reference, adjustment : rsgeo.registration.Mesh
        In metres.
    truth : ndarray of int
        True reference label of each adjustment segment, 0 = none.
    """
    ccd = data.load("cbers2b_rgb342")
    vegetation = registration.ndvi(ccd.array[0], ccd.array[1])
    centre = ccd.transform @ (ccd.shape[1] / 2, ccd.shape[0] / 2)
    adjustment_transform = (affine.Affine.translation(centre[0] + 150, centre[1] - 90)
                            @ affine.Affine.rotation(5)
                            @ affine.Affine(30, 0, -106 * 30, 0, -30, 106 * 30))
    # scale=1.0: plain 2 x 2 bilinear sampling of the 20 m scene at 30 m, as chapter 6 does
    # (gdalwarp would widen the kernel for this downsampling; chapter 4 shows the difference)
    adjustment = resample.warp(vegetation, ~ccd.transform, (212, 212), adjustment_transform,
                               method="bilinear", dst_nodata=-1.0, scale=1.0)
    reference = registration.keep_largest(
        registration.forest_segments(vegetation, threshold=0.55, min_area=25), 8)
    moved = registration.keep_largest(
        registration.forest_segments(adjustment, threshold=0.55, min_area=11), 8)
    to_reference = ~ccd.transform @ adjustment_transform
    mapped = np.column_stack(to_reference @ (moved.centroids[:, 0], moved.centroids[:, 1]))
    truth, _ = true_matching(reference.centroids, mapped, tolerance=10)
    return (Mesh(reference.centroids, reference.areas, pixel_size=20),
            Mesh(moved.centroids, moved.areas, pixel_size=30), truth)


def real_table(seeds=range(30), alpha=0.5):
    """The real scene of :func:`real_scene`: each fitness's optimum, the truth and the GA's runs.

    The optimum over all 9^8 solutions is found by exhaustive search; the
    paper's GA runs once per seed.

    Parameters
    ----------
    seeds : iterable of int
        One run of the GA per seed, for each fitness variant.
    alpha : float
        Weight a of size against layout in FA, in [0, 1].

    Returns
    -------
    pandas.DataFrame
        One row per fitness variant: the truth and the optimum with their FA,
        whether the optimum is the truth, and how often the GA finds each.

    Raises
    ------
    ValueError
        For alpha outside [0, 1] (from :func:`rsgeo.registration.fitness`). No
        seeds give NaN percentages, not an error.

    References
    ----------
    The GA paper: *Homologous regions by genetic algorithms for the registration
    of multi-sensor images* (GEOSAFRAS programme), whose fitness and GA these are.
    """
    seeds = list(seeds)
    reference, adjustment, truth = real_scene()
    rows = []
    for variant in VARIANTS:
        best = exhaustive_match(reference, adjustment, alpha, one_to_one=False, variant=variant)
        runs = [genetic_match(reference, adjustment, alpha, seed=seed, variant=variant)
                for seed in seeds]
        rows.append({"case": "CBERS-2B CCD, 20 m against 30 m", "n": len(adjustment), "a": alpha,
                     "fitness": variant, "runs": len(seeds), "truth": str(truth.tolist()),
                     "FA of the truth": fitness(truth, reference, adjustment, alpha, variant),
                     "optimum": str(best.solution.tolist()), "FA of the optimum": best.fitness,
                     "optimum is the truth (%)": 100.0 * np.array_equal(best.solution, truth),
                     "GA finds the truth (%)":
                         100 * np.mean([np.array_equal(run.solution, truth) for run in runs]),
                     "GA finds the optimum (%)":
                         100 * np.mean([run.fitness >= best.fitness - 1e-9 for run in runs])})
    return pd.DataFrame(rows)
