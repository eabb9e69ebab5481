// `blocklab analyze CONFIG`: analyses that are not (image x format x metric) cells. The config is strict YAML
// (experiments/strict_yaml.h: unknown / duplicate keys, YAML 1.1 booleans, octal-looking numbers are errors at
// file:line:col). Schema 1:
// ```yaml
// analysis: banterle_filtering     # required: the analysis kind (the only one today, see below). Written FIRST by
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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
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

namespace blocklab::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFilteringKind = "banterle_filtering";
constexpr int kMaxCurveSamples = 100001;

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

AnalysisConfig parse_analysis_config(const std::string& text, const std::string& source) {
  const StrictYaml yaml(text, source);
  const YAML::Node& root = yaml.root();
  if (!root.IsDefined() || root.IsNull()) fail(source, "the config is empty");
  AnalysisConfig config;
  config.source_path = source;
  config.source_text = text;
  yaml.check_map(root, "the top level",
                 {"schema", "name", "description", "analysis", "data_root", "images", "input_policy", "output",
                  "intervals", "samples", "tmo"},
                 {"schema", "name", "analysis", "images"});
  const YAML::Node schema = StrictYaml::child(root, "schema");
  if (yaml.integer(schema, "schema") != 1) yaml.fail_at(schema, "schema must be 1 (this blocklab reads analysis schema 1)");
  const YAML::Node name = StrictYaml::child(root, "name");
  config.name = yaml.identifier(name, "name");
  // The name is the default folder runs/<name>: "." and ".." would point outside runs/.
  if (config.name == "." || config.name == "..") yaml.fail_at(name, "name '" + config.name + "' is not a folder name");
  if (const YAML::Node n = StrictYaml::child(root, "description"); n.IsDefined()) config.description = yaml.scalar(n, "description");
  const YAML::Node kind = StrictYaml::child(root, "analysis");
  config.kind = yaml.identifier(kind, "analysis");
  if (config.kind != kFilteringKind)
    yaml.fail_at(kind, "unknown analysis '" + config.kind + "'; valid analyses: " + kFilteringKind);
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
  write_file_atomically((out / "config.yaml").string(), config.source_text);
  write_file_atomically((out / "filtering_curves.csv").string(), curves);
  write_file_atomically((out / "filtering_measured.csv").string(), measured);
  write_file_atomically((out / "analysis.json").string(), record.dump(2) + "\n");
  std::printf("\noutput folder: %s (filtering_curves.csv, filtering_measured.csv; plot: python3 "
              "configs/papers/banterle2008/plot_filtering.py %s)\n",
              out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace blocklab::cli
