// `blocklab bench sweep`: what spreading an experiment over MPI ranks buys on this machine, and what it costs.
//   1. The same sweep (default configs/cluster/sweep_bench.yaml, >= 24 cells of unequal cost) run fresh twice, as
//      1 process x 1 thread and as `mpirun -np R` x 1 thread each, timed as whole commands; prints both wall times,
//      their ratio, the load average before each (the machine may be shared) and whether both runs' results.jsonl
//      agree apart from the execution fields (experiments/results_writer.h).
//   2. Rank 0's merge cost per cell: a synthetic run folder of N cells (copies of a real record under distinct
//      keys) is read back and results.jsonl / results.csv written from it, exactly rank 0's last step
//      (experiments/runner.cpp step 5), on 1 thread and on all hardware threads.
// docs/cluster.md holds measured numbers and how they scale.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "experiments/cell_dispatch.h"
#include "experiments/provenance.h"
#include "experiments/results_writer.h"
#include "experiments/run_folder.h"
#include "experiments/sha256.h"

extern char** environ;

namespace blocklab::cli {

namespace {
namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one.empty() ? "unknown" : one + " " + five + " " + fifteen;
}

struct CommandTime {
  double wall = 0, cpu = 0;   // seconds; cpu = user + system of the command and the processes it waited for
};

// Runs argv (stdout to /dev/null, stderr kept) and returns its times; throws Error when it fails.
CommandTime timed_command(const std::vector<std::string>& argv) {
  std::vector<char*> pointers;
  for (const std::string& arg : argv) pointers.push_back(const_cast<char*>(arg.c_str()));
  pointers.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, pointers.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) fail(argv[0], "cannot start (" + std::string(std::strerror(spawned)) + ")");
  int status = 0;
  struct rusage usage {};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  const double wall = seconds_since(start);
  const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                     static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string command;
    for (const std::string& arg : argv) command += (command.empty() ? "" : " ") + arg;
    fail("bench sweep", "'" + command + "' failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
  }
  return {wall, cpu};
}

std::vector<nlohmann::json> read_results(const fs::path& file) {
  std::ifstream in(file);
  if (!in) fail(file.string(), "missing after the run");
  std::vector<nlohmann::json> records;
  for (std::string line; std::getline(in, line);) records.push_back(nlohmann::json::parse(line));
  return records;
}

// Rank 0's step 5 on `keys`: read every record, then write results.jsonl / results.csv. Seconds per cell.
double merge_seconds_per_cell(const RunFolder& folder, const std::vector<std::string>& keys,
                              const std::vector<std::string>& metric_names, int threads) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<nlohmann::json> records;
  records.reserve(keys.size());
  for (std::optional<nlohmann::json>& record : folder.read_cells(keys, threads)) {
    if (!record) fail(folder.dir(), "a synthetic cell did not read back");
    records.push_back(std::move(*record));
  }
  write_results_files(folder.dir(), records, metric_names);
  return seconds_since(start) / static_cast<double>(keys.size());
}

}  // namespace

int run_bench_sweep(const BenchArgs& args) {
  if (mpi_library_version().empty())
    fail("bench sweep", "this blocklab was built without MPI (CMake option BLOCKLAB_MPI; install libopenmpi-dev)");
  const std::string mpirun = find_on_path("mpirun");
  if (mpirun.empty()) fail("bench sweep", "mpirun not found on PATH (Debian: apt-get install openmpi-bin)");
  std::string config = args.config;
  if (!fs::exists(config) && fs::path(config).is_relative() && fs::exists(fs::path(BLOCKLAB_SOURCE_DIR) / config))
    config = (fs::path(BLOCKLAB_SOURCE_DIR) / config).string();
  if (!fs::exists(config)) fail(args.config, "no such config");
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  char pattern[] = "/tmp/blocklab-bench-sweep-XXXXXX";
  if (::mkdtemp(pattern) == nullptr) fail("/tmp", "cannot create a temporary folder");
  const fs::path work(pattern);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{work};

  auto run_command = [&](const std::string& out) {
    std::vector<std::string> argv = {self, "run", config, "--out", (work / out).string(), "--threads", "1",
                                     "--fresh", "--quiet"};
    if (!args.data_root.empty()) argv.insert(argv.end(), {"--data-root", args.data_root});
    return argv;
  };
  std::vector<std::string> mpi_command = {mpirun};
  if (::geteuid() == 0) mpi_command.push_back("--allow-run-as-root");
  mpi_command.insert(mpi_command.end(), {"--oversubscribe", "--bind-to", "none", "-np", std::to_string(args.ranks)});
  for (const std::string& arg : run_command("ranks")) mpi_command.push_back(arg);

  std::printf("bench sweep %s: %s on %s (%s, %u hardware threads), %s\n", utc_timestamp_now().c_str(),
              config.c_str(), host_name().c_str(), cpu_model().c_str(), std::thread::hardware_concurrency(),
              mpi_library_version().c_str());
  const std::string load_single = load_average();
  const CommandTime single = timed_command(run_command("single"));
  const std::string load_ranks = load_average();
  const CommandTime ranked = timed_command(mpi_command);
  const std::vector<nlohmann::json> one = read_results(work / "single" / "results.jsonl");
  const std::vector<nlohmann::json> many = read_results(work / "ranks" / "results.jsonl");
  bool equal = one.size() == many.size();
  std::string difference;
  double cheapest = 0, dearest = 0, total = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    if (equal && without_execution_fields(one[i]) != without_execution_fields(many[i])) {
      equal = false;
      const nlohmann::json a = without_execution_fields(one[i]), b = without_execution_fields(many[i]);
      for (const auto& [field, value] : a.items())
        if (b.value(field, nlohmann::json()) != value) difference += " " + field + ": " + value.dump() + " vs " + b.value(field, nlohmann::json()).dump() + ";";
      difference = one[i].value("image", std::string()) + " " + one[i].value("label", std::string()) + ":" + difference;
    }
    const double cost = one[i].value("encode_seconds", 0.0) + one[i].value("decode_seconds", 0.0);
    cheapest = i == 0 ? cost : std::min(cheapest, cost);
    dearest = std::max(dearest, cost);
    total += cost;
  }
  std::printf("| run | wall s | cpu s | load average before (1, 5, 15 min) |\n|---|---|---|---|\n");
  std::printf("| 1 rank x 1 thread | %.2f | %.2f | %s |\n", single.wall, single.cpu, load_single.c_str());
  std::printf("| %d ranks x 1 thread | %.2f | %.2f | %s |\n", args.ranks, ranked.wall, ranked.cpu, load_ranks.c_str());
  std::printf("speed-up: %.2fx with %d ranks (%zu cells; encode+decode per cell %.4f s to %.3f s, sum %.2f s)\n",
              single.wall / ranked.wall, args.ranks, one.size(), cheapest, dearest, total);
  std::printf("results.jsonl of both runs equal apart from execution fields: %s\n", equal ? "yes" : "NO");
  if (!equal) fail("bench sweep", "the MPI run's results differ from the single process's (" + difference + ")");

  // 2. Rank 0's merge on a synthetic run folder.
  if (one.empty()) fail(config, "the sweep has no cells");
  const RunFolder synthetic((work / "synthetic").string());
  std::vector<std::string> keys;
  std::vector<std::string> metric_names;
  for (const auto& [name, value] : one.front().at("metrics").items()) metric_names.push_back(name);
  nlohmann::json record = one.front();
  for (std::size_t i = 0; i < args.synthetic_cells; ++i) {
    keys.push_back(sha256_hex("synthetic cell " + std::to_string(i)));
    record["key"] = keys.back();
    synthetic.write_cell(keys.back(), record);
  }
  const double serial = merge_seconds_per_cell(synthetic, keys, metric_names, 1);
  const double parallel = merge_seconds_per_cell(synthetic, keys, metric_names, 0);
  std::error_code ec;
  const auto jsonl_bytes = fs::file_size(work / "synthetic" / "results.jsonl", ec);
  std::printf("rank 0's merge of %zu cells (read + verify every cell file, write results.jsonl %.1f MB and "
              "results.csv): %.1f us per cell on 1 thread (%.2f s), %.1f us per cell on %u threads (%.2f s)\n",
              keys.size(), static_cast<double>(jsonl_bytes) / 1e6, serial * 1e6, serial * keys.size(),
              parallel * 1e6, std::thread::hardware_concurrency(), parallel * keys.size());
  return 0;
}

}  // namespace blocklab::cli
