// Run provenance (see provenance.h). Build facts come from macros CMake defines on blocklab_flags; library versions
// from each library's version header (yaml-cpp 0.7 has no version macro, so the Debian package version is stated).
#include "experiments/provenance.h"

#include <Eigen/Core>
#include <OpenEXR/OpenEXRConfig.h>
#include <boost/version.hpp>
#include <ceres/version.h>
#include <nlopt.hpp>
#include <oneapi/tbb/version.h>
#include <openssl/opensslv.h>

#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

namespace blocklab {
namespace {

// Single-quotes `text` for /bin/sh (a quote inside becomes '\'').
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs a command and returns its stdout; `ok` is false when it cannot start or exits non-zero.
std::string capture(const std::string& command, bool& ok) {
  ok = false;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {};
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  ok = pclose(pipe) == 0;
  return out;
}

bool is_full_sha(const std::string& text) {
  if (text.size() != 40) return false;
  for (char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace

GitState read_git_state(const std::string& source_dir) {
  GitState state;
  const std::string git = "git -C " + shell_quote(source_dir) + " ";
  bool ok = false;
  std::string sha = capture(git + "rev-parse HEAD 2>/dev/null", ok);
  while (!sha.empty() && (sha.back() == '\n' || sha.back() == '\r')) sha.pop_back();
  // git missing, not a repository, or no commit yet: keep "unknown" rather than a partial answer.
  if (!ok || !is_full_sha(sha)) return state;
  state.sha = sha;
  const std::string status = capture(git + "status --porcelain 2>/dev/null", ok);
  if (ok) state.dirty = !status.empty();
  return state;
}

nlohmann::json library_versions() {
  int nlopt_major = 0, nlopt_minor = 0, nlopt_bugfix = 0;
  nlopt::version(nlopt_major, nlopt_minor, nlopt_bugfix);
  return {
      {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                    std::to_string(EIGEN_MINOR_VERSION)},
      {"ceres", CERES_VERSION_STRING},
      {"tbb", std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR)},
      {"openexr", OPENEXR_VERSION_STRING},
      {"nlopt", std::to_string(nlopt_major) + "." + std::to_string(nlopt_minor) + "." + std::to_string(nlopt_bugfix)},
      {"boost", BOOST_LIB_VERSION},
      {"yaml-cpp", "0.7 (Debian)"},   // no version macro in yaml-cpp 0.7
      {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." + std::to_string(NLOHMANN_JSON_VERSION_MINOR) +
                            "." + std::to_string(NLOHMANN_JSON_VERSION_PATCH)},
      {"openssl", OPENSSL_VERSION_TEXT},
  };
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";   // not Linux, or an architecture whose cpuinfo has no "model name"
}

std::string utc_timestamp_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "unknown";
  return name;
}

nlohmann::json make_provenance(const ProvenanceInputs& in) {
  return {
      {"experiment", in.experiment},
      {"config_path", in.config_path},
      {"config_sha256", in.config_sha256},
      {"data_root", in.data_root},
      {"run_dir", in.run_dir},
      {"blocklab_version", BLOCKLAB_VERSION},
      {"git_sha", in.git.sha},
      {"git_dirty", in.git.dirty},
      {"source_dir", BLOCKLAB_SOURCE_DIR},
      {"compiler", BLOCKLAB_COMPILER},
      {"build_type", BLOCKLAB_BUILD_TYPE},
      {"invariant_build", static_cast<bool>(BLOCKLAB_INVARIANT_BUILD)},
      {"sanitize_build", static_cast<bool>(BLOCKLAB_SANITIZE_BUILD)},
      {"libraries", library_versions()},
      {"cpu_model", cpu_model()},
      {"host", host_name()},
      {"hardware_threads", std::thread::hardware_concurrency()},
      {"threads_requested", in.threads_requested},
      {"threads_used", in.threads_used},
      {"seed", in.seed},
      {"start_time", in.start_time},
  };
}

}  // namespace blocklab
