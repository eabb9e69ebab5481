#!/usr/bin/python3
"""Plot of Munkberg et al. 2008 section 4, Figure 1, from a `blocklab analyze` folder (analysis munkberg_filtering).

Usage: python3 configs/papers/munkberg2008/plot_fig1_filtering.py <folder> [output.png]
Reads <folder>/fig1_curve.csv and <folder>/filtering_measured.csv (written by
`blocklab analyze configs/papers/munkberg2008/fig1_filtering.yaml`) and writes <folder>/fig1_filtering.png (or
output.png). Left panel: Figure 1, the absolute error in the red component of filtering logYuv texels before the
colour transform (eq. 9 - eq. 8) against Y2, without normalisation (blue, as in the paper; dotted: eq. 10) and with
the luminance normalisation (red). Right panel: the measured log2[RGB] RMSE of both filters on each image against
filtering in linear RGB. Needs only matplotlib (Debian python3-matplotlib, /usr/bin/python3).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plot_common import folder_and_output, plt, read_rows  # noqa: E402


def main(argv):
    folder, output = folder_and_output(argv, __doc__, "fig1_filtering.png")
    curve = read_rows(folder + "/fig1_curve.csv")
    measured = read_rows(folder + "/filtering_measured.csv")
    if not curve:
        sys.exit(folder + "/fig1_curve.csv has no rows")

    fig, (left, right) = plt.subplots(1, 2, figsize=(12.0, 4.8))
    y2 = [float(r["y2"]) for r in curve]
    left.plot(y2, [float(r["plain_error"]) for r in curve], color="tab:blue", label="without normalisation (eq. 9 - eq. 8)")
    left.plot(y2, [float(r["plain_closed_form"]) for r in curve], color="black", linestyle=":", linewidth=1.0,
              label="eq. 10")
    left.plot(y2, [float(r["normalised_error"]) for r in curve], color="tab:red", label="with normalisation")
    left.axhline(0.0, color="grey", linewidth=0.5)
    left.set_xlabel("Y2 (Y1 = 1)")
    left.set_ylabel("absolute error in R")
    left.set_xlim(min(y2), max(y2))
    left.set_title("Figure 1")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)

    if measured:
        names = [r["image"].split("/")[-1] for r in measured]
        positions = range(len(measured))
        width = 0.38
        right.bar([p - width / 2 for p in positions], [float(r["plain_log2_rmse"]) for r in measured], width,
                  color="tab:blue", label="without normalisation")
        right.bar([p + width / 2 for p in positions], [float(r["normalised_log2_rmse"]) for r in measured], width,
                  color="tab:red", label="with normalisation")
        right.set_xticks(list(positions))
        right.set_xticklabels(names, rotation=15, fontsize=8)
        right.set_ylabel("log2[RGB] RMSE vs filtering in linear RGB")
        first = measured[0]
        right.set_title("bilinear, %s samples per quad side (shift %s, reference %s)" % (
            first["magnification"], first["shift"], first["reference"]), fontsize=9)
        right.grid(True, axis="y", alpha=0.3)
        right.legend(fontsize=8)
    else:
        right.axis("off")
    fig.suptitle("Munkberg et al. 2008 section 4: filtering logYuv before the colour transform")
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    print("wrote " + output)


if __name__ == "__main__":
    main(sys.argv)
