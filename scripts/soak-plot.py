#!/usr/bin/env python3
"""Draws the soak's samples (scripts/soak.sh): resident memory, open files and the
checkpoint's size against time, one line per run.

Usage: scripts/soak-plot.py OUT.png RUN.csv [RUN.csv ...]
Each CSV has the columns elapsed_s, rss_kib, fds, checkpoint_bytes; the run's name is the
file's stem. Needs matplotlib (pip install matplotlib).
"""

import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = list(csv.DictReader(open(path)))
    column = lambda key, scale: [float(r[key]) / scale for r in rows]  # noqa: E731
    return {
        "minutes": column("elapsed_s", 60.0),
        "rss": column("rss_kib", 1024.0),
        "fds": column("fds", 1.0),
        "checkpoint": column("checkpoint_bytes", 1024.0 * 1024.0),
    }


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, runs = sys.argv[1], sys.argv[2:]
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for path in runs:
        name = pathlib.Path(path).stem
        data = read(path)
        axes[0].plot(data["minutes"], data["rss"], label=name)
        axes[1].plot(data["minutes"], data["checkpoint"], label=name)
        axes[2].plot(data["minutes"], data["fds"], label=name)
    axes[0].set_ylabel("resident memory (MiB)")
    axes[1].set_ylabel("checkpoint.json (MiB)")
    axes[2].set_ylabel("open files")
    axes[2].set_xlabel("minutes")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.set_ylim(bottom=0)
        ax.legend(loc="lower right")
    fig.suptitle("shapegen soak: memory, model size and open files over a long search")
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    main()
