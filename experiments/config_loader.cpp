// Loading an experiment config: walks the YAML tree against the schema documented in experiments/config.h, checks
// every name against the catalog (format registry, metric registry) and expands the sweeps, so that every mistake
// is reported with its file and line before any image is read.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/options.h"
#include "experiments/config.h"
#include "experiments/strict_yaml.h"
#include "experiments/sweep.h"

namespace blocklab {
namespace {

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::vector<std::string> format_names(const Catalog& catalog) {
  std::vector<std::string> names;
  for (const Format* f : catalog.formats) names.push_back(f->name());
  return names;
}

std::vector<std::string> metric_names_of(const Catalog& catalog) {
  std::vector<std::string> names;
  for (const Metric* m : catalog.metrics) names.push_back(m->name());
  return names;
}

std::vector<std::string> option_names_of(const Format& format) {
  std::vector<std::string> names;
  for (const OptionSpec& spec : all_option_specs(format)) names.push_back(spec.name);   // own + common (seed)
  return names;
}

// A small smooth HDR-ish image pair for the dry metric evaluation (positive, non-constant, not identical).
std::pair<Image, Image> probe_images() {
  Image reference(4, 4, 3), test(4, 4, 3);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float value = 0.05f * static_cast<float>(1 + x + 4 * y + c);
        reference.texel(x, y)[c] = value;
        test.texel(x, y)[c] = value * 1.01f;
      }
    }
  }
  return {reference, test};
}

class ConfigParser {
 public:
  ConfigParser(const std::string& text, const std::string& source, const Catalog& catalog, std::uint64_t max_cells)
      : yaml_(text, source), catalog_(catalog), max_cells_(max_cells) {}

  ExperimentConfig parse(const std::string& text) {
    ExperimentConfig config;
    config.source_path = yaml_.source_name();
    config.source_text = text;
    const YAML::Node& root = yaml_.root();
    if (!root.IsDefined() || root.IsNull()) fail(yaml_.source_name(), "the config is empty");
    yaml_.check_map(root, "the top level",
                    {"schema", "name", "description", "data_root", "images", "input_policy", "seed", "metrics",
                     "formats", "ablations", "save_decoded", "error_maps", "mode_maps", "crop"},
                    {"schema", "name", "images", "metrics", "formats"});

    const YAML::Node schema = StrictYaml::child(root, "schema");
    const std::int64_t schema_version = yaml_.integer(schema, "schema");
    if (schema_version != 1) {
      yaml_.fail_at(schema, "schema " + std::to_string(schema_version) + " is not supported (this blocklab reads 1)");
    }
    config.schema = 1;
    const YAML::Node name = StrictYaml::child(root, "name");
    config.name = yaml_.identifier(name, "name");
    // The name is the default run folder runs/<name>: "." and ".." would point outside runs/.
    if (config.name == "." || config.name == "..") yaml_.fail_at(name, "name '" + config.name + "' is not a folder name");
    if (const YAML::Node n = StrictYaml::child(root, "description"); n.IsDefined()) {
      config.description = yaml_.scalar(n, "description");
    }
    if (const YAML::Node n = StrictYaml::child(root, "data_root"); n.IsDefined()) {
      config.data_root = yaml_.scalar(n, "data_root");
    }
    parse_images(StrictYaml::child(root, "images"), config);
    if (const YAML::Node n = StrictYaml::child(root, "input_policy"); n.IsDefined()) {
      const std::string policy = yaml_.scalar(n, "input_policy");
      try {
        config.input_policy = input_policy_from_string(policy);
      } catch (const Error& e) {
        yaml_.fail_at(n, std::string("input_policy: ") + e.what());
      }
    }
    if (const YAML::Node n = StrictYaml::child(root, "seed"); n.IsDefined()) {
      config.seed = yaml_.integer(n, "seed");
      // CodecContext::seed is unsigned: a negative seed would wrap around silently.
      if (config.seed < 0) yaml_.fail_at(n, "seed must be >= 0");
      config.seed_given = true;
    }
    parse_metrics(StrictYaml::child(root, "metrics"), config);
    parse_formats(StrictYaml::child(root, "formats"), config);
    if (const YAML::Node n = StrictYaml::child(root, "ablations"); n.IsDefined()) parse_ablations(n, config);
    if (const YAML::Node n = StrictYaml::child(root, "crop"); n.IsDefined()) parse_crop(n, config);
    if (const YAML::Node n = StrictYaml::child(root, "mode_maps"); n.IsDefined()) {
      config.mode_maps = yaml_.boolean(n, "mode_maps");
    }
    if (const YAML::Node n = StrictYaml::child(root, "save_decoded"); n.IsDefined()) {
      config.save_decoded = yaml_.boolean(n, "save_decoded");
    }
    if (const YAML::Node n = StrictYaml::child(root, "error_maps"); n.IsDefined()) parse_error_maps(n, config);
    // The size is known from the list lengths alone: a sweep too large is refused before anything is expanded.
    // Every image pattern matches at least one file, so the pattern count bounds the image count from below.
    check_cell_limit(config, sweep_size(config, catalog_), config.images.size(),
                     "at least " + std::to_string(config.images.size()) + " image" +
                         (config.images.size() == 1 ? "" : "s"),
                     max_cells_);
    expand_experiment(config, catalog_);
    return config;
  }

 private:
  void parse_images(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.sequence(node, "images");
    if (node.size() == 0) yaml_.fail_at(node, "images must list at least one image");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string path = indexed("images", i);
      const std::string pattern = yaml_.scalar(node[i], path);
      if (pattern.empty()) yaml_.fail_at(node[i], path + " is empty");
      // Images are named relative to the data root so that runs are portable; cell keys hash that relative path.
      if (pattern.front() == '/') yaml_.fail_at(node[i], path + ": '" + pattern + "' must be relative to the data root");
      config.images.push_back(pattern);
    }
  }

  void parse_metrics(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.sequence(node, "metrics");
    if (node.size() == 0) yaml_.fail_at(node, "metrics must list at least one metric");
    std::set<std::string> seen;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string path = indexed("metrics", i);
      const YAML::Node item = node[i];
      MetricRequest request;
      if (item.IsMap()) {
        const std::vector<std::string> keys = yaml_.map_keys(item, path);
        if (std::find(keys.begin(), keys.end(), "name") == keys.end()) {
          yaml_.fail_at(item, "missing required key 'name' in " + path);
        }
      }
      // Never assign one YAML::Node to another: yaml-cpp assignment overwrites the shared node's contents.
      const YAML::Node name_node = item.IsMap() ? StrictYaml::child(item, "name") : item;
      request.name = yaml_.identifier(name_node, item.IsMap() ? path + ".name" : path);
      request.metric = catalog_.find_metric(request.name);
      if (request.metric == nullptr) {
        yaml_.fail_at(name_node, "unknown metric '" + request.name + "' in " + path + "; valid metrics: " +
                                     join_names(metric_names_of(catalog_)));
      }
      if (item.IsMap() && StrictYaml::child(item, "column").IsDefined()) {
        request.label = yaml_.identifier(StrictYaml::child(item, "column"), path + ".column");
      }
      if (!seen.insert(request.column()).second) {
        yaml_.fail_at(name_node, "metric column '" + request.column() + "' is listed twice in " + path +
                                     " (results have one column per metric; give the second one `column: <name>`)");
      }
      if (item.IsMap()) {
        const std::vector<std::string> valid = request.metric->option_names();
        for (auto it = item.begin(); it != item.end(); ++it) {
          const std::string key = it->first.Scalar();
          if (key == "name" || key == "column") continue;
          if (std::find(valid.begin(), valid.end(), key) == valid.end()) {
            yaml_.fail_at(it->first, "unknown option '" + key + "' for metric '" + request.name + "' in " + path +
                                         "; valid options: column" + (valid.empty() ? "" : ", " + join_names(valid)));
          }
          request.options[key] = yaml_.scalar(it->second, path + "." + key);
        }
      }
      dry_run_metric(request, item);
      config.metrics.push_back(std::move(request));
    }
  }

  // Metric option VALUES are only checked by Metric::compute: evaluate once on a 4x4 pair now, so a bad value stops
  // the run before any image is read.
  void dry_run_metric(const MetricRequest& request, const YAML::Node& item) const {
    if (request.options.empty()) return;
    static const std::pair<Image, Image> probe = probe_images();
    try {
      (void)request.metric->compute(probe.first, probe.second, request.options);
    } catch (const Error& e) {
      yaml_.fail_at(item, "metric '" + request.name + "': " + e.what());
    }
  }

  void parse_formats(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.sequence(node, "formats");
    if (node.size() == 0) yaml_.fail_at(node, "formats must list at least one format entry");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string path = indexed("formats", i);
      const YAML::Node item = node[i];
      yaml_.check_map(item, path, {"format", "label", "options"}, {"format"});
      FormatEntry entry;
      entry.where = yaml_.where(item);
      const YAML::Node format_node = StrictYaml::child(item, "format");
      entry.format = yaml_.identifier(format_node, path + ".format");
      const Format* format = catalog_.find_format(entry.format);
      if (format == nullptr) {
        yaml_.fail_at(format_node, "unknown format '" + entry.format + "' in " + path + "; valid formats: " +
                                       join_names(format_names(catalog_)));
      }
      if (const YAML::Node n = StrictYaml::child(item, "label"); n.IsDefined()) {
        entry.label = yaml_.scalar(n, path + ".label");
        if (entry.label.empty()) yaml_.fail_at(n, path + ".label is empty");
      }
      if (const YAML::Node options = StrictYaml::child(item, "options"); options.IsDefined()) {
        const std::string options_path = path + ".options";
        yaml_.map_keys(options, options_path);
        const std::vector<std::string> valid = option_names_of(*format);
        for (auto it = options.begin(); it != options.end(); ++it) {
          OptionAxis axis;
          axis.key = it->first.Scalar();
          if (std::find(valid.begin(), valid.end(), axis.key) == valid.end()) {
            yaml_.fail_at(it->first, "unknown option '" + axis.key + "' for format '" + entry.format + "' in " +
                                         options_path + "; valid options: " +
                                         (valid.empty() ? "(none)" : join_names(valid)));
          }
          axis.values = option_values(it->second, options_path + "." + axis.key, axis.swept);
          entry.options.push_back(std::move(axis));
        }
      }
      config.formats.push_back(std::move(entry));
    }
  }

  // A scalar, or a non-empty list of distinct scalars (a sweep axis).
  std::vector<std::string> option_values(const YAML::Node& node, const std::string& path, bool& swept) const {
    swept = node.IsSequence();
    if (!swept) return {yaml_.scalar(node, path)};
    if (node.size() == 0) yaml_.fail_at(node, path + ": an empty list sweeps over nothing");
    std::vector<std::string> values;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string value = yaml_.scalar(node[i], indexed(path, i));
      if (std::find(values.begin(), values.end(), value) != values.end()) {
        yaml_.fail_at(node[i], indexed(path, i) + ": value '" + value + "' appears twice in the sweep");
      }
      values.push_back(value);
    }
    return values;
  }

  void parse_ablations(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.map_keys(node, "ablations");   // rejects duplicate ablation names
    for (auto it = node.begin(); it != node.end(); ++it) {
      Ablation ablation;
      ablation.name = yaml_.identifier(it->first, "ablations key");
      ablation.where = yaml_.where(it->first);
      const std::string path = "ablations." + ablation.name;
      if (ablation.name == kBaselineAblation) yaml_.fail_at(it->first, "'baseline' is reserved for the unpatched cells");
      const std::vector<std::string> keys = yaml_.map_keys(it->second, path);
      if (keys.empty()) yaml_.fail_at(it->second, path + " is an empty patch");
      for (auto option = it->second.begin(); option != it->second.end(); ++option) {
        const std::string key = option->first.Scalar();
        if (option->second.IsSequence()) {
          yaml_.fail_at(option->second, path + "." + key + ": an ablation is one patch; sweeps belong in formats[].options");
        }
        ablation.patch[key] = yaml_.scalar(option->second, path + "." + key);
      }
      config.ablations.push_back(std::move(ablation));
    }
  }

  void parse_crop(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.check_map(node, "crop", {"x", "y", "width", "height"}, {"width", "height"});
    ImageCrop& crop = config.crop;
    crop.enabled = true;
    // Sizes beyond 2^20 texels per side are no image this tool reads (core/image_io.h size caps).
    const auto dimension = [&](const char* key, std::int64_t lo) {
      const YAML::Node n = StrictYaml::child(node, key);
      const std::int64_t value = yaml_.integer(n, std::string("crop.") + key);
      if (value < lo || value > (std::int64_t{1} << 20))
        yaml_.fail_at(n, std::string("crop.") + key + " must be in [" + std::to_string(lo) + ", 1048576], got " +
                             std::to_string(value));
      return static_cast<int>(value);
    };
    crop.width = dimension("width", 1);
    crop.height = dimension("height", 1);
    const bool has_x = StrictYaml::child(node, "x").IsDefined(), has_y = StrictYaml::child(node, "y").IsDefined();
    if (has_x != has_y) yaml_.fail_at(node, "crop needs both x and y, or neither (then the rectangle is centred)");
    if (has_x) {
      crop.centred = false;
      crop.x = dimension("x", 0);
      crop.y = dimension("y", 0);
    }
  }

  void parse_error_maps(const YAML::Node& node, ExperimentConfig& config) {
    yaml_.sequence(node, "error_maps");
    const std::vector<std::string> requested = config.metric_names();
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string path = indexed("error_maps", i);
      const std::string name = yaml_.identifier(node[i], path);
      if (std::find(requested.begin(), requested.end(), name) == requested.end()) {
        yaml_.fail_at(node[i],
                      path + ": '" + name + "' is not one of this config's metrics (" + join_names(requested) + ")");
      }
      if (std::find(config.error_maps.begin(), config.error_maps.end(), name) != config.error_maps.end()) {
        yaml_.fail_at(node[i], path + ": '" + name + "' is listed twice");
      }
      config.error_maps.push_back(name);
    }
  }

  StrictYaml yaml_;
  const Catalog& catalog_;
  std::uint64_t max_cells_;
};

}  // namespace

const Format* Catalog::find_format(const std::string& name) const {
  for (const Format* f : formats) {
    if (f->name() == name) return f;
  }
  return nullptr;
}

const Metric* Catalog::find_metric(const std::string& name) const {
  for (const Metric* m : metrics) {
    if (m->name() == name) return m;
  }
  return nullptr;
}

std::vector<std::string> ExperimentConfig::metric_names() const {
  std::vector<std::string> names;
  for (const MetricRequest& m : metrics) names.push_back(m.column());
  return names;
}

ExperimentConfig parse_experiment(const std::string& yaml_text, const std::string& source_name, const Catalog& catalog,
                                  std::uint64_t max_cells) {
  ConfigParser parser(yaml_text, source_name, catalog, max_cells);
  return parser.parse(yaml_text);
}

ExperimentConfig load_experiment(const std::string& path, const Catalog& catalog, std::uint64_t max_cells) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the experiment config");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail(path, "cannot read the experiment config");
  return parse_experiment(text.str(), path, catalog, max_cells);
}

}  // namespace blocklab
