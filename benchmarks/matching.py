"""Region matching: success rate and time per run of each solver, on seeded synthetic meshes.

    python benchmarks/matching.py [--sizes 5 8 12] [--seeds 30]

Prints rsgeo.matching.success_table: the paper's binary GA, an integer-coded GA and SciPy's
quadratic assignment (FAQ, 20 restarts), with exact-match rate, share of segments matched right,
and mean and worst seconds per run, all measured in the same run.
"""

import argparse

import pandas as pd

from rsgeo.matching import success_table

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[5, 8, 12])
    parser.add_argument("--seeds", type=int, default=30)
    arguments = parser.parse_args()
    with pd.option_context("display.width", 120, "display.max_columns", 10):
        print(success_table(sizes=arguments.sizes, seeds=range(arguments.seeds)).round(3))
