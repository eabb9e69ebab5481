// The BC1/BC3 cluster fit (formats/common/s3tc_cluster_fit.cpp) against a plain scalar transcription of its
// definition: every partition in the documented order, the same float operations in the same order, quantised
// endpoints scored in closed form, the first partition with the smallest score wins. Every code path of the
// optimised search (pruning by the continuous least-squares bound, out-of-order seeding, SSE2 and AVX2) must
// return exactly the same candidate on random, structured and real blocks, in both modes, with unit and non-unit
// channel weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "formats/common/s3tc_color_fit.h"
#include "test_s3tc_helpers.h"

namespace blocklab {
namespace {

// One partition's closed-form score of its quantised least-squares endpoints, exactly as the file header defines
// it (float arithmetic, no contraction: the build uses -ffp-contract=off).
struct ReferenceScore {
  float error;
  int lattice_a[3], lattice_b[3];
};

constexpr float kScale[3] = {31.0f / 255.0f, 63.0f / 255.0f, 31.0f / 255.0f};
constexpr int kLeft[3] = {3, 2, 3}, kRight[3] = {2, 4, 2};

bool score_partition(const ColorBlock& block, const float prefix[3][17], float aa, float bb, float ab,
                     const float alpha_x[3], ReferenceScore& score) {
  const float determinant = aa * bb - ab * ab;
  if (!(determinant > 1e-3f)) return false;   // singular: every texel on one code
  const float inverse = 1.0f / determinant;
  score.error = 0.0f;
  for (int channel = 0; channel < 3; ++channel) {
    const float beta_x = prefix[channel][16] - alpha_x[channel];
    const float a = (bb * alpha_x[channel] - ab * beta_x) * inverse;
    const float b = (aa * beta_x - ab * alpha_x[channel]) * inverse;
    const auto quantise = [&](float value, int& lattice) {
      const float clamped = std::min(value > 0.0f ? value : 0.0f, 255.0f);
      lattice = static_cast<int>(std::nearbyint(clamped * kScale[channel]));
      return static_cast<float>((lattice << kLeft[channel]) | (lattice >> kRight[channel]));
    };
    const float qa = quantise(a, score.lattice_a[channel]), qb = quantise(b, score.lattice_b[channel]);
    score.error = score.error + block.weights[channel] * (qa * (qa * aa + 2.0f * (qb * ab - alpha_x[channel])) +
                                                          qb * (qb * bb - 2.0f * beta_x));
  }
  return true;
}

ColorCandidate reference_cluster_fit(const ColorBlock& block, const std::array<float, 3>& axis, Bc1Mode mode) {
  float key[16];
  int order[16];
  for (int texel = 0; texel < 16; ++texel)
    key[texel] = axis[0] * block.texels[texel][0] + axis[1] * block.texels[texel][1] + axis[2] * block.texels[texel][2];
  std::iota(order, order + 16, 0);
  std::stable_sort(order, order + 16, [&](int x, int y) { return key[x] < key[y]; });
  float prefix[3][17];
  for (int channel = 0; channel < 3; ++channel) {
    prefix[channel][0] = 0.0f;
    for (int n = 0; n < 16; ++n) prefix[channel][n + 1] = prefix[channel][n] + block.texels[order[n]][channel];
  }
  ReferenceScore best{std::numeric_limits<float>::infinity(), {0, 0, 0}, {0, 0, 0}}, score{};
  const auto keep_if_better = [&](const ReferenceScore& candidate) {
    if (candidate.error < best.error) best = candidate;
  };
  const float ninth = 1.0f / 9.0f, third = 1.0f / 3.0f;
  if (mode == Bc1Mode::four_color) {
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j)
        for (int k = 0; i + j + k <= 16; ++k) {
          const float fi = static_cast<float>(i), fj = static_cast<float>(j), fk = static_cast<float>(k);
          const float l = static_cast<float>(16 - i - j) - fk;
          const float aa = fi + (4.0f * fj + fk) * ninth, bb = l + (fj + 4.0f * fk) * ninth;
          const float ab = 2.0f * (fj + fk) * ninth;
          float alpha_x[3];
          for (int c = 0; c < 3; ++c) alpha_x[c] = (prefix[c][i] + prefix[c][i + j] + prefix[c][i + j + k]) * third;
          if (score_partition(block, prefix, aa, bb, ab, alpha_x, score)) keep_if_better(score);
        }
  } else {
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; i + j <= 16; ++j) {
        const float fi = static_cast<float>(i), fj = static_cast<float>(j);
        const float l = static_cast<float>(16 - i) - fj;
        const float aa = fi + fj * 0.25f, bb = l + fj * 0.25f, ab = fj * 0.25f;
        float alpha_x[3];
        for (int c = 0; c < 3; ++c) alpha_x[c] = (prefix[c][i] + prefix[c][i + j]) * 0.5f;
        if (score_partition(block, prefix, aa, bb, ab, alpha_x, score)) keep_if_better(score);
      }
  }
  ColorCandidate candidate;
  candidate.mode = mode;
  candidate.endpoints[0] = {best.lattice_a[0], best.lattice_a[1], best.lattice_a[2]};
  candidate.endpoints[1] = {best.lattice_b[0], best.lattice_b[1], best.lattice_b[2]};
  return candidate;
}

// Blocks of several kinds, from a fixed seed: uniform noise, integer noise, two colours, gradients along a random
// direction with noise, near-flat blocks, few distinct values, and values at the ends of the range.
std::vector<ColorBlock> test_blocks(int count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto weights_of = [&](ColorBlock& block, int kind) {
    const float choices[][3] = {{1, 1, 1}, {0.299f, 0.587f, 0.114f}, {2.5f, 0.75f, 1.25f}, {0, 1, 3}, {7, 0.01f, 1}};
    const auto& w = choices[kind % 5];
    for (int c = 0; c < 3; ++c) block.weights[c] = w[c];
  };
  std::vector<ColorBlock> blocks;
  for (int n = 0; n < count; ++n) {
    ColorBlock block{};
    const int kind = n % 8;
    float base[3], other[3];
    for (int c = 0; c < 3; ++c) {
      base[c] = 255.0f * unit(random);
      other[c] = 255.0f * unit(random);
    }
    for (int texel = 0; texel < 16; ++texel)
      for (int c = 0; c < 3; ++c) {
        float value = 0.0f;
        switch (kind) {
          case 0: value = 255.0f * unit(random); break;
          case 1: value = std::floor(256.0f * unit(random)); break;
          case 2: value = (random() & 1) ? base[c] : other[c]; break;   // two colours
          case 3: {                                                       // noisy gradient
            const float t = unit(random);
            value = base[c] + t * (other[c] - base[c]) + 6.0f * (unit(random) - 0.5f);
            break;
          }
          case 4: value = base[c] + 1.5f * (unit(random) - 0.5f); break;   // near flat
          case 5: value = std::round(base[c] / 64.0f) * 64.0f + 64.0f * static_cast<float>(random() % 3); break;
          case 6: value = (random() % 3 == 0) ? 0.0f : 255.0f; break;          // range ends
          default: value = texel < 8 ? base[c] : base[c] + static_cast<float>(texel - 7); break;
        }
        block.texels[texel][c] = std::clamp(value, 0.0f, 255.0f);
      }
    weights_of(block, n / 8);
    blocks.push_back(block);
  }
  return blocks;
}

std::array<float, 3> random_axis(std::mt19937_64& random) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::array<float, 3> axis{normal(random), normal(random), normal(random)};
  const float length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (float& a : axis) a /= length;
  return axis;
}

std::string describe(const ColorCandidate& c) {
  std::string text;
  for (const auto& endpoint : c.endpoints)
    text += "(" + std::to_string(endpoint[0]) + "," + std::to_string(endpoint[1]) + "," +
            std::to_string(endpoint[2]) + ")";
  return text;
}

// Every code path (the default, SSE2/portable, AVX2 where the CPU has it, and the unpruned scan) against the
// reference, in both modes.
void expect_same_as_reference(const ColorBlock& block, const std::array<float, 3>& axis, const std::string& what) {
  const struct { ClusterFitPath path; const char* name; } paths[] = {{ClusterFitPath::automatic, "automatic"},
                                                                     {ClusterFitPath::portable, "portable"},
                                                                     {ClusterFitPath::avx2, "avx2"},
                                                                     {ClusterFitPath::unpruned, "unpruned"}};
  for (const Bc1Mode mode : {Bc1Mode::four_color, Bc1Mode::three_color}) {
    const ColorCandidate reference = reference_cluster_fit(block, axis, mode);
    for (const auto& path : paths) {
      const ColorCandidate fast = path.path == ClusterFitPath::automatic ? cluster_fit(block, axis, mode)
                                                                          : cluster_fit(block, axis, mode, path.path);
      ASSERT_EQ(fast.endpoints, reference.endpoints)
          << what << (mode == Bc1Mode::four_color ? " four-colour, " : " three-colour, ") << path.name << " path "
          << describe(fast) << " vs " << describe(reference);
      ASSERT_EQ(fast.mode, mode);
    }
  }
}

TEST(S3tcClusterFit, MatchesScalarReferenceOnStructuredRandomBlocksAlongPrincipalAxis) {
  const std::vector<ColorBlock> blocks = test_blocks(4000, 20261127);
  for (std::size_t n = 0; n < blocks.size(); ++n)
    expect_same_as_reference(blocks[n], principal_axis(blocks[n]), "block " + std::to_string(n));
}

TEST(S3tcClusterFit, MatchesScalarReferenceAlongRandomAxes) {
  const std::vector<ColorBlock> blocks = test_blocks(1600, 77);
  std::mt19937_64 random(5);
  for (std::size_t n = 0; n < blocks.size(); ++n)
    expect_same_as_reference(blocks[n], random_axis(random), "block " + std::to_string(n));
}

TEST(S3tcClusterFit, MatchesScalarReferenceOnFlatBlocksAndDegenerateAxes) {
  std::mt19937_64 random(11);
  for (int n = 0; n < 64; ++n) {
    ColorBlock block{};
    const float rgb[3] = {static_cast<float>(random() % 256), static_cast<float>(random() % 256),
                          static_cast<float>(random() % 256)};
    for (auto& texel : block.texels)
      for (int c = 0; c < 3; ++c) texel[c] = rgb[c];
    block.weights[0] = block.weights[1] = block.weights[2] = n % 2 ? 1.0f : 0.5f;
    expect_same_as_reference(block, {0.57735f, 0.57735f, 0.57735f}, "flat " + std::to_string(n));
    expect_same_as_reference(block, {0.0f, 0.0f, 0.0f}, "flat, zero axis " + std::to_string(n));
  }
}

TEST(S3tcClusterFit, MatchesScalarReferenceOnRealImageBlocks) {
  const std::vector<Image> crops = s3tc_test::real_crops();
  if (crops.empty()) GTEST_SKIP() << "shared LDR images absent";
  int checked = 0;
  for (const Image& crop : crops) {
    const BlockGrid grid(crop.width, crop.height);
    for (std::size_t index = 0; index < grid.block_count(); ++index, ++checked) {
      const ColorBlock block = make_color_block(load_block(crop, grid, index), {1.0f, 1.0f, 1.0f});
      expect_same_as_reference(block, principal_axis(block), "real block " + std::to_string(checked));
    }
  }
  EXPECT_GT(checked, 500);
}

// Texels outside [0, 255] (a caller building ColorBlock directly) take the unpruned path; still the same answer.
TEST(S3tcClusterFit, MatchesScalarReferenceOutsideTheEightBitRange) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<float> wide(-300.0f, 600.0f);
  for (int n = 0; n < 200; ++n) {
    ColorBlock block{};
    for (auto& texel : block.texels)
      for (float& value : texel) value = wide(random);
    block.weights[0] = 1.0f;
    block.weights[1] = 2.0f;
    block.weights[2] = 0.25f;
    expect_same_as_reference(block, principal_axis(block), "wide block " + std::to_string(n));
  }
}

}  // namespace
}  // namespace blocklab
