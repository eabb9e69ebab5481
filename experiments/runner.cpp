// The experiment runner: validate, plan, freeze the plan into the run folder, run or reuse each cell, then
// regenerate results.jsonl / results.csv from the cell files (contract in runner.h and run_folder.h).
#include "experiments/runner.h"

#include <filesystem>
#include <map>

#include "core/error.h"
#include "core/parallel.h"
#include "experiments/cell_key.h"
#include "experiments/cell_pipeline.h"
#include "experiments/image_set.h"
#include "experiments/provenance.h"
#include "experiments/results_writer.h"
#include "experiments/run_folder.h"
#include "experiments/sha256.h"
#include "experiments/sweep.h"

namespace blocklab {
namespace fs = std::filesystem;

namespace {

struct PlannedCell {
  std::size_t image_index = 0;
  std::size_t treatment_index = 0;
  std::string key;
};

std::string describe_cell(const ExperimentConfig& config, const std::string& image, const Treatment& treatment) {
  std::string text = fs::path(image).filename().string() + " " + config.variants[treatment.variant_index].label;
  if (treatment.ablation != kBaselineAblation) text += " +" + treatment.ablation;
  return text;
}

// The options of `resolved` that differ from the format's defaults (all of them when the defaults do not resolve).
nlohmann::json options_beyond_defaults(const FormatOptions& resolved, const nlohmann::json& defaults) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : resolved) {
    const auto it = defaults.find(key);
    if (it == defaults.end() || *it != value) out[key] = value;
  }
  return out;
}

// resolved.json: the frozen plan. Kept compact for large sweeps (a few hundred bytes per cell): each format's
// default options once, each variant's options as the ones that differ from those defaults, and each cell as one
// line naming its image and variant by index and its ablation by name (the patch is in "ablations").
std::string resolved_document(const ExperimentConfig& config, const std::string& data_root,
                              const std::vector<ImageIdentity>& images, const std::vector<PlannedCell>& cells) {
  nlohmann::json doc;
  doc["results_schema"] = kResultsSchemaVersion;
  doc["experiment"] = config.name;
  doc["description"] = config.description;
  doc["config_path"] = config.source_path;
  doc["data_root"] = data_root;
  doc["input_policy"] = to_string(config.input_policy);
  doc["seed"] = config.seed;
  doc["save_decoded"] = config.save_decoded;
  doc["error_maps"] = config.error_maps;
  doc["mode_maps"] = config.mode_maps;
  if (config.crop.enabled) doc["crop"] = crop_json(config.crop);
  doc["metrics"] = nlohmann::json::array();
  for (const MetricRequest& m : config.metrics)
    doc["metrics"].push_back({{"name", m.name}, {"column", m.column()}, {"options", m.options}});
  doc["images"] = nlohmann::json::array();
  for (const ImageIdentity& image : images) {
    doc["images"].push_back({{"path", image.relative_path}, {"sha256", image.sha256}});
  }
  doc["formats"] = nlohmann::json::object();
  for (const FormatVariant& v : config.variants) {
    const std::string& name = v.format->name();
    if (doc["formats"].contains(name)) continue;
    nlohmann::json defaults = nlohmann::json::object();
    try {
      defaults = resolve_format_options(*v.format, {});
    } catch (const Error&) {
      // a format without usable defaults: its variants list every option
    }
    doc["formats"][name] = {{"revision", v.format->revision()}, {"default_options", defaults}};
  }
  doc["ablations"] = nlohmann::json::object();
  for (const Ablation& a : config.ablations) doc["ablations"][a.name] = a.patch;
  doc["cells_fields"] = "each cell: index, key, image (index into images), variant (index into variants), ablation "
                        "(baseline or a name in ablations; the patch applied is the part of it that the variant's "
                        "format declares)";

  // The document in the usual two-space form, then the two long arrays with one compact line per element.
  std::string text = doc.dump(2);
  text.erase(text.size() - 2);   // "\n}"
  text += ",\n  \"variants\": [";
  for (std::size_t i = 0; i < config.variants.size(); ++i) {
    const FormatVariant& v = config.variants[i];
    const nlohmann::json variant = {
        {"label", v.label}, {"format", v.format->name()}, {"entry", v.entry_index},
        {"options", options_beyond_defaults(v.resolved, doc["formats"][v.format->name()]["default_options"])}};
    text += (i ? ",\n    " : "\n    ") + variant.dump();
  }
  text += config.variants.empty() ? "]" : "\n  ]";
  text += ",\n  \"cells\": [";
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Treatment& t = config.treatments[cells[i].treatment_index];
    const nlohmann::json cell = {{"index", i},
                                 {"key", cells[i].key},
                                 {"image", cells[i].image_index},
                                 {"variant", t.variant_index},
                                 {"ablation", t.ablation}};
    text += (i ? ",\n    " : "\n    ") + cell.dump();
  }
  text += cells.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return text;
}

}  // namespace

RunSummary run_experiment(const RunOptions& options, const Catalog& catalog) {
  // 1. Everything that can be wrong with the config, the data root or the image list fails here, before any output.
  const ExperimentConfig config = load_experiment(options.config_path, catalog, options.max_cells);
  const std::string data_root = resolve_data_root(config, options.data_root);
  const std::vector<std::string> image_paths = resolve_images(config, data_root);
  const int threads_used = resolve_thread_count(options.threads);
  check_cell_limit(config, sweep_size(config, catalog), image_paths.size(),
                   std::to_string(image_paths.size()) + (image_paths.size() == 1 ? " image" : " images"),
                   options.max_cells);
  if (options.on_plan) {
    options.on_plan({config.treatments.size() * image_paths.size(), config.treatments.size(), image_paths.size()});
  }

  // 2. Plan: hash every image file once, key every cell.
  std::vector<ImageIdentity> images;
  for (const std::string& relative : image_paths) {
    images.push_back({relative, sha256_file_hex((fs::path(data_root) / relative).string())});
  }
  std::vector<PlannedCell> cells;
  for (std::size_t i = 0; i < images.size(); ++i) {
    for (std::size_t t = 0; t < config.treatments.size(); ++t) {
      cells.push_back({i, t, cell_key(cell_key_document(config, images[i], config.treatments[t]))});
    }
  }

  // 3. Freeze the plan into the run folder.
  const std::string run_dir_text = options.out_dir.empty() ? (fs::path("runs") / config.name).string() : options.out_dir;
  std::error_code ec;
  const std::string run_dir = fs::absolute(run_dir_text, ec).lexically_normal().string();
  const RunFolder folder(run_dir);
  folder.remove_stray_temp_files();
  const GitState git = read_git_state(BLOCKLAB_SOURCE_DIR);
  ProvenanceInputs provenance_inputs;
  provenance_inputs.experiment = config.name;
  provenance_inputs.config_path = fs::absolute(config.source_path, ec).lexically_normal().string();
  provenance_inputs.config_sha256 = sha256_hex(config.source_text);
  provenance_inputs.data_root = data_root;
  provenance_inputs.run_dir = run_dir;
  provenance_inputs.threads_requested = options.threads;
  provenance_inputs.threads_used = threads_used;
  provenance_inputs.seed = config.seed;
  provenance_inputs.start_time = utc_timestamp_now();
  provenance_inputs.git = git;
  nlohmann::json provenance = make_provenance(provenance_inputs);
  write_file_atomically(folder.path("config.yaml"), config.source_text);
  write_file_atomically(folder.path("resolved.json"), resolved_document(config, data_root, images, cells));
  write_file_atomically(folder.path("provenance.json"), provenance.dump(2) + "\n");

  // 4. Run the cells in order; a source image is read once for all its cells, and only when one needs computing.
  RunSummary summary;
  summary.run_dir = run_dir;
  summary.total = cells.size();
  summary.metric_names = config.metric_names();
  for (const MetricRequest& m : config.metrics) {
    std::string options;
    for (const auto& [key, value] : m.options) options += (options.empty() ? " [" : ", ") + key + "=" + value;
    summary.metric_legend.push_back(m.metric->description() + (options.empty() ? "" : options + "]"));
  }
  std::size_t loaded_index = images.size();
  SourceImage source;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const PlannedCell& cell = cells[c];
    const Treatment& treatment = config.treatments[cell.treatment_index];
    const ImageIdentity& image = images[cell.image_index];
    if (options.on_progress) {
      options.on_progress({summary.cached + summary.computed + summary.failed, summary.total, summary.cached,
                           describe_cell(config, image.relative_path, treatment)});
    }
    if (!options.fresh) {
      const std::optional<nlohmann::json> stored = folder.read_cell(cell.key);
      // Only successful records are cached; an "error" record is retried.
      if (stored && stored->value("status", std::string()) == "ok") {
        ++summary.cached;
        continue;
      }
    }
    if (loaded_index != cell.image_index) {
      source = SourceImage{};   // release the previous image before reading the next
      source = load_source_image((fs::path(data_root) / image.relative_path).string(), image.relative_path,
                                 config.input_policy, config.crop);
      loaded_index = cell.image_index;
    }
    CellJob job;
    job.config = &config;
    job.treatment = &treatment;
    job.image = image;
    job.key = cell.key;
    job.threads_used = threads_used;
    job.git_sha = git.sha;
    const nlohmann::json record = compute_cell(job, source, folder);
    folder.write_cell(cell.key, record);
    if (record.value("status", std::string()) == "ok") {
      ++summary.computed;
    } else {
      ++summary.failed;
    }
  }
  if (options.on_progress) options.on_progress({summary.total, summary.total, summary.cached, ""});

  // 5. Derived files from the cell store, in cell order: every cell exactly once, whatever happened before.
  for (const PlannedCell& cell : cells) {
    std::optional<nlohmann::json> record = folder.read_cell(cell.key);
    if (!record) fail(folder.cell_path(cell.key), "cell record missing or unreadable right after the run");
    summary.records.push_back(std::move(*record));
  }
  write_file_atomically(folder.path("results.jsonl"), results_jsonl(summary.records));
  write_file_atomically(folder.path("results.csv"), results_csv(summary.records, summary.metric_names));
  provenance["finish_time"] = utc_timestamp_now();
  provenance["cells"] = {{"total", summary.total},
                         {"computed", summary.computed},
                         {"cached", summary.cached},
                         {"failed", summary.failed}};
  write_file_atomically(folder.path("provenance.json"), provenance.dump(2) + "\n");
  return summary;
}

}  // namespace blocklab
