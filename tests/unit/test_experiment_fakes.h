// Small, fully specified formats and metrics for the experiment tests, so that config validation, sweep expansion,
// cell keys and the runner can be tested on their own (the real formats and metrics have their own tests).
//   fake_quant : stores each channel rounded to a multiple of `step` (real, default 0.25) as a float; options
//                `mode` (choice a|b, default a, does not change the bytes), `flag` (boolean, default false) and the
//                common `seed`. 64 floats per 4x4 block = 256 bytes.
//   fake_broken: encode always throws blocklab::Error.
//   fake_mae   : mean absolute difference of R, G, B times option `scale` (default 1).
//   fake_peak  : +inf when the images are equal, else 1 / max absolute difference.
#pragma once

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "core/error.h"
#include "experiments/config.h"

namespace blocklab::testing {

class FakeQuantFormat final : public Format {
 public:
  std::string name() const override { return "fake_quant"; }
  std::string description() const override { return "test format: channels rounded to multiples of step"; }
  std::vector<OptionSpec> option_specs() const override {
    OptionSpec step{"step", OptionType::real, "0.25", {}, "quantisation step", 0.001, 10.0};
    OptionSpec mode{"mode", OptionType::choice, "a", {"a", "b"}, "a label-only choice", 0.0, 0.0};
    OptionSpec flag{"flag", OptionType::boolean, "false", {}, "a label-only flag", 0.0, 0.0};
    return {step, mode, flag};
  }
  std::vector<ModeSpec> mode_table() const override { return {{"quant", "uniform quantiser"}}; }
  int block_bytes(const FormatOptions&) const override { return 16 * 4 * 4; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext&) const override {
    const double step = option_real(options, "step");
    EncodedTexture texture;
    texture.format = name();
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = image.channels;
    texture.block_bytes = block_bytes(options);
    const int bx = (image.width + 3) / 4, by = (image.height + 3) / 4;
    texture.blocks.assign(static_cast<std::size_t>(bx) * by * texture.block_bytes, 0);
    for (int y = 0; y < by * 4; ++y) {
      for (int x = 0; x < bx * 4; ++x) {
        const float* texel = image.texel(std::min(x, image.width - 1), std::min(y, image.height - 1));
        const std::size_t block = static_cast<std::size_t>(y / 4) * bx + x / 4;
        for (int c = 0; c < 4; ++c) {
          const float q = static_cast<float>(std::round(texel[c] / step) * step);
          std::memcpy(&texture.blocks[block * 256 + ((y % 4) * 4 + x % 4) * 16 + c * 4], &q, 4);
        }
      }
    }
    return texture;
  }
  Image decode(const EncodedTexture& texture, const CodecContext&) const override {
    Image image(texture.width, texture.height, texture.channels);
    const int bx = (texture.width + 3) / 4;
    for (int y = 0; y < texture.height; ++y) {
      for (int x = 0; x < texture.width; ++x) {
        const std::size_t block = static_cast<std::size_t>(y / 4) * bx + x / 4;
        for (int c = 0; c < 4; ++c) {
          std::memcpy(&image.texel(x, y)[c], &texture.blocks[block * 256 + ((y % 4) * 4 + x % 4) * 16 + c * 4], 4);
        }
      }
    }
    return image;
  }
};

class FakeBrokenFormat final : public Format {
 public:
  std::string name() const override { return "fake_broken"; }
  std::string description() const override { return "test format whose encoder always fails"; }
  std::vector<OptionSpec> option_specs() const override { return {}; }
  std::vector<ModeSpec> mode_table() const override { return {{"none", "never encodes"}}; }
  int block_bytes(const FormatOptions&) const override { return 8; }
  EncodedTexture encode(const Image&, const FormatOptions&, const CodecContext&) const override {
    fail("fake_broken", "this encoder always fails");
  }
  Image decode(const EncodedTexture&, const CodecContext&) const override { fail("fake_broken", "no decoder"); }
};

inline double mean_abs_rgb(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) fail("fake metric", "image sizes differ");
  double sum = 0.0;
  for (std::size_t i = 0; i < a.texel_count(); ++i) {
    for (int c = 0; c < 3; ++c) sum += std::fabs(double(a.pixels[i * 4 + c]) - double(b.pixels[i * 4 + c]));
  }
  return sum / (3.0 * static_cast<double>(a.texel_count()));
}

class FakeMaeMetric final : public Metric {
 public:
  std::string name() const override { return "fake_mae"; }
  std::string description() const override { return "test metric: mean absolute RGB difference"; }
  std::string unit() const override { return "code values"; }
  bool higher_is_better() const override { return false; }
  std::vector<std::string> option_names() const override { return {"scale"}; }
  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    double scale = 1.0;
    if (auto it = options.find("scale"); it != options.end()) {
      char* end = nullptr;
      scale = std::strtod(it->second.c_str(), &end);
      if (end == it->second.c_str() || *end != '\0') fail("fake_mae", "option 'scale' must be a number");
    }
    return {scale * mean_abs_rgb(reference, test), {{"scale", std::to_string(scale)}}};
  }
  Image error_map(const Image& reference, const Image& test, const MetricOptions&) const override {
    Image map(reference.width, reference.height, 3);
    for (std::size_t i = 0; i < reference.texel_count(); ++i) {
      float e = 0.0f;
      for (int c = 0; c < 3; ++c) e += std::fabs(reference.pixels[i * 4 + c] - test.pixels[i * 4 + c]) / 3.0f;
      for (int c = 0; c < 3; ++c) map.pixels[i * 4 + c] = e;
    }
    return map;
  }
};

class FakePeakMetric final : public Metric {
 public:
  std::string name() const override { return "fake_peak"; }
  std::string description() const override { return "test metric: 1 / max abs difference, +inf when equal"; }
  std::string unit() const override { return "1"; }
  bool higher_is_better() const override { return true; }
  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    if (!options.empty()) fail("fake_peak", "takes no options");
    double worst = 0.0;
    for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
      worst = std::max(worst, std::fabs(double(reference.pixels[i]) - double(test.pixels[i])));
    }
    // Identical images: 1/0 is +inf on purpose (the runner must write it as the string "inf").
    return {worst == 0.0 ? HUGE_VAL : 1.0 / worst, {}};
  }
  Image error_map(const Image& reference, const Image&, const MetricOptions&) const override {
    return Image(reference.width, reference.height, 3);
  }
};

inline const Catalog& fake_catalog() {
  static const FakeQuantFormat quant;
  static const FakeBrokenFormat broken;
  static const FakeMaeMetric mae;
  static const FakePeakMetric peak;
  static const Catalog catalog{{&quant, &broken}, {&mae, &peak}};
  return catalog;
}

// Parses `yaml` as "test.yaml" with the fake catalog.
inline ExperimentConfig parse_fake(const std::string& yaml) { return parse_experiment(yaml, "test.yaml", fake_catalog()); }

}  // namespace blocklab::testing
