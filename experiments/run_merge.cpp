// Merging run folders of one plan (contract in experiments/run_merge.h).
#include "experiments/run_merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/parallel.h"
#include "experiments/provenance.h"
#include "experiments/results_writer.h"
#include "experiments/run_folder.h"

namespace blocklab {
namespace fs = std::filesystem;

namespace {

// Where a folder's plan is kept: everything in it but these names the plan.
const char* const kLocationFields[] = {"config_path", "data_root"};

struct InputFolder {
  std::string dir;
  std::string resolved_text;
  nlohmann::json plan;   // resolved.json less kLocationFields
};

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

InputFolder open_input(const std::string& dir_text) {
  std::error_code ec;
  const std::string dir = fs::absolute(dir_text, ec).lexically_normal().string();
  if (!fs::is_directory(dir, ec)) fail(dir_text, "no such run folder");
  const fs::path resolved_path = fs::path(dir) / "resolved.json";
  const std::optional<std::string> text = read_text(resolved_path);
  if (!text) fail(dir_text, "not a run folder (no resolved.json): give the --out folders of `blocklab run`");
  InputFolder input{dir, *text, nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false)};
  if (input.plan.is_discarded() || !input.plan.is_object()) fail(resolved_path.string(), "not valid JSON");
  for (const char* field : {"cells", "metrics", "images", "variants"}) {
    if (!input.plan.contains(field) || !input.plan[field].is_array())
      fail(resolved_path.string(), std::string("has no '") + field + "' list: not a resolved.json of `blocklab run`");
  }
  for (const char* field : kLocationFields) input.plan.erase(field);
  return input;
}

std::string shortened(const nlohmann::json& value) {
  std::string text = value.dump();
  return text.size() > 100 ? text.substr(0, 97) + "..." : text;
}

// The first part of the plan in which `a` and `b` differ, for the refusal.
std::string plan_difference(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.value("experiment", nlohmann::json()) != b.value("experiment", nlohmann::json()))
    return "experiment " + shortened(a.value("experiment", nlohmann::json())) + " vs " +
           shortened(b.value("experiment", nlohmann::json()));
  std::vector<std::string> fields = {"images", "formats", "variants", "metrics", "ablations", "cells"};
  for (const auto& [key, value] : a.items())
    if (std::find(fields.begin(), fields.end(), key) == fields.end()) fields.push_back(key);
  for (const auto& [key, value] : b.items())
    if (std::find(fields.begin(), fields.end(), key) == fields.end()) fields.push_back(key);
  for (const std::string& field : fields) {
    const nlohmann::json left = a.value(field, nlohmann::json()), right = b.value(field, nlohmann::json());
    if (left == right) continue;
    if (left.is_array() && right.is_array()) {
      if (left.size() != right.size())
        return field + ": " + std::to_string(left.size()) + " vs " + std::to_string(right.size()) + " entries";
      for (std::size_t i = 0; i < left.size(); ++i) {
        if (left[i] != right[i])
          return field + "[" + std::to_string(i) + "]: " + shortened(left[i]) + " vs " + shortened(right[i]);
      }
    }
    return field + ": " + shortened(left) + " vs " + shortened(right);
  }
  return "resolved.json differs";
}

// "hdr/Desk.exr bc7 +ablation" for cell `index` of a plan.
std::string describe_planned_cell(const nlohmann::json& plan, std::size_t index) {
  const nlohmann::json& cell = plan["cells"][index];
  std::string text = plan["images"].at(cell.at("image").get<std::size_t>()).value("path", std::string("?")) + " " +
                     plan["variants"].at(cell.at("variant").get<std::size_t>()).value("label", std::string("?"));
  const std::string ablation = cell.value("ablation", std::string("baseline"));
  if (ablation != "baseline") text += " +" + ablation;
  return text;
}

}  // namespace

MergeSummary merge_run_folders(const std::vector<std::string>& run_dirs, const std::string& out_dir, int threads) {
  if (run_dirs.empty()) fail("merge", "no run folders given");
  std::vector<InputFolder> inputs;
  for (const std::string& dir : run_dirs) {
    inputs.push_back(open_input(dir));
    if (inputs.back().plan != inputs.front().plan) {
      fail("merge", inputs.back().dir + " is a run of another plan than " + inputs.front().dir + " (" +
                        plan_difference(inputs.front().plan, inputs.back().plan) +
                        "): only run folders of one config, on the same images, merge");
    }
  }
  const nlohmann::json& plan = inputs.front().plan;
  std::vector<std::string> keys;
  for (const nlohmann::json& cell : plan["cells"]) keys.push_back(cell.at("key").get<std::string>());
  MergeSummary summary;
  for (const nlohmann::json& metric : plan["metrics"]) summary.metric_names.push_back(metric.at("column"));

  // Each cell from the first folder holding it with status "ok", else the first holding it at all.
  std::vector<RunFolder> folders;
  for (const InputFolder& input : inputs) folders.emplace_back(input.dir);
  std::vector<std::optional<nlohmann::json>> chosen(keys.size());
  parallel_for_index(keys.size(), threads, [&](std::size_t c) {
    for (const RunFolder& folder : folders) {
      std::optional<nlohmann::json> record = folder.read_cell(keys[c]);
      if (!record) continue;
      const bool ok = record->value("status", std::string()) == "ok";
      if (ok || !chosen[c]) chosen[c] = std::move(record);
      if (ok) break;
    }
  });
  std::size_t missing = 0, first_missing = 0;
  for (std::size_t c = keys.size(); c-- > 0;) {
    if (!chosen[c]) {
      ++missing;
      first_missing = c;
    }
  }
  if (missing > 0) {
    fail("merge", std::to_string(missing) + " of " + std::to_string(keys.size()) + " cells are in none of the " +
                      std::to_string(inputs.size()) + " run folders (first: " +
                      describe_planned_cell(plan, first_missing) + ", key " + keys[first_missing] +
                      "): run the shards that computed them to the end, then merge again");
  }

  // The output run folder: plan, every cell file, derived results, provenance.
  std::error_code ec;
  summary.out_dir = fs::absolute(out_dir, ec).lexically_normal().string();
  const RunFolder out(summary.out_dir);
  out.remove_stray_temp_files(std::chrono::hours(1));
  nlohmann::json sources = nlohmann::json::object();
  for (const InputFolder& input : inputs) {
    nlohmann::json files = nlohmann::json::object();
    for (const auto& entry : fs::directory_iterator(input.dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("provenance", 0) != 0 || entry.path().extension() != ".json") continue;
      const std::optional<std::string> text = read_text(entry.path());
      if (!text) continue;
      const nlohmann::json parsed = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
      files[name] = parsed.is_discarded() ? nlohmann::json(*text) : parsed;
    }
    sources[input.dir] = files;
  }
  if (const std::optional<std::string> config = read_text(fs::path(inputs.front().dir) / "config.yaml"))
    out.write_file_unless_same("config.yaml", *config);
  out.write_file_unless_same("resolved.json", inputs.front().resolved_text);
  for (const std::string& key : keys) fs::create_directories(fs::path(out.cell_path(key)).parent_path(), ec);
  parallel_for_index(keys.size(), threads, [&](std::size_t c) {
    const std::optional<nlohmann::json> existing = out.read_cell(keys[c]);
    if (!existing || *existing != *chosen[c]) out.write_cell(keys[c], *chosen[c]);
  });
  for (std::optional<nlohmann::json>& record : chosen) {
    ++(record->value("status", std::string()) == "ok" ? summary.ok : summary.failed);
    summary.records.push_back(std::move(*record));
  }
  summary.cells = summary.records.size();
  write_results_files(summary.out_dir, summary.records, summary.metric_names);
  nlohmann::json provenance;
  provenance["experiment"] = plan.value("experiment", std::string());
  provenance["merged_from"] = nlohmann::json::array();
  for (const InputFolder& input : inputs) provenance["merged_from"].push_back(input.dir);
  provenance["merge_time"] = utc_timestamp_now();
  provenance["host"] = host_name();
  provenance["blocklab_version"] = BLOCKLAB_VERSION;
  provenance["cells"] = {{"total", summary.cells}, {"ok", summary.ok}, {"failed", summary.failed}};
  provenance["sources"] = sources;
  write_file_atomically(out.path("provenance.json"), provenance.dump(2) + "\n");
  return summary;
}

}  // namespace blocklab
