// The BC1/BC3 colour encoder pipeline (formats/common/s3tc_color_fit.h): candidates from the single-colour tables,
// cluster fit along the principal axis in each allowed mode, polish, optional exhaustive neighbourhood, then the
// best candidate by exact error (reference palette) is stored in canonical form.
#include "formats/common/s3tc_color_fit.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr int kHillClimbPasses = 4;

struct ScoredCandidate {
  ColorCandidate candidate;
  float error = std::numeric_limits<float>::infinity();
};

void keep_better(ScoredCandidate& best, const ColorCandidate& candidate, float error) {
  if (error < best.error) {   // strict: earlier candidates win ties (deterministic order below)
    best.candidate = candidate;
    best.error = error;
  }
}

bool block_is_flat(const ColorBlock& block) {
  for (int texel = 1; texel < 16; ++texel)
    for (int channel = 0; channel < 3; ++channel)
      if (block.texels[texel][channel] != block.texels[0][channel]) return false;
  return true;
}

// `fast`: the texels with the smallest and largest projection on the principal axis as endpoints (the bounding
// box of the block along the axis), then least-squares rounds; 4-colour mode only.
ColorCandidate fast_candidate(const ColorBlock& block) {
  const std::array<float, 3> axis = principal_axis(block);
  int lowest = 0, highest = 0;
  float low = std::numeric_limits<float>::infinity(), high = -std::numeric_limits<float>::infinity();
  for (int texel = 0; texel < 16; ++texel) {
    const float projection = axis[0] * block.texels[texel][0] + axis[1] * block.texels[texel][1] +
                             axis[2] * block.texels[texel][2];
    if (projection < low) { low = projection; lowest = texel; }
    if (projection > high) { high = projection; highest = texel; }
  }
  ColorCandidate candidate;
  candidate.mode = Bc1Mode::four_color;
  for (int channel = 0; channel < 3; ++channel) {
    candidate.endpoints[0][channel] = quantize_to_565_channel(block.texels[highest][channel], channel);
    candidate.endpoints[1][channel] = quantize_to_565_channel(block.texels[lowest][channel], channel);
  }
  polish_color_candidate(block, candidate, 0);   // least-squares rounds only, no hill climbing
  return candidate;
}

}  // namespace

std::vector<std::pair<std::string, S3tcSearch>> s3tc_search_choices() {
  return {{"fast", S3tcSearch::fast}, {"default", S3tcSearch::standard}, {"exhaustive", S3tcSearch::exhaustive}};
}

std::array<float, 3> parse_channel_weights(const std::string& text, const std::string& who) {
  std::array<float, 3> weights{};
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, ',')) parts.push_back(part);
  const auto bad = [&](const std::string& why) {
    fail(who, "option 'weights' must be three non-negative reals 'r,g,b' (not all zero), got '" + text + "': " + why);
  };
  // A trailing comma ("1,1,1,") would be dropped by getline: count the separators instead.
  std::size_t commas = 0;
  for (char c : text) commas += c == ',';
  if (parts.size() != 3 || commas != 2) bad("expected exactly three comma-separated values");
  std::array<double, 3> values{};
  double largest = 0.0;
  for (int channel = 0; channel < 3; ++channel) {
    std::string value = parts[static_cast<std::size_t>(channel)];
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.erase(0, 1);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.pop_back();
    if (!value.empty() && value.front() == '+') value.erase(0, 1);
    double parsed = 0.0;
    const char* first = value.data();
    const char* last = first + value.size();
    const auto result = std::from_chars(first, last, parsed);
    if (value.empty() || result.ec != std::errc() || result.ptr != last || !std::isfinite(parsed))
      bad("'" + parts[static_cast<std::size_t>(channel)] + "' is not a finite real");
    if (parsed < 0.0) bad("weights must be non-negative");
    values[static_cast<std::size_t>(channel)] = parsed;
    largest = std::max(largest, parsed);
  }
  // All-zero weights would make every endpoint equally good: reject instead of encoding arbitrary blocks.
  if (!(largest > 0.0)) bad("at least one weight must be positive");
  // Only the weights' ratios matter, so they are scaled to a largest weight of 1 (in double, then rounded to float):
  // any finite weights then give finite weighted errors (1e100 would overflow the float error sums to +inf and
  // every candidate would tie). A ratio below the float range (e.g. 1e-300 beside 1) flushes to 0: that channel
  // then does not count, which is what such a weight asks for. The default 1,1,1 is unchanged.
  for (int channel = 0; channel < 3; ++channel)
    weights[static_cast<std::size_t>(channel)] =
        static_cast<float>(values[static_cast<std::size_t>(channel)] / largest);
  return weights;
}

ColorBlock make_color_block(const BlockTexels& texels, const std::array<float, 3>& weights) {
  ColorBlock block;
  for (int texel = 0; texel < 16; ++texel)
    for (int channel = 0; channel < 3; ++channel) {
      const float value = texels.rgba[texel][channel];
      // Code values live in [0, 1]: HDR values above 1 clamp to 255; NaN fails the test and becomes 0.
      block.texels[texel][channel] = value >= 1.0f ? 255.0f : (value > 0.0f ? value * 255.0f : 0.0f);
    }
  for (int channel = 0; channel < 3; ++channel) block.weights[channel] = weights[static_cast<std::size_t>(channel)];
  return block;
}

Bc1Params fit_color_block(const ColorBlock& block, const ColorFitSettings& settings) {
  const bool allow_three = settings.allow_three_color;
  ScoredCandidate best;
  if (settings.search == S3tcSearch::fast) {
    const ColorCandidate candidate = fast_candidate(block);
    keep_better(best, candidate, evaluate_color_candidate(block, candidate, nullptr));
  } else {
    float mean[3] = {0, 0, 0};
    for (int texel = 0; texel < 16; ++texel)
      for (int channel = 0; channel < 3; ++channel) mean[channel] += block.texels[texel][channel] / 16.0f;
    // Step 1: the mean colour through the single-colour tables, in each allowed mode.
    const ColorCandidate single_four = single_color_candidate(mean, Bc1Mode::four_color);
    keep_better(best, single_four, evaluate_color_candidate(block, single_four, nullptr));
    if (allow_three) {
      const ColorCandidate single_three = single_color_candidate(mean, Bc1Mode::three_color);
      keep_better(best, single_three, evaluate_color_candidate(block, single_three, nullptr));
    }
    if (!block_is_flat(block)) {
      // Steps 2-4: cluster fit per mode, polished on the real palette.
      const std::array<float, 3> axis = principal_axis(block);
      const int mode_count = allow_three ? 2 : 1;
      for (int m = 0; m < mode_count; ++m) {
        const Bc1Mode mode = m == 0 ? Bc1Mode::four_color : Bc1Mode::three_color;
        ColorCandidate candidate = cluster_fit(block, axis, mode);
        float error = polish_color_candidate(block, candidate, kHillClimbPasses);
        // Step 5: the whole +-1 box around the polished endpoints.
        if (settings.search == S3tcSearch::exhaustive) error = exhaustive_color_neighbourhood(block, candidate, 1);
        keep_better(best, candidate, error);
      }
    }
  }
  Bc1Params params;
  params.endpoints = best.candidate.endpoints;
  params.mode = best.candidate.mode;
  evaluate_color_candidate(block, best.candidate, params.indices.data());
  return allow_three ? canonicalise_bc1(params) : canonicalise_bc3_color(params);
}

}  // namespace blocklab
