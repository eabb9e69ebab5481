#!/usr/bin/python3
"""Plot of the Wang et al. 2007 filtering analysis (section 4.4, Fig. 5) from a `blocklab analyze` folder.

Usage: python3 configs/papers/wang2007/plot_filtering.py <folder> [output.png]
Reads <folder>/filtering_measured.csv (written by `blocklab analyze configs/papers/wang2007/filtering.yaml`) and
writes <folder>/filtering.png (or output.png): per image, log2[RGB] of the shader on filtered channels against the
decoded-then-filtered RGB (the filtering artefact alone), one bar per variant (residual S, residual ratio T).
Needs only matplotlib (Debian python3-matplotlib, /usr/bin/python3).
"""
import os
import sys
from collections import OrderedDict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plot_common import folder_and_output, plt, read_rows  # noqa: E402


def main(argv):
    folder, output = folder_and_output(argv, __doc__, "filtering.png")
    values = OrderedDict()
    for row in read_rows(folder + "/filtering_measured.csv"):
        values.setdefault(row["variant"], OrderedDict())[row["image"]] = float(row["shader_vs_decoded_log2rgb"])
    if not values:
        sys.exit(folder + "/filtering_measured.csv has no rows")
    images = list(next(iter(values.values())).keys())
    width = 0.8 / len(values)
    fig, axis = plt.subplots(figsize=(max(6.0, 0.5 * len(images) * len(values)), 5.0))
    for k, (variant, per_image) in enumerate(values.items()):
        axis.bar([i + k * width for i in range(len(images))], [per_image.get(name, 0.0) for name in images], width,
                 label=variant)
    axis.set_xticks([i + 0.4 - width / 2 for i in range(len(images))])
    axis.set_xticklabels([os.path.basename(name) for name in images], rotation=60, ha="right", fontsize=8)
    axis.set_yscale("log")
    axis.set_ylabel("log2[RGB]: shader on filtered channels vs filtered decoded RGB")
    axis.set_title("Wang 2007 Fig. 5: filtering artefact of residual S and residual ratio T")
    axis.legend()
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    print("wrote", output)


if __name__ == "__main__":
    main(sys.argv)
