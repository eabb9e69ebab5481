// Analysis munkberg_filtering (Munkberg et al. 2008 section 4, eqs. 7-10 and the luminance normalisation trick;
// formats/munkberg/analysis/logyuv_filtering.h, filtering_measurement.h), in the analysis registry
// (experiments/analysis.h). Its keys (all optional):
//   curve: {v1: 0.25, v2: 0.1, y1: 1, y2: [0.1, 10], alpha: 0.5, samples: 991, spacing: linear}
//                                  # Figure 1 (these are the paper's values and the defaults); spacing linear |
//                                  # geometric; samples 2..100001; v, Y >= 0, alpha in [0, 1]
//   normalisation: {shift: nearest, reference: first}   # k rule nearest | exponent | truncate; reference first |
//                                  # brightest (logyuv_filtering.h)
//   magnification: 2               # bilinear sample positions (j + 1/2) / m inside each 2x2 quad, m in 1..16
// It writes fig1_curve.csv (the red error against Y2 without and with normalisation, direct and by eq. 10) and
// filtering_measured.csv (per image: log2[RGB] RMSE and more of both pre-transform filters against linear RGB).
// Plot: configs/papers/munkberg2008/plot_fig1_filtering.py.
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
#include "formats/munkberg/analysis/filtering_measurement.h"
#include "formats/munkberg/analysis/logyuv_filtering.h"

namespace blocklab {

namespace {

constexpr int kMaxCurveSamples = 100001;

struct MunkbergFilteringSettings {
  munkberg::Figure1Setup figure1;
  int magnification = 2;
};

MunkbergFilteringSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  MunkbergFilteringSettings settings;
  munkberg::Figure1Setup& f = settings.figure1;
  if (const YAML::Node curve = StrictYaml::child(root, "curve"); curve.IsDefined()) {
    yaml.check_map(curve, "curve", {"v1", "v2", "y1", "y2", "alpha", "samples", "spacing"}, {});
    const auto non_negative = [&](const char* key, double& slot) {
      const YAML::Node n = StrictYaml::child(curve, key);
      if (!n.IsDefined()) return;
      slot = analysis_number(yaml, n, std::string("curve.") + key);
      if (slot < 0.0) yaml.fail_at(n, std::string("curve.") + key + " must be >= 0");
    };
    non_negative("v1", f.v1);
    non_negative("v2", f.v2);
    non_negative("y1", f.y1);
    if (const YAML::Node n = StrictYaml::child(curve, "y2"); n.IsDefined()) {
      yaml.sequence(n, "curve.y2");
      if (n.size() != 2) yaml.fail_at(n, "curve.y2 must be a pair [first, last]");
      f.y2_first = analysis_number(yaml, n[0], "curve.y2[0]");
      f.y2_last = analysis_number(yaml, n[1], "curve.y2[1]");
      if (!(f.y2_first >= 0.0 && f.y2_first < f.y2_last))
        yaml.fail_at(n, "curve.y2 must satisfy 0 <= first < last");
    }
    if (const YAML::Node n = StrictYaml::child(curve, "alpha"); n.IsDefined()) {
      f.alpha = analysis_number(yaml, n, "curve.alpha");
      if (!(f.alpha >= 0.0 && f.alpha <= 1.0)) yaml.fail_at(n, "curve.alpha must be in [0, 1]");
    }
    if (const YAML::Node n = StrictYaml::child(curve, "samples"); n.IsDefined())
      f.samples = analysis_bounded_integer(yaml, n, "curve.samples", 2, kMaxCurveSamples);
    if (const YAML::Node n = StrictYaml::child(curve, "spacing"); n.IsDefined()) {
      const std::string spacing = yaml.scalar(n, "curve.spacing");
      if (spacing != "linear" && spacing != "geometric")
        yaml.fail_at(n, "curve.spacing must be linear or geometric, got '" + spacing + "'");
      f.geometric = spacing == "geometric";
      // A geometric range takes log(Y2): Y2 = 0 is not allowed there.
      if (f.geometric && !(f.y2_first > 0.0)) yaml.fail_at(n, "curve.spacing geometric needs curve.y2 first > 0");
    }
  }
  if (const YAML::Node n = StrictYaml::child(root, "normalisation"); n.IsDefined()) {
    yaml.check_map(n, "normalisation", {"shift", "reference"}, {});
    try {
      if (const YAML::Node v = StrictYaml::child(n, "shift"); v.IsDefined())
        f.rule = munkberg::shift_rule_from_string(yaml.scalar(v, "normalisation.shift"));
      if (const YAML::Node v = StrictYaml::child(n, "reference"); v.IsDefined())
        f.reference = munkberg::shift_reference_from_string(yaml.scalar(v, "normalisation.reference"));
    } catch (const Error& e) {
      yaml.fail_at(n, std::string("normalisation: ") + e.what());
    }
  }
  if (const YAML::Node n = StrictYaml::child(root, "magnification"); n.IsDefined())
    settings.magnification = analysis_bounded_integer(yaml, n, "magnification", 1, 16);
  return settings;
}

std::string statistics_fields(const munkberg::FilterErrorStatistics& s) {
  return g17(s.log2_rmse) + "," + g17(s.max_log2) + "," + g17(s.fraction_above_1_percent) + "," +
         g17(s.rms_relative_red);
}

nlohmann::json statistics_json(const munkberg::FilterErrorStatistics& s) {
  return {{"log2_rmse", s.log2_rmse},
          {"max_log2", s.max_log2},
          {"fraction_above_1_percent", s.fraction_above_1_percent},
          {"rms_relative_red", s.rms_relative_red}};
}


// munkberg_filtering: Figure 1's curve and the measurement on every image.
void run_munkberg_filtering(const MunkbergFilteringSettings& settings, const AnalysisRun& run) {
  const munkberg::Figure1Setup& f = settings.figure1;
  const std::vector<munkberg::Figure1Point> curve = munkberg::figure1_curve(f);
  std::string curve_csv =
      "y2,correct_red,plain_red,plain_error,plain_closed_form,shift1,shift2,normalised_red,normalised_error,"
      "normalised_closed_form\n";
  double plain_min = curve.front().plain_error, plain_max = plain_min, normalised_max_abs = 0.0;
  for (const munkberg::Figure1Point& p : curve) {
    curve_csv += g17(p.y2) + "," + g17(p.correct_red) + "," + g17(p.plain_red) + "," + g17(p.plain_error) + "," +
                 g17(p.plain_closed_form) + "," + std::to_string(p.shift1) + "," + std::to_string(p.shift2) + "," +
                 g17(p.normalised_red) + "," + g17(p.normalised_error) + "," + g17(p.normalised_closed_form) + "\n";
    plain_min = std::min(plain_min, p.plain_error);
    plain_max = std::max(plain_max, p.plain_error);
    normalised_max_abs = std::max(normalised_max_abs, std::fabs(p.normalised_error));
  }
  std::printf("Figure 1 (v1 %g, v2 %g, Y1 %g, Y2 %g..%g, alpha %g, shift %s, reference %s):\n", f.v1, f.v2, f.y1,
              f.y2_first, f.y2_last, f.alpha, munkberg::to_string(f.rule), munkberg::to_string(f.reference));
  std::printf("  red error without normalisation: %.4f at Y2 = %g .. %.4f at Y2 = %g (min %.4f, max %.4f; paper: "
              "about -0.1 .. over 1.1)\n",
              curve.front().plain_error, curve.front().y2, curve.back().plain_error, curve.back().y2, plain_min,
              plain_max);
  std::printf("  red error with normalisation: largest |error| %.4f (paper: much smaller)\n\n", normalised_max_abs);

  std::string measured =
      "image,width,height,magnification,shift,reference,samples,quads,shifted_quads,fraction_quads_ratio_above_2,"
      "plain_log2_rmse,plain_max_log2,plain_fraction_above_1_percent,plain_rms_relative_red,"
      "normalised_log2_rmse,normalised_max_log2,normalised_fraction_above_1_percent,normalised_rms_relative_red\n";
  nlohmann::json record = analysis_base_record(run);
  record["figure1"] = {{"v1", f.v1}, {"v2", f.v2}, {"y1", f.y1}, {"y2", {f.y2_first, f.y2_last}},
                       {"alpha", f.alpha}, {"samples", f.samples}, {"spacing", f.geometric ? "geometric" : "linear"},
                       {"plain_error_first", curve.front().plain_error}, {"plain_error_last", curve.back().plain_error},
                       {"plain_error_min", plain_min}, {"plain_error_max", plain_max},
                       {"normalised_max_abs_error", normalised_max_abs}};
  record["normalisation"] = {{"shift", munkberg::to_string(f.rule)}, {"reference", munkberg::to_string(f.reference)}};
  record["magnification"] = settings.magnification;
  std::printf("%-36s %10s %12s %12s %10s %10s %12s %12s\n", "image", "size", "log2 plain", "log2 norm.", ">1% plain",
              ">1% norm.", "max plain", "max norm.");
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    munkberg::FilteringMeasurement m;
    try {
      m = munkberg::measure_logyuv_filtering(image, settings.magnification, f.rule, f.reference);
    } catch (const Error& e) {
      fail(path, e.what());   // e.g. an image smaller than 2x2: name the file
    }
    measured += csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) + "," +
                std::to_string(settings.magnification) + "," + munkberg::to_string(f.rule) + "," +
                munkberg::to_string(f.reference) + "," + std::to_string(m.samples) + "," + std::to_string(m.quads) +
                "," + std::to_string(m.shifted_quads) + "," + g17(m.fraction_quads_ratio_above_2) + "," +
                statistics_fields(m.plain) + "," + statistics_fields(m.normalised) + "\n";
    char size[32];
    std::snprintf(size, sizeof size, "%dx%d", image.width, image.height);
    std::printf("%-36s %10s %12.4g %12.4g %9.3f%% %9.3f%% %12.4g %12.4g\n", relative.c_str(), size, m.plain.log2_rmse,
                m.normalised.log2_rmse, 100.0 * m.plain.fraction_above_1_percent,
                100.0 * m.normalised.fraction_above_1_percent, m.plain.max_log2, m.normalised.max_log2);
    record["images"].push_back({{"image", relative},
                                {"sha256", sha256_file_hex(path)},
                                {"width", image.width},
                                {"height", image.height},
                                {"samples", m.samples},
                                {"shifted_quads", m.shifted_quads},
                                {"plain", statistics_json(m.plain)},
                                {"normalised", statistics_json(m.normalised)}});
  }
  write_analysis_folder(run,
                        {{"fig1_curve.csv", curve_csv},
                        {"filtering_measured.csv", measured}},
                        record, "configs/papers/munkberg2008/plot_fig1_filtering.py");
}

}  // namespace

Analysis munkberg_filtering_analysis() {
  return {"munkberg_filtering", {"curve", "normalisation", "magnification"},
          [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const MunkbergFilteringSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_munkberg_filtering(*settings, run); });
          }};
}

}  // namespace blocklab
