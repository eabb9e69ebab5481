#!/usr/bin/python3
"""Plot of Munkberg et al. 2008 section 7.3, Figure 8, from a `blocklab analyze` folder
(analysis munkberg_luminance_histogram).

Usage: python3 configs/papers/munkberg2008/plot_fig8_histogram.py <folder> [output.png]
Reads <folder>/luminance_range_histogram.csv and <folder>/luminance_range_precision.csv (written by
`blocklab analyze configs/papers/munkberg2008/fig8_histogram.yaml`) and writes <folder>/fig8_histogram.png (or
output.png): the share of 4x4 blocks per bin of log2-luminance range (max - min of log2 Y, black texels excluded),
pooled over all images ("all"), with the precision limits (range <= 2^(9 - k) for k bits) marked and our shares
beside the paper's in the legend. Needs only matplotlib (Debian python3-matplotlib, /usr/bin/python3).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plot_common import folder_and_output, plt, read_rows  # noqa: E402


def main(argv):
    folder, output = folder_and_output(argv, __doc__, "fig8_histogram.png")
    bins = [r for r in read_rows(folder + "/luminance_range_histogram.csv") if r["image"] == "all"]
    precision = [r for r in read_rows(folder + "/luminance_range_precision.csv") if r["image"] == "all"]
    if not bins:
        sys.exit(folder + "/luminance_range_histogram.csv has no pooled ('all') rows")
    images = len({r["image"] for r in read_rows(folder + "/luminance_range_histogram.csv")}) - 1

    fig, axis = plt.subplots(figsize=(8.0, 4.8))
    width = float(bins[0]["range_high"]) - float(bins[0]["range_low"]) if bins[0]["range_high"] != "inf" else 1.0
    lows = [float(r["range_low"]) for r in bins]
    axis.bar(lows, [100.0 * float(r["share"]) for r in bins], width=width, align="edge", color="tab:blue",
             edgecolor="white", linewidth=0.5)
    colours = ["tab:green", "tab:orange", "tab:red", "tab:purple", "tab:brown"]
    for index, row in enumerate(precision):
        label = "%s bits: range <= %s, %.1f%% of blocks" % (row["bits"], row["range_limit"],
                                                            float(row["share_percent"]))
        if row["paper_percent"]:
            label += " (paper %s%%)" % row["paper_percent"]
        axis.axvline(float(row["range_limit"]), color=colours[index % len(colours)], linestyle="--", label=label)
    axis.set_xlabel("max - min of log2 luminance over a 4x4 block (last bin: this and above)")
    axis.set_ylabel("share of blocks (%)")
    axis.set_xlim(0.0, lows[-1] + width)
    axis.grid(True, axis="y", alpha=0.3)
    axis.legend(fontsize=8)
    axis.set_title("Munkberg et al. 2008 Figure 8: %d images, %s blocks with a range" % (
        images, precision[0]["ranged_blocks"] if precision else "?"))
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    print("wrote " + output)


if __name__ == "__main__":
    main(sys.argv)
