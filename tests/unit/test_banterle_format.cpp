// The `banterle` Format: registration and options, container round trips, side-data validation (bad values are
// rejected with a message naming the key), thread-count independence, channel handling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/common/container.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

const Format& banterle() { return find_format("banterle"); }

// 23x13 HDR gradient over ~20 stops with coloured texels and a few black ones (exact integer formulas + ldexp).
Image test_image(int channels = 3) {
  Image image(23, 13, channels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float* t = image.texel(x, y);
      const float base = std::ldexp(1.0f + static_cast<float>((x * 13 + y * 7) % 17) / 17.0f, (x + 2 * y) % 20 - 10);
      t[0] = base;
      t[1] = base * static_cast<float>(1 + x % 3) / 3.0f;
      t[2] = base * static_cast<float>(1 + y % 4) / 4.0f;
      if ((x + 3 * y) % 29 == 0) t[0] = t[1] = t[2] = 0.0f;
      if (channels == 4) t[3] = 0.5f;
    }
  return image;
}

EncodedTexture encode(const FormatOptions& given, int threads = 1, const Image& image = test_image()) {
  CodecContext context;
  context.threads = threads;
  return banterle().encode(image, resolve_format_options(banterle(), given), context);
}

Image decode(const EncodedTexture& texture, int threads = 1) {
  CodecContext context;
  context.threads = threads;
  return banterle().decode(texture, context);
}

void expect_bit_identical(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
}

std::string error_of(const EncodedTexture& texture) {
  try {
    decode(texture);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(BanterleFormat, IsRegisteredWithFourAndEightBitsPerPixel) {
  EXPECT_EQ(banterle().name(), "banterle");
  EXPECT_EQ(banterle().bits_per_pixel(resolve_format_options(banterle(), {})), 4.0);
  EXPECT_EQ(banterle().bits_per_pixel(resolve_format_options(banterle(), {{"bpp", "8"}})), 8.0);
  EXPECT_THROW(resolve_format_options(banterle(), {{"bpp", "6"}}), Error);
  EXPECT_THROW(resolve_format_options(banterle(), {{"fit", "levenberg"}}), Error);
  EXPECT_THROW(resolve_format_options(banterle(), {{"mean", "arithmetic"}}), Error);
  const FormatOptions resolved = resolve_format_options(banterle(), {});
  EXPECT_EQ(resolved.at("mean"), "geometric");
  EXPECT_EQ(resolved.at("fit"), "ceres_lm");
}

TEST(BanterleFormat, SideDataHoldsTheFittedParametersAndTheResidualRangeOnlyAtEightBpp) {
  const EncodedTexture four = encode({});
  EXPECT_EQ(four.side_data.size(), 3u);
  EXPECT_GT(four.side_data.at("alpha")[0], 0.0);
  EXPECT_GT(four.side_data.at("l_white")[0], 0.0);
  EXPECT_GT(four.side_data.at("mean")[0], 0.0);
  const EncodedTexture eight = encode({{"bpp", "8"}});
  ASSERT_EQ(eight.side_data.count("residual_range"), 1u);
  EXPECT_LE(eight.side_data.at("residual_range")[0], eight.side_data.at("residual_range")[1]);
  EXPECT_EQ(eight.block_bytes, 16);
  for (std::uint8_t mode : eight.block_modes) EXPECT_GE(mode, 2);   // eight_alpha / six_alpha
}

TEST(BanterleFormat, ContainerRoundTripKeepsBytesSideDataAndDecodedBits) {
  const std::string path = (std::filesystem::temp_directory_path() / "test_banterle_roundtrip.blk").string();
  for (const char* bpp : {"4", "8"}) {
    const EncodedTexture texture = encode({{"bpp", bpp}});
    write_container(path, texture);
    const EncodedTexture read = read_container(path);
    EXPECT_EQ(read.blocks, texture.blocks) << bpp;
    EXPECT_EQ(read.side_data, texture.side_data) << bpp;   // doubles survive the JSON header exactly
    EXPECT_EQ(read.options, texture.options) << bpp;
    expect_bit_identical(decode(read), decode(texture));
  }
  std::filesystem::remove(path);
}

TEST(BanterleFormat, BytesAndDecodedImageDoNotDependOnTheThreadCount) {
  for (const char* bpp : {"4", "8"}) {
    const EncodedTexture one = encode({{"bpp", bpp}}, 1);
    const EncodedTexture four = encode({{"bpp", bpp}}, 4);
    EXPECT_EQ(one.blocks, four.blocks) << bpp;
    EXPECT_EQ(one.side_data, four.side_data) << bpp;
    expect_bit_identical(decode(one, 1), decode(one, 4));
  }
}

TEST(BanterleFormat, FitOptionsReachTheFitSolverAndDefaultsAreTheMethodsOwn) {
  // Spelling the nlopt method's defaults out gives the same bytes as no fit_options.
  const EncodedTexture plain = encode({{"fit", "nlopt"}});
  const EncodedTexture spelled =
      encode({{"fit", "nlopt"}, {"fit_options", " algorithm=LN_SBPLX , max_evaluations=400, initial_step=0.05"}});
  EXPECT_EQ(plain.blocks, spelled.blocks);
  EXPECT_EQ(plain.side_data, spelled.side_data);
  // Another algorithm with a tiny budget reaches the solver: the fitted parameters change.
  const EncodedTexture other = encode({{"fit", "nlopt"}, {"fit_options", "algorithm=LN_NELDERMEAD, max_evaluations=10"}});
  EXPECT_NE(other.side_data.at("alpha"), plain.side_data.at("alpha"));
  // ceres_lm's options go to its LM stage.
  EXPECT_NO_THROW(encode({{"fit", "ceres_lm"}, {"fit_options", "max_iterations=5"}}));
}

TEST(BanterleFormat, BadFitOptionsAreErrorsNamingTheKey) {
  const auto message = [](const FormatOptions& given) -> std::string {
    try {
      encode(given);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(message({{"fit", "nlopt"}, {"fit_options", "algorithmm=LN_SBPLX"}}).find("unknown option 'algorithmm'"),
            std::string::npos);
  EXPECT_NE(message({{"fit", "nlopt"}, {"fit_options", "algorithm=NOT_ONE"}}).find("NOT_ONE"), std::string::npos);
  EXPECT_NE(message({{"fit", "none"}, {"fit_options", "max_evaluations=5"}}).find("fit is 'none'"), std::string::npos);
  EXPECT_NE(message({{"fit", "nlopt"}, {"fit_options", "max_evaluations=5,"}}).find("empty item"), std::string::npos);
  EXPECT_NE(message({{"fit", "nlopt"}, {"fit_options", "max_evaluations"}}).find("is not key=value"),
            std::string::npos);
  EXPECT_NE(message({{"fit", "nlopt"}, {"fit_options", "max_evaluations=5, max_evaluations=6"}}).find("twice"),
            std::string::npos);
  // The options of format revision 1 are gone (fit_options replaces them).
  EXPECT_NE(message({{"fit_algorithm", "LN_SBPLX"}}).find("fit_algorithm"), std::string::npos);
}

TEST(BanterleFormat, RejectsBadSideDataWithAMessageNamingTheKey) {
  for (const char* bpp : {"4", "8"}) {
    const EncodedTexture good = encode({{"bpp", bpp}});
    ASSERT_EQ(error_of(good), "");
    const auto with = [&](const std::string& key, std::vector<double> values) {
      EncodedTexture bad = good;
      bad.side_data[key] = std::move(values);
      return error_of(bad);
    };
    EXPECT_NE(with("alpha", {std::nan("")}).find("'alpha'"), std::string::npos);
    EXPECT_NE(with("l_white", {0.0}).find("'l_white' must be finite and > 0"), std::string::npos);
    EXPECT_NE(with("l_white", {-2.0}).find("'l_white'"), std::string::npos);
    EXPECT_NE(with("mean", {INFINITY}).find("'mean'"), std::string::npos);
    EXPECT_NE(with("alpha", {0.1, 0.2}).find("must hold 1 value"), std::string::npos);
    EXPECT_NE(with("gamma", {1.0}).find("unexpected side data 'gamma'"), std::string::npos);
    EncodedTexture missing = good;
    missing.side_data.erase("mean");
    EXPECT_NE(error_of(missing).find("'mean' is missing"), std::string::npos);
    // alpha tiny and Lwhite huge: the inverse-TMO peak leaves the float range.
    EncodedTexture peak = good;
    peak.side_data["alpha"] = {1e-20};
    peak.side_data["l_white"] = {1e20};
    EXPECT_NE(error_of(peak).find("peak"), std::string::npos);
  }
  const EncodedTexture four = encode({});
  EncodedTexture stray = four;
  stray.side_data["residual_range"] = {0.0, 1.0};
  EXPECT_NE(error_of(stray).find("unexpected side data 'residual_range' for bpp 4"), std::string::npos);
  const EncodedTexture eight = encode({{"bpp", "8"}});
  EncodedTexture reversed = eight;
  reversed.side_data["residual_range"] = {1.0, -1.0};
  EXPECT_NE(error_of(reversed).find("lo <= hi"), std::string::npos);
  EncodedTexture huge = eight;
  huge.side_data["residual_range"] = {-1e31, 1.0};
  EXPECT_NE(error_of(huge).find("'residual_range'"), std::string::npos);
  EncodedTexture short_range = eight;
  short_range.side_data["residual_range"] = {0.0};
  EXPECT_NE(error_of(short_range).find("must hold 2 value"), std::string::npos);
}

TEST(BanterleFormat, BadSideDataInAFileIsRejectedOnDecode) {
  const std::string path = (std::filesystem::temp_directory_path() / "test_banterle_bad_side.blk").string();
  EncodedTexture texture = encode({});
  texture.side_data["l_white"] = {-1.0};   // finite, so the container accepts it; the format must not
  write_container(path, texture);
  const EncodedTexture read = read_container(path);
  EXPECT_NE(error_of(read).find("side data 'l_white' must be finite and > 0, got -1"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(BanterleFormat, FourChannelSourceDecodesAsRgbAndBlackStaysBlack) {
  const Image source = test_image(4);
  const EncodedTexture texture = encode({}, 1, source);
  EXPECT_EQ(texture.channels, 4);
  const Image decoded = decode(texture);
  EXPECT_EQ(decoded.channels, 3);
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x) {
      EXPECT_EQ(decoded.texel(x, y)[3], 1.0f);
      for (int c = 0; c < 3; ++c) EXPECT_GE(decoded.texel(x, y)[c], 0.0f);
    }
}

TEST(BanterleFormat, EightBppReconstructsLuminanceCloserThanFourBpp) {
  const Image source = test_image();
  const Image four = decode(encode({}));
  const Image eight = decode(encode({{"bpp", "8"}}));
  double error4 = 0.0, error8 = 0.0;
  const auto luma = [](const float* t) { return 0.21 * t[0] + 0.72 * t[1] + 0.07 * t[2]; };
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x) {
      const double l = std::max(luma(source.texel(x, y)), 0x1p-24);
      error4 += std::pow(std::log2(l) - std::log2(std::max(luma(four.texel(x, y)), 0x1p-24)), 2);
      error8 += std::pow(std::log2(l) - std::log2(std::max(luma(eight.texel(x, y)), 0x1p-24)), 2);
    }
  EXPECT_LT(error8, error4);
}

}  // namespace
}  // namespace blocklab

namespace blocklab {
namespace {

TEST(BanterleFormat, BlackAndSinglePixelImagesEncodeAndDecodeToBlack) {
  for (const char* bpp : {"4", "8"}) {
    for (int size : {1, 5}) {
      const Image black(size, size);   // RGB 0, alpha 1
      const Image decoded = decode(encode({{"bpp", bpp}}, 1, black));
      for (std::size_t i = 0; i < decoded.texel_count(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(decoded.pixels[i * 4 + c], 0.0f) << bpp << " size " << size;
    }
  }
}

}  // namespace
}  // namespace blocklab
