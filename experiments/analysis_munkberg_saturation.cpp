// Analysis munkberg_saturation (Munkberg et al. 2008 sections 5-7: logYuv chroma on a 7-bit base-colour lattice,
// 8-bit log-luminance endpoints; formats/munkberg), in the analysis registry (experiments/analysis.h). Where does the
// format lose on saturated colours and dark texels? Per image and per encoder option set, every texel is put in one
// class and its log2[RGB] error (eq. 1, metric floor 2^-24: sum over R, G, B of squared log2 differences) is summed
// per class and split into a luminance part (3 x the squared log2 difference of the Rec. 601 luminance of source and
// decoded texel) and the rest (chroma), and for saturated texels the part in their smallest channel.
//   saturated  smallest channel > 0 and below `saturation` x the texel's luminance Y (default 0.05)
//   below_range  not saturated, 0 < Y < 2^-16: below the 32-stop log-luminance range (section 7.3), only true black
//              or 2^-16 (and the DCT's clamped values) are representable
//   dark       not saturated, 2^-16 <= Y < 2^`dark_log2` (default -10)
//   black      Y == 0
//   other      the rest
// A format limit for saturated texels, `lattice_floor`: the error the texel would keep with its exact luminance and
// the best chroma (u, v) on the 7-bit base-colour lattice (the four lattice points around it; eq. 2's decoding,
// G = max(0, 1 - u - v) Y / wg). Shape landmarks 2 and 3 can fall between lattice points, so a block can beat it, but
// a texel whose chroma is a base colour cannot.
// Keys:
//   encoders:                        # required: name -> munkberg options
//     both: {preset: medium}
//     all: {preset: medium, modes: all, mode_predictor: 0.5}
//   saturation: 0.05
//   dark_log2: -10
// Writes saturation_classes.csv (image, encoder, class, texels, texel share, error, error share, mean error per
// texel, luminance part, smallest-channel part, lattice floor) and prints the pooled table.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/color_spaces.h"
#include "core/error.h"
#include "experiments/analysis.h"
#include "formats/registry.h"

namespace blocklab {

namespace {

constexpr double kFloor = 5.9604644775390625e-08;   // 2^-24, metrics/zero_rule.h
constexpr int kLatticeSteps = 127;                   // 7-bit base colours (formats/munkberg/munkberg_layout.h)
constexpr std::array<const char*, 5> kClasses = {"saturated", "below_range", "dark", "black", "other"};
constexpr double kLogLuminanceFloor = -16.0;         // formats/munkberg: Ybar in [-16, 16]
constexpr std::array<double, 3> kWeights = {kRec601WeightR, kRec601WeightG, kRec601WeightB};

struct SaturationSettings {
  std::vector<std::pair<std::string, FormatOptions>> encoders;
  double saturation = 0.05;
  double dark_log2 = -10.0;
};

SaturationSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  SaturationSettings settings;
  const YAML::Node encoders = StrictYaml::child(root, "encoders");
  if (!encoders.IsDefined()) fail(yaml.source_name(), "munkberg_saturation needs the key 'encoders'");
  const Format& format = find_format("munkberg");
  for (const std::string& name : yaml.map_keys(encoders, "encoders")) {
    const YAML::Node node = StrictYaml::child(encoders, name);
    FormatOptions options;
    for (const std::string& key : yaml.map_keys(node, "encoders." + name))
      options[key] = yaml.scalar(StrictYaml::child(node, key), "encoders." + name + "." + key);
    resolve_format_options(format, options);   // unknown keys / bad values: an error naming them, before any work
    settings.encoders.emplace_back(name, options);
  }
  if (const YAML::Node n = StrictYaml::child(root, "saturation"); n.IsDefined()) {
    settings.saturation = analysis_number(yaml, n, "saturation");
    if (!(settings.saturation > 0.0 && settings.saturation < 1.0)) yaml.fail_at(n, "saturation must be in (0, 1)");
  }
  if (const YAML::Node n = StrictYaml::child(root, "dark_log2"); n.IsDefined())
    settings.dark_log2 = analysis_number(yaml, n, "dark_log2");
  return settings;
}

double log2_floored(double x) { return std::log2(std::max(x, kFloor)); }

// Smallest squared log2[RGB] error of a texel with luminance y and chroma on the 7-bit lattice around (u, v).
double lattice_floor(const float* rgb, double y) {
  const double u = kRec601WeightB * rgb[2] / y, v = kRec601WeightR * rgb[0] / y;
  const double u0 = std::floor(u * kLatticeSteps), v0 = std::floor(v * kLatticeSteps);
  double best = -1.0;
  for (int du = 0; du < 2; ++du)
    for (int dv = 0; dv < 2; ++dv) {
      const double lu = std::min(1.0, (u0 + du) / kLatticeSteps), lv = std::min(1.0, (v0 + dv) / kLatticeSteps);
      const double decoded[3] = {lv * y / kRec601WeightR, std::max(0.0, 1.0 - lu - lv) * y / kRec601WeightG,
                                 lu * y / kRec601WeightB};
      double e = 0.0;
      for (int c = 0; c < 3; ++c) e += std::pow(log2_floored(decoded[c]) - log2_floored(rgb[c]), 2.0);
      if (best < 0.0 || e < best) best = e;
    }
  return best;
}

struct ClassSums {
  std::size_t texels = 0;
  double error = 0.0, luminance = 0.0, smallest_channel = 0.0, floor = 0.0;
};
using Sums = std::array<ClassSums, kClasses.size()>;

void run_saturation(const SaturationSettings& settings, const AnalysisRun& run) {
  const Format& format = find_format("munkberg");
  std::string csv =
      "image,encoder,class,texels,texel_share,error,error_share,mean_error,luminance_part,smallest_channel_part,"
      "lattice_floor\n";
  nlohmann::json record = analysis_base_record(run);
  std::vector<Sums> pooled(settings.encoders.size());
  const auto add_rows = [&](const std::string& image, const std::string& encoder, const Sums& sums) {
    std::size_t texels = 0;
    double error = 0.0;
    for (const ClassSums& s : sums) {
      texels += s.texels;
      error += s.error;
    }
    for (std::size_t k = 0; k < kClasses.size(); ++k) {
      const ClassSums& s = sums[k];
      const double n = s.texels > 0 ? static_cast<double>(s.texels) : 1.0;
      csv += csv_field(image) + "," + csv_field(encoder) + "," + kClasses[k] + "," + std::to_string(s.texels) + "," +
             g17(static_cast<double>(s.texels) / std::max<double>(1.0, texels)) + "," + g17(s.error) + "," +
             g17(error > 0.0 ? s.error / error : 0.0) + "," + g17(s.error / n) + "," + g17(s.luminance) + "," +
             g17(s.smallest_channel) + "," + g17(s.floor) + "\n";
      std::printf("%-34s %-10s %-11s %6.2f%% texels %6.2f%% error  %8.4f/texel  lum %5.1f%%  min-ch %5.1f%%  floor "
                  "%8.4f/texel\n",
                  image.c_str(), encoder.c_str(), kClasses[k], 100.0 * s.texels / std::max<double>(1.0, texels),
                  error > 0.0 ? 100.0 * s.error / error : 0.0, s.error / n,
                  s.error > 0.0 ? 100.0 * s.luminance / s.error : 0.0,
                  s.error > 0.0 ? 100.0 * s.smallest_channel / s.error : 0.0, s.floor / n);
    }
  };
  for (const std::string& relative : run.images) {
    const Image image = load_analysis_image(run, relative);
    for (std::size_t e = 0; e < settings.encoders.size(); ++e) {
      const FormatOptions options = resolve_format_options(format, settings.encoders[e].second);
      const Image decoded = format.decode(format.encode(image, options, CodecContext{1, 1}), CodecContext{1, 1});
      Sums sums{};
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
          const float* s = image.texel(x, y);
          const float* d = decoded.texel(x, y);
          double ys = 0.0, yd = 0.0, error = 0.0;
          int smallest = 0;
          for (int c = 0; c < 3; ++c) {
            ys += kWeights[static_cast<std::size_t>(c)] * s[c];
            yd += kWeights[static_cast<std::size_t>(c)] * d[c];
            error += std::pow(log2_floored(d[c]) - log2_floored(s[c]), 2.0);
            if (s[c] < s[smallest]) smallest = c;
          }
          std::size_t k = 4;
          if (ys <= 0.0) {
            k = 3;
          } else if (s[smallest] > 0.0 && s[smallest] < settings.saturation * ys) {
            k = 0;
          } else if (std::log2(ys) < kLogLuminanceFloor) {
            k = 1;
          } else if (std::log2(ys) < settings.dark_log2) {
            k = 2;
          }
          ClassSums& sum = sums[k];
          ++sum.texels;
          sum.error += error;
          sum.luminance += 3.0 * std::pow(log2_floored(yd) - log2_floored(ys), 2.0);
          if (k == 0) {
            sum.smallest_channel += std::pow(log2_floored(d[smallest]) - log2_floored(s[smallest]), 2.0);
            sum.floor += lattice_floor(s, ys);
          }
        }
      add_rows(relative, settings.encoders[e].first, sums);
      for (std::size_t k = 0; k < kClasses.size(); ++k) {
        pooled[e][k].texels += sums[k].texels;
        pooled[e][k].error += sums[k].error;
        pooled[e][k].luminance += sums[k].luminance;
        pooled[e][k].smallest_channel += sums[k].smallest_channel;
        pooled[e][k].floor += sums[k].floor;
      }
    }
  }
  for (std::size_t e = 0; e < settings.encoders.size(); ++e) add_rows("all", settings.encoders[e].first, pooled[e]);
  record["saturation"] = settings.saturation;
  record["dark_log2"] = settings.dark_log2;
  write_analysis_folder(run, {{"saturation_classes.csv", csv}}, record, "");
}

}  // namespace

Analysis munkberg_saturation_analysis() {
  return {"munkberg_saturation", {"encoders", "saturation", "dark_log2"},
          [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const SaturationSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_saturation(*settings, run); });
          }};
}

}  // namespace blocklab
