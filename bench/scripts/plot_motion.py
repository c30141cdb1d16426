#!/usr/bin/env python3
"""Plots lgh-bench motion's per-frame CSV: each configuration's error and temporal error over the sequence.

Usage: bench/scripts/plot_motion.py motion.csv out.png [title]
The CSV is lgh-bench motion --csv's: frame, time, configuration, error, temporal_error, ms, ...
(docs/measurements.md, "Under motion", has the commands that made the committed figures).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = list(csv.DictReader(open(sys.argv[1])))
    configurations = list(dict.fromkeys(r["configuration"] for r in rows))
    figure, (error, temporal) = plt.subplots(1, 2, figsize=(11, 4), sharex=True)
    for name in configurations:
        mine = [r for r in rows if r["configuration"] == name]
        style = "--" if name.startswith("lightcuts") else "-"
        frames = [int(r["frame"]) for r in mine]
        error.plot(frames, [float(r["error"]) for r in mine], style, label=name)
        changes = [(int(r["frame"]), float(r["temporal_error"])) for r in mine if r["temporal_error"]]
        temporal.plot([f for f, _ in changes], [t for _, t in changes], style, label=name)
    error.set_title("error: relative RMSE against the frame's reference")
    temporal.set_title("temporal error: of the frame-to-frame change")
    for axis in (error, temporal):
        axis.set_xlabel("frame")
        axis.set_ylim(bottom=0)
        axis.grid(alpha=0.3)
    temporal.legend(fontsize=8)
    if len(sys.argv) > 3:
        figure.suptitle(sys.argv[3])
    figure.tight_layout()
    figure.savefig(sys.argv[2], dpi=110)
    print("wrote", sys.argv[2])


if __name__ == "__main__":
    main()
