// Acceptance check: log2rgb and mpsnr agree to 1e-6 relative with tests/tools/reference_metrics.py, an independent
// numpy implementation of SPECS.md 1a / 1b, on synthetic HDR pairs. The pairs are written as PFM by hand (one
// little-endian, one big-endian file per pair, rows bottom to top) so this test does not depend on core/image_io.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "metrics/metric.h"

namespace blocklab {
namespace {

constexpr double kAgreement = 1e-6;   // relative, the acceptance criterion
const char* const kPython = "/usr/bin/python3";

void write_pfm(const std::filesystem::path& path, const Image& image, bool little_endian) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << image.width << " " << image.height << "\n" << (little_endian ? "-1.0" : "1.0") << "\n";
  for (int y = image.height - 1; y >= 0; --y)   // PFM stores the bottom row first
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        std::uint32_t bits;
        std::memcpy(&bits, &image.texel(x, y)[c], 4);
        unsigned char bytes[4];
        for (int i = 0; i < 4; ++i) bytes[i] = static_cast<unsigned char>(bits >> (8 * (little_endian ? i : 3 - i)));
        out.write(reinterpret_cast<const char*>(bytes), 4);
      }
  ASSERT_TRUE(out.good()) << path;
}

struct ScratchDir {
  std::filesystem::path path;
  ScratchDir() {
    path = std::filesystem::temp_directory_path() / ("blocklab_metric_reference_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() { std::filesystem::remove_all(path); }
};

nlohmann::json run_reference(const ScratchDir& dir, const Image& reference, const Image& test,
                             const std::string& extra_args = "") {
  const auto a = dir.path / "ref.pfm", b = dir.path / "test.pfm", out = dir.path / "out.json";
  write_pfm(a, reference, true);
  write_pfm(b, test, false);
  const std::string command = std::string(kPython) + " " BLOCKLAB_SOURCE_DIR "/tests/tools/reference_metrics.py " +
                              a.string() + " " + b.string() + " " + extra_args + " > " + out.string();
  const int status = std::system(command.c_str());
  if (status != 0) return nullptr;
  std::ifstream in(out);
  return nlohmann::json::parse(in);   // the pairs here are never identical, so no Infinity in the output
}

// Smooth HDR content over `stops` decades of exposure plus per-sample multiplicative noise of relative size `noise`.
Image synthetic_hdr(int w, int h, double stops, double noise, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Image image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const double base = std::exp2(-stops / 2 + stops * (x + 0.37 * y) / (w + 0.37 * h) + 0.3 * c);
        image.texel(x, y)[c] = static_cast<float>(base * (1.0 + noise * unit(generator)));
      }
  return image;
}

// Rounds every value to `bits` mantissa bits, like a coarse shared-exponent or half-float coding.
Image quantised_copy(const Image& image, int bits) {
  Image copy = image;
  for (std::size_t i = 0; i < copy.pixels.size(); ++i) {
    if (i % 4 == 3 || !(copy.pixels[i] > 0.0f)) continue;
    int exponent = 0;
    const double mantissa = std::frexp(copy.pixels[i], &exponent);
    copy.pixels[i] = static_cast<float>(std::ldexp(std::round(std::ldexp(mantissa, bits)), exponent - bits));
  }
  return copy;
}

void expect_agreement(const Image& reference, const Image& test, const std::string& label) {
  if (std::system((std::string(kPython) + " -c 'import numpy' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << kPython << " with numpy is not available";
  ScratchDir dir;
  const nlohmann::json theirs = run_reference(dir, reference, test);
  ASSERT_FALSE(theirs.is_null()) << label << ": reference_metrics.py failed";
  for (const char* name : {"log2rgb", "mpsnr"}) {
    const double ours = find_metric(name).compute(reference, test, {}).value;
    const double expected = theirs.at(name).get<double>();
    ASSERT_TRUE(std::isfinite(ours)) << label << " " << name;
    EXPECT_LE(std::abs(ours - expected), kAgreement * std::abs(expected))
        << label << " " << name << ": blocklab " << ours << " vs reference " << expected;
  }
}

TEST(MetricReference, AgreesOnAWideRangeGradientWithSmallNoise) {
  const Image reference = synthetic_hdr(64, 48, 24.0, 0.0, 1);
  expect_agreement(reference, synthetic_hdr(64, 48, 24.0, 0.01, 2), "gradient+noise");
}

TEST(MetricReference, AgreesOnCoarselyQuantisedCopies) {
  const Image reference = synthetic_hdr(53, 31, 16.0, 0.2, 3);
  expect_agreement(reference, quantised_copy(reference, 8), "8-bit mantissa");
  expect_agreement(reference, quantised_copy(reference, 4), "4-bit mantissa");
}

TEST(MetricReference, AgreesOnZerosNegativesNanAndSaturatedValues) {
  Image reference = synthetic_hdr(40, 30, 30.0, 0.1, 4);
  Image test = quantised_copy(reference, 6);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float special[] = {0.0f, -1.0f, nan, 1e-30f, 5e-8f, 60000.0f, 0.0f, -0.0f};
  for (int i = 0; i < 120; ++i) {
    const std::size_t index = (static_cast<std::size_t>(i) * 37) % (reference.texel_count() * 4);
    if (index % 4 == 3) continue;
    (i % 2 ? reference : test).pixels[index] = special[i % 8];
  }
  expect_agreement(reference, test, "special values");
}

TEST(MetricReference, AgreesOnCustomStopsAndFloor) {
  if (std::system((std::string(kPython) + " -c 'import numpy' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << kPython << " with numpy is not available";
  const Image reference = synthetic_hdr(20, 20, 12.0, 0.0, 5), test = synthetic_hdr(20, 20, 12.0, 0.05, 6);
  ScratchDir dir;
  const nlohmann::json theirs = run_reference(dir, reference, test, "--start -3 --stop 5 --floor 0.001");
  ASSERT_FALSE(theirs.is_null());
  const double mpsnr = find_metric("mpsnr").compute(reference, test, {{"start", "-3"}, {"stop", "5"}}).value;
  const double log2rgb = find_metric("log2rgb").compute(reference, test, {{"floor", "0.001"}}).value;
  EXPECT_LE(std::abs(mpsnr - theirs.at("mpsnr").get<double>()), kAgreement * std::abs(mpsnr));
  EXPECT_LE(std::abs(log2rgb - theirs.at("log2rgb").get<double>()), kAgreement * std::abs(log2rgb));
}

}  // namespace
}  // namespace blocklab
