"""benchmarks/ga_experiments.py: the experiment harness behind chapter 6's saved tables."""

import importlib.util

import numpy as np
import pytest

from rsgeo import registration

from notebook_runner import ROOT

_SPEC = importlib.util.spec_from_file_location("ga_experiments",
                                               ROOT / "benchmarks" / "ga_experiments.py")
ga_experiments = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(ga_experiments)


def test_success_table_counts_optimum_and_truth():
    table = ga_experiments.success_table(sizes=(5,), seeds=range(3))
    assert list(table.index.get_level_values("matcher")) == list(ga_experiments.MATCHERS)
    assert (table["runs"] == 3).all()
    assert table["optimum"].iloc[0].startswith("max FA over all 6^5 solutions by branch and "
                                               "bound: certified in 3 of 3 seeds")
    assert (table["optimum reached (%)"] >= table["exact matches (%)"]).all()
    assert (table["worst s/run"] >= table["mean s/run"]).all()
    # a matcher that returns the zero solution reaches nothing
    nothing = ga_experiments.success_table(sizes=(5,), seeds=range(2), matchers={
        "none": lambda ref, adj, alpha, seed: registration.MatchResult(np.zeros(len(adj), int),
                                                                       0.0,
                                                                   [], 0)})
    assert nothing.loc[(5, "none"), "optimum reached (%)"] == 0
    assert nothing.loc[(5, "none"), "exact matches (%)"] == 0


def test_fitness_comparison_and_success_table_examples():
    table = ga_experiments.fitness_comparison(sizes=(4,), seeds=range(2), alphas=(0.5,))
    assert table["GA finds the optimum (%)"].tolist() == [100.0, 100.0, 100.0, 100.0]
    table = ga_experiments.success_table(sizes=(5,), seeds=range(2))
    assert table.loc[(5, "GA, binary (the paper)"), "optimum reached (%)"] == 100.0


def test_rsgeo_does_not_import_the_harness():
    import rsgeo

    assert "ga_experiments" not in rsgeo.__all__ and not hasattr(rsgeo, "experiments")


@pytest.mark.parametrize("call, message", [
    (lambda: ga_experiments.fitness_comparison(sizes=(9,), seeds=[0]), "sizes must be 3 to 7"),
    (lambda: ga_experiments.fitness_comparison(sizes=(4,), seeds=[0], variants=("tight",)),
     "unknown variant"),
    (lambda: ga_experiments.success_table(sizes=(2,), seeds=[0]), "sizes of 3 or more"),
])
def test_bad_input_is_a_clear_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()
