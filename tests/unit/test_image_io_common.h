// Helpers shared by the image I/O tests (unit and stress): a self-deleting temporary directory, raw byte file
// access and deterministic synthetic images.
#pragma once

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "core/image.h"

namespace blocklab::test_io {

using Bytes = std::vector<std::uint8_t>;

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("blocklab_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline void write_bytes(const std::string& path, const Bytes& bytes, std::size_t length) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(length));
}
inline void write_bytes(const std::string& path, const Bytes& bytes) { write_bytes(path, bytes, bytes.size()); }
inline void write_text(const std::string& path, const std::string& text) {
  write_bytes(path, Bytes(text.begin(), text.end()));
}

inline Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A deterministic image with smooth gradients, a few exact repeats (so RLE/ZIP have runs to find) and, for HDR,
// values spread over many octaves. Values are in [0, 1] when `ldr`, otherwise in about [2^-10, 2^10].
inline Image synthetic_image(int width, int height, int channels, bool ldr, std::uint32_t seed = 1) {
  Image image(width, height, channels);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float* texel = image.texel(x, y);
      const bool flat_run = (x / 5 + y) % 3 == 0;  // stretches of identical texels
      for (int c = 0; c < 3; ++c) {
        const float base = flat_run ? 0.25f + 0.25f * static_cast<float>(c) : unit(random);
        texel[c] = ldr ? base : std::exp2(20.0f * base - 10.0f);
      }
      if (channels == 1) texel[1] = texel[2] = texel[0];
      if (channels == 4) texel[3] = flat_run ? 1.0f : unit(random);
    }
  }
  return image;
}

}  // namespace blocklab::test_io
