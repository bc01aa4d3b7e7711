"""Scenes larger than memory: one warp against the same warp tile by tile and on Dask.

    python benchmarks/tiling.py [--sizes 4096] [--tile 1024] [--method bilinear] [--repeat 3]
                                [--output FILE]

The source is a random uint8 GeoTIFF of ``size``² pixels (tiled 256 x 256, written to a
temporary folder), warped onto a grid of the same size through a polynomial of order 2 fitted
to 25 GCPs of a mildly curved mapping (the course's GCP case; compiled in rsgeo's kernels), by:

* ``warp``: the whole source read into memory, one :func:`rsgeo.resample.warp` call;
* ``warp_tiled -> array``: :func:`rsgeo.resample.warp_tiled` from the file, each tile reading
  its own window, into an array in memory;
* ``warp_tiled -> GeoTIFF``: the same, each tile written into a tiled GeoTIFF: memory is one
  tile and its window;
* ``warp_dask threads`` and ``warp_dask processes`` with 1 and 2 workers:
  :func:`rsgeo.resample.warp_dask` computed by Dask's thread or process scheduler into an array.

Each case runs in a fresh Python process (``--case``), which imports rsgeo, warms the kernels
on a small warp (so Numba's cache loading is not timed), then times the case once; the parent
reads the child's peak resident set size from ``os.wait4`` (as benchmarks/memory.py does), and
the child reports its own children's peak (``RUSAGE_CHILDREN``: the largest Dask worker
process; their start, an import of rsgeo each, is inside the seconds). Seconds are the best of
``--repeat`` children, peaks the largest. Every result is compared with the one-shot warp's:
``differing_pixels`` must be 0 (no seams).

Writes benchmarks/results/tiling.csv (or ``--output``), opening with '# key: value' lines
(benchmarks/machine.py) that give the command, the machine and the versions.
"""

import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from machine import describe, git, header_lines  # noqa: E402  (benchmarks/machine.py)

RESULTS = Path(__file__).parent / "results"
REPO = Path(__file__).resolve().parents[1]
MiB = 2.0**20
# (case, workers): the rows of the table, in order
CASES = [("warp", 1), ("warp_tiled -> array", 1), ("warp_tiled -> GeoTIFF", 1),
         ("warp_dask threads", 1), ("warp_dask threads", 2),
         ("warp_dask processes", 1), ("warp_dask processes", 2)]
PIXEL = 10.0          # metres: the source's and the grid's pixel size (binary: tiles add up)


def model_and_grid(n):
    """The polynomial (map -> image) of a curved n x n scene, and the output grid."""
    import affine

    from rsgeo import transforms

    rng = np.random.default_rng(3)
    image_xy = rng.uniform(0, n, (25, 2))
    u, v = (image_xy[:, 0] - n / 2) / n, (image_xy[:, 1] - n / 2) / n
    # a rotation of about 3°, and up to some 20 pixels of curvature at the corners
    map_xy = np.column_stack([
        600_000 + PIXEL * (image_xy[:, 0] + 0.05 * image_xy[:, 1]) + 20 * PIXEL * u * v,
        7_300_000 - PIXEL * (image_xy[:, 1] - 0.05 * image_xy[:, 0]) + 20 * PIXEL * u * u])
    model = transforms.fit_polynomial(map_xy, image_xy, 2)
    # the grid: 10 m pixels over the source's map footprint (x from 600 000 to about
    # 600 000 + 10.5 n, y from about 7 300 000 - 10 n to 7 300 000 + 0.5 n), its origin on
    # whole metres for n a multiple of 4
    grid = affine.Affine(PIXEL, 0, 600_000.0 - 0.25 * n, 0, -PIXEL, 7_300_000.0 + 0.75 * n)
    return model, grid, (int(n * 1.1), int(n * 1.1))


def write_source(path, n):
    """A random uint8 n x n GeoTIFF, tiled 256 x 256, one band."""
    import rasterio

    image = np.random.default_rng(0).integers(0, 256, (n, n), dtype=np.uint8)
    with rasterio.open(path, "w", driver="GTiff", width=n, height=n, count=1, dtype="uint8",
                       tiled=True, blockxsize=256, blockysize=256) as dataset:
        dataset.write(image, 1)


def warm_up(method):
    """Load the kernels Numba cached (the first call in a process), outside the timing."""
    import affine

    from rsgeo.resample import warp

    warp(np.zeros((64, 64), dtype=np.uint8), affine.Affine.scale(0.9), (64, 64), method=method,
         scale=1.0, src_offset=(0, 0))


def child(case, workers, n, tile, method, folder):
    """Run one case; print 'seconds output_file children_peak_bytes' for the parent."""
    import resource

    import rasterio

    from rsgeo import resample
    from rsgeo.resample import warp

    source = Path(folder) / "source.tif"
    model, grid, shape = model_and_grid(n)
    warm_up(method)
    result = Path(folder) / f"{case.replace(' ', '_').replace('>', '')}_{workers}.npy"
    start = time.perf_counter()
    if case == "warp":
        with rasterio.open(source) as dataset:
            image = dataset.read(1)
        out = warp(image, model, shape, grid, method=method)
    elif case == "warp_tiled -> array":
        out = resample.warp_tiled(source, model, shape, grid, tile_shape=(tile, tile),
                                  method=method)
    elif case == "warp_tiled -> GeoTIFF":
        result = result.with_suffix(".tif")
        with rasterio.open(result, "w", driver="GTiff", width=shape[1], height=shape[0],
                           count=1, dtype="uint8", transform=grid, tiled=True,
                           blockxsize=256, blockysize=256) as dataset:
            resample.warp_tiled(source, model, shape, grid, tile_shape=(tile, tile), method=method,
                              out=dataset)
        out = None
    else:
        import dask

        scheduler = case.split()[-1]
        array = resample.warp_dask(source, model, shape, grid, tile_shape=(tile, tile),
                                   method=method)
        with dask.config.set(scheduler=scheduler, num_workers=workers):
            out = array.compute()
    seconds = time.perf_counter() - start
    if out is not None:
        np.save(result, out)
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024
    print(f"{seconds:.3f} {result} {children}")


def run_case(case, workers, arguments, folder):
    """(seconds, output file, own peak bytes, children's peak bytes) or an error text."""
    command = [sys.executable, __file__, "--case", case, str(workers), "--sizes",
               str(arguments.size), "--tile", str(arguments.tile), "--method",
               arguments.method, "--folder", str(folder)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    # wait4 gives this child's own rusage (RUSAGE_CHILDREN would be a maximum over all children)
    _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    stdout, stderr = process.stdout.read(), process.stderr.read()
    if process.returncode != 0:
        last = (stderr.strip().splitlines() or ["killed"])[-1]
        return f"failed: {last[:200]}"
    seconds, output, children = stdout.split()[-3:]
    return float(seconds), Path(output), usage.ru_maxrss * 1024, int(children)


def read_output(path):
    if path.suffix == ".npy":
        return np.load(path)
    import rasterio

    with rasterio.open(path) as dataset:
        return dataset.read(1)


def benchmark(arguments):
    """The table's rows, for each size: every case, best of --repeat children."""
    rows = []
    for n in arguments.sizes:
        with tempfile.TemporaryDirectory(prefix="rsgeo-tiling-") as folder:
            write_source(Path(folder) / "source.tif", n)
            arguments.size = n
            reference = None
            for case, workers in CASES:
                runs = [run_case(case, workers, arguments, folder)
                        for _ in range(arguments.repeat)]
                failed = [run for run in runs if isinstance(run, str)]
                row = {"size": n, "case": case, "workers": workers, "seconds": None,
                       "peak_rss_MiB": None, "worker_peak_rss_MiB": None,
                       "differing_pixels": None, "status": failed[0] if failed else "measured"}
                if not failed:
                    output = read_output(runs[0][1])
                    if reference is None:
                        reference = output          # the first case: one warp
                    row.update(seconds=min(run[0] for run in runs),
                               peak_rss_MiB=max(run[2] for run in runs) / MiB,
                               worker_peak_rss_MiB=(max(run[3] for run in runs) / MiB
                                                    if "processes" in case else None),
                               differing_pixels=int(np.count_nonzero(output != reference)))
                print(row, flush=True)
                rows.append(row)
    return rows


def machine():
    import dask
    import numba
    import rasterio

    return describe(numba=numba.__version__, dask=dask.__version__,
                    GDAL=rasterio.__gdal_version__, rasterio=rasterio.__version__)


def save_csv(rows, file, command, arguments):
    file = Path(file)
    file.parent.mkdir(parents=True, exist_ok=True)
    header = {"command": command,
              "measure": "seconds of the warp (reading and writing included; Dask's worker "
                         "processes start inside it), best of the children; peak_rss = the "
                         "child process's ru_maxrss (os.wait4); worker_peak_rss = its largest "
                         "Dask worker process (RUSAGE_CHILDREN); differing_pixels against "
                         "the one-shot warp",
              "mapping": "polynomial of order 2 fitted to 25 GCPs (compiled), uint8, one band",
              "tile": f"{arguments.tile} x {arguments.tile}", "method": arguments.method,
              "rsgeo commit": git("rev-parse", "--short", "HEAD"),
              "uncommitted changes measured": git("status", "--short", "--", "rsgeo")
              .replace("\n", "; ") or "none",
              **machine()}
    columns = ["size", "case", "workers", "seconds", "peak_rss_MiB", "worker_peak_rss_MiB",
               "differing_pixels", "status"]
    with open(file, "w", newline="") as handle:
        handle.write(header_lines(header))
        writer = csv.DictWriter(handle, columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({key: (f"{value:.3f}" if key == "seconds" and value is not None
                                   else f"{value:.1f}" if key.endswith("MiB")
                                   and value is not None else value)
                             for key, value in row.items()})
    return file


def print_table(rows):
    print(f"{'size':>6} {'case':>22} {'workers':>7} {'s':>8} {'peak MiB':>9} "
          f"{'worker MiB':>10} {'differing':>9}")
    for row in rows:
        if row["seconds"] is None:
            print(f"{row['size']:>6} {row['case']:>22} {row['workers']:>7} {row['status']}")
            continue
        worker = (f"{row['worker_peak_rss_MiB']:10.1f}" if row["worker_peak_rss_MiB"]
                  else f"{'':>10}")
        print(f"{row['size']:>6} {row['case']:>22} {row['workers']:>7} {row['seconds']:8.3f} "
              f"{row['peak_rss_MiB']:9.1f} {worker} {row['differing_pixels']:>9}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[4096])
    parser.add_argument("--tile", type=int, default=1024)
    parser.add_argument("--method", default="bilinear")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--output", default=RESULTS / "tiling.csv",
                        help="CSV file to write (default: benchmarks/results/tiling.csv)")
    parser.add_argument("--case", nargs=2, metavar=("CASE", "WORKERS"), help=argparse.SUPPRESS)
    parser.add_argument("--folder", help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.case:
        child(arguments.case[0], int(arguments.case[1]), arguments.sizes[0], arguments.tile,
              arguments.method, arguments.folder)
        return
    rows = benchmark(arguments)
    print_table(rows)
    command = ("python benchmarks/tiling.py --sizes " + " ".join(map(str, arguments.sizes))
               + f" --tile {arguments.tile} --method {arguments.method}"
               + f" --repeat {arguments.repeat}")
    print("saved", save_csv(rows, arguments.output, command, arguments))


if __name__ == "__main__":
    main()
