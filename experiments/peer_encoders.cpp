// The peer-encoder table and the process helpers the peers share (experiments/peer_encoders.h).
#include "experiments/peer_encoders.h"

#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "core/error.h"

namespace blocklab {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double children_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void run_peer_command(const std::string& command) {
  if (std::system((command + " > /dev/null 2>&1").c_str()) != 0) fail("peer encoder", "command failed: " + command);
}

std::string peer_command_output(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) fail("peer encoder", "cannot start: " + command);
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  if (::pclose(pipe) != 0) fail("peer encoder", "command failed: " + command + ": " + output);
  return output;
}

namespace {
bool on_path(const char* program) {
  return std::system(("command -v " + std::string(program) + " > /dev/null 2>&1").c_str()) == 0;
}
}  // namespace

bool squish_linked();   // experiments/peer_encoders_squish.cpp

bool peer_tool_available(const std::string& tool) {
  if (tool == "astcenc") return on_path("astcenc");
  if (tool == "nvtt") return on_path("nvcompress");
  if (tool == "squish") return squish_linked();
  return false;
}

std::vector<PeerEncoder> available_peers(bool hdr, const std::vector<std::string>& presets) {
  std::vector<PeerEncoder> peers;
  const auto wanted = [&](const std::string& preset) {
    for (const std::string& p : presets)
      if (p == preset) return true;
    return false;
  };
  const char* const levels[] = {"fast", "medium", "thorough"};
  if (peer_tool_available("astcenc"))
    for (const char* block : {"4x4", "6x6", "8x8"})
      for (const char* preset : levels)
        if (wanted(preset)) peers.push_back(astcenc_peer(block, preset, hdr));
  if (hdr) return peers;
  for (const char* format : {"bc1", "bc3"}) {
    if (peer_tool_available("squish"))
      for (const char* preset : levels)
        if (wanted(preset)) peers.push_back(squish_peer(format, preset));
    if (peer_tool_available("nvtt"))
      for (const char* preset : {"fast", "medium"})
        if (wanted(preset)) peers.push_back(nvtt_peer(format, preset));
  }
  return peers;
}

}  // namespace blocklab
