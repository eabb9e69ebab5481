// `blocklab analyze CONFIG`: analyses that are not (image x format x metric) cells. The config is strict YAML
// (experiments/strict_yaml.h: unknown / duplicate keys, YAML 1.1 booleans, octal-looking numbers are errors at
// file:line:col). Schema 1:
// ```yaml
// analysis: banterle_filtering     # required: the analysis kind (banterle_filtering, munkberg_filtering,
//                                  # munkberg_luminance_histogram; see below). Written FIRST by
//                                  # convention: tools (and tests/unit/test_experiment_registry_run.cpp) tell an
//                                  # analysis config from an experiment config by its first key (`schema`)
// schema: 1                        # required, must be 1
// name: banterle2008_filtering     # required, [A-Za-z0-9_.-]+; default output folder runs/<name>
// description: "..."               # optional
// data_root: samples               # optional, as in `blocklab run` (repository-relative; BLOCKLAB_DATA_ROOT and
//                                  # --data-root override it)
// images: [hdr/Desk.exr]           # required, paths or globs relative to the data root (as in `blocklab run`)
// input_policy: clamp              # optional: error | clamp | zero
// output: runs/filtering           # optional output folder (relative to the working directory); --out overrides
// intervals: [[0.3, 0.6], [0, 1]]  # banterle_filtering, required: [a, b] pairs, 0 <= a < b <= 1
// samples: 101                     # banterle_filtering, optional: points x per curve (2..100001), default 101
// tmo: {fit: ceres_lm}             # banterle_filtering, optional. Either options of the `banterle` format (every
//                                  # option except bpp and search: fit, mean, ...), fitted per image exactly as the
//                                  # encoder does (default: the format's defaults); or the given parameters
//                                  # {alpha: A, l_white: W, mean_luminance: M} (all three) for every image.
// ```
// banterle_filtering (Banterle et al. 2008 section 4.5, eqs. 5-7; formats/banterle/filtering_error.h) writes into
// the output folder:
//   filtering_curves.csv    per image and interval, `samples` rows: x, the interpolated tone-mapped value, eq. 5,
//                           eq. 6, eq. 7 (through g and by the paper's closed form), eq. 7 / eq. 5
//   filtering_measured.csv  per image: the TMO parameters and the bilinear 2x magnification error of the image
//   config.yaml, analysis.json   the config as given; the resolved data root, images, parameters, versions
// The plot is drawn from the CSVs by configs/papers/banterle2008/plot_filtering.py (matplotlib).
//
// munkberg_filtering (Munkberg et al. 2008 section 4, eqs. 7-10 and the luminance normalisation trick;
// formats/munkberg/analysis/logyuv_filtering.h, filtering_measurement.h). Its keys (all optional):
//   curve: {v1: 0.25, v2: 0.1, y1: 1, y2: [0.1, 10], alpha: 0.5, samples: 991, spacing: linear}
//                                  # Figure 1 (these are the paper's values and the defaults); spacing linear |
//                                  # geometric; samples 2..100001; v, Y >= 0, alpha in [0, 1]
//   normalisation: {shift: nearest, reference: first}   # k rule nearest | exponent | truncate; reference first |
//                                  # brightest (logyuv_filtering.h)
//   magnification: 2               # bilinear sample positions (j + 1/2) / m inside each 2x2 quad, m in 1..16
// It writes fig1_curve.csv (the red error against Y2 without and with normalisation, direct and by eq. 10) and
// filtering_measured.csv (per image: log2[RGB] RMSE and more of both pre-transform filters against linear RGB).
// Plot: configs/papers/munkberg2008/plot_fig1_filtering.py.
//
// munkberg_luminance_histogram (Munkberg et al. 2008 section 7.3, Figure 8;
// formats/munkberg/analysis/luminance_range_histogram.h). Its keys (all optional):
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
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "experiments/config.h"
#include "experiments/image_set.h"
#include "experiments/run_folder.h"
#include "experiments/sha256.h"
#include "experiments/strict_yaml.h"
#include "formats/banterle/banterle_format.h"
#include "formats/banterle/filtering_error.h"
#include "formats/banterle/tmo_fit.h"
#include "formats/munkberg/analysis/filtering_measurement.h"
#include "formats/munkberg/analysis/logyuv_filtering.h"
#include "formats/munkberg/analysis/luminance_range_histogram.h"

namespace blocklab::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFilteringKind = "banterle_filtering";
constexpr const char* kMunkbergFilteringKind = "munkberg_filtering";
constexpr const char* kMunkbergHistogramKind = "munkberg_luminance_histogram";
constexpr int kMaxCurveSamples = 100001;
constexpr int kMaxHistogramBins = 100000;

struct PrecisionRow {
  int bits = 10;
  bool has_paper = false;
  double paper_percent = 0.0;
};

struct Interval {
  double a = 0.0, b = 1.0;
};

struct AnalysisConfig {
  std::string source_path, source_text;
  std::string name, description, kind, data_root, output;
  std::vector<std::string> images;
  InputPolicy input_policy = InputPolicy::clamp;
  std::vector<Interval> intervals;
  int samples = 101;
  bool tmo_given = false;
  ReinhardParameters given;      // tmo_given
  FormatOptions fit_options;     // !tmo_given: resolved banterle options
  // munkberg_filtering
  munkberg::Figure1Setup figure1;
  int magnification = 2;
  // munkberg_luminance_histogram
  double bin_width = 0.25;
  int bins = 49;
  std::vector<PrecisionRow> precision = {{10, true, 51.0}, {8, true, 84.7}, {6, true, 99.8}};
};

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

// A finite decimal number (the whole scalar; StrictYaml::scalar already rejects octal-looking and boolean words).
double number(const StrictYaml& yaml, const YAML::Node& node, const std::string& path) {
  const std::string text = yaml.scalar(node, path);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  // strtod accepts "inf", "nan" and hex floats: only finite values that consume the whole text are numbers here.
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) ||
      text.find_first_of("xXnN") != std::string::npos)
    yaml.fail_at(node, path + " must be a finite number, got '" + text + "'");
  return value;
}

// An integer scalar in [lo, hi].
int bounded_integer(const StrictYaml& yaml, const YAML::Node& node, const std::string& path, int lo, int hi) {
  const std::int64_t value = yaml.integer(node, path);
  if (value < lo || value > hi)
    yaml.fail_at(node, path + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                           std::to_string(value));
  return static_cast<int>(value);
}

// munkberg_filtering: curve, normalisation, magnification (all optional; the defaults are the paper's Figure 1).
void parse_munkberg_filtering(const StrictYaml& yaml, const YAML::Node& root, AnalysisConfig& config) {
  munkberg::Figure1Setup& f = config.figure1;
  if (const YAML::Node curve = StrictYaml::child(root, "curve"); curve.IsDefined()) {
    yaml.check_map(curve, "curve", {"v1", "v2", "y1", "y2", "alpha", "samples", "spacing"}, {});
    const auto non_negative = [&](const char* key, double& slot) {
      const YAML::Node n = StrictYaml::child(curve, key);
      if (!n.IsDefined()) return;
      slot = number(yaml, n, std::string("curve.") + key);
      if (slot < 0.0) yaml.fail_at(n, std::string("curve.") + key + " must be >= 0");
    };
    non_negative("v1", f.v1);
    non_negative("v2", f.v2);
    non_negative("y1", f.y1);
    if (const YAML::Node n = StrictYaml::child(curve, "y2"); n.IsDefined()) {
      yaml.sequence(n, "curve.y2");
      if (n.size() != 2) yaml.fail_at(n, "curve.y2 must be a pair [first, last]");
      f.y2_first = number(yaml, n[0], "curve.y2[0]");
      f.y2_last = number(yaml, n[1], "curve.y2[1]");
      if (!(f.y2_first >= 0.0 && f.y2_first < f.y2_last))
        yaml.fail_at(n, "curve.y2 must satisfy 0 <= first < last");
    }
    if (const YAML::Node n = StrictYaml::child(curve, "alpha"); n.IsDefined()) {
      f.alpha = number(yaml, n, "curve.alpha");
      if (!(f.alpha >= 0.0 && f.alpha <= 1.0)) yaml.fail_at(n, "curve.alpha must be in [0, 1]");
    }
    if (const YAML::Node n = StrictYaml::child(curve, "samples"); n.IsDefined())
      f.samples = bounded_integer(yaml, n, "curve.samples", 2, kMaxCurveSamples);
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
    config.magnification = bounded_integer(yaml, n, "magnification", 1, 16);
}

// munkberg_luminance_histogram: bin_width, bins, precision (all optional).
void parse_munkberg_histogram(const StrictYaml& yaml, const YAML::Node& root, AnalysisConfig& config) {
  if (const YAML::Node n = StrictYaml::child(root, "bin_width"); n.IsDefined()) {
    config.bin_width = number(yaml, n, "bin_width");
    if (!(config.bin_width > 0.0)) yaml.fail_at(n, "bin_width must be > 0");
  }
  if (const YAML::Node n = StrictYaml::child(root, "bins"); n.IsDefined())
    config.bins = bounded_integer(yaml, n, "bins", 1, kMaxHistogramBins);
  if (const YAML::Node list = StrictYaml::child(root, "precision"); list.IsDefined()) {
    yaml.sequence(list, "precision");
    config.precision.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = indexed("precision", i);
      yaml.check_map(list[i], path, {"bits", "paper"}, {"bits"});
      PrecisionRow row;
      row.bits = bounded_integer(yaml, StrictYaml::child(list[i], "bits"), path + ".bits", 1, 30);
      if (const YAML::Node p = StrictYaml::child(list[i], "paper"); p.IsDefined()) {
        row.paper_percent = number(yaml, p, path + ".paper");
        if (!(row.paper_percent >= 0.0 && row.paper_percent <= 100.0))
          yaml.fail_at(p, path + ".paper must be a percentage in [0, 100]");
        row.has_paper = true;
      }
      config.precision.push_back(row);
    }
  }
}

AnalysisConfig parse_analysis_config(const std::string& text, const std::string& source) {
  const StrictYaml yaml(text, source);
  const YAML::Node& root = yaml.root();
  if (!root.IsDefined() || root.IsNull()) fail(source, "the config is empty");
  AnalysisConfig config;
  config.source_path = source;
  config.source_text = text;
  // The kind decides which keys are valid, so it is read (and checked) first.
  yaml.map_keys(root, "the top level");
  std::vector<std::string> allowed = {"schema", "name", "description", "analysis", "data_root", "images",
                                      "input_policy", "output"};
  if (const YAML::Node kind = StrictYaml::child(root, "analysis"); kind.IsDefined()) {
    config.kind = yaml.identifier(kind, "analysis");
    if (config.kind == kFilteringKind) {
      allowed.insert(allowed.end(), {"intervals", "samples", "tmo"});
    } else if (config.kind == kMunkbergFilteringKind) {
      allowed.insert(allowed.end(), {"curve", "normalisation", "magnification"});
    } else if (config.kind == kMunkbergHistogramKind) {
      allowed.insert(allowed.end(), {"bin_width", "bins", "precision"});
    } else {
      yaml.fail_at(kind, "unknown analysis '" + config.kind + "'; valid analyses: " + kFilteringKind + ", " +
                             kMunkbergFilteringKind + ", " + kMunkbergHistogramKind);
    }
  }
  yaml.check_map(root, "the top level", allowed, {"schema", "name", "analysis", "images"});
  const YAML::Node schema = StrictYaml::child(root, "schema");
  if (yaml.integer(schema, "schema") != 1) yaml.fail_at(schema, "schema must be 1 (this blocklab reads analysis schema 1)");
  const YAML::Node name = StrictYaml::child(root, "name");
  config.name = yaml.identifier(name, "name");
  // The name is the default folder runs/<name>: "." and ".." would point outside runs/.
  if (config.name == "." || config.name == "..") yaml.fail_at(name, "name '" + config.name + "' is not a folder name");
  if (const YAML::Node n = StrictYaml::child(root, "description"); n.IsDefined()) config.description = yaml.scalar(n, "description");
  if (const YAML::Node n = StrictYaml::child(root, "data_root"); n.IsDefined()) config.data_root = yaml.scalar(n, "data_root");
  if (const YAML::Node n = StrictYaml::child(root, "output"); n.IsDefined()) config.output = yaml.scalar(n, "output");
  if (const YAML::Node n = StrictYaml::child(root, "input_policy"); n.IsDefined()) {
    try {
      config.input_policy = input_policy_from_string(yaml.scalar(n, "input_policy"));
    } catch (const Error& e) {
      yaml.fail_at(n, std::string("input_policy: ") + e.what());
    }
  }
  const YAML::Node images = StrictYaml::child(root, "images");
  yaml.sequence(images, "images");
  if (images.size() == 0) yaml.fail_at(images, "images must list at least one image");
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::string pattern = yaml.scalar(images[i], indexed("images", i));
    // Relative to the data root, as in `blocklab run`.
    if (pattern.empty() || pattern.front() == '/')
      yaml.fail_at(images[i], indexed("images", i) + ": '" + pattern + "' must be a path relative to the data root");
    config.images.push_back(pattern);
  }

  if (config.kind == kMunkbergFilteringKind) {
    parse_munkberg_filtering(yaml, root, config);
    return config;
  }
  if (config.kind == kMunkbergHistogramKind) {
    parse_munkberg_histogram(yaml, root, config);
    return config;
  }

  // banterle_filtering keys.
  const YAML::Node intervals = StrictYaml::child(root, "intervals");
  if (!intervals.IsDefined()) yaml.fail_at(root, "analysis " + config.kind + " needs the key 'intervals'");
  yaml.sequence(intervals, "intervals");
  if (intervals.size() == 0) yaml.fail_at(intervals, "intervals must list at least one [a, b] pair");
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const std::string path = indexed("intervals", i);
    const YAML::Node pair = intervals[i];
    yaml.sequence(pair, path);
    if (pair.size() != 2) yaml.fail_at(pair, path + " must be a pair [a, b], got " + std::to_string(pair.size()) + " values");
    Interval interval{number(yaml, pair[0], path + "[0]"), number(yaml, pair[1], path + "[1]")};
    if (!(interval.a >= 0.0 && interval.a < interval.b && interval.b <= 1.0))
      yaml.fail_at(pair, path + " must satisfy 0 <= a < b <= 1 (tone-mapped values), got [" + yaml.scalar(pair[0], path) +
                             ", " + yaml.scalar(pair[1], path) + "]");
    config.intervals.push_back(interval);
  }
  if (const YAML::Node n = StrictYaml::child(root, "samples"); n.IsDefined()) {
    const std::int64_t samples = yaml.integer(n, "samples");
    if (samples < 2 || samples > kMaxCurveSamples)
      yaml.fail_at(n, "samples must be in [2, " + std::to_string(kMaxCurveSamples) + "], got " + std::to_string(samples));
    config.samples = static_cast<int>(samples);
  }
  FormatOptions given_options;
  if (const YAML::Node tmo = StrictYaml::child(root, "tmo"); tmo.IsDefined()) {
    const std::vector<std::string> keys = yaml.map_keys(tmo, "tmo");
    const std::vector<std::string> given_keys = {"alpha", "l_white", "mean_luminance"};
    std::size_t given_count = 0;
    for (const std::string& key : keys) given_count += std::count(given_keys.begin(), given_keys.end(), key);
    if (given_count > 0) {
      yaml.check_map(tmo, "tmo", given_keys, given_keys);
      config.tmo_given = true;
      double* const slots[] = {&config.given.alpha, &config.given.l_white, &config.given.mean};
      for (std::size_t k = 0; k < given_keys.size(); ++k) {
        const YAML::Node value = StrictYaml::child(tmo, given_keys[k]);
        const double parsed = number(yaml, value, "tmo." + given_keys[k]);
        if (!(parsed > 0.0)) yaml.fail_at(value, "tmo." + given_keys[k] + " must be > 0");
        *slots[k] = parsed;
      }
    } else {
      for (const std::string& key : keys) {
        const YAML::Node value = StrictYaml::child(tmo, key);
        // bpp and search change the S3TC texture, not the TMO parameters: not meaningful here.
        if (key == "bpp" || key == "search")
          yaml.fail_at(value, "tmo." + key + " does not affect the TMO parameters; use the fit options or "
                              "alpha, l_white, mean_luminance");
        given_options[key] = yaml.scalar(value, "tmo." + key);
      }
      try {
        config.fit_options = resolve_format_options(banterle_format(), given_options);
        // The fit's solver options are checked now, so a bad key is reported at the config's line.
        resolve_tmo_fit_options(parse_tmo_fit_method(config.fit_options.at("fit"), "banterle"),
                                parse_tmo_fit_options(config.fit_options.at("fit_options"), "banterle"), "banterle");
      } catch (const Error& e) {
        yaml.fail_at(tmo, std::string("tmo: ") + e.what());
      }
    }
  } else {
    config.fit_options = resolve_format_options(banterle_format(), {});
  }
  return config;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read the config file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The shortest of %.15g / %.16g / %.17g that reads back as the same double (0.3 stays "0.3").
std::string g17(double value) {
  char buffer[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string csv_field(const std::string& text) {
  // Paths with a comma or a quote are quoted (RFC 4180).
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

Image load_analysis_image(const AnalysisConfig& config, const std::string& data_root, const std::string& relative) {
  const std::string path = (fs::path(data_root) / relative).string();
  Image image = read_image(path);
  apply_input_policy(image, config.input_policy, path);
  return image;
}

nlohmann::json base_record(const AnalysisConfig& config, const std::string& data_root) {
  nlohmann::json record;
  record["analysis"] = config.kind;
  record["name"] = config.name;
  record["blocklab_version"] = BLOCKLAB_VERSION;
  record["config"] = config.source_path;
  record["data_root"] = data_root;
  record["input_policy"] = to_string(config.input_policy);
  return record;
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


// Writes the run folder of an analysis: the config as given, each (file name, CSV text), analysis.json, and prints
// where they are and the command that plots them.
void write_analysis_folder(const fs::path& out, const AnalysisConfig& config,
                           const std::vector<std::pair<std::string, std::string>>& csv_files,
                           const nlohmann::json& record, const std::string& plot_script) {
  write_file_atomically((out / "config.yaml").string(), config.source_text);
  std::string names;
  for (const auto& [name, text] : csv_files) {
    write_file_atomically((out / name).string(), text);
    names += (names.empty() ? "" : ", ") + name;
  }
  write_file_atomically((out / "analysis.json").string(), record.dump(2) + "\n");
  std::printf("\noutput folder: %s (%s; plot: python3 %s %s)\n", out.string().c_str(), names.c_str(),
              plot_script.c_str(), out.string().c_str());
}

// munkberg_filtering: Figure 1's curve and the measurement on every image.
int run_munkberg_filtering(const AnalysisConfig& config, const std::string& data_root,
                           const std::vector<std::string>& images, const fs::path& out) {
  const munkberg::Figure1Setup& f = config.figure1;
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
  nlohmann::json record = base_record(config, data_root);
  record["figure1"] = {{"v1", f.v1}, {"v2", f.v2}, {"y1", f.y1}, {"y2", {f.y2_first, f.y2_last}},
                       {"alpha", f.alpha}, {"samples", f.samples}, {"spacing", f.geometric ? "geometric" : "linear"},
                       {"plain_error_first", curve.front().plain_error}, {"plain_error_last", curve.back().plain_error},
                       {"plain_error_min", plain_min}, {"plain_error_max", plain_max},
                       {"normalised_max_abs_error", normalised_max_abs}};
  record["normalisation"] = {{"shift", munkberg::to_string(f.rule)}, {"reference", munkberg::to_string(f.reference)}};
  record["magnification"] = config.magnification;
  std::printf("%-36s %10s %12s %12s %10s %10s %12s %12s\n", "image", "size", "log2 plain", "log2 norm.", ">1% plain",
              ">1% norm.", "max plain", "max norm.");
  for (const std::string& relative : images) {
    const std::string path = (fs::path(data_root) / relative).string();
    const Image image = load_analysis_image(config, data_root, relative);
    munkberg::FilteringMeasurement m;
    try {
      m = munkberg::measure_logyuv_filtering(image, config.magnification, f.rule, f.reference);
    } catch (const Error& e) {
      fail(path, e.what());   // e.g. an image smaller than 2x2: name the file
    }
    measured += csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) + "," +
                std::to_string(config.magnification) + "," + munkberg::to_string(f.rule) + "," +
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
  write_analysis_folder(out, config,
                        {{"fig1_curve.csv", curve_csv},
                        {"filtering_measured.csv", measured}},
                        record, "configs/papers/munkberg2008/plot_fig1_filtering.py");
  return 0;
}

// munkberg_luminance_histogram: Figure 8 per image and pooled over all images ("all").
int run_munkberg_histogram(const AnalysisConfig& config, const std::string& data_root,
                           const std::vector<std::string>& images, const fs::path& out) {
  std::string histogram = "image,bin,range_low,range_high,count,share\n";
  std::string summary =
      "image,width,height,blocks,black_blocks,ranged_blocks,black_texels,mean_range,median_range,max_range\n";
  std::string precision = "image,bits,range_limit,ranged_blocks,within,share_percent,paper_percent\n";
  nlohmann::json record = base_record(config, data_root);
  record["bin_width"] = config.bin_width;
  record["bins"] = config.bins;
  std::vector<double> pooled;
  std::size_t pooled_blocks = 0, pooled_black_blocks = 0, pooled_black_texels = 0;

  const auto add_rows = [&](const std::string& name, const std::string& size_fields, std::vector<double> ranges,
                            std::size_t blocks, std::size_t black_blocks, std::size_t black_texels,
                            nlohmann::json& json) {
    const std::vector<std::uint64_t> counts = munkberg::range_histogram(ranges, config.bin_width, config.bins);
    for (int b = 0; b < config.bins; ++b) {
      const double share = ranges.empty() ? 0.0 : static_cast<double>(counts[b]) / static_cast<double>(ranges.size());
      // The last bin is open-ended: its upper edge is written as "inf".
      histogram += csv_field(name) + "," + std::to_string(b) + "," + g17(b * config.bin_width) + "," +
                   (b == config.bins - 1 ? std::string("inf") : g17((b + 1) * config.bin_width)) + "," +
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
    for (const PrecisionRow& row : config.precision) {
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
  for (const PrecisionRow& row : config.precision) {
    char cell[48];
    std::snprintf(cell, sizeof cell, " %7s", ("<=" + g17(munkberg::range_for_precision_bits(row.bits))).c_str());
    header += cell;
    if (row.has_paper) header += " (paper)";
  }
  std::printf("share of 4x4 blocks whose log2-luminance range is within the limit (k bits: range <= 2^(9-k)):\n");
  std::printf("%-36s %8s %7s %7s %7s%s\n", "image", "blocks", "black", "mean", "median", header.c_str());
  for (const std::string& relative : images) {
    const std::string path = (fs::path(data_root) / relative).string();
    const Image image = load_analysis_image(config, data_root, relative);
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
  nlohmann::json all = {{"images", images.size()}};
  add_rows("all", ",", std::move(pooled), pooled_blocks, pooled_black_blocks, pooled_black_texels, all);
  record["all"] = all;
  write_analysis_folder(out, config,
                        {{"luminance_range_histogram.csv", histogram},
                        {"luminance_range_summary.csv", summary},
                        {"luminance_range_precision.csv", precision}},
                        record, "configs/papers/munkberg2008/plot_fig8_histogram.py");
  return 0;
}

}  // namespace

int run_analyze(const AnalyzeArgs& args) {
  const AnalysisConfig config = parse_analysis_config(read_text(args.config), args.config);
  ExperimentConfig experiment;   // only for the data-root and image rules shared with `blocklab run`
  experiment.source_path = config.source_path;
  experiment.data_root = config.data_root;
  experiment.images = config.images;
  const std::string data_root = resolve_data_root(experiment, args.data_root);
  const std::vector<std::string> images = resolve_images(experiment, data_root);
  const std::string out_dir =
      !args.out_dir.empty() ? args.out_dir : (!config.output.empty() ? config.output : (fs::path("runs") / config.name).string());
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) fail(out_dir, "cannot create the output folder: " + ec.message());
  if (config.kind == kMunkbergFilteringKind) return run_munkberg_filtering(config, data_root, images, fs::path(out_dir));
  if (config.kind == kMunkbergHistogramKind) return run_munkberg_histogram(config, data_root, images, fs::path(out_dir));

  std::string curves =
      "image,a,b,x,tone_mapped,hdr_filtered,tone_mapped_filtered,error,closed_form_error,relative_error\n";
  std::string measured =
      "image,width,height,tmo,alpha,l_white,mean,samples,mean_interval,max_interval,fraction_interval_above_0_3,"
      "rms_error,max_error,mean_signed_error,rms_relative_error,max_relative_error,"
      "fraction_relative_above_1_percent,rms_log2_error,max_log2_error\n";
  nlohmann::json record;
  record["analysis"] = config.kind;
  record["name"] = config.name;
  record["blocklab_version"] = BLOCKLAB_VERSION;
  record["config"] = config.source_path;
  record["data_root"] = data_root;
  record["samples"] = config.samples;
  for (const Interval& interval : config.intervals) record["intervals"].push_back({interval.a, interval.b});
  if (!config.tmo_given) record["tmo_options"] = config.fit_options;

  std::printf("%-36s %9s %9s %9s %10s %10s %10s %10s %10s\n", "image", "alpha", "l_white", "mean", "interval",
              "max eq.7", "at x", "max rel.", "rel. x");
  for (const std::string& relative : images) {
    const std::string path = (fs::path(data_root) / relative).string();
    Image image = read_image(path);
    apply_input_policy(image, config.input_policy, path);
    ReinhardParameters parameters = config.given;
    std::string tmo = "given";
    if (!config.tmo_given) {
      try {
        parameters = banterle_fit_tmo(image, config.fit_options).fitted;
      } catch (const Error& e) {
        fail(path, e.what());   // e.g. fit_options the fit's solver rejects
      }
      tmo = "fit=" + config.fit_options.at("fit") + " mean=" + config.fit_options.at("mean");
    }
    nlohmann::json image_record = {{"image", relative},
                                   {"sha256", sha256_file_hex(path)},
                                   {"alpha", parameters.alpha},
                                   {"l_white", parameters.l_white},
                                   {"mean", parameters.mean},
                                   {"tmo", tmo}};
    for (const Interval& interval : config.intervals) {
      const std::vector<FilteringCurvePoint> curve =
          filtering_error_curve(parameters, interval.a, interval.b, config.samples);
      const FilteringCurvePoint* peak = &curve.front();
      const FilteringCurvePoint* peak_relative = &curve.front();
      for (const FilteringCurvePoint& p : curve) {
        curves += csv_field(relative) + "," + g17(interval.a) + "," + g17(interval.b) + "," + g17(p.x) + "," +
                  g17(p.tone_mapped) + "," + g17(p.hdr_filtered) + "," + g17(p.tone_mapped_filtered) + "," +
                  g17(p.error) + "," + g17(p.closed_form_error) + "," + g17(p.relative_error) + "\n";
        if (p.error > peak->error) peak = &p;
        if (p.relative_error > peak_relative->relative_error) peak_relative = &p;
      }
      char label[64];
      std::snprintf(label, sizeof label, "[%g, %g]", interval.a, interval.b);
      std::printf("%-36s %9.4g %9.4g %9.4g %10s %10.4g %10.3f %10.4g %10.3f\n", relative.c_str(), parameters.alpha,
                  parameters.l_white, parameters.mean, label, peak->error, peak->x, peak_relative->relative_error,
                  peak_relative->x);
      image_record["curves"].push_back({{"a", interval.a},
                                        {"b", interval.b},
                                        {"max_error", peak->error},
                                        {"max_error_x", peak->x},
                                        {"max_relative_error", peak_relative->relative_error},
                                        {"max_relative_error_x", peak_relative->x}});
    }
    FilteringMeasurement m;
    try {
      m = measure_bilinear_filtering_error(image, parameters);
    } catch (const Error& e) {
      fail(path, e.what());   // e.g. an image smaller than 2x2: name the file
    }
    measured += csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) + "," +
                csv_field(tmo) + "," + g17(parameters.alpha) + "," + g17(parameters.l_white) + "," +
                g17(parameters.mean) + "," + std::to_string(m.samples) + "," + g17(m.mean_interval) + "," +
                g17(m.max_interval) + "," + g17(m.fraction_interval_above_0_3) + "," + g17(m.rms_error) + "," +
                g17(m.max_error) + "," + g17(m.mean_signed_error) + "," + g17(m.rms_relative_error) + "," +
                g17(m.max_relative_error) + "," + g17(m.fraction_relative_above_1_percent) + "," +
                g17(m.rms_log2_error) + "," + g17(m.max_log2_error) + "\n";
    std::printf("  bilinear 2x on the image: %zu samples, mean interval %.4f (%.2f %% of quads wider than 0.3), "
                "relative error RMS %.3g max %.3g (%.3f %% above 1 %%), log2 error RMS %.3g max %.3g\n",
                m.samples, m.mean_interval, 100.0 * m.fraction_interval_above_0_3, m.rms_relative_error,
                m.max_relative_error, 100.0 * m.fraction_relative_above_1_percent, m.rms_log2_error, m.max_log2_error);
    image_record["measured"] = {{"samples", m.samples},
                                {"mean_interval", m.mean_interval},
                                {"rms_relative_error", m.rms_relative_error},
                                {"max_relative_error", m.max_relative_error},
                                {"rms_log2_error", m.rms_log2_error}};
    record["images"].push_back(image_record);
  }
  const fs::path out(out_dir);
  write_analysis_folder(out, config,
                        {{"filtering_curves.csv", curves},
                        {"filtering_measured.csv", measured}},
                        record, "configs/papers/banterle2008/plot_filtering.py");
  return 0;
}

}  // namespace blocklab::cli
