#!/usr/bin/env python3
"""Work-precision of dopri against rk4, and dopri's error against its tolerance.

Runs `tumble bench SCENE --integrators dopri,rk4` (dopri over its tolerances, rk4 over fixed
steps), then prints every run (largest orientation error against the scene's reference, the
right-hand-side evaluations, the median time) and, for each rk4 run at high accuracy (largest
orientation error <= 1e-7 rad), the cheapest dopri run at least as accurate, with the ratios of
their evaluations and median times (< 1: dopri is left of rk4 on the work-precision plot).
Last, dopri's largest error over its tolerance at each tolerance (the target: <= 100).

Usage: tests/bench/dopri_work_precision.py [--build DIR] [--repeat N] [--out DIR] [SCENE]
(defaults: build, 5, a temporary directory removed at the end,
assets/scenes/t_handle_flip.json). With --out the plots of `tumble bench` are kept there.
"""
import argparse
import csv
import pathlib
import subprocess
import sys
import tempfile

HIGH_ACCURACY = 1e-7  # rad: the rk4 runs compared
TOLERANCES = "1e-4,1e-6,1e-8,1e-10,1e-11,1e-12"


def run_bench(tumble, scene, repeat, out, dts):
    command = [str(tumble), "bench", str(scene), "--integrators", "dopri,rk4", "--tolerances",
               TOLERANCES, "--repeat", str(repeat), "-o", str(out)]
    if dts:
        command += ["--dts", dts]
    print("$ " + " ".join(command), flush=True)
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(out / "results.csv", newline="") as f:
        return list(csv.DictReader(f))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", default="assets/scenes/t_handle_flip.json")
    parser.add_argument("--build", default="build")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out")
    parser.add_argument("--dts", default="0.004,0.002,0.001,0.0005,0.00025,0.000125",
                        help="rk4's steps (default: 4 ms to 0.125 ms, for the T-handle)")
    args = parser.parse_args()
    tumble = pathlib.Path(args.build) / "app" / "tumble"
    if not tumble.is_file():
        sys.exit(f"dopri_work_precision.py: {tumble} not found (build the tumble target first)")

    with tempfile.TemporaryDirectory() as temporary:
        out = pathlib.Path(args.out) if args.out else pathlib.Path(temporary) / "bench"
        rows = run_bench(tumble, args.scene, args.repeat, out, args.dts)

    runs = [{"integrator": r["integrator"],
             "setting": r["tolerance"] if r["integrator"] == "dopri" else r["dt"],
             "error": float(r["orientation_error_max"]),
             "evaluations": int(r["evaluations"]),
             "seconds": float(r["seconds_median"])} for r in rows]
    print(f"\n{'integrator':10} {'tol / dt':>9} {'max error rad':>14} {'evaluations':>12}"
          f" {'median s':>10}")
    for run in runs:
        print(f"{run['integrator']:10} {float(run['setting']):9.3g} {run['error']:14.3g}"
              f" {run['evaluations']:12d} {run['seconds']:10.3g}")

    dopri = [r for r in runs if r["integrator"] == "dopri"]
    print("\nrk4 at high accuracy against the cheapest dopri run at least as accurate:")
    print(f"{'rk4 dt':>9} {'rk4 error':>10} {'dopri tol':>10} {'dopri error':>12}"
          f" {'evaluations ratio':>18} {'time ratio':>11}")
    for rk4 in (r for r in runs if r["integrator"] == "rk4" and r["error"] <= HIGH_ACCURACY):
        better = [d for d in dopri if d["error"] <= rk4["error"]]
        if not better:
            print(f"{float(rk4['setting']):9.3g} {rk4['error']:10.3g}   no dopri run as accurate")
            continue
        best = min(better, key=lambda d: d["evaluations"])
        print(f"{float(rk4['setting']):9.3g} {rk4['error']:10.3g} {float(best['setting']):10.3g}"
              f" {best['error']:12.3g} {best['evaluations'] / rk4['evaluations']:18.3f}"
              f" {best['seconds'] / rk4['seconds']:11.3f}")

    print("\ndopri's largest orientation error over its tolerance (target <= 100):")
    for d in dopri:
        print(f"  tol {float(d['setting']):7.0e}: {d['error'] / float(d['setting']):8.3g}")


if __name__ == "__main__":
    main()
