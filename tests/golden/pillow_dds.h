// Debian's Pillow (python3-pil DdsImagePlugin) as an independent DDS decoder for the golden tests: whether it is
// installed, the command that decodes one DDS file to raw RGBA8 (tests/tools/pil_decode_dds.py), and reading that
// raw file back. Tests that use it GTEST_SKIP when Pillow is absent.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace blocklab::pillow_dds {

inline bool available() {
  return std::filesystem::exists("/usr/bin/python3") &&
         std::system("/usr/bin/python3 -c 'import PIL.DdsImagePlugin' > /dev/null 2>&1") == 0;
}

// The shell command that writes Pillow's RGBA8 decode of `dds` (top row first) to `raw`; its output goes to `log`
// (default: discarded).
inline std::string decode_command(const std::filesystem::path& dds, const std::filesystem::path& raw,
                                  const std::string& log = "/dev/null") {
  return "/usr/bin/python3 '" + std::string(BLOCKLAB_SOURCE_DIR) + "/tests/tools/pil_decode_dds.py' '" + dds.string() +
         "' '" + raw.string() + "' > '" + log + "' 2>&1";
}

inline std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
}

}  // namespace blocklab::pillow_dds
