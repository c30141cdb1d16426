#!/usr/bin/env python3
"""Markdown tables of bench/scripts/convergence.sh's sweeps: relative RMSE of the shadowed indirect light
against k and against accumulated frames for the shadow modes at 1x1 (convergence.md); with --interleave,
the shadowed interleaved frames and the unshadowed error of accumulated 4x4 interleaving
(convergence_interleave.md). Usage: convergence_table.py [--interleave] OUT_DIR"""
import csv
import glob
import os
import sys


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(f) if r["method"] == "lgh"]


def case_names(out):
    """The (scene, VPLs) cases under OUT: its folders are named SCENE_VPLS_MODE."""
    return sorted({os.path.basename(d).rsplit("_", 1)[0] for d in glob.glob(os.path.join(out, "*_*_*"))})


def print_header(header):
    print(header)
    print("|" + "---|" * (header.count("|") - 1))


def main(out):
    cases = case_names(out)
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
    print_header(header)
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


def interleave_tables(out):
    """The interleaving part: shadowed interleaved frames for the default estimator and without its
    correction (one frame: medians of 3 repeats; 4 and 16 accumulated frames: one each), and the
    unshadowed error of one and 16 accumulated 4x4 frames against 1x1."""
    cases = case_names(out)
    print("Relative RMSE of the shadowed indirect light (irradiance x visibility) against the Embree reference;")
    print("320x180, alpha 2, S1, n x n interleaving. One frame: the median of 3 single frames; 4 and 16 frames:")
    print("accumulated still frames (the light-to-tile dealing rotated every frame), one run each. `default`: the")
    print("converging estimator; `uncorrected`: --set shadow-correct-irradiance=false. raw: --filter-passes 0 (with")
    print("interleaving the ratio and D are still resolved over the interleaving window). Floor: the LGH irradiance")
    print("times the reference's own visibility ratio (one frame). Last column: the largest default / uncorrected")
    print("ratio over the row's six points (k = 1, 4, 16; filtered and raw). k -> inf: the raw error's limit in k")
    print("fitted through k = 4 and 16 as e(k)^2 = a^2 + b^2 / k (sqrt((16 e16^2 - 4 e4^2) / 12)), over k = 4's error:")
    print("the least 16/4 raw any k could give is about that.\n")
    header = ("| scene, VPLs | n | frames | estimator | k=1 | k=4 | k=16 | k=1 raw | k=4 raw | k=16 raw | 16/4 raw "
              "| k -> inf / k=4 raw | floor | worst default / uncorrected |")
    print_header(header)
    for case in cases:
        scene, vpls = case.rsplit("_", 1)
        errors, floors = {}, {}
        for mode in ("lights", "uncorrected"):
            for part in ("interleave_one", "interleave_frames"):
                path = os.path.join(out, f"{case}_{mode}", part, "sweep.csv")
                if not os.path.exists(path):
                    continue
                for r in rows(path):
                    errors[(mode, r["interleave"], r["frames"], r["shadow_samples"], r["filter"])] = float(
                        r["rmse_shadowed"])
                    if r["frames"] == "1" and r.get("rmse_exact_ratio"):
                        floors[r["interleave"]] = float(r["rmse_exact_ratio"])
        points = sorted({(n, f) for (_, n, f, _, _) in errors}, key=lambda p: (int(p[0]), int(p[1])))
        for n, frames in points:
            for mode, label in (("lights", "default"), ("uncorrected", "uncorrected")):
                e = lambda k, filt: errors.get((mode, n, frames, k, filt))
                cell = lambda v: f"{v:.3f}" if v is not None else "not run"
                ratio = (f"{e('16', 'off') / e('4', 'off'):.2f}x" if e("16", "off") and e("4", "off") else "")
                limit = ""
                if e("16", "off") and e("4", "off"):
                    a2 = (16 * e("16", "off") ** 2 - 4 * e("4", "off") ** 2) / 12
                    limit = f"{max(a2, 0.0) ** 0.5 / e('4', 'off'):.2f}x"
                worst = ""
                if mode == "lights":
                    quotients = [(errors[("lights", n, frames, k, filt)] / errors[("uncorrected", n, frames, k, filt)],
                                  k, filt) for k in ("1", "4", "16") for filt in ("on", "off")
                                 if ("lights", n, frames, k, filt) in errors
                                 and ("uncorrected", n, frames, k, filt) in errors]
                    if quotients:
                        q, k, filt = max(quotients)
                        worst = f"{q:.3f} (k={k}{'' if filt == 'on' else ' raw'})"
                floor = f"{floors[n]:.3f}" if frames == "1" and n in floors else ""
                print(f"| {scene}, {int(vpls) // 1000}K | {n}x{n} | {frames} | {label} | "
                      + " | ".join(cell(e(k, "on")) for k in ("1", "4", "16")) + " | "
                      + " | ".join(cell(e(k, "off")) for k in ("1", "4", "16"))
                      + f" | {ratio} | {limit} | {floor} | {worst} |")
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
    if len(sys.argv) == 3 and sys.argv[1] == "--interleave":
        interleave_tables(sys.argv[2])
    elif len(sys.argv) == 2:
        main(sys.argv[1])
    else:
        sys.exit("usage: convergence_table.py [--interleave] OUT_DIR")
