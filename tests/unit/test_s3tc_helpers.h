// Shared helpers of the S3TC tests (bc1, bc3, bc4, dds): seeded random blocks, crops of the real LDR test images
// (empty when /work/shared/data is absent, so callers GTEST_SKIP), and bitwise float comparison.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/image_io.h"

namespace blocklab::s3tc_test {

inline std::uint32_t float_bits(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// `count` blocks of `bytes` random bytes, from a fixed seed.
inline std::vector<std::uint8_t> random_blocks(std::size_t count, int bytes, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::vector<std::uint8_t> blocks(count * static_cast<std::size_t>(bytes));
  for (auto& byte : blocks) byte = static_cast<std::uint8_t>(random() & 0xFFu);
  return blocks;
}

inline std::string shared_ldr(const std::string& relative) {
  return std::string(BLOCKLAB_TEST_SHARED_DATA) + "/ldr/" + relative;
}

// The (x0, y0, width, height) crop of a real image, or an empty image (width 0) when the file is absent.
inline Image real_crop(const std::string& relative, int x0, int y0, int width, int height) {
  const std::string path = shared_ldr(relative);
  if (!std::filesystem::exists(path)) return Image();
  const Image full = read_image(path);
  Image crop(width, height, full.channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 4; ++c) crop.texel(x, y)[c] = full.texel(x0 + x, y0 + y)[c];
  return crop;
}

// Crops used by the encoder tests: photographs, a texture with alpha, a normal map; odd sizes on purpose.
inline std::vector<Image> real_crops() {
  std::vector<Image> crops;
  const struct { const char* file; int x, y, w, h; } specs[] = {
      {"kodak/kodim01.png", 200, 100, 64, 64}, {"kodak/kodim03.png", 300, 200, 61, 47},
      {"kodak/kodim24.png", 0, 0, 32, 32},     {"textures/ldr-rgba-base.png", 400, 400, 64, 64},
      {"textures/ldr-xy-normal1.png", 100, 100, 48, 48}, {"textures/ldr-rgb-01.png", 0, 0, 64, 64},
  };
  for (const auto& spec : specs) {
    Image crop = real_crop(spec.file, spec.x, spec.y, spec.w, spec.h);
    if (crop.width > 0) crops.push_back(std::move(crop));
  }
  return crops;
}

}  // namespace blocklab::s3tc_test
