"""Plot what accuracy costs: error of the apparent position against time per
vertex, for the exact emission solve and the paper's sampled history.

Usage (from the repository root):

    cargo run --release -- bench optics --csv docs/optics_accuracy.csv
    python3 scripts/plot_optics_accuracy.py docs/optics_accuracy.csv docs/optics_accuracy.png

Needs matplotlib (pip install matplotlib).
"""

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src: str, dst: str) -> None:
    rows = list(csv.DictReader(open(src, newline="")))
    fig, ax = plt.subplots(figsize=(8, 5), dpi=120)
    floor = 1e-4  # the exact solve has no error; draw it on the floor
    for r in rows:
        err = max(float(r["max_px"]), floor)
        ns = float(r["ns_per_vertex"])
        if r["method"] == "exact":
            ax.scatter(ns, err, marker="*", s=220, color="black", zorder=3)
            ax.annotate("exact (error 0)", (ns, err), textcoords="offset points", xytext=(8, 4))
            continue
        interp = r["interpolate"] == "true"
        label = (f'{float(r["fps"]):g}/s, {r["frames"]} kept, '
                 f'steps {r["iterations"]}, {"interp." if interp else "no interp."}')
        ax.scatter(ns, err, marker="o" if interp else "x", s=60, zorder=2, label=label)
    ax.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax.text(ax.get_xlim()[0], 1.1, " 1 pixel at 1080p", color="grey", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per vertex (ns, one core)")
    ax.set_ylabel("max error of the apparent position (pixels at 1080p)")
    ax.set_title("Emission solve: exact vs the paper's sampled history (3-puck scene)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(title="sampled history", fontsize=7, title_fontsize=8, loc="center left")
    fig.tight_layout()
    fig.savefig(dst)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
