// Fuzz of the `mavridis` decoder and encoder (formats/mavridis/mavridis_format.h): random blocks, tails and side
// data of random sizes decode to finite values in [0, 1] without crashing; bad side data is an Error naming the
// key; the encoder survives extreme inputs (values above 1, zeros, 1-texel images, one channel).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "formats/mavridis/mavridis_format.h"

namespace blocklab {
namespace {

const Format& format() { return mavridis_format(); }

EncodedTexture random_texture(std::mt19937& rng) {
  static const char* rates[] = {"5", "3", "2.25", "2"};
  static const char* spaces[] = {"ycocg_r", "ycocg", "ycbcr"};
  std::uniform_int_distribution<int> size(1, 70), byte(0, 255), pick(0, 11);
  std::uniform_real_distribution<double> centre(-300.0, 300.0), half(1e-6, 600.0), gamma(0.1, 10.0);
  const int choice = pick(rng);
  EncodedTexture texture;
  texture.format = "mavridis";
  texture.options = resolve_format_options(
      format(), {{"bpp", rates[choice % 4]},
                 {"space", spaces[choice % 3]},
                 {"transform", choice % 2 ? "haar" : (choice % 5 == 0 ? "s_transform" : "pi_haar")},
                 {"packing", choice % 2 && choice % 3 == 0 ? "bc7" : "dxt5"},
                 {"color_storage", choice % 7 < 3 ? "unorm8" : "exact"}});
  texture.width = size(rng);
  texture.height = size(rng);
  texture.channels = std::string(rates[choice % 4]) == "2" ? 1 : 3;
  texture.block_bytes = format().block_bytes(texture.options);
  texture.blocks.resize(format().stored_block_count(texture) * texture.block_bytes);
  for (auto& b : texture.blocks) b = static_cast<std::uint8_t>(byte(rng));
  const std::size_t payload = mavridis_payload_bytes(texture.options, texture.width, texture.height);
  if (payload > texture.blocks.size()) {
    std::vector<double> tail(payload - texture.blocks.size());
    for (double& v : tail) v = byte(rng);
    texture.side_data["tail_bytes"] = tail;
  }
  const bool bc4_luma = std::string(rates[choice % 4]) == "5";
  for (const char* key : {"y", "co", "cg"}) {
    if (texture.channels == 1 && std::string(key) != "y") continue;
    if (bc4_luma && std::string(key) == "y") continue;
    std::vector<double> bands;
    for (int k = 0; k < 4; ++k) {
      bands.push_back(centre(rng));
      bands.push_back(half(rng));
    }
    texture.side_data[std::string(key) + "_bands"] = bands;
    texture.side_data[std::string(key) + "_gamma"] = {gamma(rng)};
    texture.side_data[std::string(key) + "_search"] = {0.1, 0.9, 1.0};
  }
  return texture;
}

void expect_error_naming(const EncodedTexture& texture, const std::string& key) {
  try {
    format().decode(texture, CodecContext{1, 1});
    FAIL() << "decode accepted bad '" << key << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(MavridisFuzz, RandomBlocksAndSideDataDecodeToFiniteValuesInRange) {
  std::mt19937 rng(2012);
  for (int trial = 0; trial < 300; ++trial) {
    const EncodedTexture texture = random_texture(rng);
    const Image decoded = format().decode(texture, CodecContext{1, 1});
    for (float v : decoded.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f) << "trial " << trial;
  }
}

TEST(MavridisFuzz, BadSideDataIsAnErrorNamingTheKey) {
  std::mt19937 rng(5);
  EncodedTexture texture;
  do texture = random_texture(rng);
  while (texture.side_data.count("tail_bytes") == 0 || texture.side_data.count("co_bands") == 0 ||
         texture.side_data.count("y_bands") == 0);
  EncodedTexture bad = texture;
  bad.side_data.erase("co_bands");
  expect_error_naming(bad, "co_bands");
  bad = texture;
  bad.side_data["y_bands"].pop_back();
  expect_error_naming(bad, "y_bands");
  bad = texture;
  bad.side_data["cg_bands"][3] = -1.0;
  expect_error_naming(bad, "cg_bands");
  bad = texture;
  bad.side_data["y_gamma"] = {0.0};
  expect_error_naming(bad, "y_gamma");
  bad = texture;
  bad.side_data["tail_bytes"][0] = 256.0;
  expect_error_naming(bad, "tail_bytes");
  bad = texture;
  bad.side_data["tail_bytes"].push_back(1.0);
  expect_error_naming(bad, "tail_bytes");
  bad = texture;
  bad.side_data["surplus"] = {1.0};
  expect_error_naming(bad, "surplus");
  bad = texture;
  bad.options.erase("bpp");
  expect_error_naming(bad, "bpp");
  bad = texture;
  bad.options["packing"] = "bc7";
  bad.options["transform"] = "s_transform";
  expect_error_naming(bad, "packing");
  bad = texture;
  bad.channels = 1;
  expect_error_naming(bad, "channel");
}

TEST(MavridisFuzz, EncoderSurvivesExtremeInputs) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> wild(0.0f, 1e6f);
  for (int channels : {1, 3, 4})
    for (const char* bpp : {"5", "3", "2.25", "2"})
      for (int kind = 0; kind < 3; ++kind) {
        Image image(kind == 2 ? 1 : 19, kind == 2 ? 1 : 11, channels);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
          if (i % 4 != 3) image.pixels[i] = kind == 0 ? wild(rng) : 0.0f;
        const FormatOptions options = resolve_format_options(format(), {{"bpp", bpp}, {"preset", "fast"}});
        const Image decoded = format().decode(format().encode(image, options, CodecContext{1, 1}), CodecContext{1, 1});
        for (float v : decoded.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
      }
}

}  // namespace
}  // namespace blocklab
