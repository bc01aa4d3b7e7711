"""Warp speed: rsgeo beside GDAL, exact and approximated, through every model the course fits.

    python benchmarks/resample.py [--sizes 2048 4096] [--dtypes uint8 int16]
                                  [--models affine poly1 poly2 poly3 tps14 tps200]
                                  [--threads 1 2] [--repeat 3] [--once-above 2]
                                  [--downsample 8] [--full-grids] [--output FILE]

One row per (model, method, size, dtype): the seconds of one warp of a
``size`` x ``size`` random image (covering the dtype's range) onto a
``size`` x ``size`` output grid, best of ``--repeat`` runs, for

* rsgeo's ``warp(image, model, ...)``, the model evaluated inside the compiled
  kernel, exactly (``error_threshold=0``) and with GDAL's approximation
  (``error_threshold=0.125``), with ``num_threads`` of each ``--threads``;
* GDAL through a VRTWarpedDataset naming its transformer (the VRT of
  tests/gdal_reference.py): exactly (``gdalwarp -et 0``) and wrapped in its
  approximate transformer with a 0.125-pixel threshold (gdalwarp's default),
  with the warp option ``NUM_THREADS`` of each ``--threads``. The warp happens
  when the VRT is read: the time is opening it and reading it (GDAL fits its
  GCP model on opening, and reads the source from an uncompressed GeoTIFF in
  a temporary folder - its I/O layer, which rsgeo, given an array, does not
  need); nothing is subtracted;
* for the affine rows only, scikit-image and OpenCV (one thread; OpenCV is
  left out when it is not installed), exact positions.

The models (``--models``):

=========  ==============================================================
affine     the source rotated by 3 degrees and zoomed by 1.02 about its centre
poly1..3   GDAL's GCP polynomial of order 1, 2, 3 fitted to 40 GCPs
tps14      GDAL's thin-plate spline through 14 GCPs (``gdalwarp -tps``)
tps200     the same through 200 GCPs
=========  ==============================================================

The GCPs come from one smooth image -> map relation (10 m pixels, rotated by
3 degrees, bent by about 0.5 % of the image's size) plus 0.2 pixel of noise;
the output grid covers the image's footprint (its corners stay empty). Both
libraries use their plain 1 x 1, 2 x 2 and 4 x 4 kernels (rsgeo's
``scale=1``, GDAL's XSCALE = YSCALE = 1) and one GDAL chunk for the whole grid
(the VRT's block), so that they do the same work: the columns
``differing_exact`` and ``differing_approx`` count the output pixels where
rsgeo and GDAL disagree (0 expected). RPC + DEM orthorectification has its own
table: ``benchmarks/orthorectify.py`` (``benchmarks/results/orthorectify.csv``).

Inverting a thin-plate spline exactly costs about a microsecond per output
cell with 14 GCPs and ten with 200, in both libraries (a 4096 x 4096 grid:
half a minute and three minutes per warp), so the spline rows warp the
grid's central rows, full width, in every peer: 1024 of 4096 for tps14 (all
of 2048), 128 of 4096 and 256 of 2048 for tps200 (``--full-grids``: the whole
grid); the column ``rows`` says how many rows each row warped. The ratios
hardly depend on it: every output row costs about the same, exact or
approximated. A peer whose run takes longer than ``--once-above`` seconds is
not run again (that run is its time). A full run at the defaults should take
about 10 minutes on two quiet cores (estimated from per-pixel times of small
runs; 20 minutes with other work on the machine).

Ratios are GDAL's time over rsgeo's, measured in the same run (> 1: rsgeo is
faster): ``x_gdal_exact_1t`` compares both exact with one thread,
``x_gdal_approx_1t`` both approximated, ``..._2t`` both with two threads;
``speedup_2t`` is rsgeo's exact one-thread time over its own two-thread time
(``speedup_2t_approx`` the same approximated). The peers of a row run in turn,
repeat after repeat, so that a busy machine slows them alike; each is run once
before it is timed (on a small grid: Numba compiles there). Numba's compile
time is measured apart, in a fresh process with an empty cache, and is in no
time of the table.

Downsampling rows (``--downsample 8``, the default; ``--downsample`` with no
factor leaves them out): the same image taken to a grid ``factor`` times
coarser (output pixel -> source pixel is a scale by ``factor``), where GDAL
widens bilinear and cubic over 1/scale source pixels and averages with
"average" (each library's own scale for the grid; rsgeo and GDAL only), their
method labelled e.g. "bilinear, 1/8", their size the source's and their rows
the output's.

The table is printed and saved as CSV (default
``benchmarks/results/resample.csv``, which chapter 4 shows), with the date, the
machine's CPU count, the library versions and the compile times as
``# key: value`` lines above the header (read it with
``pandas.read_csv(file, comment="#")``). Rows that miss the speed goals
(>= 1.0x GDAL exact and approximated single-threaded, >= 1.7x with two
threads) are listed at the end.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import affine
import numpy as np

from rsgeo.resample import METHODS, grid_scale, warp
from rsgeo.transforms import fit_transform

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
sys.path.insert(0, str(ROOT / "tests"))       # GDAL's transformer XML: tests/gdal_reference.py
from gdal_vrt import GdalWarps, gen_img_proj, warped_vrt  # noqa: E402  (benchmarks/)
from machine import describe, save_table  # noqa: E402  (benchmarks/machine.py)
from timing import time_in_turn  # noqa: E402  (benchmarks/timing.py)

#: gdalwarp's default error threshold (-et), in source pixels
ERROR_THRESHOLD = 0.125
#: model key -> (kind, polynomial order, GCPs)
MODELS = {"affine": ("affine", None, 0), "poly1": ("polynomial", 1, 40),
          "poly2": ("polynomial", 2, 40), "poly3": ("polynomial", 3, 40),
          "tps14": ("tps", None, 14), "tps200": ("tps", None, 200)}
#: models whose rows warp only the central rows of the grid that hold at most this many cells
#: (unless --full-grids): inverting a spline exactly costs about a microsecond per cell with
#: 14 GCPs and ten with 200, in both libraries, and a table of whole 4096 x 4096 grids would
#: take an hour
STRIP_CELLS = {"tps14": 2048 * 2048, "tps200": 512 * 1024}
DOWNSAMPLED_METHODS = ("bilinear", "cubic", "average")


# --- The scenes -------------------------------------------------------------------------------


def test_image(size, dtype):
    """A random image covering the dtype's whole range (the same in every run)."""
    info = np.iinfo(dtype)
    return np.random.default_rng(0).integers(info.min, int(info.max) + 1, (size, size),
                                             dtype=dtype)


def affine_mapping(size):
    """Output pixel -> source pixel: a rotation about the centre and a slight zoom."""
    centre = size / 2
    return (affine.Affine.translation(centre, centre) * affine.Affine.rotation(3.0)
            * affine.Affine.scale(1 / 1.02) * affine.Affine.translation(-centre, -centre))


def image_to_map(cols, rows, size):
    """The scene's smooth image -> map relation: 10 m pixels, 3 degrees, a bend of ~0.5 %."""
    angle = np.radians(3.0)
    u, v = cols / size - 0.5, rows / size - 0.5
    bend = 10.0 * 0.005 * size         # metres: the bend is the same share of every size
    x = 600_000 + 10 * (np.cos(angle) * cols + np.sin(angle) * rows) + bend * (4 * u * v + u**3)
    y = 7_300_000 - 10 * (np.cos(angle) * rows - np.sin(angle) * cols) + bend * 4 * u * u
    return x, y


def gcps(size, n, seed):
    """``n`` GCPs (image_xy, map_xy) of :func:`image_to_map`, 0.2 pixel of noise on the map."""
    rng = np.random.default_rng(seed)
    image_xy = rng.uniform(0, size, (n, 2))
    map_xy = np.column_stack(image_to_map(image_xy[:, 0], image_xy[:, 1], size))
    return image_xy, map_xy + rng.normal(0, 2.0, map_xy.shape)


def output_grid(size):
    """A ``size`` x ``size`` grid of square cells over the footprint of the image."""
    edge = np.linspace(0, size, 65)
    cols = np.concatenate([edge, edge, np.zeros(65), np.full(65, size)])
    rows = np.concatenate([np.zeros(65), np.full(65, size), edge, edge])
    x, y = image_to_map(cols, rows, size)
    pixel = max(x.max() - x.min(), y.max() - y.min()) / size
    return affine.Affine(pixel, 0, x.min(), 0, -pixel, y.max())


@dataclass
class Case:
    """One model on one size: what rsgeo warps with, and the GDAL transformer XML."""

    model: str
    gcps: int
    mapping: object            # rsgeo's map -> image mapping (an Affine or a fitted model)
    transform: affine.Affine   # the output grid's geotransform
    gdal_source: str           # the source's transformer XML, in a GenImgProjTransformer


def make_case(model, size):
    """The :class:`Case` of ``model`` (a key of :data:`MODELS`) for a ``size`` image."""
    from gdal_reference import affine_source, gcp_source

    kind, order, n_gcps = MODELS[model]
    if kind == "affine":
        # the source's pixels are the map: GDAL's identity geotransform, rsgeo's identity
        return Case(model, 0, affine.Affine.identity(), affine_mapping(size),
                    affine_source(affine.Affine.identity()))
    image_xy, map_xy = gcps(size, n_gcps, seed=n_gcps)
    if kind == "polynomial":
        mapping = fit_transform(map_xy, image_xy, "polynomial", order)
        source = gcp_source(image_xy, map_xy, order)
    else:
        from gdal_tps_reference import tps_source

        # gdalwarp -tps fits the spline image -> map and inverts it at every output cell
        mapping = fit_transform(image_xy, map_xy, "tps").inverse()
        source = tps_source(image_xy, map_xy)
    return Case(model, n_gcps, mapping, output_grid(size), source)


# --- The peers --------------------------------------------------------------------------------


def vrt_xml(source_path, case, shape, method, dtype, threads, max_error=None, scale=(1, 1)):
    """A VRTWarpedDataset: ``case``'s GDAL transformer, one block (GDAL chunk) for the grid.

    As tests/gdal_reference.py's ``gdal_warp`` (destination nodata 0), with the
    warp option NUM_THREADS, and ``max_error`` None for the exact transformer
    or GDAL's approximate transformer's threshold. ``scale`` None lets GDAL
    compute XSCALE and YSCALE for the chunk (downsampling).
    """
    return warped_vrt(source_path, case.transform, shape,
                      gen_img_proj(case.gdal_source, case.transform), method, dtype, threads,
                      max_error, scale)


def rsgeo_runner(image, case, shape, method, threads, error_threshold=0.0, scale=1.0):
    def run():
        return warp(image, case.mapping, shape, case.transform, method=method, dst_nodata=0,
                    num_threads=threads, scale=scale, error_threshold=error_threshold)
    return run


def skimage_runner(image, case, shape, method):
    from skimage.transform import AffineTransform
    from skimage.transform import warp as skimage_warp

    order = {"nearest": 0, "bilinear": 1, "cubic": 3}[method]
    # skimage works on pixel centres at integers: shift by half a pixel each way
    half = affine.Affine.translation(0.5, 0.5)
    matrix = ~half * case.mapping * case.transform * half
    transform = AffineTransform(matrix=np.array(matrix).reshape(3, 3))

    def run():
        return skimage_warp(image, transform, output_shape=shape, order=order,
                            preserve_range=True).astype(image.dtype)
    return run


def opencv_runner(image, case, shape, method):
    import cv2

    half = affine.Affine.translation(0.5, 0.5)
    matrix = np.array(~half * case.mapping * case.transform * half).reshape(3, 3)[:2]
    flag = {"nearest": cv2.INTER_NEAREST, "bilinear": cv2.INTER_LINEAR,
            "cubic": cv2.INTER_CUBIC}[method]

    def run():
        cv2.setNumThreads(1)
        return cv2.warpAffine(image, matrix, shape[::-1], flags=flag | cv2.WARP_INVERSE_MAP)
    return run


def _has_opencv():
    try:
        import cv2  # noqa: F401
    except ImportError:
        return False
    return True


# --- Timing -----------------------------------------------------------------------------------


def warm_up(image, case, method, thresholds, shape, scale):
    """Compile rsgeo's kernels for this model, method, dtype and scale on a small window.

    The window of ``shape``'s grid around its centre: Numba compiles for the
    types, not the size, so the timed runs compile nothing. ``scale`` as in
    the timed runs (None: the whole grid's), so that the same kernel (plain or
    widened) is compiled.
    """
    rows, cols = shape
    small = (min(rows, 32), min(cols, 32))
    centre = case.transform * affine.Affine.translation((cols - small[1]) / 2,
                                                         (rows - small[0]) / 2)
    small_case = Case(case.model, case.gcps, case.mapping, centre, case.gdal_source)
    for threshold in thresholds:
        try:
            rsgeo_runner(image, small_case, small, method, 1, threshold, scale)()
        except Exception:     # noqa: BLE001  (the timed run reports it)
            pass


def _label(library, approx, threads):
    return f"{library}_{'approx' if approx else 'exact'}_{threads}t"


def row_of(image, case, shape, method, threads, repeat, gdal, others=(), scale=(1, 1),
           once_above=2.0):
    """One table row: the seconds of every peer, their ratios and their differing pixels."""
    if scale is None:
        # the whole grid's scale, computed once: the warm-up's small window would get another
        rsgeo_scale = grid_scale(case.mapping, shape, case.transform, image.shape)
    else:
        rsgeo_scale = float(scale[0])
    warm_up(image, case, method, (0.0, ERROR_THRESHOLD), shape, rsgeo_scale)
    runners = {}
    for approx in (False, True):
        for count in threads:
            runners[_label("rsgeo", approx, count)] = rsgeo_runner(
                image, case, shape, method, count, ERROR_THRESHOLD if approx else 0.0,
                rsgeo_scale)
            runners[_label("gdal", approx, count)] = gdal.runner(vrt_xml(
                gdal.source, case, shape, method, gdal.dtype, count,
                ERROR_THRESHOLD if approx else None, scale))
    if "skimage" in others:
        runners["skimage"] = skimage_runner(image, case, shape, method)
    if "opencv" in others:
        runners["opencv"] = opencv_runner(image, case, shape, method)
    first = threads[0]
    compared = [_label(library, approx, first) for library in ("rsgeo", "gdal")
                for approx in (False, True)]
    seconds, outputs, errors = time_in_turn(runners, repeat, compared, once_above)
    row = {f"{label}_s": value for label, value in seconds.items()}
    for approx in (False, True):
        kind = "approx" if approx else "exact"
        for count in threads:
            row[f"x_gdal_{kind}_{count}t"] = (seconds[_label("gdal", approx, count)]
                                              / seconds[_label("rsgeo", approx, count)])
        ours, theirs = outputs.get(_label("rsgeo", approx, first)), outputs.get(
            _label("gdal", approx, first))
        row[f"differing_{kind}"] = (int(np.count_nonzero(ours != theirs))
                                    if ours is not None and theirs is not None else -1)
    for count in threads[1:]:
        row[f"speedup_{count}t"] = (seconds[_label("rsgeo", False, first)]
                                    / seconds[_label("rsgeo", False, count)])
        row[f"speedup_{count}t_approx"] = (seconds[_label("rsgeo", True, first)]
                                           / seconds[_label("rsgeo", True, count)])
    row["note"] = "; ".join(f"{label}: {text}" for label, text in errors.items())
    return row


def strip_of(case, size, full_grids=False):
    """``case`` on the central rows of its grid (:data:`STRIP_CELLS`), and their count."""
    rows = size if full_grids else min(size, STRIP_CELLS.get(case.model, size * size) // size)
    if rows == size:
        return case, rows
    first = (size - rows) // 2
    return Case(case.model, case.gcps, case.mapping,
                case.transform * affine.Affine.translation(0, first), case.gdal_source), rows


def benchmark(sizes=(2048, 4096), dtypes=("uint8", "int16"), models=tuple(MODELS), repeat=3,
              threads=(1, 2), downsample=(8,), once_above=2.0, full_grids=False, log=print):
    """The table: a dict per row (model, gcps, method, size, rows, dtype, then :func:`row_of`'s).

    ``rows``: the output rows warped, ``size`` unless the model is in
    :data:`STRIP_CELLS` (and not ``full_grids``).
    """
    others = ["skimage"] + (["opencv"] if _has_opencv() else [])
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for size in sizes:
            cases = [make_case(model, size) for model in models]
            for dtype in dtypes:
                image = test_image(size, dtype)
                gdal = GdalWarps(folder, image)
                for case in cases:
                    strip, n_rows = strip_of(case, size, full_grids)
                    for method in METHODS:
                        start = time.perf_counter()
                        row = row_of(image, strip, (n_rows, size), method, threads, repeat,
                                     gdal, others if case.model == "affine" else (),
                                     once_above=once_above)
                        rows.append({"model": case.model, "gcps": case.gcps, "method": method,
                                     "size": size, "rows": n_rows, "dtype": dtype, **row})
                        log(f"{case.model} {method} {size} {dtype}: "
                            f"{time.perf_counter() - start:.1f} s")
                if "affine" in models:
                    rows += _downsampling_rows(image, gdal, threads, repeat, downsample,
                                               once_above, log)
                os.remove(gdal.source)
    return rows


def _downsampling_rows(image, gdal, threads, repeat, factors, once_above, log):
    """Rows for the affine image taken to grids ``factors`` times coarser."""
    rows = []
    size, dtype = image.shape[0], image.dtype.name
    for factor in factors:
        # output pixel -> source pixel: a scale by factor (the source's pixels are the map)
        case = Case("affine", 0, affine.Affine.identity(), affine.Affine.scale(float(factor)),
                    make_case("affine", size).gdal_source)
        shape = (size // factor, size // factor)
        for method in DOWNSAMPLED_METHODS:
            start = time.perf_counter()
            row = row_of(image, case, shape, method, threads, repeat, gdal, scale=None,
                         once_above=once_above)
            rows.append({"model": "affine", "gcps": 0, "method": f"{method}, 1/{factor}",
                         "size": size, "rows": shape[0], "dtype": dtype, **row})
            log(f"affine {method}, 1/{factor} {size} {dtype}: "
                f"{time.perf_counter() - start:.1f} s")
    return rows


# --- Compile time, machine, output --------------------------------------------------------------

# the kernels alone: rsgeo.resample.interpolate, each method once (what chapter 4 quotes)
_COMPILE_KERNELS = """
import time
start = time.perf_counter()
import numpy as np
from rsgeo.resample import interpolate
image = np.zeros((8, 8), dtype={dtype!r})
for method in ("nearest", "bilinear", "cubic"):
    interpolate(image, [1.5], [2.5], method)
print(time.perf_counter() - start)
"""
# every model's transformer inside the kernels too
_COMPILE_MODELS = """
import sys, time
import rasterio  # for GDAL's transformer XML, which make_case writes too: not rsgeo's time
sys.path.insert(0, {benchmarks!r})
start = time.perf_counter()
import resample as bench
image = bench.test_image(64, {dtype!r})
for model in bench.MODELS:
    case = bench.make_case(model, 64)
    for method in bench.METHODS:
        for threshold in (0.0, bench.ERROR_THRESHOLD):
            try:
                bench.rsgeo_runner(image, case, (64, 64), method, 1, threshold)()
            except Exception:
                pass
print(time.perf_counter() - start)
"""


def jit_seconds(dtype="uint8", models=False):
    """Seconds of a first use of rsgeo's kernels in a new process: (with an empty Numba
    cache, i.e. compiling; then loading what that run cached).

    The first use: importing rsgeo.resample and interpolating with each method
    on a tiny image; with ``models``, importing rsgeo, fitting every model of
    :data:`MODELS` and warping once through each with each method, exact and
    approximated, on a small image.
    """
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        code = (_COMPILE_MODELS if models else _COMPILE_KERNELS).format(
            benchmarks=str(ROOT / "benchmarks"), dtype=dtype)
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
    return describe(numba=f"{numba.__version__} (rsgeo's threads: Python threads over blocks "
                          "of rows)",
                    GDAL=rasterio.__gdal_version__, rasterio=rasterio.__version__,
                    **{"scikit-image": skimage.__version__, "OpenCV": opencv})


def columns(threads):
    """The CSV's columns, in order, for the thread counts ``threads``."""
    names = ["model", "gcps", "method", "size", "rows", "dtype"]
    for kind in ("exact", "approx"):
        for library in ("rsgeo", "gdal"):
            names += [f"{_label(library, kind == 'approx', count)}_s" for count in threads]
    names += ["skimage_s", "opencv_s"]
    names += [f"x_gdal_{kind}_{count}t" for kind in ("exact", "approx") for count in threads]
    names += [f"speedup_{count}t{suffix}" for suffix in ("", "_approx") for count in threads[1:]]
    return names + ["differing_exact", "differing_approx", "note"]


def save_csv(rows, file, threads, command="", extra=None):
    """Write the table with the machine's description (and ``extra``) as
    ``# key: value`` lines above it."""
    return save_table(file, {**machine(), **(extra or {}), "command": command},
                      columns(threads), rows)


def print_table(rows, threads):
    first, more = threads[0], threads[1:]
    print(f"{'model':>7} {'method':>15} {'size':>5} {'rows':>5} {'dtype':>6} {'rsgeo s':>8} "
          f"{'×exact':>7} {'×approx':>7}" + "".join(f" {f'×exact {t}t':>10}" for t in more)
          + "".join(f" {f'speedup {t}t':>11}" for t in more) + f" {'differing':>10}")
    for row in rows:
        print(f"{row['model']:>7} {row['method']:>15} {row['size']:>5} {row['rows']:>5} "
              f"{row['dtype']:>6} "
              f"{row[_label('rsgeo', False, first) + '_s']:8.3f} "
              f"{row[f'x_gdal_exact_{first}t']:7.2f} {row[f'x_gdal_approx_{first}t']:7.2f}"
              + "".join(f" {row[f'x_gdal_exact_{t}t']:10.2f}" for t in more)
              + "".join(f" {row[f'speedup_{t}t']:11.2f}" for t in more)
              + f" {row['differing_exact']:>4}/{row['differing_approx']:<5}")


def misses(rows, threads, speedup_goal=0.85):
    """The rows that miss the speed goals, as text lines.

    ``speedup_goal``: the least speed-up per thread (1.7 with two threads).
    """
    first = threads[0]
    lines = []
    for row in rows:
        where = f"{row['model']} {row['method']} {row['size']} {row['dtype']}"
        for kind in ("exact", "approx"):
            ratio = row[f"x_gdal_{kind}_{first}t"]
            if not ratio >= 1.0:
                lines.append(f"{where}: {ratio:.2f}x GDAL {kind}, {first} thread(s)")
        for count in threads[1:]:
            speedup = row[f"speedup_{count}t"]
            if not speedup >= speedup_goal * count:
                lines.append(f"{where}: {count} threads {speedup:.2f}x one")
        if row["note"]:
            lines.append(f"{where}: {row['note']}")
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2048, 4096])
    parser.add_argument("--dtypes", nargs="+", default=["uint8", "int16"],
                        choices=["uint8", "int16", "uint16"])
    parser.add_argument("--models", nargs="+", default=list(MODELS), choices=list(MODELS))
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2],
                        help="thread counts to time, the first the reference (default: 1 2)")
    parser.add_argument("--repeat", type=int, default=3,
                        help="runs of each peer, the best timed (default: 3)")
    parser.add_argument("--once-above", type=float, default=2.0,
                        help="seconds: a peer's run longer than this is not repeated "
                             "(default: 2)")
    parser.add_argument("--full-grids", action="store_true",
                        help="warp the whole grid for every model (tps200 too: slow)")
    parser.add_argument("--downsample", type=int, nargs="*", default=[8],
                        help="factors of the downsampling rows (none: leave them out)")
    parser.add_argument("--output", default=ROOT / "benchmarks" / "results" / "resample.csv",
                        help="CSV file to write (default: benchmarks/results/resample.csv)")
    arguments = parser.parse_args(argv)
    if arguments.repeat < 1 or min(arguments.threads) < 1:
        parser.error("--repeat and --threads need whole numbers from 1")
    dtype = arguments.dtypes[0]
    extra = {}
    for models, what in ((False, f"first call of the 3 methods on {dtype}"),
                         (True, f"first warps through every model, exact and approximated, "
                                f"{dtype}")):
        compile_s, cached_s = jit_seconds(dtype, models)
        extra[f"Numba JIT, {what} (s)"] = (f"{compile_s:.1f} compiling (empty cache), "
                                           f"{cached_s:.1f} from the cache")
    extra["RPC + DEM rows"] = "benchmarks/results/orthorectify.csv (benchmarks/orthorectify.py)"
    print("; ".join(f"{key}: {value}" for key, value in extra.items()))
    start = time.perf_counter()
    table = benchmark(arguments.sizes, arguments.dtypes, arguments.models, arguments.repeat,
                      arguments.threads, arguments.downsample, arguments.once_above,
                      arguments.full_grids, log=lambda text: print(text, file=sys.stderr))
    extra["benchmark run time (s)"] = f"{time.perf_counter() - start:.0f}"
    print_table(table, arguments.threads)
    command = ("python benchmarks/resample.py --sizes " + " ".join(map(str, arguments.sizes))
               + " --dtypes " + " ".join(arguments.dtypes)
               + " --models " + " ".join(arguments.models)
               + " --threads " + " ".join(map(str, arguments.threads))
               + f" --repeat {arguments.repeat} --once-above {arguments.once_above:g}"
               + (" --full-grids" if arguments.full_grids else "")
               + " --downsample " + " ".join(map(str, arguments.downsample)))
    print("saved", save_csv(table, arguments.output, arguments.threads, command, extra))
    missed = misses(table, arguments.threads)
    print(f"{len(missed)} miss(es) of the speed goals" + (":" if missed else ""))
    for line in missed:
        print("  " + line)


if __name__ == "__main__":
    main()
