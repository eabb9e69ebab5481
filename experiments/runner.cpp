// The experiment runner: validate, plan, freeze the plan into the run folder, run or reuse each cell (here, or
// spread over MPI ranks), then regenerate results.jsonl / results.csv from the cell files (contract in runner.h
// and run_folder.h).
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
#include "experiments/shard.h"
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

// The cells of `images` x the config's treatments, image-major, each keyed.
std::vector<PlannedCell> plan_cells(const ExperimentConfig& config, const std::vector<ImageIdentity>& images) {
  std::vector<PlannedCell> cells;
  for (std::size_t i = 0; i < images.size(); ++i) {
    for (std::size_t t = 0; t < config.treatments.size(); ++t) {
      cells.push_back({i, t, cell_key(cell_key_document(config, images[i], config.treatments[t]))});
    }
  }
  return cells;
}

// The plan rank 0 sends the other ranks of an MPI job: run folder, data root, images with digests, cell keys.
std::vector<std::string> plan_message(const std::string& run_dir, const std::string& data_root,
                                      const std::vector<ImageIdentity>& images, const std::vector<PlannedCell>& cells) {
  std::vector<std::string> message = {run_dir, data_root, std::to_string(images.size())};
  for (const ImageIdentity& image : images) message.push_back(image.relative_path);
  for (const ImageIdentity& image : images) message.push_back(image.sha256);
  for (const PlannedCell& cell : cells) message.push_back(cell.key);
  return message;
}

// A rank other than 0: rank 0's plan, checked against this rank's own expansion of the config (a different build
// or config on one node would otherwise store cells under keys that do not describe them).
void adopt_plan(const std::vector<std::string>& message, const ExperimentConfig& config, int rank,
                std::string& run_dir, std::string& data_root, std::vector<ImageIdentity>& images,
                std::vector<PlannedCell>& cells) {
  const std::string where = "rank " + std::to_string(rank);
  if (message.size() < 3) fail(where, "malformed plan from rank 0");
  run_dir = message[0];
  data_root = message[1];
  const std::size_t image_count = std::stoul(message[2]);
  if (message.size() < 3 + 2 * image_count) fail(where, "malformed plan from rank 0");
  for (std::size_t i = 0; i < image_count; ++i) images.push_back({message[3 + i], message[3 + image_count + i]});
  cells = plan_cells(config, images);
  const std::size_t first_key = 3 + 2 * image_count;
  if (message.size() - first_key != cells.size()) {
    fail(where, "its expansion of " + config.source_path + " has " + std::to_string(cells.size()) +
                    " cells, rank 0's " + std::to_string(message.size() - first_key) +
                    ": every rank must run the same blocklab build on the same config");
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cells[c].key != message[first_key + c]) {
      fail(where, "cell " + std::to_string(c) + " of " + config.source_path + " has key " + cells[c].key +
                      " here but " + message[first_key + c] +
                      " on rank 0: every rank must run the same blocklab build on the same config and images");
    }
  }
}

}  // namespace

RunSummary run_experiment(const RunOptions& options, const Catalog& catalog) {
  CellDispatcher local_dispatcher;
  CellDispatcher& dispatcher = options.dispatcher != nullptr ? *options.dispatcher : local_dispatcher;
  const bool coordinator = dispatcher.rank() == 0;
  const int threads_used = resolve_thread_count(options.threads);
  const std::string suffix = options.shard.file_suffix();
  const std::string provenance_file = "provenance" + (options.shard.whole() ? std::string() : suffix) + ".json";

  ExperimentConfig config;
  std::string data_root, run_dir;
  std::vector<ImageIdentity> images;
  std::vector<PlannedCell> cells;
  GitState git;
  nlohmann::json provenance;
  const std::vector<std::string> plan = dispatcher.share([&]() {
    // 1. Everything that can be wrong with the config, the data root or the image list fails here, before any output.
    config = load_experiment(options.config_path, catalog, options.max_cells);
    data_root = resolve_data_root(config, options.data_root);
    const std::vector<std::string> image_paths = resolve_images(config, data_root);
    check_cell_limit(config, sweep_size(config, catalog), image_paths.size(),
                     std::to_string(image_paths.size()) + (image_paths.size() == 1 ? " image" : " images"),
                     options.max_cells);
    if (options.on_plan) {
      options.on_plan({config.treatments.size() * image_paths.size(), config.treatments.size(), image_paths.size()});
    }

    // 2. Plan: hash every image file once, key every cell.
    for (const std::string& relative : image_paths) {
      images.push_back({relative, sha256_file_hex((fs::path(data_root) / relative).string())});
    }
    cells = plan_cells(config, images);

    // 3. Freeze the plan into the run folder. Shards may share the folder with other jobs still writing.
    const std::string run_dir_text =
        options.out_dir.empty() ? (fs::path("runs") / config.name).string() : options.out_dir;
    std::error_code ec;
    run_dir = fs::absolute(run_dir_text, ec).lexically_normal().string();
    const RunFolder folder(run_dir);
    folder.remove_stray_temp_files(options.shard.whole() ? std::chrono::hours(0) : std::chrono::hours(1));
    git = read_git_state(BLOCKLAB_SOURCE_DIR);
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
    provenance = make_provenance(provenance_inputs);
    provenance["dispatch"] = dispatcher.description();
    if (!options.shard.whole()) provenance["shard"] = options.shard.text();
    folder.write_file_unless_same("config.yaml", config.source_text);
    folder.write_file_unless_same("resolved.json", resolved_document(config, data_root, images, cells));
    write_file_atomically(folder.path(provenance_file), provenance.dump(2) + "\n");
    return plan_message(run_dir, data_root, images, cells);
  });
  if (!coordinator) {
    config = load_experiment(options.config_path, catalog, options.max_cells);
    adopt_plan(plan, config, dispatcher.rank(), run_dir, data_root, images, cells);
    git = read_git_state(BLOCKLAB_SOURCE_DIR);
  }
  const RunFolder folder(run_dir);
  std::vector<std::string> keys;
  for (const PlannedCell& cell : cells) keys.push_back(cell.key);
  const std::vector<std::size_t> mine = shard_cells(keys, options.shard);
  std::vector<std::string> my_keys;
  for (const std::size_t c : mine) my_keys.push_back(keys[c]);

  RunSummary summary;
  summary.run_dir = run_dir;
  summary.rank = dispatcher.rank();
  summary.shard = options.shard;
  summary.experiment_cells = cells.size();
  summary.total = mine.size();
  summary.metric_names = config.metric_names();
  for (const MetricRequest& m : config.metrics) {
    std::string metric_options;
    for (const auto& [key, value] : m.options)
      metric_options += (metric_options.empty() ? " [" : ", ") + key + "=" + value;
    summary.metric_legend.push_back(m.metric->description() + (metric_options.empty() ? "" : metric_options + "]"));
  }

  // 4. Rank 0 finds the cells the store lacks (only successful records are cached; an "error" record is retried),
  // then the dispatcher runs them. A process reads a source image once for all the cells of it it runs in a row.
  std::vector<std::size_t> pending;
  if (coordinator) {
    if (options.fresh) {
      pending = mine;
    } else {
      const std::vector<std::optional<nlohmann::json>> stored = folder.read_cells(my_keys, threads_used);
      for (std::size_t i = 0; i < mine.size(); ++i) {
        if (stored[i] && stored[i]->value("status", std::string()) == "ok") ++summary.cached;
        else pending.push_back(mine[i]);
      }
    }
  }
  const std::string host = host_name();
  std::size_t loaded_index = images.size();
  SourceImage source;
  const CellRunner run_cell = [&](std::size_t c) {
    const PlannedCell& cell = cells[c];
    const ImageIdentity& image = images[cell.image_index];
    if (loaded_index != cell.image_index) {
      source = SourceImage{};   // release the previous image before reading the next
      source = load_source_image((fs::path(data_root) / image.relative_path).string(), image.relative_path,
                                 config.input_policy, config.crop);
      loaded_index = cell.image_index;
    }
    CellJob job;
    job.config = &config;
    job.treatment = &config.treatments[cell.treatment_index];
    job.image = image;
    job.key = cell.key;
    job.threads_used = threads_used;
    job.git_sha = git.sha;
    job.host = host;
    job.rank = dispatcher.is_mpi() ? dispatcher.rank() : -1;
    const nlohmann::json record = compute_cell(job, source, folder);
    folder.write_cell(cell.key, record);
    return record.value("status", std::string()) == "ok" ? CellStatus::ok : CellStatus::error;
  };
  CellEvents events;
  events.on_started = [&](std::size_t c, int rank) {
    if (!options.on_progress) return;
    std::string current = describe_cell(config, images[cells[c].image_index].relative_path,
                                        config.treatments[cells[c].treatment_index]);
    if (dispatcher.is_mpi()) current += " on rank " + std::to_string(rank);
    options.on_progress({summary.cached + summary.computed + summary.failed, summary.total, summary.cached, current});
  };
  events.on_finished = [&summary](std::size_t, int, CellStatus status) {
    ++(status == CellStatus::ok ? summary.computed : summary.failed);
  };
  dispatcher.run_cells(pending, run_cell, events);
  source = SourceImage{};
  if (!coordinator) return summary;
  if (options.on_progress) options.on_progress({summary.total, summary.total, summary.cached, ""});

  // 5. Derived files from the cell store, in cell order: every cell exactly once, whatever happened before.
  std::vector<std::optional<nlohmann::json>> records = folder.read_cells(my_keys, threads_used);
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (!records[i]) fail(folder.cell_path(my_keys[i]), "cell record missing or unreadable right after the run");
    summary.records.push_back(std::move(*records[i]));
  }
  write_results_files(run_dir, summary.records, summary.metric_names, options.shard.whole() ? "" : suffix);
  provenance["finish_time"] = utc_timestamp_now();
  provenance["cells"] = {{"total", summary.total},
                         {"computed", summary.computed},
                         {"cached", summary.cached},
                         {"failed", summary.failed}};
  if (!options.shard.whole()) provenance["cells"]["experiment"] = summary.experiment_cells;
  write_file_atomically(folder.path(provenance_file), provenance.dump(2) + "\n");
  return summary;
}

}  // namespace blocklab
