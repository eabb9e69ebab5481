// Fuzz of the `wang` format: random 32-byte blocks of random texture sizes with random (valid) side data decode
// through the Format to finite, non-negative values identical to the oracle in every option combination; malformed
// side data (NaN, infinity, huge, unordered, missing, unexpected keys, wrong counts) is an Error naming the key, never
// a crash; the encoder survives extreme images (all black, constant, 1x1, values at the half-float limit,
// 1e-30 .. 1e29) and refuses a luminance beyond the side data's range with an Error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/error.h"
#include "formats/registry.h"
#include "formats/wang/wang_block.h"

namespace blocklab {
namespace {

const Format& wang_fmt() { return find_format("wang"); }

struct Variant {
  std::string space, residual, l_bits;
};

EncodedTexture random_texture(std::mt19937& rng, const Variant& variant, wang::Zones& zones) {
  std::uniform_int_distribution<int> size(1, 23);
  EncodedTexture texture;
  texture.format = "wang";
  texture.options = resolve_format_options(
      wang_fmt(), {{"space", variant.space}, {"residual", variant.residual}, {"l_bits", variant.l_bits}});
  texture.width = size(rng);
  texture.height = size(rng);
  texture.channels = 3;
  texture.block_bytes = wang::kBlockBytes;
  const BlockGrid grid(texture.width, texture.height);
  texture.blocks.resize(grid.block_count() * wang::kBlockBytes);
  for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(rng() & 0xffu);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double scale = std::pow(10.0, 12.0 * unit(rng) - 4.0);
  zones.tmin = scale * unit(rng) * 0.01;
  zones.t1 = zones.tmin + scale * unit(rng) * 0.1;
  zones.tmax = zones.t1 + scale * unit(rng);
  zones.smin = -scale * unit(rng) * 0.1;
  zones.s1 = zones.smin + scale * unit(rng) * 0.05;
  zones.s2 = zones.s1 + scale * unit(rng) * 0.05;
  zones.smax = zones.s2 + scale * unit(rng) * 0.1;
  if (variant.l_bits == "2x6")
    texture.side_data["luminance_zones"] = {zones.tmin, zones.t1, zones.tmax};
  else
    texture.side_data["luminance_range"] = {zones.tmin, zones.tmax};
  if (variant.residual != "none") texture.side_data["residual_zones"] = {zones.smin, zones.s1, zones.s2, zones.smax};
  if (variant.l_bits == "1x12") zones.t1 = zones.tmin;
  return texture;
}

TEST(WangFuzz, RandomBlocksAndSideDataDecodeToFiniteNonNegativeValuesEqualToTheOracle) {
  std::mt19937 rng(2024);
  int textures = 0;
  for (const char* space : {"luvw", "luv"})
    for (const char* residual : {"s", "ratio", "none"})
      for (const char* l_bits : {"2x6", "1x12"})
        for (int trial = 0; trial < 25; ++trial) {
          wang::Zones zones;
          const Variant variant{space, residual, l_bits};
          const EncodedTexture texture = random_texture(rng, variant, zones);
          const Image decoded = wang_fmt().decode(texture, CodecContext{2, 1});
          const wang::Residual kind = variant.residual == "s"       ? wang::Residual::s
                                      : variant.residual == "ratio" ? wang::Residual::ratio
                                                                    : wang::Residual::none;
          const BlockGrid grid(texture.width, texture.height);
          for (std::size_t block = 0; block < grid.block_count(); ++block) {
            const BlockTexels oracle = wang::reference_decode_block(
                zones, variant.l_bits == "2x6" ? wang::LuminanceSplit::two_zones : wang::LuminanceSplit::one_range,
                variant.space == "luv" ? wang::ColorSpace::luv : wang::ColorSpace::luvw, kind,
                texture.blocks.data() + block * wang::kBlockBytes);
            const int bx = static_cast<int>(block % grid.blocks_x), by = static_cast<int>(block / grid.blocks_x);
            for (int texel = 0; texel < 16; ++texel) {
              const int x = bx * 4 + texel % 4, y = by * 4 + texel / 4;
              if (x >= texture.width || y >= texture.height) continue;
              for (int channel = 0; channel < 3; ++channel) {
                const float value = decoded.texel(x, y)[channel];
                ASSERT_TRUE(std::isfinite(value) && value >= 0.0f) << value;
                ASSERT_EQ(value, oracle.rgba[texel][channel]);
              }
            }
          }
          ++textures;
        }
  EXPECT_EQ(textures, 300);
}

void expect_error_naming(const EncodedTexture& texture, const std::string& key) {
  try {
    wang_fmt().decode(texture, CodecContext{1, 1});
    ADD_FAILURE() << "decoded bad side data for '" << key << "'";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
  }
}

TEST(WangFuzz, MalformedSideDataIsAnErrorNamingTheKey) {
  std::mt19937 rng(7);
  wang::Zones zones;
  const EncodedTexture good = random_texture(rng, {"luvw", "s", "2x6"}, zones);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const std::string key : {"luminance_zones", "residual_zones"}) {
    const std::size_t count = good.side_data.at(key).size();
    for (const double bad : {nan, inf, -inf, 1e31}) {
      for (std::size_t slot = 0; slot < count; ++slot) {
        EncodedTexture texture = good;
        texture.side_data[key][slot] = bad;
        if (std::isnan(bad) || std::isinf(bad)) {
          // Non-finite values are rejected by the generic texture validation or by the format, naming the key.
          try {
            wang_fmt().decode(texture, CodecContext{1, 1});
            ADD_FAILURE() << key << " accepted a non-finite value";
          } catch (const Error&) {
          }
          continue;
        }
        expect_error_naming(texture, key);
      }
    }
    EncodedTexture unordered = good;
    std::reverse(unordered.side_data[key].begin(), unordered.side_data[key].end());
    if (unordered.side_data[key] != good.side_data.at(key)) expect_error_naming(unordered, key);
    EncodedTexture missing = good;
    missing.side_data.erase(key);
    expect_error_naming(missing, key);
    EncodedTexture wrong_count = good;
    wrong_count.side_data[key].push_back(1.0);
    expect_error_naming(wrong_count, key);
  }
  EncodedTexture unexpected = good;
  unexpected.side_data["luminance_range"] = {0.0, 1.0};
  expect_error_naming(unexpected, "luminance_range");
  EncodedTexture none = good;
  none.options = resolve_format_options(wang_fmt(), {{"residual", "none"}});
  expect_error_naming(none, "residual_zones");
}

TEST(WangFuzz, EncoderSurvivesExtremeImages) {
  std::vector<Image> images;
  images.emplace_back(1, 1);
  Image black(9, 7);
  images.push_back(black);
  Image constant(8, 8);
  for (float& v : constant.pixels) v = 3.5f;
  images.push_back(constant);
  Image extreme(13, 5);
  std::mt19937 rng(3);
  for (int y = 0; y < extreme.height; ++y)
    for (int x = 0; x < extreme.width; ++x)
      for (int c = 0; c < 3; ++c)
        extreme.texel(x, y)[c] = (rng() % 5 == 0) ? 0.0f : std::ldexp(1.0f, static_cast<int>(rng() % 40) - 24);
  extreme.texel(0, 0)[0] = 65504.0f;
  images.push_back(extreme);
  Image decades(6, 6);   // 1e-30 .. 1e29: the ratio T = S / L' is far beyond float where L' is tiny
  for (int i = 0; i < 36; ++i)
    for (int c = 0; c < 3; ++c)
      decades.pixels[static_cast<std::size_t>(i) * 4 + c] = std::pow(10.0f, static_cast<float>(i * 59 / 35 - 30));
  images.push_back(decades);
  Image too_bright(4, 4);
  too_bright.texel(1, 1)[0] = 3e38f;
  EXPECT_THROW(wang_fmt().encode(too_bright, resolve_format_options(wang_fmt(), {}), CodecContext{1, 1}), Error);
  for (const Image& image : images)
    for (const FormatOptions& options :
         {FormatOptions{}, FormatOptions{{"residual", "ratio"}}, FormatOptions{{"space", "luv"}, {"l_bits", "1x12"}},
          FormatOptions{{"codec", "bc3"}, {"preset", "thorough"}}}) {
      const EncodedTexture texture =
          wang_fmt().encode(image, resolve_format_options(wang_fmt(), options), CodecContext{2, 1});
      const Image decoded = wang_fmt().decode(texture, CodecContext{2, 1});
      for (std::size_t i = 0; i < decoded.texel_count(); ++i)
        for (int c = 0; c < 3; ++c) {
          const float value = decoded.pixels[i * 4 + c];
          ASSERT_TRUE(std::isfinite(value) && value >= 0.0f) << value;
        }
    }
}

}  // namespace
}  // namespace blocklab
