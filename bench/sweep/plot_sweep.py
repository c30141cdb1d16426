#!/usr/bin/env python3
"""Plots and the numbers of docs/measurements.md from `lgh-bench sweep` (bench/sweep/sweep_bench.cpp).

    python3 bench/sweep/plot_sweep.py bench/results/sweep.csv [--out DIR]

Writes into DIR (default: the CSV's folder):
  front.{png,svg}        relative RMSE against the exact reference vs time for every scene and VPL count,
                         shadowed and unshadowed: all LGH points, the Pareto front (labelled), uniform VPL
                         subsampling (measured; dashed: its unbiased model) and brute force over all VPLs
  error_vs_time_shadowed.png, error_vs_time_unshadowed.png
                         the same per parameter: one row per scene and VPL count, one column per parameter,
                         points coloured by its value (PNG only: as SVG they would be ~350 KB each)
  scaling.{png,svg}      light-pass time, frame time and overdraw vs VPL count (log axes)
  strip.png              images of a few settings beside the reference, and their error heat maps
  summary.md             the fronts, the equal-time factors against uniform subsampling and the
                         equal-error speed-ups over brute force, as Markdown tables (also printed)

Times: `time_ms` is what the shadowed estimate costs (LGH build + light pass + interleaving + shadow
rays + filter), `time_unshadowed_ms` what the unshadowed one costs (build + light pass + interleaving).
Uniform subsampling: brute force over M random lights of the N, scaled by N/M; its error model is
rmse(M) = c sqrt(1/M - 1/N) (sampling without replacement) and its time t(M) = a + b M, both fitted to
the measured points; brute force over all N is exact (error 0) and takes t(N).
Needs Debian's python3-matplotlib (and numpy, which it pulls in).
"""

import argparse
import csv
import json
import math
import os
import sys
from collections import OrderedDict, defaultdict

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as error:  # a clear message rather than a traceback
    sys.exit(f"plot_sweep.py: {error}: install Debian's python3-matplotlib "
             f"(and run this script with the system python3, /usr/bin/python3)")

PARAMETERS = [("alpha", "alpha"), ("start_level", "start level"), ("interleave", "interleave n"),
              ("shadow_samples", "k (shadow rays)"), ("filter", "shadow filter")]
# Per error kind: the columns compared, the uniform-subsampling baselines (method, legend, marker, whether
# the unbiased error model applies) and brute force over all lights.
KINDS = {
    "shadowed": {"time": "time_ms", "error": "rmse_shadowed", "title": "shadowed (irradiance x visibility)",
                 "baselines": [("uniform_ratio", "uniform + frame's shadows", "s", False),
                               ("uniform_shadowed", "uniform, exact visibility", "x", True)],
                 "brute": "brute_force_shadowed", "brute_ratio": "brute_force_ratio"},
    "unshadowed": {"time": "time_unshadowed_ms", "error": "rmse_unshadowed", "title": "unshadowed irradiance",
                   "baselines": [("uniform", "uniform subsampling", "x", True)], "brute": "brute_force"},
}


def save(fig, path, dpi):
    """Saves a figure; PNGs are then reduced to a 256-colour palette (a third of the size, and plots have
    few colours anyway) when Pillow is there (Debian's python3-matplotlib pulls in python3-pil)."""
    fig.savefig(path, dpi=dpi, bbox_inches="tight", pad_inches=0.05)
    if path.endswith(".png"):
        try:
            from PIL import Image
        except ImportError:
            return path
        with Image.open(path) as image:
            reduced = image.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
        reduced.save(path, optimize=True)
    return path


def number(value):
    try:
        v = float(value)
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_sweep.py: {path}: no rows")
    for column in ("scene", "method", "series", "time_ms", "rmse_shadowed"):
        if column not in rows[0]:
            sys.exit(f"plot_sweep.py: {path}: no column '{column}' (not a sweep.csv?)")
    return rows


def label(row):
    text = f"a={float(row['alpha']):g} S{row['start_level']} {row['interleave']}x{row['interleave']} k={row['shadow_samples']}"
    return text + (" raw" if row["filter"] == "off" else "")


def pareto(points):
    """points: (time, error, row); the points no other point beats in both, by time."""
    front, best = [], math.inf
    for t, e, row in sorted(points, key=lambda p: (p[0], p[1])):
        if e < best:
            front.append((t, e, row))
            best = e
    return front


class UniformModel:
    """Brute force over M uniformly chosen lights of N: rmse = c sqrt(1/M - 1/N), time = a + b M."""

    def __init__(self, rows, kind, n, fit=True):
        spec = KINDS[kind]
        self.n = n
        self.points = []
        for r in rows:
            t, e, m = number(r[spec["time"]]), number(r[spec["error"]]), number(r["subset_lights"])
            if t is not None and e is not None and m:
                self.points.append((m, t, e))
        self.points.sort()
        self.ok = fit and len(self.points) >= 2
        if not self.ok:
            return
        ms = np.array([p[0] for p in self.points])
        ts = np.array([p[1] for p in self.points])
        # Time: least squares line; the error constant: geometric mean over the points whose image is
        # not mostly empty (an error near 1 or above means a handful of lights lit nothing here).
        self.b, self.a = np.polyfit(ms, ts, 1)
        self.b = max(self.b, 1e-12)
        usable = [(m, e) for m, _, e in self.points if e < 0.9] or [(m, e) for m, _, e in self.points]
        self.c = math.exp(np.mean([math.log(e) - 0.5 * math.log(max(1 / m - 1 / n, 1e-300)) for m, e in usable]))

    def time(self, m):
        return self.a + self.b * m

    def error_at_time(self, t):
        m = (t - self.a) / self.b
        return self.c * math.sqrt(max(1 / m - 1 / self.n, 0)) if m >= 1 else None

    def time_for_error(self, e):
        m = 1 / ((e / self.c) ** 2 + 1 / self.n)
        return self.time(m), m


def cases_of(rows):
    cases = OrderedDict()
    for r in rows:
        if r["series"] in ("grid", "baseline"):
            cases.setdefault((r["scene"], int(r["vpl_target"])), []).append(r)
    return cases


def analyse(rows):
    """Per case and kind: the LGH front, the uniform model, brute force, and the comparisons."""
    results = OrderedDict()
    for (scene, vpls), case_rows in cases_of(rows).items():
        lgh = [r for r in case_rows if r["method"] == "lgh"]
        n = int(case_rows[0]["input_lights"])
        for kind, spec in KINDS.items():
            points = [(number(r[spec["time"]]), number(r[spec["error"]]), r) for r in lgh]
            points = [p for p in points if p[0] is not None and p[1] is not None]
            if not points:
                continue
            front = pareto(points)
            baselines = OrderedDict()
            for method, legend, marker, fit in spec["baselines"]:
                b = UniformModel([r for r in case_rows if r["method"] == method], kind, n, fit)
                if b.points:
                    baselines[method] = {"model": b, "legend": legend, "marker": marker}
            brute = next((r for r in case_rows if r["method"] == spec["brute"]), None)
            brute_ms = number(brute[spec["time"]]) if brute else None
            ratio = next((r for r in case_rows if r["method"] == spec.get("brute_ratio")), None)
            # Equal time: each measured baseline point against the best LGH error reached in no more time.
            equal_time = OrderedDict()
            for method, b in baselines.items():
                for m, t, e in b["model"].points:
                    reached = [fe for ft, fe, _ in front if ft <= t]
                    if reached:
                        equal_time.setdefault(method, []).append(
                            {"M": m, "time": t, "uniform": e, "lgh": min(reached), "factor": e / min(reached)})
            # Equal error: each front point against the time uniform subsampling (the unbiased model) and
            # full brute force need for that error.
            model = next((b["model"] for b in baselines.values() if b["model"].ok), None)
            equal_error = []
            for t, e, r in front:
                entry = {"label": label(r), "time": t, "error": e, "row": r}
                if model:
                    tu, mu = model.time_for_error(e)
                    entry.update(uniform_time=tu, uniform_lights=mu, speedup_uniform=tu / t)
                if brute_ms:
                    entry["speedup_brute"] = brute_ms / t
                equal_error.append(entry)
            # The peer method's points (stochastic lightcuts), shadowed only, and the equal-time comparison.
            rtslc = []
            if kind == "shadowed":
                rtslc = [(number(r[spec["time"]]), number(r[spec["error"]]), r) for r in case_rows
                         if r["method"] == "rtslc"]
                rtslc = [p for p in rtslc if p[0] is not None and p[1] is not None]
            results[(scene, vpls, kind)] = {"points": points, "front": front, "baselines": baselines, "model": model,
                                            "rtslc_points": rtslc, "rtslc_front": pareto(rtslc) if rtslc else [],
                                            "versus_rtslc": versus(front, pareto(rtslc)) if rtslc else [],
                                            "curves": {measure: curves_compared(f["lgh"], f["rtslc"])
                                                       for measure, f in fronts_by_measure(case_rows).items()}
                                            if rtslc else {},
                                            "brute_ms": brute_ms,
                                            "brute_extrapolated": bool(brute and brute["extrapolated"] == "1"),
                                            "brute_ratio": (number(ratio[spec["time"]]), number(ratio[spec["error"]]))
                                            if ratio else None,
                                            "equal_time": equal_time, "equal_error": equal_error, "n": n,
                                            "rows": case_rows}
    return results


def best_within(front, t):
    reached = [e for ft, e, _ in front if ft <= t]
    return min(reached) if reached else None


def versus(lgh_front, rtslc_front):
    """At each time budget where both fronts have a point (each front point's time, from the later of the two
    fronts' first points on): the best error either reaches in no more time, and LGH / RTSLC."""
    budgets = sorted({t for t, _, _ in lgh_front} | {t for t, _, _ in rtslc_front})
    rows = []
    for t in budgets:
        el, er = best_within(lgh_front, t), best_within(rtslc_front, t)
        if el is not None and er is not None:
            rows.append({"time": t, "lgh": el, "rtslc": er, "ratio": el / er})
    return rows


def log_curve(front):
    """A Pareto front as a curve: (log time, log error) of its points, joined by straight lines in log-log."""
    return [(math.log(t), math.log(e)) for t, e, _ in front if t > 0 and e > 0]


def along(curve, x, xi=0, yi=1):
    """The curve's coordinate yi where its coordinate xi is x (linear between points); None outside it."""
    pts = sorted(curve, key=lambda p: p[xi])
    if not pts or x < pts[0][xi] or x > pts[-1][xi]:
        return None
    for a, b in zip(pts, pts[1:]):
        if a[xi] <= x <= b[xi]:
            f = (x - a[xi]) / (b[xi] - a[xi]) if b[xi] > a[xi] else 0.0
            return a[yi] + f * (b[yi] - a[yi])
    return pts[0][yi]


def curves_compared(lgh_front, rtslc_front, samples=33):
    """The two fronts as curves (log error against log time), compared only where both reach: LGH / lightcuts
    error at equal time over the time range both cover, and lightcuts / LGH time at equal error (the LGH's
    speed-up) over the error range both cover; each at `samples` log-spaced values, as median and range."""
    lc, rc = log_curve(lgh_front), log_curve(rtslc_front)
    if len(lc) < 1 or len(rc) < 1:
        return None
    result = {}
    lo, hi = max(lc[0][0], rc[0][0]), min(lc[-1][0], rc[-1][0])
    if hi >= lo:
        xs = [min(lo + (hi - lo) * i / (samples - 1), hi) for i in range(samples)] if hi > lo else [lo]
        ratios = [math.exp(along(lc, x) - along(rc, x)) for x in xs]
        result["equal_time"] = {"from_ms": math.exp(lo), "to_ms": math.exp(hi), "median": float(np.median(ratios)),
                                "min": min(ratios), "max": max(ratios)}
    # Errors fall along a front, so time is a function of error on it.
    lo, hi = max(lc[-1][1], rc[-1][1]), min(lc[0][1], rc[0][1])
    if hi >= lo:
        ys = [min(lo + (hi - lo) * i / (samples - 1), hi) for i in range(samples)] if hi > lo else [lo]
        speedups = [math.exp(along(rc, y, 1, 0) - along(lc, y, 1, 0)) for y in ys]
        result["equal_error"] = {"from": math.exp(lo), "to": math.exp(hi), "median": float(np.median(speedups)),
                                 "min": min(speedups), "max": max(speedups)}
    return result


def check_curves():
    """--self-test: two power-law fronts e = c t^-p whose answer is known: the LGH's at half the lightcuts'
    error at every time (0.5x at equal time) reaches each error 2^(1/p) times sooner; only the overlap counts."""
    p = 0.5
    lgh = [(t, 1.0 * t ** -p, None) for t in (10, 20, 40, 80, 160)]
    rtslc = [(t, 2.0 * t ** -p, None) for t in (30, 60, 120, 240, 480)]
    c = curves_compared(lgh, rtslc)
    et, ee = c["equal_time"], c["equal_error"]
    failures = []
    if not (abs(et["min"] - 0.5) < 1e-9 and abs(et["max"] - 0.5) < 1e-9):
        failures.append(f"equal time {et['min']}-{et['max']}, want 0.5")
    if not (abs(et["from_ms"] - 30) < 1e-6 and abs(et["to_ms"] - 160) < 1e-6):
        failures.append(f"time overlap {et['from_ms']}-{et['to_ms']}, want 30-160")
    if not (abs(ee["min"] - 2 ** (1 / p)) < 1e-9 and abs(ee["max"] - 2 ** (1 / p)) < 1e-9):
        failures.append(f"equal error {ee['min']}-{ee['max']}, want {2 ** (1 / p)}")
    if curves_compared(lgh, [(1000, 0.01, None), (2000, 0.005, None)]).get("equal_time"):
        failures.append("fronts with no time in common were compared")
    if failures:
        sys.exit("plot_sweep.py --self-test: " + "; ".join(failures))
    print("plot_sweep.py --self-test: the curve comparison passes")


def fronts_by_measure(case_rows):
    """Per error measure (relative RMSE, relative MAE): the LGH's and the lightcuts' shadowed Pareto fronts."""
    fronts = {}
    for measure, column in (("rmse", "rmse_shadowed"), ("mae", "mae_shadowed")):
        by_method = {}
        for method in ("lgh", "rtslc"):
            pts = [(number(r["time_ms"]), number(r.get(column, "")), r) for r in case_rows if r["method"] == method]
            by_method[method] = pareto([p for p in pts if p[0] is not None and p[1] is not None])
        fronts[measure] = by_method
    return fronts


def unit_costs(case_rows):
    """Each method's time per unit of work, medians over the case's grid points: the LGH's build per input
    light, light pass per rasterized fragment, shadow rays per ray; the light tree's build per node (2N for N
    leaves) and a lightcut sample (one descent, one shading, one shadow ray)."""
    def med(values):
        values = [x for x in values if x is not None and math.isfinite(x)]
        return float(np.median(values)) if values else None

    def col(r, name):
        return number(r.get(name, ""))

    lgh = [r for r in case_rows if r["method"] == "lgh" and r["series"] == "grid"]
    rtslc = [r for r in case_rows if r["method"] == "rtslc" and r["series"] == "grid"]
    def pixels(r):
        return col(r, "width") * col(r, "height")

    costs = {}
    if lgh:
        costs["lgh_build_ns"] = med([col(r, "build_ms") * 1e6 / col(r, "input_lights") for r in lgh
                                     if col(r, "build_ms") and col(r, "input_lights")])
        costs["fragment_ns"] = med([col(r, "light_pass_ms") * 1e6 / (col(r, "fragments_per_pixel") * pixels(r))
                                    for r in lgh if col(r, "light_pass_ms") and col(r, "fragments_per_pixel")])
        costs["shadow_ray_us"] = med([col(r, "shadow_rays_ms") * 1e3 / (col(r, "shadow_samples") * pixels(r))
                                      for r in lgh if col(r, "shadow_rays_ms") and col(r, "shadow_samples")])
    if rtslc:
        n = col(rtslc[0], "input_lights")
        costs["tree_node_ns"] = med([col(r, "build_ms") * 1e6 / (2 * col(r, "input_lights")) for r in rtslc
                                     if col(r, "build_ms") and col(r, "input_lights")])
        costs["lightcut_sample_us"] = med([col(r, "rtslc_sampling_ms") * 1e3 / (col(r, "shadow_samples") * pixels(r))
                                           for r in rtslc if col(r, "rtslc_sampling_ms") and col(r, "shadow_samples")])
        costs["tree_depth"] = math.log2(n) if n else None
    return costs


def rtslc_label(row):
    block, m = row.get("rtslc_block", ""), row["interleave"]
    return f"n={row['shadow_samples']} B{block}" + (f" {m}x{m}" if m not in ("", "1") else "") + (
        " raw" if row["filter"] == "off" else "")


def case_title(scene, vpls, n):
    return f"{scene}, {vpls // 1000}K VPLs ({n:,} lights)"


def colors_for(values):
    cmap = plt.get_cmap("viridis")
    values = sorted(values, key=lambda v: (number(v) is None, number(v) if number(v) is not None else v))
    return {v: cmap(i / max(len(values) - 1, 1)) for i, v in enumerate(values)}


def plot_error_vs_time(results, kind, out):
    keys = [k for k in results if k[2] == kind]
    if not keys:
        return []
    rows_n, cols_n = len(keys), len(PARAMETERS)
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(3.1 * cols_n, 2.5 * rows_n), squeeze=False, sharey="row")
    for i, key in enumerate(keys):
        res = results[key]
        ts = [p[0] for p in res["points"]]
        es = [p[1] for p in res["points"]]
        for j, (column, name) in enumerate(PARAMETERS):
            ax = axes[i][j]
            values = sorted({p[2][column] for p in res["points"]})
            colors = colors_for(values)
            for v in colors:
                sel = [p for p in res["points"] if p[2][column] == v]
                ax.scatter([p[0] for p in sel], [p[1] for p in sel], s=16, color=colors[v], label=v or "- (k=0)",
                           zorder=3, edgecolors="none")
            fx = [p[0] for p in res["front"]]
            fy = [p[1] for p in res["front"]]
            ax.step(fx + [max(ts) * 1.5], fy + [fy[-1]], where="post", color="black", lw=1, zorder=2,
                    label="Pareto front")
            draw_error_axes(ax, res, ts, es)
            if i == 0:
                ax.set_title(name, fontsize=9)
            if j == 0:
                ax.set_ylabel(case_title(key[0], key[1], res["n"]) + "\nrelative RMSE", fontsize=7)
            if i == rows_n - 1:
                ax.set_xlabel("time per frame (ms)", fontsize=8)
            # The parameter's values once per column; the front and the baselines once per row.
            handles, labels = ax.get_legend_handles_labels()
            if i == 0 or j == 0:
                values_shown = {v or "- (k=0)" for v in colors}
                keep = [k for k, l in enumerate(labels)
                        if (i == 0 and l in values_shown) or (j == 0 and l not in values_shown)]
                ax.legend([handles[k] for k in keep], [labels[k] for k in keep], fontsize=5.5, loc="lower left",
                          framealpha=0.7, ncol=1)
    fig.suptitle(f"Error vs time, {KINDS[kind]['title']}: LGH points coloured by one parameter, Pareto front (black), "
                 f"uniform VPL subsampling (dashed: unbiased model), brute force", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    path = save(fig, os.path.join(out, f"error_vs_time_{kind}.png"), 80)
    plt.close(fig)
    return [path]


def draw_error_axes(ax, res, ts, es):
    """An error-vs-time panel's frame: the baselines, log-log axes from the lowest error shown, a light grid."""
    draw_baselines(ax, res, ts)
    ax.set_xscale("log")
    ax.set_yscale("log")
    low = min(es + ([res["brute_ratio"][1]] if res["brute_ratio"] and res["brute_ratio"][1] else []))
    ax.set_ylim(low * 0.7, max(2.0, max(es) * 1.3))
    ax.grid(True, which="major", lw=0.3, alpha=0.5)
    ax.minorticks_off()  # log axes' minor ticks triple the SVG
    ax.tick_params(labelsize=7)


def draw_baselines(ax, res, ts):
    for bi, (method, b) in enumerate(res["baselines"].items()):
        model, color = b["model"], ("0.45", "tab:brown")[bi % 2]
        ax.plot([p[1] for p in model.points], [p[2] for p in model.points], marker=b["marker"], ms=3.5, color=color,
                lw=0.6 if not model.ok else 0, zorder=2, label=b["legend"])
        if model.ok:
            lo = max(min(p[1] for p in model.points), model.time(1)) * 0.8
            hi = max(max(ts), max(p[1] for p in model.points)) * 1.5
            curve = [(t, model.error_at_time(t)) for t in np.geomspace(max(lo, 1e-3), hi, 40)]
            curve = [(t, e) for t, e in curve if e]
            ax.plot([c[0] for c in curve], [c[1] for c in curve], ls="--", color=color, lw=0.8)
    if res["brute_ratio"] and res["brute_ratio"][0]:
        ax.scatter([res["brute_ratio"][0]], [res["brute_ratio"][1]], marker="*", s=40, color="tab:red", zorder=4,
                   label="brute force + frame's shadows")
    if res["brute_ms"]:
        ax.axvline(res["brute_ms"], ls=":", color="tab:red", lw=1,
                   label="brute force, exact" + (" (extrapolated)" if res["brute_extrapolated"] else ""))


def plot_front(results, out):
    cases = list(OrderedDict.fromkeys((k[0], k[1]) for k in results))
    kinds = [k for k in KINDS if any(key[2] == k for key in results)]
    if not cases:
        return []
    fig, axes = plt.subplots(len(kinds), len(cases), figsize=(3.6 * len(cases), 3.1 * len(kinds)), squeeze=False)
    for i, kind in enumerate(kinds):
        for j, case in enumerate(cases):
            ax = axes[i][j]
            res = results.get((case[0], case[1], kind))
            if not res:
                ax.set_visible(False)
                continue
            ts = [p[0] for p in res["points"]]
            es = [p[1] for p in res["points"]]
            for start, marker in (("0", "o"), ("1", "^")):
                sel = [p for p in res["points"] if p[2]["start_level"] == start]
                ax.scatter([p[0] for p in sel], [p[1] for p in sel], s=10, marker=marker, color="tab:blue", alpha=0.35,
                           edgecolors="none", label=f"LGH, start S{start}")
            fx, fy = [p[0] for p in res["front"]], [p[1] for p in res["front"]]
            ax.step(fx + [max(ts) * 1.5], fy + [fy[-1]], where="post", color="black", lw=1, zorder=3)
            ax.scatter(fx, fy, s=14, color="black", zorder=4, label="LGH Pareto front")
            for n, (t, e, r) in enumerate(res["front"]):  # labels alternately above and below the front
                ax.annotate(short_label(r), (t, e), fontsize=4.5, xytext=(3, 2 if n % 2 else -6),
                            textcoords="offset points")
            if res.get("rtslc_points"):
                rp = res["rtslc_points"]
                ax.scatter([p[0] for p in rp], [p[1] for p in rp], s=10, marker="s", color="tab:orange", alpha=0.4,
                           edgecolors="none", label="stochastic lightcuts")
                rx, ry = [p[0] for p in res["rtslc_front"]], [p[1] for p in res["rtslc_front"]]
                ax.step(rx + [max(rx + ts) * 1.5], ry + [ry[-1]], where="post", color="tab:orange", lw=1, zorder=3,
                        label="lightcuts Pareto front")
                for n, (t, e, r) in enumerate(res["rtslc_front"]):
                    ax.annotate(rtslc_label(r), (t, e), fontsize=4.5, color="tab:orange",
                                xytext=(3, -6 if n % 2 else 2), textcoords="offset points")
                ts, es = ts + rx, es + [p[1] for p in rp]
            draw_error_axes(ax, res, ts, es)
            ax.set_title(f"{case_title(case[0], case[1], res['n'])}\n{KINDS[kind]['title']}", fontsize=7.5)
            ax.set_xlabel("time per frame (ms)", fontsize=7)
            if j == 0:
                ax.set_ylabel("relative RMSE vs exact", fontsize=7)
                ax.legend(fontsize=5, loc="lower left", framealpha=0.7)
    fig.tight_layout()
    files = [save(fig, os.path.join(out, f"front.{ext}"), 90) for ext in ("png", "svg")]
    plt.close(fig)
    return files


def plot_scaling(rows, out):
    rows = [r for r in rows if r["series"] == "scaling"]
    if not rows:
        return []
    fig, (ax_t, ax_o) = plt.subplots(1, 2, figsize=(10, 3.8))
    markers = ["o", "s", "^", "D"]
    for si, scene in enumerate(OrderedDict.fromkeys(r["scene"] for r in rows)):
        srows = [r for r in rows if r["scene"] == scene]
        for n in ("1", "4"):
            sel = sorted((r for r in srows if r["method"] == "lgh" and r["interleave"] == n), key=lambda r: int(r["input_lights"]))
            if not sel:
                continue
            x = [int(r["input_lights"]) for r in sel]
            light = [number(r["light_pass_ms"]) + (number(r["interleave_ms"]) or 0) for r in sel]
            color = f"C{si * 2 + (n == '4')}"
            ax_t.plot(x, light, marker=markers[si % 4], ms=4, color=color, label=f"{scene} light pass {n}x{n}")
            ax_t.plot(x, [number(r["frame_ms"]) for r in sel], marker=markers[si % 4], ms=3, ls=":", color=color,
                      label=f"{scene} frame {n}x{n}")
            ax_o.plot(x, [number(r["fragments_per_pixel"]) for r in sel], marker=markers[si % 4], ms=4, color=color,
                      label=f"{scene} {n}x{n}")
        brute = sorted((r for r in srows if r["method"] == "brute_force"), key=lambda r: int(r["input_lights"]))
        if brute:
            x = [int(r["input_lights"]) for r in brute]
            y = [number(r["time_unshadowed_ms"]) for r in brute]
            ax_t.plot(x, y, "--", color=f"C{si * 2}", alpha=0.6, lw=1, label=f"{scene} brute force (dashed: extrap.)")
            measured = [(a, b) for a, b, r in zip(x, y, brute) if r["extrapolated"] != "1"]
            if measured:
                ax_t.plot(*zip(*measured), "x", color=f"C{si * 2}", alpha=0.8)
    for ax in (ax_t, ax_o):
        ax.set_xscale("log")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.set_xlabel("input lights |S0|")
        ax.legend(fontsize=6)
    ax_t.set_yscale("log")
    ax_t.set_ylabel("ms")
    ax_t.set_title("light pass and frame time (alpha 1, S1, k 4)", fontsize=9)
    ax_o.set_ylabel("fragments rasterized per pixel")
    ax_o.set_title("overdraw of the light pass", fontsize=9)
    fig.tight_layout()
    files = [save(fig, os.path.join(out, f"scaling.{ext}"), 90) for ext in ("png", "svg")]
    plt.close(fig)
    return files


def load_npy(folder, name):
    path = os.path.join(folder, name)
    return np.load(path) if os.path.exists(path) else None


def tone(rgb, exposure):
    x = np.clip(rgb * exposure, 0, None)
    return np.clip((x / (1 + x)) ** (1 / 2.2), 0, 1)


def plot_strip(results, rows, out, csv_dir):
    """For the first case with images: the reference, a few settings and uniform subsampling at equal time."""
    for (scene, vpls, kind), res in results.items():
        if kind != "shadowed":
            continue
        prefix = f"{scene}_{vpls // 1000}K_" if vpls % 1000 == 0 else None
        images = os.path.join(csv_dir, "images")
        ref = load_npy(images, f"{prefix}reference_shadowed.npy") if prefix else None
        albedo = load_npy(images, f"{prefix}albedo.npy") if prefix else None
        if ref is None or albedo is None:
            continue
        lgh = {label(p[2]): p for p in res["points"] if p[2]["image"]}
        chosen = []
        for wanted in ("a=1 S1 1x1 k=4", "a=2 S0 1x1 k=4", "a=1 S1 4x4 k=4"):
            if wanted in lgh:
                chosen.append((wanted, lgh[wanted]))
        if not chosen:
            continue
        default_time = chosen[0][1][0]
        for method, name in (("uniform_ratio", "uniform + frame's shadows"), ("uniform_shadowed", "uniform, exact vis.")):
            uniform = [r for r in res["rows"] if r["method"] == method and r["image"]]
            if uniform:
                u = min(uniform, key=lambda r: abs(math.log(number(r["time_ms"]) / default_time)))
                chosen.append((f"{name} M={int(u['subset_lights']):,}", (number(u["time_ms"]), number(u["rmse_shadowed"]), u)))
        radiance = lambda irr: irr * albedo / math.pi
        ref_rad = radiance(ref)
        lum = lambda x: 0.2126 * x[..., 0] + 0.7152 * x[..., 1] + 0.0722 * x[..., 2]
        exposure = 1.0 / max(np.percentile(lum(ref_rad), 99), 1e-12)
        ref_lum = lum(ref)
        scale = max(float(np.mean(ref_lum)), 1e-30)
        cols = 1 + len(chosen)
        fig, axes = plt.subplots(2, cols, figsize=(2.3 * cols, 3.0), squeeze=False)
        # Half resolution keeps the PNG small; the error maps are computed at full resolution first.
        half = lambda a: a[::2, ::2]
        axes[0][0].imshow(half(tone(ref_rad, exposure)), interpolation="lanczos")
        axes[0][0].set_title("reference (exact)", fontsize=7)
        vis = np.where(lum(load_npy(images, f"{prefix}reference_unshadowed.npy")) > 0, ref_lum /
                       np.maximum(lum(load_npy(images, f"{prefix}reference_unshadowed.npy")), 1e-30), 1)
        axes[1][0].imshow(half(vis), cmap="gray", vmin=0, vmax=1)
        axes[1][0].set_title("reference visibility", fontsize=7)
        heat = None
        for c, (name, (t, e, r)) in enumerate(chosen, start=1):
            img = np.load(os.path.join(csv_dir, r["image"]))
            axes[0][c].imshow(half(tone(radiance(img), exposure)), interpolation="lanczos")
            axes[0][c].set_title(f"{name}\n{t:,.0f} ms, rmse {e:.3f}", fontsize=7)
            heat = axes[1][c].imshow(half(np.abs(lum(img) - ref_lum) / scale), cmap="magma", vmin=0, vmax=2)
            axes[1][c].set_title("|error| / mean", fontsize=7)
        for ax in axes.flat:
            ax.set_xticks([])
            ax.set_yticks([])
        if heat is not None:
            fig.colorbar(heat, ax=list(axes[1]), fraction=0.02, pad=0.01).ax.tick_params(labelsize=6)
        fig.suptitle(f"{case_title(scene, vpls, res['n'])}: shadowed indirect light (albedo/pi x irradiance)", fontsize=8)
        path = save(fig, os.path.join(out, "strip.png"), 100)
        plt.close(fig)
        return [path]
    return []


def fmt_factor(value, digits):
    """'2.3x', or '-' where there is no such factor (a baseline the run did not measure)."""
    if value is None or not np.isfinite(value):
        return "-"
    return f"{value:,.{digits}f}x"


def fmt_ms(v):
    return "-" if v is None else (f"{v:,.0f}" if v >= 100 else f"{v:.1f}")


def short_label(row, spell_k=False):
    """'a=2 S0 4x4' (+ ' k=1', ' raw' where not the default k = 4 with the filter; k = 0 is implied);
    spell_k: k always spelled out, as the summary's tables do."""
    text = f"a={float(row['alpha']):g} S{row['start_level']} {row['interleave']}x{row['interleave']}"
    if spell_k or row["shadow_samples"] not in ("0", "4"):
        text += f" k={row['shadow_samples']}"
    return text + (" raw" if row["filter"] == "off" else "")


def load_json(csv_path):
    path = os.path.splitext(csv_path)[0] + ".json"
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def summary(results, rows, info):
    """Markdown: a headline table over the cases, then each case's fronts and comparisons."""
    lines = []
    add = lines.append
    cases = OrderedDict()
    for (scene, vpls, kind), res in results.items():
        cases.setdefault((scene, vpls), {})[kind] = res
    references = {}
    for c in (info or {}).get("cases", []):
        if c.get("series") == "grid":
            references[(c["name"], c["vpl_target"])] = c
    if info:
        add(f"Measured {info.get('generated', '?')} on {info.get('device', '?')}, {info.get('hardware_threads', '?')} "
            f"hardware threads, {info.get('width')}x{info.get('height')}, median of {info.get('repeats')} frames per point.")
        others = [number(r.get("others_cpu")) for r in rows]
        others = [o for o in others if o is not None]
        if "samples_retaken" in info:
            add(f"Timed samples taken again because other processes used more than 25% of the machine: "
                f"{info['samples_retaken']}, still contended after the last try: {info['samples_contended']}; "
                f"largest share of the machine other processes took during a kept sample: "
                f"{max(others) if others else 0:.2f}.")
        add("")

    # Headline: equal-time factors (the median over the baseline's measured points that the LGH front
    # reaches in no more time) and equal-error speed-ups (the range over the front).
    add("| scene, VPLs | lights | reference (Embree) | unshadowed: error of uniform / LGH at equal time | "
        "shadowed: uniform, exact visibility / LGH | shadowed: uniform + frame's shadows / LGH | "
        "unshadowed: speed-up at equal error vs uniform | vs brute force |")
    add("|---|---:|---|---|---|---|---|---|")
    for (scene, vpls), kinds in cases.items():
        any_res = next(iter(kinds.values()))
        ref = references.get((scene, vpls), {}).get("reference", {})
        ref_text = "-"
        if ref:
            ref_text = (f"{ref['pixels']:,} px, {ref['seconds']:.0f} s, {ref['rays'] / max(ref['seconds'], 1e-9) / 1e6:.1f} M rays/s"
                        + (" (cached)" if ref.get("from_cache") else ""))

        def factor(kind, method):
            entries = kinds.get(kind, {}).get("equal_time", {}).get(method, [])
            if not entries:
                return "-"
            f = [x["factor"] for x in entries]
            return f"{float(np.median(f)):.2f}x ({min(f):.2f}-{max(f):.2f}, {len(f)} pts)"

        un = kinds.get("unshadowed", {})
        ee = un.get("equal_error", [])
        su = [x["speedup_uniform"] for x in ee if "speedup_uniform" in x]
        sb = [x["speedup_brute"] for x in ee if "speedup_brute" in x]
        add(f"| {scene}, {vpls // 1000}K | {any_res['n']:,} | {ref_text} | {factor('unshadowed', 'uniform')} | "
            f"{factor('shadowed', 'uniform_shadowed')} | {factor('shadowed', 'uniform_ratio')} | "
            + (f"{min(su):.1f}-{max(su):.1f}x" if su else "-") + " | "
            + (f"{min(sb):.1f}-{max(sb):.0f}x" if sb else "-") + " |")
    add("")

    for (scene, vpls), kinds in cases.items():
        any_res = next(iter(kinds.values()))
        add(f"### {case_title(scene, vpls, any_res['n'])}\n")
        c = references.get((scene, vpls))
        if c:
            ref = c["reference"]
            full_rays = ref["rays"] / max(ref["fraction"], 1e-9)
            add(f"Reference: {ref['pixels']:,} of {ref['image_pixels']:,} pixels (fraction {ref['fraction']:.3g}), "
                f"{ref['rays']:,} shadow rays in {ref['seconds']:.1f} s on {ref['threads']} threads "
                f"({ref['rays'] / max(ref['seconds'], 1e-9) / 1e6:.1f} M rays/s)"
                + (", from the cache" if ref.get("from_cache") else "") + ". "
                f"LGH build {float(np.median(c['build_ms'])):.0f} ms, L = {c['levels']}.")
        un, sh = kinds.get("unshadowed"), kinds.get("shadowed")
        if un and un["brute_ms"]:
            add(f"Brute force over all {un['n']:,} lights: unshadowed {fmt_ms(un['brute_ms'])} ms"
                + (" (extrapolated from the uniform series)" if un["brute_extrapolated"] else " (measured)")
                + (f"; shadowed through the GPU BVH {fmt_ms(sh['brute_ms'])} ms (extrapolated"
                   + (f", {sh['brute_ms'] * 1e6 / full_rays:.0f} ns per ray" if c else "") + ")" if sh and sh["brute_ms"] else "")
                + (f"; brute-force light pass + the frame's shadows: {fmt_ms(sh['brute_ratio'][0])} ms, "
                   f"shadowed rel. RMSE {sh['brute_ratio'][1]:.3f}" if sh and sh["brute_ratio"] else "") + ".")
        add("")
        if un:
            add("Unshadowed front (time = LGH build + light pass + interleaving):\n")
            add("| settings | ms | rel. RMSE | fragments/px | uniform subsampling at this error: M, ms | speed-up | "
                "vs brute force |")
            add("|---|---:|---:|---:|---|---:|---:|")
            for x in un["equal_error"]:
                r = x["row"]
                add(f"| {short_label(r, spell_k=True)} | {fmt_ms(x['time'])} | {x['error']:.3f} | "
                    f"{float(r['fragments_per_pixel']):,.0f} | "
                    + (f"{x['uniform_lights']:,.0f}, {fmt_ms(x['uniform_time'])}" if "uniform_time" in x else "-")
                    + f" | {fmt_factor(x.get('speedup_uniform'), 1)} | {fmt_factor(x.get('speedup_brute'), 0)} |")
            add("")
        if sh:
            add("Shadowed front (time = build + light pass + shadow rays + filter):\n")
            add("| settings | ms | rel. RMSE shadowed | unshadowed | fragments/px | vs shadowed brute force |")
            add("|---|---:|---:|---:|---:|---:|")
            for x in sh["equal_error"]:
                r = x["row"]
                add(f"| {short_label(r, spell_k=True)} | {fmt_ms(x['time'])} | {x['error']:.3f} | "
                    f"{float(r['rmse_unshadowed']):.3f} | {float(r['fragments_per_pixel']):,.0f} | "
                    f"{fmt_factor(x.get('speedup_brute'), 0)} |")
            add("")
        if sh and sh.get("rtslc_front"):
            add("Stochastic lightcuts front (time = light tree build + cuts + sampling + irradiance filter):\n")
            add("| settings | ms | rel. RMSE shadowed | cuts ms | sampling ms |")
            add("|---|---:|---:|---:|---:|")
            for t, e, r in sh["rtslc_front"]:
                add(f"| {rtslc_label(r)} | {fmt_ms(t)} | {e:.3f} | {fmt_ms(number(r.get('rtslc_cuts_ms')))} | "
                    f"{fmt_ms(number(r.get('rtslc_sampling_ms')))} |")
            add("")
            for measure, name in (("rmse", "relative RMSE"), ("mae", "relative MAE")):
                c = sh["curves"].get(measure)
                if not c:
                    continue
                text = f"The fronts as curves ({name}; log error against log time, compared where both reach): "
                if "equal_time" in c:
                    et = c["equal_time"]
                    text += (f"LGH / lightcuts error at equal time median {et['median']:.2f}x, range {et['min']:.2f}-"
                             f"{et['max']:.2f}x over {fmt_ms(et['from_ms'])}-{fmt_ms(et['to_ms'])} ms")
                if "equal_error" in c:
                    ee = c["equal_error"]
                    text += ("; " if "equal_time" in c else "") + (
                        f"the LGH's speed-up at equal error (lightcuts' time / LGH's) median {ee['median']:.2f}x, "
                        f"range {ee['min']:.2f}-{ee['max']:.2f}x over errors {ee['to']:.3f}-{ee['from']:.3f}")
                add(text + ".\n")
            v = sh["versus_rtslc"]
            if v:
                ratios = [x["ratio"] for x in v]
                add(f"LGH or light tree, at equal time (each budget where both fronts have a point; the best error "
                    f"each reaches in no more time): LGH / lightcuts median {float(np.median(ratios)):.2f}x, range "
                    f"{min(ratios):.2f}-{max(ratios):.2f}x over {len(ratios)} budgets (below 1: the LGH is more "
                    "accurate).\n")
                add("| budget ms | LGH | lightcuts | LGH / lightcuts |")
                add("|---:|---:|---:|---:|")
                for x in v:
                    add(f"| {fmt_ms(x['time'])} | {x['lgh']:.3f} | {x['rtslc']:.3f} | {x['ratio']:.2f}x |")
                add("")
        for kind, res in kinds.items():
            for method, entries in res["equal_time"].items():
                add(f"Equal time, {kind}, {res['baselines'][method]['legend']} (its error / the best LGH error in no more "
                    "time): " + ", ".join(f"M={x['M']:,.0f} at {fmt_ms(x['time'])} ms: {x['uniform']:.3f} / {x['lgh']:.3f} "
                                          f"= {x['factor']:.2f}x" for x in entries) + ".\n")
    costs = [(scene, vpls, unit_costs(next(iter(kinds.values()))["rows"])) for (scene, vpls), kinds in cases.items()]
    if any(c for _, _, c in costs):
        add("Cost per unit of work on this device (medians over the grid points; pixels: the image's, W x H), so "
            "that the times can be re-weighted for another device:\n")
        add("| scene, VPLs | LGH build, ns per input light | light pass, ns per rasterized fragment | shadow rays "
            "(targets + rays), us per ray | light tree build, ns per node | lightcut sample (descent of ~log2 N "
            "nodes, shading, ray), us | tree depth log2 N |")
        add("|---|---:|---:|---:|---:|---:|---:|")
        for scene, vpls, c in costs:
            def v(key, digits=2):
                return f"{c[key]:.{digits}f}" if c.get(key) is not None else "-"
            add(f"| {scene}, {vpls // 1000}K | {v('lgh_build_ns', 0)} | {v('fragment_ns', 1)} | {v('shadow_ray_us')} | "
                f"{v('tree_node_ns', 0)} | {v('lightcut_sample_us')} | {v('tree_depth', 1)} |")
        add("")
    curves = [(scene, vpls, kinds["shadowed"]["curves"]) for (scene, vpls), kinds in cases.items()
              if kinds.get("shadowed", {}).get("curves")]
    if curves:
        add("LGH or light tree, the fronts as curves (shadowed; log error against log time, each compared only where "
            "both fronts reach; below 1 at equal time and above 1 at equal error: the LGH is better):\n")
        add("| scene, VPLs | time range both cover, ms | LGH / lightcuts error at equal time, RMSE | the same, MAE | "
            "LGH speed-up at equal error, RMSE | the same, MAE |")
        add("|---|---|---|---|---|---|")

        def cell(c, key):
            x = (c or {}).get(key)
            return f"{x['median']:.2f}x ({x['min']:.2f}-{x['max']:.2f})" if x else "no overlap"

        for scene, vpls, c in curves:
            et = (c.get("rmse") or {}).get("equal_time")
            span = f"{fmt_ms(et['from_ms'])}-{fmt_ms(et['to_ms'])}" if et else "-"
            add(f"| {scene}, {vpls // 1000}K | {span} | {cell(c.get('rmse'), 'equal_time')} | "
                f"{cell(c.get('mae'), 'equal_time')} | {cell(c.get('rmse'), 'equal_error')} | "
                f"{cell(c.get('mae'), 'equal_error')} |")
        add("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", nargs="?", help="sweep.csv written by lgh-bench sweep")
    parser.add_argument("--out", help="output folder (default: the CSV's folder)")
    parser.add_argument("--self-test", action="store_true", help="check the curve comparison on known fronts")
    args = parser.parse_args()
    if args.self_test:
        check_curves()
        return
    if not args.csv:
        parser.error("the sweep.csv to plot is missing")
    if not os.path.isfile(args.csv):
        sys.exit(f"plot_sweep.py: {args.csv}: no such file (run lgh-bench sweep first)")
    csv_dir = os.path.dirname(os.path.abspath(args.csv))
    out = args.out or csv_dir
    os.makedirs(out, exist_ok=True)
    plt.rcParams.update({"svg.fonttype": "none", "font.size": 8})
    rows = read_rows(args.csv)
    results = analyse(rows)
    files = plot_front(results, out)
    for kind in KINDS:
        files += plot_error_vs_time(results, kind, out)
    files += plot_scaling(rows, out)
    files += plot_strip(results, rows, out, csv_dir)
    text = summary(results, rows, load_json(args.csv))
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write(text + "\n")
    files.append(os.path.join(out, "summary.md"))
    print(text)
    print("\nwrote " + ", ".join(os.path.relpath(p) for p in files))


if __name__ == "__main__":
    main()
