// Golden bytes and the bit-exact decode of the `banterle` format.
//   1. A small synthetic HDR image (exact integer formulas and ldexp) is encoded at 4 and 8 bpp with fit = none and
//      fit = ceres_lm; FNV-1a 64 hashes of the packed blocks and of the decoded floats are compared with committed
//      constants. (The encoder's estimate and fit use log/exp2 of glibc; the Debian 12 toolchain of CI is the
//      reference. A deliberate change of these bytes must bump BanterleFormat::revision().)
//   2. decode(unpack) equals, bit for bit, an independent spec-literal decode written here from the definition in
//      formats/banterle/README.md / itmo_lut.h: the S3TC oracles (reference_decode_bc1_block /
//      reference_decode_bc3_block, KDFS text), a half rounding written with integer arithmetic on the quantum
//      (not Imath), the table lookup and Listing 1 in float. Checked on the encoded synthetic image, on
//      samples/hdr/Desk.exr, and on random block bytes (every BC1/BC3 mode) with valid side data.
// To regenerate the hashes after a deliberate change: run this test; each failing EXPECT_EQ prints the actual value.
#include <gtest/gtest.h>

#include "golden_hash.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/bc1/bc1_block.h"
#include "formats/bc3/bc3_block.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

using golden::fnv1a64;
using golden::hash_floats;

// 18x10, values over 2^-12 .. 2^11 from integer formulas, with exact zeros and a saturated colour.
Image synthetic_hdr_image() {
  Image image(18, 10);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int mantissa = (x * 37 + y * 101 + c * 53) % 97 + 32;
        const int exponent = (x + 2 * y) % 24 - 12;
        float value = std::ldexp(static_cast<float>(mantissa) / 128.0f, exponent);
        if ((x + y) % 11 == 0) value = 0.0f;
        image.texel(x, y)[c] = value;
      }
  image.texel(4, 4)[0] = 5000.0f;   // saturated red: tone-mapped red above 1
  return image;
}

// ---- the independent decoder ------------------------------------------------------------------------------------

// float -> nearest half value (ties to even), as a float; non-negative finite input below 65520.
float to_half_value(float value) {
  if (value == 0.0f) return 0.0f;
  const int exponent = std::ilogb(value);                          // 2^e <= value < 2^(e+1)
  const double quantum = std::ldexp(1.0, exponent < -14 ? -24 : exponent - 10);   // half spacing there
  const double steps = static_cast<double>(value) / quantum;       // exact: a power-of-two division
  double whole = std::floor(steps);
  const double fraction = steps - whole;
  if (fraction > 0.5 || (fraction == 0.5 && std::fmod(whole, 2.0) != 0.0)) whole += 1.0;   // nearest, ties even
  return static_cast<float>(whole * quantum);
}

struct SpecDecoder {
  float table[256];
  int scale_exponent;
  bool residual;
  float lo = 0.0f, hi = 0.0f;

  explicit SpecDecoder(const EncodedTexture& texture) {
    const double alpha = texture.side_data.at("alpha")[0];
    const double l_white = texture.side_data.at("l_white")[0];
    const double mean = texture.side_data.at("mean")[0];
    // g(q) = (2 q L_H / alpha) / (sqrt((1 - q)^2 + 4 q / Lwhite^2) + 1 - q)   (eq. 2, rationalised)
    const auto g = [&](double q) {
      return (2.0 * q * mean / alpha) / (std::sqrt((1.0 - q) * (1.0 - q) + 4.0 * q / (l_white * l_white)) + 1.0 - q);
    };
    int e = 0;
    std::frexp(g(1.0), &e);
    scale_exponent = e - 15;
    for (int k = 0; k < 256; ++k)
      table[k] = to_half_value(static_cast<float>(std::ldexp(g(static_cast<double>(k) / 255.0), -scale_exponent)));
    residual = texture.side_data.count("residual_range") > 0;
    if (residual) {
      lo = static_cast<float>(texture.side_data.at("residual_range")[0]);
      hi = static_cast<float>(texture.side_data.at("residual_range")[1]);
    }
  }

  void texel(const float rgba[4], float out[3]) const {
    const float l = 0.21f * rgba[0] + 0.72f * rgba[1] + 0.07f * rgba[2];
    float t = l * 255.0f;
    t = t < 0.0f ? 0.0f : (t > 255.0f ? 255.0f : t);
    int i = static_cast<int>(std::floor(t));
    if (i > 254) i = 254;
    const float w = t - static_cast<float>(i);
    const float lw = std::ldexp(table[i] + (table[i + 1] - table[i]) * w, scale_exponent);
    const float delta = residual ? lo + (hi - lo) * rgba[3] : 0.0f;
    float total = lw + delta;
    if (total < 0.0f) total = 0.0f;
    for (int c = 0; c < 3; ++c) out[c] = l > 0.0f ? (rgba[c] * total) / l : total;
  }

  Image decode(const EncodedTexture& texture) const {
    const BlockGrid grid(texture.width, texture.height);
    Image image(texture.width, texture.height, texture.channels == 4 ? 3 : texture.channels);
    for (std::size_t b = 0; b < grid.block_count(); ++b) {
      const std::uint8_t* bytes = &texture.blocks[b * static_cast<std::size_t>(texture.block_bytes)];
      BlockTexels texels = residual ? reference_decode_bc3_block(bytes) : reference_decode_bc1_block(bytes);
      for (auto& t : texels.rgba) {
        float out[3];
        texel(t, out);
        t[0] = out[0], t[1] = out[1], t[2] = out[2], t[3] = 1.0f;
      }
      store_block(image, grid, b, texels);
    }
    return image;
  }
};

void expect_matches_spec_decoder(const EncodedTexture& texture, const std::string& what) {
  const Format& format = find_format("banterle");
  const Image ours = format.decode(texture, CodecContext{});
  const Image spec = SpecDecoder(texture).decode(texture);
  ASSERT_EQ(ours.pixels.size(), spec.pixels.size()) << what;
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i)
    if (std::memcmp(&ours.pixels[i], &spec.pixels[i], sizeof(float)) != 0 && mismatches++ < 5)
      ADD_FAILURE() << what << ": float " << i << " decodes to " << ours.pixels[i] << ", spec " << spec.pixels[i];
  EXPECT_EQ(mismatches, 0u) << what;
}

struct Golden {
  FormatOptions options;
  std::uint64_t blocks_hash;
  std::uint64_t decoded_hash;
};

const std::vector<Golden> kGolden = {
    {{{"bpp", "4"}, {"fit", "none"}}, 14699426205325410599ull, 8565315689233962021ull},
    {{{"bpp", "8"}, {"fit", "none"}}, 18186312961135443110ull, 2554043889502586011ull},
    {{{"bpp", "4"}, {"fit", "ceres_lm"}}, 12932178463846240417ull, 4848129657102825159ull},
    {{{"bpp", "8"}, {"fit", "ceres_lm"}}, 2971170640452586977ull, 6944109387076781217ull},
};

TEST(BanterleGolden, EncodedBytesAndDecodedFloatsMatchTheCommittedHashes) {
  const Format& format = find_format("banterle");
  const Image image = synthetic_hdr_image();
  for (const Golden& golden : kGolden) {
    const EncodedTexture texture = format.encode(image, resolve_format_options(format, golden.options), CodecContext{});
    const Image decoded = format.decode(texture, CodecContext{});
    const std::string label = "bpp " + golden.options.at("bpp") + " fit " + golden.options.at("fit");
    EXPECT_EQ(fnv1a64(texture.blocks.data(), texture.blocks.size()), golden.blocks_hash) << label;
    EXPECT_EQ(hash_floats(decoded.pixels), golden.decoded_hash) << label;
    expect_matches_spec_decoder(texture, label);
  }
}

TEST(BanterleGolden, DecodeOfASampleImageEqualsTheSpecLiteralDecode) {
  Image image = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/Desk.exr");
  apply_input_policy(image, InputPolicy::clamp, "Desk.exr");
  const Format& format = find_format("banterle");
  for (const char* bpp : {"4", "8"}) {
    const EncodedTexture texture = format.encode(image, resolve_format_options(format, {{"bpp", bpp}}), CodecContext{});
    expect_matches_spec_decoder(texture, std::string("Desk.exr bpp ") + bpp);
  }
}

TEST(BanterleGolden, DecodeOfRandomBlocksEqualsTheSpecLiteralDecode) {
  const Format& format = find_format("banterle");
  std::mt19937_64 random(6);
  for (const char* bpp : {"4", "8"}) {
    EncodedTexture texture = format.encode(synthetic_hdr_image(), resolve_format_options(format, {{"bpp", bpp}}),
                                           CodecContext{});
    for (auto& byte : texture.blocks) byte = static_cast<std::uint8_t>(random());   // every mode and index
    if (texture.side_data.count("residual_range")) texture.side_data["residual_range"] = {-3.5, 120.25};
    texture.block_modes.clear();
    expect_matches_spec_decoder(texture, std::string("random blocks bpp ") + bpp);
  }
}

}  // namespace
}  // namespace blocklab
