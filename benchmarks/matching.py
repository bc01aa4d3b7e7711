"""Region matching: each solver's success and time, and each fitness's optimum, on seeded meshes.

    python benchmarks/matching.py [--sizes 5 8 12] [--seeds 30] [--no-real]

Writes three tables under benchmarks/results/ (chapter 6 of the book loads and shows them),
each CSV opening with '#' lines that give the command, the seeds and the machine:

- matching_solvers.csv: rsgeo.matching.success_table: the paper's binary GA, an integer-coded
  GA and SciPy's quadratic assignment (FAQ, 20 restarts) on synthetic meshes of each size, with
  exact-match rate, share of segments matched right, mean and worst seconds per run.
- matching_fitness.csv: rsgeo.matching.fitness_comparison: how often the exhaustive optimum of
  the paper's fitness and of the "compact" variant is the true matching, and how often the
  paper's GA searching each finds the truth (n = 5 and 6, a = 0.5 and 0.7, as-is and with one
  segment at 31 % of its area).
- matching_real.csv: the same for chapter 6's real scene (CBERS-2B CCD NDVI, 20 m, against a
  30 m copy rotated 5° and shifted): exhaustive search over all 9^8 solutions (minutes) and
  the GA with each of the seeds. --no-real skips it.
"""

import argparse
import platform
import sys
import time
from datetime import date
from pathlib import Path

import affine
import numpy as np
import pandas as pd

from rsgeo import data, matching, regions, resample

RESULTS = Path(__file__).resolve().parent / "results"


def real_scene():
    """Chapter 6's real scene: reference and adjustment meshes, and the true matching."""
    ccd = data.load("cbers2b_rgb342")
    vegetation = regions.ndvi(ccd.array[0], ccd.array[1])
    centre = ccd.transform @ (ccd.shape[1] / 2, ccd.shape[0] / 2)
    adjustment_transform = (affine.Affine.translation(centre[0] + 150, centre[1] - 90)
                            @ affine.Affine.rotation(5)
                            @ affine.Affine(30, 0, -106 * 30, 0, -30, 106 * 30))
    adjustment = resample.warp(vegetation, ~ccd.transform, (212, 212), adjustment_transform,
                               method="bilinear", nodata=-1.0)
    reference = regions.keep_largest(
        regions.forest_segments(vegetation, threshold=0.55, min_area=25), 8)
    moved = regions.keep_largest(regions.forest_segments(adjustment, threshold=0.55, min_area=11), 8)
    to_reference = ~ccd.transform @ adjustment_transform
    mapped = np.column_stack(to_reference @ (moved.centroids[:, 0], moved.centroids[:, 1]))
    truth, _ = matching.true_matching(reference.centroids, mapped, tolerance=10)
    return (matching.Mesh(reference.centroids, reference.areas, pixel_size=20),
            matching.Mesh(moved.centroids, moved.areas, pixel_size=30), truth)


def real_table(seeds):
    reference, adjustment, truth = real_scene()
    rows = []
    for variant in matching.VARIANTS:
        best = matching.exhaustive_match(reference, adjustment, one_to_one=False, variant=variant)
        runs = [matching.genetic_match(reference, adjustment, seed=seed, variant=variant).solution
                for seed in seeds]
        rows.append({"case": "CBERS-2B CCD, 20 m against 30 m", "n": len(adjustment), "a": 0.5,
                     "fitness": variant, "runs": len(seeds), "truth": str(truth.tolist()),
                     "FA of the truth": matching.fitness(truth, reference, adjustment, variant=variant),
                     "optimum": str(best.solution.tolist()), "FA of the optimum": best.fitness,
                     "optimum is the truth (%)": 100.0 * np.array_equal(best.solution, truth),
                     "GA finds the truth (%)": 100 * np.mean([np.array_equal(s, truth) for s in runs]),
                     "GA finds the optimum (%)":
                         100 * np.mean([np.array_equal(s, best.solution) for s in runs])})
    return pd.DataFrame(rows)


def save(table, name, seeds, seconds):
    RESULTS.mkdir(exist_ok=True)
    header = (f"# command: python benchmarks/{Path(__file__).name} {' '.join(sys.argv[1:])}\n"
              f"# seeds: {seeds[0]} to {seeds[-1]} ({len(seeds)} seeds)\n"
              f"# run on {date.today()}, {platform.machine()} {platform.python_version()}, "
              f"{seconds:.0f} s; times depend on the machine and its load\n")
    path = RESULTS / name
    path.write_text(header + table.to_csv(index=False, float_format="%.4f"))
    print(f"wrote {path.relative_to(RESULTS.parent.parent)}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[5, 8, 12])
    parser.add_argument("--seeds", type=int, default=30)
    parser.add_argument("--no-real", action="store_true", help="skip the real scene (minutes)")
    arguments = parser.parse_args()
    seeds = list(range(arguments.seeds))
    with pd.option_context("display.width", 160, "display.max_columns", 12):
        for name, compute in (
                ("matching_solvers.csv",
                 lambda: matching.success_table(sizes=arguments.sizes, seeds=seeds).reset_index()),
                ("matching_fitness.csv", lambda: matching.fitness_comparison(seeds=seeds)),
                ("matching_real.csv", lambda: real_table(seeds))):
            if name == "matching_real.csv" and arguments.no_real:
                continue
            start = time.perf_counter()
            table = compute()
            print(table.round(3))
            save(table, name, seeds, time.perf_counter() - start)
