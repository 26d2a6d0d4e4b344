#!/usr/bin/python3
"""Plots the CSV of `clmarch bench --sweep`: kernel time against each error measure, one panel per
measure, with the Pareto front (no other row is both faster and more accurate) drawn as a line and
the defaults (the scene file's own settings and the default program: the `defaults` column) ringed. Needs matplotlib (scripts/setup.sh --plots).

    /usr/bin/python3 scripts/sweep-plot.py docs/sweeps/torus.csv -o docs/images/sweep_torus.png
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TIME_LABELS = {"kernel_ms": "kernel time, median (ms)", "kernel_ms_min": "kernel time, fastest run (ms)"}
# (column, axis label, True when larger is better). On the log axes an error of exactly 0 is drawn
# at the bottom of the panel (half the smallest error above 0).
MEASURES = [
    ("depth_rms", "depth error RMS (scene units)", False),
    ("normal_p99_deg", "normal angle error p99 (degrees)", False),
    ("mask_rate", "hit-mask mismatch rate (silhouette + interior; 0 at the bottom)", False),
    ("color_psnr_db", "color PSNR (dB, higher is better)", True),
]


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                for column in ("kernel_ms", "kernel_ms_min", "kernel_ms_max"):
                    row[column] = float(row[column])
                row["mask_rate"] = float(row["mask_silhouette_rate"]) + float(row["mask_interior_rate"])
                for column, _, _ in MEASURES:
                    row[column] = float(row[column])
                rows.append(row)
    return rows


def axis_of(row):
    """The swept key of a row ('render.epsilon'), or 'base' for the scene as given."""
    label = row["combination"]
    if not label:
        return "base"
    keys = [part.split("=", 1)[0] for part in label.split(" ")]
    return " ".join(k.replace("render.", "") for k in keys)


def value_of(row):
    label = row["combination"]
    return " ".join(part.split("=", 1)[1] for part in label.split(" ")) if label else "base"


def pareto_front(points, larger_is_better):
    """Indices of the points no other point beats in both time and error, sorted by time."""
    sign = -1.0 if larger_is_better else 1.0
    order = sorted(range(len(points)), key=lambda i: (points[i][0], sign * points[i][1]))
    front, best = [], math.inf
    for i in order:
        error = sign * points[i][1]
        if error < best:
            front.append(i)
            best = error
    return front


def plot(rows, title, output, time_column):
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    groups = sorted({axis_of(r) for r in rows}, key=lambda g: (g != "base", g))
    # tab20 keeps up to 20 swept settings apart (tab10 repeated its colours past 10).
    colors = {g: plt.cm.tab20(i % 20) for i, g in enumerate(groups)}
    for ax, (column, label, larger_is_better) in zip(axes.flat, MEASURES):
        values = [r[column] for r in rows]
        finite = [v for v in values if math.isfinite(v)]
        ceiling = max(finite) if finite else 1.0
        # An infinite PSNR (identical images) is drawn at the top of the panel.
        ys = [v if math.isfinite(v) else ceiling for v in values]
        if not larger_is_better:
            positive = [v for v in ys if v > 0.0]
            floor = 0.5 * min(positive) if positive else 1.0
            ys = [max(v, floor) for v in ys]
            ax.set_yscale("log")
        xs = [r[time_column] for r in rows]
        for group in groups:
            idx = [i for i, r in enumerate(rows) if axis_of(r) == group]
            ax.scatter([xs[i] for i in idx], [ys[i] for i in idx], color=colors[group], label=group, s=28, zorder=3)
        for i, r in enumerate(rows):
            ax.annotate(value_of(r), (xs[i], ys[i]), fontsize=6, xytext=(3, 3), textcoords="offset points")
        front = pareto_front(list(zip(xs, ys)), larger_is_better)
        ax.plot([xs[i] for i in front], [ys[i] for i in front], color="black", linewidth=1, zorder=2,
                label="Pareto front")
        defaults = [i for i, r in enumerate(rows) if r["defaults"] == "1"]
        ax.scatter([xs[i] for i in defaults], [ys[i] for i in defaults], s=140, facecolors="none", edgecolors="red",
                   linewidths=1.5, zorder=4, label="defaults")
        ax.set_xscale("log")
        ax.set_xlabel(TIME_LABELS[time_column])
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes.flat[0].legend(fontsize=7, loc="best")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(output, dpi=90)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="CSV files of clmarch bench --sweep (rows are pooled)")
    parser.add_argument("-o", "--output", required=True, help="the PNG to write")
    parser.add_argument("--title", help="figure title (default: the scene and size of the first row)")
    parser.add_argument("--time", choices=sorted(TIME_LABELS), default="kernel_ms",
                        help="the time axis: the median (default) or the fastest of the timed runs")
    args = parser.parse_args()
    rows = read_rows(args.csv)
    if not rows:
        sys.exit("sweep-plot.py: no rows in " + ", ".join(args.csv))
    first = rows[0]
    title = args.title or f"{first['scene']} {first['width']}x{first['height']}: time against error"
    plot(rows, title, args.output, args.time)
    print(f"sweep-plot.py: wrote {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
