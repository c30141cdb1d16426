#!/usr/bin/env python3
"""Markdown tables of bench/convergence.sh's sweeps: relative RMSE of the shadowed indirect light
against k and against accumulated frames for both shadow-ray target modes, and the unshadowed error
of accumulated 4x4 interleaving. Usage: convergence_table.py OUT_DIR"""
import csv
import glob
import os
import sys


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(f) if r["method"] == "lgh"]


def main(out):
    cases = sorted({os.path.basename(d).rsplit("_", 1)[0] for d in glob.glob(os.path.join(out, "*_*_*"))})
    print("Relative RMSE of the shadowed indirect light (irradiance x visibility) against the Embree reference;")
    print("320x180, alpha 2, S1, 1x1. `lights`: the converging estimator (--shadow-estimator converging, the default):")
    print("rays to input lights drawn by share, resampled, weighed and blended by their own distance, the irradiance")
    print("corrected by the samples' mean weight D as far as its variance allows, f^2 / (f^2 + var D), f = 0.1;")
    print("`uncorrected`: the same without the correction (--set shadow-correct-irradiance=false); `unshrunk`: the")
    print("correction trusted whatever its variance (--set shadow-correction-lgh-error=10); `centres`: uncorrected,")
    print("blended by their grid light's centre's distance (--set shadow-blend-targets=false);")
    print("`paper`: --shadow-estimator paper, jittered cluster centres, S1 not selected. Unshadowed LGH error in")
    print("brackets. Floor: the error of")
    print("the LGH irradiance times the reference's own visibility ratio (sweep column rmse_exact_ratio), what exact")
    print("shadows would reach on the uncorrected irradiance: the `uncorrected`, `centres` and `paper` rows cannot go below")
    print("it, the corrected ones (`lights`, `unshrunk`) can. Beyond the floor: sqrt(e^2 - floor^2), the shadow estimate's")
    print("own error, where e > floor.\n")
    header = ("| scene, VPLs | targets | k=1 | k=4 | k=16 | k=4 raw | k=16 raw | 16/4 raw | floor | 16/4 raw beyond the floor "
              "| 4 frames | 16 frames | 64 frames | 64 frames / unshadowed |")
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for case in cases:
        scene, vpls = case.rsplit("_", 1)
        k_rows = {m: rows(p) for m in ("lights", "uncorrected", "unshrunk", "centres", "paper")
                  if os.path.exists(p := os.path.join(out, f"{case}_{m}", "k", "sweep.csv"))}
        # The floor depends on the irradiance alone, the same in both modes: taken from whichever measured it.
        case_floors = [float(r["rmse_exact_ratio"]) for rs in k_rows.values() for r in rs if r.get("rmse_exact_ratio")]
        for mode, mode_rows in k_rows.items():
            d = os.path.join(out, f"{case}_{mode}")
            ks = {(r["shadow_samples"], r["filter"]): float(r["rmse_shadowed"]) for r in mode_rows}
            floor = case_floors[0] if case_floors else None
            beyond = lambda e: (e * e - floor * floor) ** 0.5 if floor is not None and e > floor else None
            noise = (f"{beyond(ks[('16', 'off')]) / beyond(ks[('4', 'off')]):.2f}x"
                     if beyond(ks[("16", "off")]) and beyond(ks[("4", "off")]) else "not measured")
            fs = {}
            if os.path.exists(f"{d}/frames/sweep.csv"):
                fs = {(r["frames"], r["filter"]): float(r["rmse_shadowed"]) for r in rows(f"{d}/frames/sweep.csv")}
            unshadowed = float(mode_rows[0]["rmse_unshadowed"])
            cell = lambda v: f"{v:.3f}" if v is not None else "not run"
            print(f"| {scene}, {int(vpls) // 1000}K ({unshadowed:.3f}) | {mode} | "
                  + " | ".join(cell(ks[(k, "on")]) for k in ("1", "4", "16")) + " | "
                  + f"{cell(ks[('4', 'off')])} | {cell(ks[('16', 'off')])} | {ks[('16', 'off')] / ks[('4', 'off')]:.2f}x | "
                  + (f"{floor:.3f}" if floor is not None else "not measured") + f" | {noise} | "
                  + " | ".join(cell(fs.get((f, "on"))) for f in ("4", "16", "64")) + " | "
                  + (f"{fs[('64', 'on')] / unshadowed:.2f}x" if ("64", "on") in fs else "not run") + " |")
    print("\nUnshadowed error of n x n interleaving, one frame and 16 accumulated still frames (light-to-tile")
    print("assignment rotated every frame):\n")
    print("| scene, VPLs | 1x1, 1 frame | 4x4, 1 frame | 4x4, 16 frames | 4x4 16 frames / 1x1 |")
    print("|---|---|---|---|---|")
    for case in cases:
        path = os.path.join(out, f"{case}_interleave", "sweep.csv")
        if not os.path.exists(path):
            continue
        e = {(r["interleave"], r["frames"]): float(r["rmse_unshadowed"]) for r in rows(path)}
        scene, vpls = case.rsplit("_", 1)
        print(f"| {scene}, {int(vpls) // 1000}K | {e[('1', '1')]:.3f} | {e[('4', '1')]:.3f} | {e[('4', '16')]:.3f} | "
              f"{e[('4', '16')] / e[('1', '1')]:.2f}x |")


if __name__ == "__main__":
    main(sys.argv[1])
