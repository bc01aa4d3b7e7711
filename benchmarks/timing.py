"""Timing peers in turn, for the benchmarks: the best of several rounds, every peer once a round.

Running each peer's repeats back to back lets one of them catch a quiet moment the others do
not; taking turns spreads the machine's noise over all of them (benchmarks/resample.py and
benchmarks/orthorectify.py).
"""

import time

import numpy as np


def time_in_turn(runners, repeat, keep=(), once_above=2.0):
    """Best seconds of each runner over ``repeat`` rounds, the runners in turn in each round.

    A runner whose run took longer than ``once_above`` seconds is not run
    again: one run that long is its time (a busy machine's noise is a small
    part of it), and a full run of the table stays within minutes.

    Returns ``(seconds, outputs, errors)``: dicts by label (``outputs`` only for
    the labels in ``keep``); a runner that raises gets NaN seconds and its
    error's text, and is not run again.
    """
    seconds = {label: np.inf for label in runners}
    outputs, errors = {}, {}
    finished = set()
    for _ in range(repeat):
        for label, run in runners.items():
            if label in finished:
                continue
            start = time.perf_counter()
            try:
                out = run()
            except Exception as error:    # noqa: BLE001  (reported in the row, not fatal)
                errors[label] = f"{type(error).__name__}: {str(error)[:120]}"
                seconds[label] = np.nan
                finished.add(label)
                continue
            elapsed = time.perf_counter() - start
            seconds[label] = min(seconds[label], elapsed)
            if elapsed > once_above:
                finished.add(label)
            if label in keep:
                outputs[label] = out
            del out     # a 4096 x 4096 output is 16 or 32 MB: keep none that is not compared
    return seconds, outputs, errors
