"""Region matching: each solver's success and time, and each fitness's optimum, on seeded meshes.

    python benchmarks/matching.py [--sizes 5 8 12] [--seeds 100] [--fitness-seeds 30] [--no-real]

Writes three tables under benchmarks/results/ (chapter 6 of the book loads and shows them),
each CSV opening with '# key: value' lines that give the command, the seeds and the machine.
The experiments themselves live in benchmarks/ga_experiments.py (the chapter's live run calls
the same code):

- matching_solvers.csv: ga_experiments.success_table: the paper's binary GA, an integer-coded
  GA and SciPy's quadratic assignment (FAQ, 20 restarts) on synthetic meshes of each size (100
  seeds): how often each reaches the optimum of the paper's fitness over all (n + 1)^n solutions
  (certified by branch and bound,
   rsgeo.registration.optimum_match; the "optimum" column says in how
  many seeds) and the true matching, with mean and worst seconds per run.
- matching_fitness.csv: ga_experiments.fitness_comparison: how often the exhaustive optimum
  of the paper's fitness and of the "compact" variant is the true matching, and how often the
  paper's GA searching each finds the truth and the optimum (n = 5 and 6, a = 0.5 and 0.7, as-is
  and with one segment at 31 % of its area; 30 seeds).
- matching_real.csv: ga_experiments.real_table: the same for chapter 6's real scene (CBERS-2B
  CCD NDVI, 20 m, against a 30 m copy rotated 5° and shifted): exhaustive search over all 9^8
  solutions and the GA with each of the seeds. --no-real skips it.
"""

import argparse
import sys
import time
from pathlib import Path

import numba
import pandas as pd
import scipy

import ga_experiments  # benchmarks/ga_experiments.py
from machine import describe, header_lines  # benchmarks/machine.py

RESULTS = Path(__file__).resolve().parent / "results"


def machine():
    """'# key: value' lines naming the machine and the versions."""
    return describe(scipy=scipy.__version__, numba=numba.__version__, pandas=pd.__version__)


def save(table, name, seeds, seconds):
    RESULTS.mkdir(exist_ok=True)
    command = f"python benchmarks/{Path(__file__).name} {' '.join(sys.argv[1:])}".strip()
    header = {"command": command,
              "seeds": f"{seeds[0]} to {seeds[-1]} ({len(seeds)} seeds)", **machine(),
              "seconds": f"{seconds:.0f} (the whole table; times depend on the machine and its "
                         "load)"}
    text = header_lines(header)
    path = RESULTS / name
    path.write_text(text + table.to_csv(index=False, float_format="%.4f"))
    print(f"wrote {path.relative_to(RESULTS.parent.parent)}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[5, 8, 12])
    parser.add_argument("--seeds", type=int, default=100, help="seeds of the solvers' table")
    parser.add_argument("--fitness-seeds", type=int, default=30,
                        help="seeds of the fitness and real-scene tables")
    parser.add_argument("--only", choices=["solvers", "fitness", "real"], nargs="+",
                        default=["solvers", "fitness", "real"], help="tables to compute")
    parser.add_argument("--no-real", action="store_true", help="skip the real scene")
    arguments = parser.parse_args()
    seeds, fitness_seeds = list(range(arguments.seeds)), list(range(arguments.fitness_seeds))
    tables = {
        "solvers": ("matching_solvers.csv", seeds,
                    lambda: ga_experiments.success_table(sizes=arguments.sizes,
                                                         seeds=seeds).reset_index()),
        "fitness": ("matching_fitness.csv", fitness_seeds,
                    lambda: ga_experiments.fitness_comparison(seeds=fitness_seeds)),
        "real": ("matching_real.csv", fitness_seeds,
                 lambda: ga_experiments.real_table(fitness_seeds)),
    }
    with pd.option_context("display.width", 200, "display.max_columns", 12,
                           "display.max_colwidth", 60):
        for key in arguments.only:
            if key == "real" and arguments.no_real:
                continue
            name, table_seeds, compute = tables[key]
            start = time.perf_counter()
            table = compute()
            print(table.round(3).to_string())
            save(table, name, table_seeds, time.perf_counter() - start)
