// Provenance of a run (ECOSYSTEM.md section 3 "Provenance fields per record"): full git SHA + dirty flag, compiler,
// build type, invariant/sanitize build flags, library versions, CPU model, hardware threads, threads used, seed and
// start time. Written to <run>/provenance.json before work starts; each cell record carries the git SHA and version.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace blocklab {

struct GitState {
  std::string sha = "unknown";       // full 40-hex object name, never abbreviated (Flowfin/lab#128)
  nlohmann::json dirty = "unknown";  // true / false, or "unknown" when git or the repository is missing
};

// Runs `git -C <source_dir> rev-parse HEAD` and `git status --porcelain` through popen; tolerates git missing.
GitState read_git_state(const std::string& source_dir);

nlohmann::json library_versions();
std::string cpu_model();              // "model name" from /proc/cpuinfo, or "unknown"
std::string utc_timestamp_now();      // ISO 8601, e.g. 2024-05-01T12:34:56Z
std::string host_name();              // gethostname(), or "unknown"

struct ProvenanceInputs {
  std::string experiment, config_path, config_sha256, data_root, run_dir;
  int threads_requested = 0, threads_used = 1;
  std::int64_t seed = 1;
  std::string start_time;
  GitState git;
};
nlohmann::json make_provenance(const ProvenanceInputs& inputs);

}  // namespace blocklab
