"""Resampling speed: rsgeo beside GDAL, scikit-image and OpenCV, measured in the same run.

    python benchmarks/resample.py [--sizes 2048 4096] [--dtypes uint8 int16] [--repeat 3]
                                  [--output FILE]

Each peer warps the same random image (of each ``--dtypes``) with the same
affine mapping (a rotation of 3° and a scale of 1.02, so that GDAL uses its
plain 2 × 2 and 4 × 4 kernels). GDAL runs through rasterio's ``reproject``,
single-threaded and with ``NUM_THREADS=2``; rsgeo's Numba kernels run with
``num_threads=1`` and 2; scikit-image, and OpenCV (single-threaded; skipped
when it is not installed) run once each. The table gives megapixels of output
per second (best of ``--repeat`` runs) and the ratio to GDAL with the same
number of threads. Numba's compile time is measured apart, in fresh processes
with an empty cache, and is not in the speeds: every peer is warmed up first.
The table is printed and saved as CSV (default
``benchmarks/results/resample.csv``, which chapter 4 shows), with the date, the
machine's CPU count, the library versions and the compile times as
``# key: value`` lines above the header (read it with
``pandas.read_csv(file, comment="#")``).

Downsampling rows (``--downsample 8``, the default; ``--downsample`` with no
factor leaves them out): the same image taken to a grid ``factor`` times
coarser (output pixel -> source pixel is a scale by ``factor``), where GDAL
widens bilinear and cubic over 1/scale source pixels and averages with
"average"; rsgeo and GDAL only (the others do not widen), their method
labelled e.g. "bilinear, 1/8". Their speed is in megapixels of *source* per
second, the work such a warp does.
"""

import argparse
import csv
import functools
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import affine
import numpy as np

from rsgeo.resample import warp

from machine import describe, header_lines  # noqa: E402  (benchmarks/machine.py)

METHODS = ("nearest", "bilinear", "cubic")


def mapping(size):
    """Output-to-source affine: a rotation about the centre and a slight zoom."""
    centre = size / 2
    return (affine.Affine.translation(centre, centre) * affine.Affine.rotation(3.0)
            * affine.Affine.scale(1 / 1.02) * affine.Affine.translation(-centre, -centre))


def run_rsgeo(image, to_source, method, threads=1, shape=None):
    return warp(image, to_source, shape or image.shape, method=method, num_threads=threads)


def run_gdal(image, to_source, method, threads=1, shape=None):
    from rasterio.enums import Resampling
    from rasterio.warp import reproject

    out = np.zeros(shape or image.shape, dtype=image.dtype)
    # source pixel -> "map" is the identity; output pixel -> map is to_source.
    reproject(image, out, src_transform=affine.Affine.identity(), dst_transform=to_source,
              src_crs="EPSG:3857", dst_crs="EPSG:3857", resampling=Resampling[method],
              num_threads=threads)
    return out


def run_skimage(image, to_source, method, threads=1):
    from skimage.transform import AffineTransform, warp

    order = {"nearest": 0, "bilinear": 1, "cubic": 3}[method]
    # skimage works on pixel centres at integers: shift by half a pixel each way.
    half = affine.Affine.translation(0.5, 0.5)
    matrix = ~half * to_source * half
    transform = AffineTransform(matrix=np.array(matrix).reshape(3, 3))
    return warp(image, transform, order=order, preserve_range=True).astype(image.dtype)


def run_opencv(image, to_source, method, threads=1):
    import cv2

    cv2.setNumThreads(threads)
    half = affine.Affine.translation(0.5, 0.5)
    matrix = np.array(~half * to_source * half).reshape(3, 3)[:2]
    flag = {"nearest": cv2.INTER_NEAREST, "bilinear": cv2.INTER_LINEAR,
            "cubic": cv2.INTER_CUBIC}[method]
    return cv2.warpAffine(image, matrix, image.shape[::-1], flags=flag | cv2.WARP_INVERSE_MAP)


# (label in the table, function, threads)
PEERS = [("rsgeo", run_rsgeo, 1), ("GDAL", run_gdal, 1),
         ("rsgeo, 2 threads", run_rsgeo, 2), ("GDAL, 2 threads", run_gdal, 2),
         ("scikit-image", run_skimage, 1), ("OpenCV", run_opencv, 1)]
# the GDAL row each peer is compared with: the same number of threads
REFERENCE = {1: "GDAL", 2: "GDAL, 2 threads"}


def best_time(function, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def test_image(size, dtype):
    """A random image covering the dtype's whole range (the same in every run)."""
    info = np.iinfo(dtype)
    return np.random.default_rng(0).integers(info.min, int(info.max) + 1, (size, size),
                                             dtype=dtype)


DOWNSAMPLED_METHODS = ("bilinear", "cubic", "average")
DOWNSAMPLING_PEERS = ("rsgeo", "GDAL", "rsgeo, 2 threads", "GDAL, 2 threads")


def benchmark(sizes=(2048, 4096), dtypes=("uint8", "int16"), repeat=3, peers=None,
              downsample=(8,)):
    """Rows of (size, dtype, method, peer, threads, megapixels per second, ratio to GDAL).

    Within one (size, dtype, method) the peers run one after another, each
    warmed up once, then timed ``repeat`` times; the ratio compares speeds of
    the same run, which is what stays meaningful on a busy machine.
    """
    peers = [peer for peer in PEERS if peers is None or peer[0] in peers]
    rows = []
    for size in sizes:
        to_source = mapping(size)
        for dtype in dtypes:
            image = test_image(size, dtype)
            for method in METHODS:
                speeds = {}
                for label, function, threads in peers:
                    try:
                        function(image, to_source, method, threads)       # warm up
                    except ImportError:
                        continue
                    seconds = best_time(
                        functools.partial(function, image, to_source, method, threads),
                        repeat)
                    speeds[label] = (threads, size * size / seconds / 1e6)
                for label, (threads, speed) in speeds.items():
                    reference = speeds.get(REFERENCE[threads])
                    ratio = speed / reference[1] if reference else np.nan
                    rows.append((size, dtype, method, label, threads, speed, ratio))
            rows += _downsampling_rows(image, peers, repeat, downsample)
    return rows


def _downsampling_rows(image, peers, repeat, factors):
    """Rows for the image taken to grids ``factors`` times coarser (source Mpx/s)."""
    rows = []
    size, dtype = image.shape[0], image.dtype.name
    for factor in factors:
        coarse = affine.Affine.scale(float(factor))   # output pixel -> source pixel
        shape = (size // factor, size // factor)
        for method in DOWNSAMPLED_METHODS:
            speeds = {}
            for label, function, threads in peers:
                if label not in DOWNSAMPLING_PEERS:
                    continue
                function(image, coarse, method, threads, shape)                # warm up
                seconds = best_time(
                    functools.partial(function, image, coarse, method, threads, shape),
                    repeat)
                speeds[label] = (threads, size * size / seconds / 1e6)
            for label, (threads, speed) in speeds.items():
                reference = speeds.get(REFERENCE[threads])
                ratio = speed / reference[1] if reference else np.nan
                rows.append((size, dtype, f"{method}, 1/{factor}", label, threads, speed, ratio))
    return rows


_COMPILE = """
import time
start = time.perf_counter()
import numpy as np
from rsgeo.resample import interpolate
image = np.zeros((8, 8), dtype="{dtype}")
for method in ("nearest", "bilinear", "cubic"):
    interpolate(image, [1.5], [2.5], method)
print(time.perf_counter() - start)
"""


def jit_seconds(dtype="uint8"):
    """Seconds to import rsgeo.resample and run the 3 methods once on a tiny image,
    in a new process: (with an empty Numba cache, i.e. compiling; then loading
    what that run cached)."""
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        code = _COMPILE.format(dtype=dtype)
        runs = [float(subprocess.run([sys.executable, "-c", code], env=env, check=True,
                                     capture_output=True, text=True).stdout)
                for _ in range(2)]
    return runs[0], runs[1]


def machine():
    """What the numbers depend on: date, processor, CPU count and library versions."""
    import numba
    import rasterio
    import skimage

    try:
        import cv2

        opencv = cv2.__version__
    except ImportError:
        opencv = "not installed"
    return describe(numba=f"{numba.__version__} (threading layer {_threading_layer()})",
                    GDAL=rasterio.__gdal_version__, rasterio=rasterio.__version__,
                    **{"scikit-image": skimage.__version__, "OpenCV": opencv})


def _threading_layer():
    import numba

    try:
        return numba.threading_layer()
    except ValueError:              # no parallel region has run yet
        warp(np.zeros((2, 2), dtype=np.uint8), affine.Affine.identity(), (2, 2))
        return numba.threading_layer()


def save_csv(rows, file, command="", extra=None):
    """Write the table with the machine's description (and ``extra``) as
    ``# key: value`` lines above it."""
    file = Path(file)
    file.parent.mkdir(parents=True, exist_ok=True)
    with open(file, "w", newline="") as handle:
        handle.write(header_lines({**machine(), **(extra or {}), "command": command}))
        writer = csv.writer(handle)
        writer.writerow(["size", "dtype", "method", "peer", "threads", "Mpx_per_s",
                         "ratio_to_GDAL"])
        for size, dtype, method, peer, threads, speed, ratio in rows:
            writer.writerow([size, dtype, method, peer, threads, f"{speed:.2f}", f"{ratio:.3f}"])
    return file


def print_table(rows):
    print(f"{'size':>6} {'dtype':>6} {'method':>9} {'peer':>17} {'Mpx/s':>8} {'× GDAL':>7}")
    for size, dtype, method, peer, _threads, speed, ratio in rows:
        print(f"{size:>6} {dtype:>6} {method:>9} {peer:>17} {speed:8.1f} {ratio:7.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2048, 4096])
    parser.add_argument("--dtypes", nargs="+", default=["uint8", "int16"])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--downsample", type=int, nargs="*", default=[8],
                        help="factors of the downsampling rows (none: leave them out)")
    parser.add_argument("--output", default=Path(__file__).parent / "results" / "resample.csv",
                        help="CSV file to write (default: benchmarks/results/resample.csv)")
    arguments = parser.parse_args()
    compile_s, cached_s = jit_seconds()
    jit = {"Numba JIT, first call of the 3 methods on uint8 (s)":
           f"{compile_s:.1f} compiling (empty cache), {cached_s:.1f} from the cache"}
    print("; ".join(f"{key}: {value}" for key, value in jit.items()))
    table = benchmark(arguments.sizes, arguments.dtypes, arguments.repeat,
                      downsample=arguments.downsample)
    print_table(table)
    command = ("python benchmarks/resample.py --sizes " + " ".join(map(str, arguments.sizes))
               + " --dtypes " + " ".join(arguments.dtypes) + f" --repeat {arguments.repeat}"
               + " --downsample " + " ".join(map(str, arguments.downsample)))
    print("saved", save_csv(table, arguments.output, command, jit))
