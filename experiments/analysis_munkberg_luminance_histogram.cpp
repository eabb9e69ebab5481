// Analysis munkberg_luminance_histogram (Munkberg et al. 2008 section 7.3, Figure 8;
// formats/munkberg/analysis/luminance_range_histogram.h), in the analysis registry (experiments/analysis.h). Its
// keys (all optional):
//   bin_width: 0.25                # histogram bin width in log2 units (> 0)
//   bins: 49                       # number of bins (1..100000); the last one also takes every larger range
//   precision:                     # the shares to report: blocks at least as precise as `bits`-bit log-luminance
//     - {bits: 10, paper: 51.0}    # (range <= 2^(9 - bits)); `paper` (optional) is the published percentage
// It writes luminance_range_histogram.csv (per image and pooled "all": bin, count, share),
// luminance_range_summary.csv (per image and pooled: blocks, black blocks, range statistics) and
// luminance_range_precision.csv (per image and pooled: bits, range limit, our share, the paper's).
// Plot: configs/papers/munkberg2008/plot_fig8_histogram.py.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/munkberg/analysis/luminance_range_histogram.h"

namespace blocklab {

namespace {

constexpr int kMaxHistogramBins = 100000;

struct PrecisionRow {
  int bits = 10;
  bool has_paper = false;
  double paper_percent = 0.0;
};

struct MunkbergHistogramSettings {
  double bin_width = 0.25;
  int bins = 49;
  std::vector<PrecisionRow> precision = {{10, true, 51.0}, {8, true, 84.7}, {6, true, 99.8}};
};

MunkbergHistogramSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  MunkbergHistogramSettings settings;
  if (const YAML::Node n = StrictYaml::child(root, "bin_width"); n.IsDefined()) {
    settings.bin_width = analysis_number(yaml, n, "bin_width");
    if (!(settings.bin_width > 0.0)) yaml.fail_at(n, "bin_width must be > 0");
  }
  if (const YAML::Node n = StrictYaml::child(root, "bins"); n.IsDefined())
    settings.bins = analysis_bounded_integer(yaml, n, "bins", 1, kMaxHistogramBins);
  if (const YAML::Node list = StrictYaml::child(root, "precision"); list.IsDefined()) {
    yaml.sequence(list, "precision");
    settings.precision.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = indexed_path("precision", i);
      yaml.check_map(list[i], path, {"bits", "paper"}, {"bits"});
      PrecisionRow row;
      row.bits = analysis_bounded_integer(yaml, StrictYaml::child(list[i], "bits"), path + ".bits", 1, 30);
      if (const YAML::Node p = StrictYaml::child(list[i], "paper"); p.IsDefined()) {
        row.paper_percent = analysis_number(yaml, p, path + ".paper");
        if (!(row.paper_percent >= 0.0 && row.paper_percent <= 100.0))
          yaml.fail_at(p, path + ".paper must be a percentage in [0, 100]");
        row.has_paper = true;
      }
      settings.precision.push_back(row);
    }
  }
  return settings;
}

// munkberg_luminance_histogram: Figure 8 per image and pooled over all images ("all").
void run_munkberg_histogram(const MunkbergHistogramSettings& settings, const AnalysisRun& run) {
  std::string histogram = "image,bin,range_low,range_high,count,share\n";
  std::string summary =
      "image,width,height,blocks,black_blocks,ranged_blocks,black_texels,mean_range,median_range,max_range\n";
  std::string precision = "image,bits,range_limit,ranged_blocks,within,share_percent,paper_percent\n";
  nlohmann::json record = analysis_base_record(run);
  record["bin_width"] = settings.bin_width;
  record["bins"] = settings.bins;
  std::vector<double> pooled;
  std::size_t pooled_blocks = 0, pooled_black_blocks = 0, pooled_black_texels = 0;

  const auto add_rows = [&](const std::string& name, const std::string& size_fields, std::vector<double> ranges,
                            std::size_t blocks, std::size_t black_blocks, std::size_t black_texels,
                            nlohmann::json& json) {
    const std::vector<std::uint64_t> counts = munkberg::range_histogram(ranges, settings.bin_width, settings.bins);
    for (int b = 0; b < settings.bins; ++b) {
      const double share = ranges.empty() ? 0.0 : static_cast<double>(counts[b]) / static_cast<double>(ranges.size());
      // The last bin is open-ended: its upper edge is written as "inf".
      histogram += csv_field(name) + "," + std::to_string(b) + "," + g17(b * settings.bin_width) + "," +
                   (b == settings.bins - 1 ? std::string("inf") : g17((b + 1) * settings.bin_width)) + "," +
                   std::to_string(counts[b]) + "," + g17(share) + "\n";
    }
    double mean = 0.0, median = 0.0, max = 0.0;
    if (!ranges.empty()) {   // statistics of no blocks stay 0
      for (double r : ranges) mean += r;
      mean /= static_cast<double>(ranges.size());
      std::sort(ranges.begin(), ranges.end());
      const std::size_t n = ranges.size();
      median = n % 2 == 1 ? ranges[n / 2] : 0.5 * (ranges[n / 2 - 1] + ranges[n / 2]);
      max = ranges.back();
    }
    summary += csv_field(name) + "," + size_fields + "," + std::to_string(blocks) + "," + std::to_string(black_blocks) +
               "," + std::to_string(ranges.size()) + "," + std::to_string(black_texels) + "," + g17(mean) + "," +
               g17(median) + "," + g17(max) + "\n";
    json["blocks"] = blocks;
    json["black_blocks"] = black_blocks;
    json["ranged_blocks"] = ranges.size();
    json["mean_range"] = mean;
    json["median_range"] = median;
    json["max_range"] = max;
    std::string line;
    for (const PrecisionRow& row : settings.precision) {
      const double limit = munkberg::range_for_precision_bits(row.bits);
      const double share = munkberg::fraction_within(ranges, limit);
      const auto within = static_cast<std::size_t>(std::llround(share * static_cast<double>(ranges.size())));
      precision += csv_field(name) + "," + std::to_string(row.bits) + "," + g17(limit) + "," +
                   std::to_string(ranges.size()) + "," + std::to_string(within) + "," + g17(100.0 * share) + "," +
                   (row.has_paper ? g17(row.paper_percent) : std::string()) + "\n";
      nlohmann::json entry = {{"bits", row.bits}, {"range_limit", limit}, {"share_percent", 100.0 * share}};
      if (row.has_paper) entry["paper_percent"] = row.paper_percent;
      json["precision"].push_back(entry);
      char cell[48];
      std::snprintf(cell, sizeof cell, " %6.1f%%", 100.0 * share);
      line += cell;
      if (row.has_paper) {
        std::snprintf(cell, sizeof cell, " (%5.1f)", row.paper_percent);
        line += cell;
      }
    }
    std::printf("%-36s %8zu %7zu %7.3f %7.3f%s\n", name.c_str(), ranges.size(), black_blocks, mean, median,
                line.c_str());
  };

  std::string header;
  for (const PrecisionRow& row : settings.precision) {
    char cell[48];
    std::snprintf(cell, sizeof cell, " %7s", ("<=" + g17(munkberg::range_for_precision_bits(row.bits))).c_str());
    header += cell;
    if (row.has_paper) header += " (paper)";
  }
  std::printf("share of 4x4 blocks whose log2-luminance range is within the limit (k bits: range <= 2^(9-k)):\n");
  std::printf("%-36s %8s %7s %7s %7s%s\n", "image", "blocks", "black", "mean", "median", header.c_str());
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    munkberg::BlockLuminanceRanges r = munkberg::block_log_luminance_ranges(image);
    pooled.insert(pooled.end(), r.ranges.begin(), r.ranges.end());
    pooled_blocks += r.blocks;
    pooled_black_blocks += r.black_blocks;
    pooled_black_texels += r.black_texels;
    nlohmann::json json = {{"image", relative}, {"sha256", sha256_file_hex(path)}, {"width", image.width},
                           {"height", image.height}};
    add_rows(relative, std::to_string(image.width) + "," + std::to_string(image.height), std::move(r.ranges), r.blocks,
             r.black_blocks, r.black_texels, json);
    record["images"].push_back(json);
  }
  nlohmann::json all = {{"images", run.images.size()}};
  add_rows("all", ",", std::move(pooled), pooled_blocks, pooled_black_blocks, pooled_black_texels, all);
  record["all"] = all;
  write_analysis_folder(run,
                        {{"luminance_range_histogram.csv", histogram},
                        {"luminance_range_summary.csv", summary},
                        {"luminance_range_precision.csv", precision}},
                        record, "configs/papers/munkberg2008/plot_fig8_histogram.py");
}

}  // namespace

Analysis munkberg_luminance_histogram_analysis() {
  return {"munkberg_luminance_histogram", {"bin_width", "bins", "precision"},
          [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const MunkbergHistogramSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_munkberg_histogram(*settings, run); });
          }};
}

}  // namespace blocklab
