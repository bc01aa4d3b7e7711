"""Automatic registration: success rate, accuracy and time of each method, on seeded cases.

    python benchmarks/registration.py [--seeds 10]

Writes benchmarks/results/registration.csv (chapter 6c of the book loads and shows it), opening
with '# key: value' lines that give the command, the seeds and the machine. Every number comes
from this one run. Each method runs the shared pipeline of rsgeo.registration: tie points ->
GCPSet -> affine model -> refinement (tolerance 1 px) -> check points.

Cases (the moving image gets seeded Gaussian noise, 2 DN, in every run):

- "synthetic, two dates": chapter 6's landscape (rsgeo.synthetic.two_date_landscape): reference
  20 m, moving 30 m, rotated 4° and shifted; crop fields redrawn between the dates. Check points:
  the known transform, on every 10th pixel of the moving image; target 0.5 px.
- "CBERS-2B CCD red vs HRC": the CCD's band 3 (20 m) against the HRC (2.5 m, averaged to 20 m).
  Check: agreement with the model of the 14 hand-made GCPs (refined, 13 kept), over the scene;
  target: those GCPs' own leave-one-out RMS. The HRC's corner outside its scene (0) is masked.
- "CCD near-infrared vs HRC": the same with the CCD's band 4: a radiometric change (vegetation
  bright in the near infrared, dark in the HRC's visible band).

Methods: the GA paper's region matching (rsgeo.registration.register_by_regions; synthetic case
only: the HRC has no near-infrared band for the paper's forest classification), correlation tie
points (rsgeo.registration.correlation_tiepoints,
        from a seeded approximate georeferencing: the true
or the file's geotransform moved by N(0, 60 m) per axis and turned by N(0, 1°); 4 passes, and 1
pass), SIFT and ORB feature tie points (rsgeo.registration.feature_tiepoints). A run that raises
ValueError (too few tie points) is a failure with an infinite error.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # small FFT products: one thread is faster

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import scipy  # noqa: E402
import skimage  # noqa: E402

from rsgeo import accuracy, data, registration, synthetic  # noqa: E402

from machine import describe, header_lines  # noqa: E402  (benchmarks/machine.py)

RESULTS = Path(__file__).resolve().parent / "results"
NOISE_DN = 2.0
SHIFT_M, ROTATION_DEG = 60.0, 1.0


def synthetic_case():
    land = synthetic.two_date_landscape()
    reference_segments = registration.forest_segments(land.reference, threshold=185)
    return {"case": "synthetic, two dates", "reference": land.reference.astype(float),
            "reference_transform": land.reference_transform,
            "moving": land.adjustment.astype(float),
            "approximate": land.adjustment_transform, "pixel_m": 30.0,
            "truth": ~land.adjustment_transform, "check_transform": land.adjustment_transform,
            "check_shape": land.adjustment.shape, "target": 0.5,
            "target_text": "0.5 px against the known transform", "valid": None,
            "regions": reference_segments}


def real_cases():
    ccd, hrc = data.load("cbers2b_rgb342"), data.load("cbers2b_hrc")
    blocks, block_transform = registration.coarsen(hrc.array, hrc.transform, 8)
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    hand, kept = accuracy.refine_gcps(gcps.map_xy, gcps.image_xy, 1, 2.5)
    loo = accuracy.leave_one_out_errors(gcps.map_xy[kept], gcps.image_xy[kept], 1)
    loo_rms = float(np.sqrt(np.mean(loo**2)))
    common = {"reference": blocks, "reference_transform": block_transform,
              "approximate": ccd.transform, "pixel_m": 20.0, "truth": hand,
              "check_transform": block_transform, "check_shape": blocks.shape, "target": loo_rms,
              "target_text": f"{loo_rms:.2f} px: the hand-made GCPs' leave-one-out RMS",
              "regions": None, "valid": blocks > 0}     # the HRC's corner outside its scene is 0
    return [{**common, "case": "CBERS-2B CCD red vs HRC", "moving": ccd.array[0].astype(float)},
            {**common, "case": "CCD near-infrared vs HRC", "moving": ccd.array[1].astype(float)}]


def tie_points(case, method, moving, seed):
    """The method's GCPSet (or, for the GA, its registration) on one seeded run."""
    rng = np.random.default_rng(seed + 1000)
    if method.startswith("correlation"):
        rows, cols = moving.shape
        centre = case["approximate"] @ (cols / 2, rows / 2)
        approximate = registration.perturb_transform(case["approximate"],
                                                  rng.normal(0, SHIFT_M, 2),
                                                  rng.normal(0, ROTATION_DEG), centre)
        return registration.correlation_tiepoints(
            case["reference"], moving, 32, 64, case["reference_transform"],
            initial=~approximate, iterations=1 if "1 pass" in method else 4,
            valid=case["valid"], seed=seed)
    if method in ("SIFT", "ORB"):
        return registration.feature_tiepoints(case["reference"], moving, method.lower(),
                                           case["reference_transform"], seed=seed)
    adjustment = registration.forest_segments(moving, threshold=185)
    return registration.register_by_regions(case["regions"], adjustment,
                                            case["reference_transform"],
                                        20, case["pixel_m"], seed=seed)


def run(case, method, seed):
    """(check-point error in px, tie points used, seconds) of one seeded run."""
    rng = np.random.default_rng(seed)
    moving = case["moving"] + rng.normal(0, NOISE_DN, case["moving"].shape)
    start = time.perf_counter()
    try:
        found = tie_points(case, method, moving, seed)
        if isinstance(found, registration.Registration):
            model, used = found.model, int(found.kept.sum())
        else:
            result = registration.register(found, tolerance=1.0)
            model, used = result.model, int(result.kept.sum())
    except ValueError:
        return np.inf, 0, time.perf_counter() - start
    seconds = time.perf_counter() - start
    error = registration.grid_error(model, case["truth"], case["check_transform"],
                                 case["check_shape"])
    return error, used, seconds


def table(seeds):
    rows = []
    methods = ["GA regions (paper)", "correlation", "correlation, 1 pass", "SIFT", "ORB"]
    for case in [synthetic_case(), *real_cases()]:
        for method in methods:
            if method.startswith("GA") and case["regions"] is None:
                continue
            results = np.array([run(case, method, seed) for seed in seeds])
            errors, used, seconds = results.T
            rows.append({"case": case["case"], "method": method, "runs": len(seeds),
                         "target": case["target_text"],
                         "success (%)": 100.0 * np.mean(errors < case["target"]),
                         "median error (px)": float(np.median(errors)),
                         "worst error (px)": float(errors.max()),
                         "median error (m)": float(np.median(errors)) * case["pixel_m"],
                         "tie points (median)": float(np.median(used)),
                         "mean s/run": float(seconds.mean())})
            print(f"{case['case']:28s} {method:22s} {rows[-1]['success (%)']:5.0f} % "
                  f"median {rows[-1]['median error (px)']:.3f} px  "
                  f"worst {rows[-1]['worst error (px)']:.3f} px  "
                  f"{rows[-1]['mean s/run']:.2f} s/run", flush=True)
    return pd.DataFrame(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="seeded runs per case and method")
    args = parser.parse_args(argv)
    seeds = range(args.seeds)
    header = {"command": "python benchmarks/registration.py"
              + ("" if args.seeds == 10 else f" --seeds {args.seeds}"),
              "seeds": f"0 to {args.seeds - 1} ({args.seeds} seeds)",
              "perturbations": f"moving image + N(0, {NOISE_DN} DN); correlation's first "
                               f"estimate moved N(0, {SHIFT_M} m) per axis, turned "
                               f"N(0, {ROTATION_DEG} deg)",
              **describe(skimage=skimage.__version__, scipy=scipy.__version__,
                         pandas=pd.__version__),
              "OPENBLAS_NUM_THREADS": os.environ["OPENBLAS_NUM_THREADS"]}
    result = table(seeds)
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / "registration.csv"
    path.write_text(header_lines(header) + result.to_csv(index=False, float_format="%.4f"))
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
