#!/usr/bin/python3
"""Plot of Banterle et al. 2008 section 4.5, eq. 7 (their Figure 4) from a `blocklab analyze` folder.

Usage: python3 configs/papers/banterle2008/plot_filtering.py <folder> [output.png]
Reads <folder>/filtering_curves.csv and <folder>/filtering_measured.csv (written by
`blocklab analyze configs/papers/banterle2008/filtering.yaml`) and writes <folder>/filtering.png (or output.png):
one panel per interval [a, b], eq. 7's absolute error |x g(a) + (1 - x) g(b) - g(x a + (1 - x) b)| against x
(solid, left axis, HDR luminance units) and the same error relative to the correct value eq. 5 (dashed, right
axis), one colour per image; the legend carries each image's measured bilinear 2x error.
Needs only matplotlib (Debian python3-matplotlib, /usr/bin/python3).
"""
import os
import sys
from collections import OrderedDict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plot_common import folder_and_output, plt, read_rows  # noqa: E402


def main(argv):
    folder, output = folder_and_output(argv, __doc__, "filtering.png")
    curves = OrderedDict()
    for row in read_rows(folder + "/filtering_curves.csv"):
        key = (float(row["a"]), float(row["b"]))
        curves.setdefault(key, OrderedDict()).setdefault(row["image"], []).append(row)
    measured = {row["image"]: row for row in read_rows(folder + "/filtering_measured.csv")}
    if not curves:
        sys.exit(folder + "/filtering_curves.csv has no rows")

    fig, axes = plt.subplots(1, len(curves), figsize=(6.0 * len(curves), 5.0), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for panel, ((a, b), images) in zip(axes[0], curves.items()):
        relative_axis = panel.twinx()
        for index, (image, rows) in enumerate(images.items()):
            colour = colours[index % len(colours)]
            x = [float(r["x"]) for r in rows]
            m = measured.get(image)
            label = image
            if m is not None:
                label += " (alpha %.3g, Lwhite %.3g; bilinear 2x: rel. RMS %.3g, log2 RMS %.3g)" % (
                    float(m["alpha"]), float(m["l_white"]), float(m["rms_relative_error"]), float(m["rms_log2_error"]))
            panel.plot(x, [float(r["error"]) for r in rows], color=colour, label=label)
            relative_axis.plot(x, [float(r["relative_error"]) for r in rows], color=colour, linestyle="--")
        panel.set_title("eq. 7 on [%g, %g]" % (a, b))
        panel.set_xlabel("x (weight of a)")
        panel.set_ylabel("absolute error (solid, HDR luminance)")
        relative_axis.set_ylabel("error / eq. 5 (dashed)")
        panel.set_xlim(0.0, 1.0)
        panel.set_ylim(bottom=0.0)
        relative_axis.set_ylim(bottom=0.0)
        panel.grid(True, alpha=0.3)
    # The legend goes below the panels (one line per image), where it hides no curve.
    handles, labels = axes[0][0].get_legend_handles_labels()
    legend_height = 0.05 + 0.045 * len(labels)
    fig.legend(handles, labels, loc="lower center", fontsize=8, frameon=False)
    fig.suptitle("Banterle et al. 2008 section 4.5: filtering the tone-mapped texture vs the HDR values")
    fig.tight_layout(rect=(0.0, legend_height, 1.0, 1.0))
    fig.savefig(output, dpi=110)
    print("wrote " + output)


if __name__ == "__main__":
    main(sys.argv)
