"""Share a kernel's output rows among threads: blocks of rows, one compiled loop.

rsgeo's per-pixel loops are compiled once each, without Numba's ``parallel=True``: a
parallel loop costs four to five times as long to compile as the same loop run serially
(about 8 CPU-s against 2 for each image type a warp meets), and that cost is paid on every
machine whose cache is cold. The loops are compiled with ``nogil=True`` instead, and
Python's threads run them side by side, each over its own block of output rows, as
GDAL's warper shares a chunk's rows among its threads (``GDAL_NUM_THREADS``). Each output
pixel is computed alone, so the pixels do not depend on the blocks or on the threads.
"""

from concurrent.futures import ThreadPoolExecutor

__all__ = ["run_in_row_blocks"]

# blocks per thread: more blocks than threads even out rows that cost more than others
# (rows that fall outside the source cost almost nothing)
_BLOCKS_PER_THREAD = 4


def run_in_row_blocks(loop, n_rows, num_threads):
    """Run ``loop(first_row, stop_row)`` over rows 0 .. n_rows - 1; return the sum of its results.

    Parameters
    ----------
    loop : callable
        ``loop(first_row, stop_row)`` processes output rows ``first_row`` to
        ``stop_row - 1`` and returns a count (a compiled loop with ``nogil=True``,
        which lets threads run it at the same time).
    n_rows : int
        The rows to process.
    num_threads : int
        Threads to share them (1: in the calling thread).

    Returns
    -------
    int
        The sum of the counts ``loop`` returned.
    """
    if num_threads <= 1 or n_rows <= 1:
        return int(loop(0, n_rows))
    n_blocks = min(n_rows, num_threads * _BLOCKS_PER_THREAD)
    bounds = [n_rows * k // n_blocks for k in range(n_blocks + 1)]
    with ThreadPoolExecutor(max_workers=num_threads) as pool:
        counts = pool.map(loop, bounds[:-1], bounds[1:])
        return int(sum(counts))
