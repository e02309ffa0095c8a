#!/usr/bin/env python3
"""Work-precision plot of a Fissure study: error against integration wall time, log-log, one
line per integrator configuration. Usage: plot_study.py results.csv [out_stem]
Writes out_stem.png and out_stem.svg (default: work_precision next to results.csv)."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        value = float(text)
    except ValueError:
        return math.nan
    return value


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    results = sys.argv[1]
    stem = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
        os.path.dirname(results) or ".", "work_precision")
    lines = {}
    measure = "error_max"
    with open(results, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    if rows and all(math.isnan(number(r["error_max"])) for r in rows):
        measure = "probe_error"
    for r in rows:
        x, y = number(r["step_seconds"]), number(r[measure])
        if x > 0 and y > 0:
            lines.setdefault(r["run"], []).append((x, y, r["parameter"], number(r["value"])))
    fig, ax = plt.subplots(figsize=(7, 5))
    for name, points in lines.items():
        points.sort()
        ax.loglog([p[0] for p in points], [p[1] for p in points], "o-", label=name)
        for x, y, parameter, value in points:
            ax.annotate(f"{value:.2g}", (x, y), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
    ax.set_xlabel("integration wall time [s]")
    ax.set_ylabel("max |x - x_ref| / d" if measure == "error_max" else "probe |x - x_ref| / d")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("work-precision (labels: dt or rtol)")
    fig.tight_layout()
    for extension in ("png", "svg"):
        fig.savefig(f"{stem}.{extension}", dpi=120)


if __name__ == "__main__":
    main()
