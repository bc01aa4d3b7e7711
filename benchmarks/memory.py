"""Peak memory of the big verbs: rsgeo.resample.warp, rsgeo.ortho.orthorectify and
rsgeo.resample.georeference on uint8 scenes of 2048², 8192² and 16384² pixels.

Each case runs in a fresh Python process (``python benchmarks/memory.py --case VERB SIZE``),
which builds its input, calls the verb once and exits; the parent reads that child's peak
resident set size (``ru_maxrss``) from ``os.wait4``, and subtracts nothing: the table gives the
peak, the bytes of input + output, and what the process held beyond them (the interpreter,
NumPy, Numba's compiled kernels and the verb's working arrays: compare with the ``baseline``
row, a child that imports everything and runs the verb on a 64² scene). A size whose estimated
peak (the verb's bytes per output pixel at the size below, times the pixels) exceeds the memory
the machine has available (``MemAvailable``) is not run, and the table says so.

Writes benchmarks/results/memory.csv, opening with '# key: value' lines (benchmarks/machine.py)
that give the command, the machine and the commit of rsgeo measured.

Usage: ``python benchmarks/memory.py`` (every verb at every size the memory allows), or
``python benchmarks/memory.py --cases warp:2048,8192,16384 orthorectify:2048,8192`` to choose
(a case left out is listed as "not requested").
"""

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from machine import describe, git, header_lines  # noqa: E402  (benchmarks/machine.py)

RESULTS = Path(__file__).parent / "results"
REPO = Path(__file__).resolve().parents[1]
VERBS = ("warp", "orthorectify", "georeference")
SIZES = (2048, 8192, 16384)
MiB = 2.0**20


def _warp(n):
    import affine

    from rsgeo.resample import warp

    image = np.random.default_rng(0).integers(0, 256, (n, n), dtype=np.uint8)
    # output pixel -> source pixel: a rotation of 3° about the centre and a 2 % zoom, through a
    # callable (a fitted model), so that warp goes strip by strip as it does for GCP models
    about = affine.Affine.translation(n / 2, n / 2)
    mapping = about @ affine.Affine.rotation(3) @ affine.Affine.scale(0.98) @ ~about
    model = _AffineModel(mapping)
    out = warp(image, model, (n, n), method="bilinear", dst_nodata=0)
    return image, out


class _AffineModel:
    """A callable mapping (n, 2) points through an Affine: what a fitted model looks like."""

    def __init__(self, mapping):
        self.mapping = mapping

    def __call__(self, points):
        points = np.asarray(points, dtype=np.float64)
        x, y = self.mapping * (points[:, 0], points[:, 1])
        return np.column_stack([x, y])


def _orthorectify(n):
    import affine

    from rsgeo.ortho import orthorectify
    from rsgeo.sensors import simple_rpc_dict

    # simple_rpc_dict's nadir view, stretched to an n x n image of 10 m pixels
    rpc = simple_rpc_dict()
    half = n / 2
    degrees = 0.045 * half / 500
    rpc.update(LINE_OFF=half, SAMP_OFF=half, LINE_SCALE=half, SAMP_SCALE=half,
               LAT_SCALE=degrees, LONG_SCALE=degrees)
    image = np.random.default_rng(0).integers(0, 256, (n, n), dtype=np.uint8)
    step = 2 * degrees / n
    dem_n = 200
    dem_step = 2.2 * degrees / dem_n
    dem = np.random.default_rng(1).uniform(0, 300, (dem_n, dem_n))
    dem_gt = affine.Affine(dem_step, 0, -34.9 - 1.1 * degrees, 0, -dem_step, -8.0 + 1.1 * degrees)
    grid = affine.Affine(step, 0, -34.9 - degrees, 0, -step, -8.0 + degrees)
    # the DEM's heights are above the ellipsoid, as GDAL takes a DEM without a vertical CRS
    out = orthorectify(image, rpc, dem, dem_gt, grid, (n, n), "bilinear",
                       dem_vertical="ellipsoidal")
    return image, out


def _georeference(n):
    import affine

    from rsgeo.data import Raster
    from rsgeo.gcp import GCPSet
    from rsgeo.resample import georeference

    image = np.random.default_rng(0).integers(0, 256, (n, n), dtype=np.uint8)
    # 9 GCPs of a 20 m image rotated by 3° (UTM zone 23S), fitted by a first-order polynomial
    cols, rows = np.meshgrid([0, n / 2, n], [0, n / 2, n])
    image_xy = np.column_stack([cols.ravel(), rows.ravel()])
    to_map = (affine.Affine.translation(300_000, 7_400_000) @ affine.Affine.rotation(3)
              @ affine.Affine.scale(20, -20))
    map_xy = np.column_stack(to_map * (image_xy[:, 0], image_xy[:, 1]))
    gcps = GCPSet(map_xy, image_xy, crs="EPSG:31983")
    raster = Raster(image, affine.Affine.identity(), None, None, "", "memory")
    out = georeference(raster, gcps, order=1, resolution=20.0)
    return image, out.array


CASES = {"warp": _warp, "orthorectify": _orthorectify, "georeference": _georeference}


def child(verb, n):
    """Run one case and print 'input_bytes output_bytes seconds' for the parent."""
    start = time.perf_counter()
    image, out = CASES[verb](n)
    seconds = time.perf_counter() - start
    print(image.nbytes, out.nbytes, f"{seconds:.2f}")


def run_case(verb, n):
    """The child's (input bytes, output bytes, seconds, peak RSS bytes) or its error text."""
    command = [sys.executable, __file__, "--case", verb, str(n)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    # wait4 gives this child's own rusage (RUSAGE_CHILDREN would be a maximum over all children)
    _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    stdout, stderr = process.stdout.read(), process.stderr.read()
    peak = usage.ru_maxrss * 1024  # kilobytes on Linux
    if process.returncode != 0:
        last = (stderr.strip().splitlines() or ["killed"])[-1]
        return None, peak, f"failed: {last[:200]}"
    input_bytes, output_bytes, seconds = stdout.split()
    return (int(input_bytes), int(output_bytes), float(seconds)), peak, "measured"


def available_bytes():
    """MemAvailable from /proc/meminfo (what can be allocated without swapping)."""
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemAvailable:"):
            return int(line.split()[1]) * 1024
    return None


def parse_cases(texts):
    """['warp:2048,8192', ...] -> {verb: set of sizes}; None -> every verb at every size."""
    if not texts:
        return {verb: set(SIZES) for verb in VERBS}
    chosen = {}
    for text in texts:
        verb, _, sizes = text.partition(":")
        if verb not in VERBS:
            raise SystemExit(f"unknown verb {verb!r}: one of {', '.join(VERBS)}")
        chosen[verb] = {int(size) for size in sizes.split(",")} if sizes else set(SIZES)
    return chosen


def main():
    import pandas as pd

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", nargs=2, metavar=("VERB", "SIZE"), help=argparse.SUPPRESS)
    parser.add_argument("--cases", nargs="*", metavar="VERB:SIZES",
                        help="verbs and sizes to run, e.g. warp:2048,8192 (default: all)")
    args = parser.parse_args()
    if args.case:
        child(args.case[0], int(args.case[1]))
        return
    chosen = parse_cases(args.cases)
    rows = []
    for verb in VERBS:
        # the interpreter, NumPy, rsgeo and the verb's compiled kernels, on a 64² scene
        sizes, baseline, status = run_case(verb, 64)
        rows.append({"verb": verb, "size": 64, "input_MiB": sizes[0] / MiB if sizes else None,
                     "output_MiB": sizes[1] / MiB if sizes else None,
                     "peak_rss_MiB": baseline / MiB, "beyond_io_MiB": None,
                     "bytes_per_output_pixel": None, "seconds": sizes[2] if sizes else None,
                     "status": "baseline (imports and compiled kernels)"
                     if status == "measured" else status})
        per_pixel = None
        for n in SIZES:
            row = {"verb": verb, "size": n, "input_MiB": n * n / MiB, "output_MiB": None,
                   "peak_rss_MiB": None, "beyond_io_MiB": None, "bytes_per_output_pixel": None,
                   "seconds": None}
            free = available_bytes()
            estimate = None if per_pixel is None else baseline + per_pixel * n * n
            if n not in chosen.get(verb, ()):
                row["status"] = "not requested (--cases)"
                if estimate is not None:
                    row["status"] += f"; estimated peak {estimate / 2**30:.1f} GiB"
            elif estimate is not None and free is not None and estimate > 0.8 * free:
                row["status"] = (f"not run: estimated peak {estimate / 2**30:.1f} GiB "
                                 f"> 80 % of the {free / 2**30:.1f} GiB available")
            else:
                print(f"{verb} {n}² ...", flush=True)
                sizes, peak, status = run_case(verb, n)
                row["peak_rss_MiB"] = peak / MiB
                row["status"] = status
                if sizes is not None:
                    input_bytes, output_bytes, seconds = sizes
                    row.update(input_MiB=input_bytes / MiB, output_MiB=output_bytes / MiB,
                               beyond_io_MiB=(peak - input_bytes - output_bytes) / MiB,
                               seconds=seconds)
                    pixels = output_bytes / np.dtype(np.uint8).itemsize
                    per_pixel = (peak - baseline) / pixels
                    row["bytes_per_output_pixel"] = per_pixel
            print(row, flush=True)
            rows.append(row)
    result = pd.DataFrame(rows)
    print(result.to_string(index=False))
    changed = git("status", "--short", "--", "rsgeo/resample.py", "rsgeo/terrain.py",
                  "rsgeo/georef.py").replace("\n", "; ")
    total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    header = {"command": "python benchmarks/memory.py"
              + (" --cases " + " ".join(args.cases) if args.cases else ""),
              "measure": "peak RSS of a fresh process per case (os.wait4 ru_maxrss); "
                         "beyond_io = peak - input - output; bytes_per_output_pixel = "
                         "(peak - baseline) / output pixels",
              "rsgeo commit": git("rev-parse", "--short", "HEAD"),
              "uncommitted changes measured": changed or "none",
              "memory total": f"{total / 2**30:.1f} GiB",
              **describe()}
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / "memory.csv"
    path.write_text(header_lines(header) + result.to_csv(index=False, float_format="%.1f"))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
