// The analysis registry and the keys every analysis config shares (experiments/analysis.h).
#include "experiments/analysis.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "experiments/config.h"
#include "experiments/image_set.h"
#include "experiments/run_folder.h"

namespace blocklab {

namespace fs = std::filesystem;

const std::vector<Analysis>& all_analyses() {
  static const std::vector<Analysis> table = {
      banterle_filtering_analysis(),
      munkberg_filtering_analysis(),
      munkberg_luminance_histogram_analysis(),
      munkberg_mode_predictor_analysis(),
      munkberg_saturation_analysis(),
      wang_filtering_analysis(),
      wang_codec_error_analysis(),
      mavridis_coefficient_search_analysis(),
      mavridis_error_breakdown_analysis(),
  };
  return table;
}

std::string analysis_names() {
  std::string names;
  for (const Analysis& analysis : all_analyses()) names += (names.empty() ? "" : ", ") + analysis.name;
  return names;
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read the config file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The shared keys, then the analysis's own (through its parser): every error before any work.
AnalysisRunner parse_analysis_config(const std::string& text, const std::string& source, AnalysisConfig& config) {
  const StrictYaml yaml(text, source);
  const YAML::Node& root = yaml.root();
  if (!root.IsDefined() || root.IsNull()) fail(source, "the config is empty");
  config.source_path = source;
  config.source_text = text;
  // The kind decides which keys are valid, so it is read (and checked) first.
  yaml.map_keys(root, "the top level");
  std::vector<std::string> allowed = {"schema", "name", "description", "analysis", "data_root", "images",
                                      "input_policy", "output"};
  const Analysis* analysis = nullptr;
  if (const YAML::Node kind = StrictYaml::child(root, "analysis"); kind.IsDefined()) {
    config.kind = yaml.identifier(kind, "analysis");
    for (const Analysis& candidate : all_analyses())
      if (candidate.name == config.kind) analysis = &candidate;
    if (analysis == nullptr)
      yaml.fail_at(kind, "unknown analysis '" + config.kind + "'; valid analyses: " + analysis_names());
    allowed.insert(allowed.end(), analysis->keys.begin(), analysis->keys.end());
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
    const std::string pattern = yaml.scalar(images[i], indexed_path("images", i));
    // Relative to the data root, as in `blocklab run`.
    if (pattern.empty() || pattern.front() == '/')
      yaml.fail_at(images[i], indexed_path("images", i) + ": '" + pattern + "' must be a path relative to the data root");
    config.images.push_back(pattern);
  }
  return analysis->parse(yaml, root);
}

}  // namespace

void run_analysis_config(const std::string& config_path, const AnalyzeOptions& options) {
  AnalysisConfig config;
  const AnalysisRunner runner = parse_analysis_config(read_text(config_path), config_path, config);
  ExperimentConfig experiment;   // only for the data-root and image rules shared with `blocklab run`
  experiment.source_path = config.source_path;
  experiment.data_root = config.data_root;
  experiment.images = config.images;
  const std::string data_root = resolve_data_root(experiment, options.data_root);
  const std::vector<std::string> images = resolve_images(experiment, data_root);
  const std::string out_dir = !options.out_dir.empty()
                                  ? options.out_dir
                                  : (!config.output.empty() ? config.output : (fs::path("runs") / config.name).string());
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) fail(out_dir, "cannot create the output folder: " + ec.message());
  runner(AnalysisRun{config, data_root, images, fs::path(out_dir)});
}

double analysis_number(const StrictYaml& yaml, const YAML::Node& node, const std::string& path) {
  const std::string text = yaml.scalar(node, path);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  // strtod accepts "inf", "nan" and hex floats: only finite values that consume the whole text are numbers here.
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) ||
      text.find_first_of("xXnN") != std::string::npos)
    yaml.fail_at(node, path + " must be a finite number, got '" + text + "'");
  return value;
}

int analysis_bounded_integer(const StrictYaml& yaml, const YAML::Node& node, const std::string& path, int lo, int hi) {
  const std::int64_t value = yaml.integer(node, path);
  if (value < lo || value > hi)
    yaml.fail_at(node, path + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                           std::to_string(value));
  return static_cast<int>(value);
}

std::vector<AnalysisVariant> analysis_format_variants(const StrictYaml& yaml, const YAML::Node& root,
                                                    const Format& format,
                                                    const std::vector<std::pair<std::string, FormatOptions>>& defaults) {
  std::vector<std::pair<std::string, FormatOptions>> given = defaults;
  const YAML::Node variants = StrictYaml::child(root, "variants");
  if (variants.IsDefined()) {
    given.clear();
    const std::vector<std::string> labels = yaml.map_keys(variants, "variants");
    if (labels.empty()) yaml.fail_at(variants, "variants must name at least one variant");
    for (const std::string& label : labels) {
      const YAML::Node options = StrictYaml::child(variants, label);
      FormatOptions variant;
      for (const std::string& key : yaml.map_keys(options, "variants." + label))
        variant[key] = yaml.scalar(StrictYaml::child(options, key), "variants." + label + "." + key);
      given.emplace_back(label, variant);
    }
  }
  std::vector<AnalysisVariant> resolved;
  for (const auto& [label, options] : given) {
    try {
      resolved.push_back({label, resolve_format_options(format, options)});
    } catch (const Error& e) {
      yaml.fail_at(variants, "variants." + label + ": " + e.what());
    }
  }
  return resolved;
}

std::string indexed_path(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string g17(double value) {
  char buffer[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

Image load_analysis_image(const AnalysisRun& run, const std::string& relative) {
  const std::string path = (fs::path(run.data_root) / relative).string();
  Image image = read_image(path);
  apply_input_policy(image, run.config.input_policy, path);
  return image;
}

nlohmann::json analysis_base_record(const AnalysisRun& run) {
  nlohmann::json record;
  record["analysis"] = run.config.kind;
  record["name"] = run.config.name;
  record["blocklab_version"] = BLOCKLAB_VERSION;
  record["config"] = run.config.source_path;
  record["data_root"] = run.data_root;
  record["input_policy"] = to_string(run.config.input_policy);
  return record;
}

void write_analysis_folder(const AnalysisRun& run, const std::vector<std::pair<std::string, std::string>>& csv_files,
                           const nlohmann::json& record, const std::string& plot_script) {
  write_file_atomically((run.out / "config.yaml").string(), run.config.source_text);
  std::string names;
  for (const auto& [name, text] : csv_files) {
    write_file_atomically((run.out / name).string(), text);
    names += (names.empty() ? "" : ", ") + name;
  }
  write_file_atomically((run.out / "analysis.json").string(), record.dump(2) + "\n");
  if (plot_script.empty())
    std::printf("\noutput folder: %s (%s)\n", run.out.string().c_str(), names.c_str());
  else
    std::printf("\noutput folder: %s (%s; plot: python3 %s %s)\n", run.out.string().c_str(), names.c_str(),
                plot_script.c_str(), run.out.string().c_str());
}

}  // namespace blocklab
