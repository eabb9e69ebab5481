// The `mavridis` Format (formats/mavridis/mavridis_format.h): Table 2 rates, YCoCg-R round trip, any image size,
// gray output, thread-count independence, stored sizes, 8-bit colour storage and Errors naming bad options.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/color_spaces.h"
#include "core/error.h"
#include "formats/mavridis/mavridis_format.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

FormatOptions options_with(const std::map<std::string, std::string>& given) {
  return resolve_format_options(mavridis_format(), given);
}

Image test_image(int width, int height, int channels = 3) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      t[0] = static_cast<float>(0.5 + 0.4 * std::sin(0.2 * x + 0.1 * y));
      t[1] = static_cast<float>(0.5 + 0.3 * std::cos(0.15 * y));
      t[2] = static_cast<float>((x * 5 + y * 3) % 64 / 255.0 + 0.3);
      if (channels == 1) t[1] = t[2] = t[0];
    }
  return image;
}

double psnr(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.texel_count(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double d = 255.0 * (a.pixels[i * 4 + k] - b.pixels[i * 4 + k]);
      sum += d * d;
    }
  return 10.0 * std::log10(255.0 * 255.0 / (sum / (3.0 * a.texel_count())));
}

TEST(MavridisFormat, PayloadRatesAreThoseOfTable2) {
  const std::map<std::string, double> rates = {{"5", 5.0}, {"3", 3.0}, {"2.25", 2.25}, {"2", 2.0}};
  for (const auto& rate : rates) {
    const FormatOptions options = options_with({{"bpp", rate.first}});
    const std::size_t bytes = mavridis_payload_bytes(options, 768, 512);
    EXPECT_DOUBLE_EQ(bytes * 8.0 / (768.0 * 512.0), rate.second) << rate.first;
    EXPECT_DOUBLE_EQ(mavridis_format().bits_per_pixel(options), rate.second) << rate.first;
  }
}

TEST(MavridisFormat, StoredBytesOfA32MultipleSizeAreThePayloadAtEveryRate) {
  // 2.25 bpp (4.5 bytes per 4x4 block) stores its textures at their true size, the other rates whole blocks; at a
  // size of whole coded tiles both are exactly the Table 2 rate, with nothing in side data tail_bytes.
  const Image image = test_image(64, 32);
  for (const char* bpp : {"5", "3", "2.25", "2"}) {
    const FormatOptions options = options_with({{"bpp", bpp}});
    const EncodedTexture texture = mavridis_format().encode(image, options, CodecContext{1, 1});
    EXPECT_EQ(texture.blocks.size(), mavridis_payload_bytes(options, 64, 32)) << bpp;
    EXPECT_DOUBLE_EQ(texture.blocks.size() * 8.0 / (64.0 * 32.0), mavridis_format().bits_per_pixel(options)) << bpp;
    EXPECT_EQ(texture.side_data.count("tail_bytes"), 0u) << bpp;
    EXPECT_EQ(texture.blocks.size(), mavridis_format().stored_block_count(texture) * texture.block_bytes) << bpp;
  }
}

TEST(MavridisFormat, UnormColorStorageDecodesCloseToTheSourceInEverySpace) {
  // color_storage=unorm8 (mavridis_color_storage.h): the planes as 8-bit textures on both sides of the wavelet;
  // YCoCg and YCbCr lose precision there, so their decodes differ from the exact storage's.
  const Image image = test_image(48, 40);
  for (const char* space : {"ycocg_r", "ycocg", "ycbcr"}) {
    const EncodedTexture exact = mavridis_format().encode(image, options_with({{"space", space}}), CodecContext{1, 1});
    const EncodedTexture stored = mavridis_format().encode(
        image, options_with({{"space", space}, {"color_storage", "unorm8"}}), CodecContext{1, 1});
    const Image decoded = mavridis_format().decode(stored, CodecContext{1, 1});
    EXPECT_GT(psnr(image, decoded), 30.0) << space;
    if (std::string(space) != "ycocg_r") EXPECT_NE(exact.blocks, stored.blocks) << space;
  }
}

TEST(MavridisFormat, YCoCgRRoundTripsEveryEightBitColourOnAGrid) {
  for (int r = 0; r < 256; r += 3)
    for (int g = 0; g < 256; g += 5)
      for (int b = 0; b < 256; b += 1) {
        const Rgb<std::int32_t> back = ycocg_r_to_rgb(rgb_to_ycocg_r(r, g, b));
        ASSERT_EQ(back.r, r);
        ASSERT_EQ(back.g, g);
        ASSERT_EQ(back.b, b);
      }
}

TEST(MavridisFormat, EveryRateAndSpaceDecodesOddSizesCloseToTheSource) {
  for (const char* bpp : {"5", "3", "2.25", "2"})
    for (const char* space : {"ycocg_r", "ycocg", "ycbcr"})
      for (const auto& size : std::vector<std::pair<int, int>>{{1, 1}, {13, 7}, {37, 41}, {64, 32}}) {
        const Image image = test_image(size.first, size.second);
        const FormatOptions options = options_with({{"bpp", bpp}, {"space", space}, {"preset", "fast"}});
        const EncodedTexture texture = mavridis_format().encode(image, options, CodecContext{1, 1});
        const Image decoded = mavridis_format().decode(texture, CodecContext{1, 1});
        ASSERT_EQ(decoded.width, image.width);
        ASSERT_EQ(decoded.height, image.height);
        EXPECT_EQ(decoded.channels, std::string(bpp) == "2" ? 1 : 3);
        if (std::string(bpp) != "2" && size.first >= 13) {
          // 2.25 bpp keeps a sixteenth of the chroma samples; the blue sawtooth of the test image suffers most.
          EXPECT_GT(psnr(image, decoded), std::string(bpp) == "2.25" ? 24.0 : 26.0) << bpp << " " << space << " " << size.first;
        }
      }
}

TEST(MavridisFormat, GrayModeOfAGraySourceKeepsItsValues) {
  const Image image = test_image(40, 24, 1);
  const EncodedTexture texture = mavridis_format().encode(image, options_with({{"bpp", "2"}}), CodecContext{1, 1});
  const Image decoded = mavridis_format().decode(texture, CodecContext{1, 1});
  EXPECT_GT(psnr(image, decoded), 35.0);
}

TEST(MavridisFormat, BytesAndDecodingDoNotDependOnTheThreadCount) {
  const Image image = test_image(70, 45);
  for (const char* bpp : {"5", "2.25"}) {
    const FormatOptions options = options_with({{"bpp", bpp}});
    const EncodedTexture one = mavridis_format().encode(image, options, CodecContext{1, 1});
    const EncodedTexture two = mavridis_format().encode(image, options, CodecContext{2, 1});
    EXPECT_EQ(one.blocks, two.blocks);
    EXPECT_EQ(one.side_data, two.side_data);
    EXPECT_EQ(mavridis_format().decode(one, CodecContext{1, 1}).pixels,
              mavridis_format().decode(one, CodecContext{2, 1}).pixels);
  }
}

TEST(MavridisFormat, HaarAndPiHaarBothDecodeTheSmoothTestImageAbove30dB) {
  const Image image = test_image(64, 64);
  const Image pi = mavridis_format().decode(
      mavridis_format().encode(image, options_with({{"transform", "pi_haar"}}), CodecContext{1, 1}), CodecContext{1, 1});
  const Image haar = mavridis_format().decode(
      mavridis_format().encode(image, options_with({{"transform", "haar"}}), CodecContext{1, 1}), CodecContext{1, 1});
  EXPECT_GT(psnr(image, pi), 30.0);
  EXPECT_GT(psnr(image, haar), 30.0);
}

TEST(MavridisFormat, PlhaarDecodesTheSmoothTestImageAtEveryColourRate) {
  const Image image = test_image(64, 64);
  for (const char* bpp : {"5", "3", "2.25"}) {
    const Image decoded = mavridis_format().decode(
        mavridis_format().encode(image, options_with({{"transform", "plhaar"}, {"bpp", bpp}}), CodecContext{1, 1}),
        CodecContext{1, 1});
    EXPECT_GT(psnr(image, decoded), 24.0) << bpp;
  }
}

TEST(MavridisFormat, TwoLevelsGiveTheGray15AndColour175BppVariants) {
  const FormatOptions gray = options_with({{"bpp", "2"}, {"levels", "2"}});
  EXPECT_DOUBLE_EQ(mavridis_payload_bytes(gray, 768, 512) * 8.0 / (768.0 * 512.0), 1.5);
  EXPECT_EQ(mavridis_format().block_bytes(gray), 3);
  const FormatOptions colour = options_with({{"bpp", "2.25"}, {"levels", "2"}});
  EXPECT_DOUBLE_EQ(mavridis_payload_bytes(colour, 768, 512) * 8.0 / (768.0 * 512.0), 1.75);
  EXPECT_DOUBLE_EQ(mavridis_format().bits_per_pixel(gray), 1.5);
  EXPECT_DOUBLE_EQ(mavridis_format().bits_per_pixel(colour), 1.75);
  const Image image = test_image(53, 37);
  for (const FormatOptions& options : {gray, colour, options_with({{"bpp", "3"}, {"levels", "3"}})}) {
    const EncodedTexture texture = mavridis_format().encode(image, options, CodecContext{1, 1});
    EXPECT_TRUE(texture.side_data.count("y_level1_bands"));
    const Image decoded = mavridis_format().decode(texture, CodecContext{2, 1});
    if (decoded.channels == 3) {
      EXPECT_GT(psnr(image, decoded), 22.0);
    }
    const EncodedTexture again = mavridis_format().encode(image, options, CodecContext{2, 1});
    EXPECT_EQ(again.blocks, texture.blocks);
  }
  EXPECT_THROW(mavridis_format().block_bytes(options_with({{"bpp", "5"}, {"levels", "2"}})), Error);
  EXPECT_THROW(mavridis_format().block_bytes(options_with({{"transform", "plhaar"}, {"levels", "2"}})), Error);
}

TEST(MavridisFormat, BestPackingKeepsTheLowerErrorAndRecordsIt) {
  const Image image = test_image(48, 40);
  for (const char* bpp : {"3", "2"}) {
    const EncodedTexture best =
        mavridis_format().encode(image, options_with({{"bpp", bpp}, {"packing", "best"}}), CodecContext{1, 1});
    ASSERT_EQ(best.side_data.count("packing"), 1u);
    const bool bc7 = best.side_data.at("packing").at(0) == 1.0;
    const EncodedTexture alone =
        mavridis_format().encode(image, options_with({{"bpp", bpp}, {"packing", bc7 ? "bc7" : "dxt5"}}), CodecContext{1, 1});
    EXPECT_EQ(best.blocks, alone.blocks);
    EXPECT_EQ(mavridis_format().decode(best, CodecContext{1, 1}).pixels,
              mavridis_format().decode(alone, CodecContext{1, 1}).pixels);
    if (std::string(bpp) == "3") {
      const EncodedTexture other = mavridis_format().encode(
          image, options_with({{"bpp", bpp}, {"packing", bc7 ? "dxt5" : "bc7"}}), CodecContext{1, 1});
      EXPECT_GE(psnr(image, mavridis_format().decode(best, CodecContext{1, 1})),
                psnr(image, mavridis_format().decode(other, CodecContext{1, 1})));
    }
  }
  EncodedTexture broken =
      mavridis_format().encode(image, options_with({{"packing", "best"}, {"preset", "fast"}}), CodecContext{1, 1});
  broken.side_data["packing"] = {2.0};
  EXPECT_THROW(mavridis_format().decode(broken, CodecContext{1, 1}), Error);
}

TEST(MavridisFormat, GpuTexturesAreThePayloadAtEachLevelsResolution) {
  const Image image = test_image(70, 45);
  struct Case { std::map<std::string, std::string> options; std::vector<std::string> suffixes, formats; };
  const std::vector<Case> cases = {
      {{{"bpp", "3"}}, {"y", "co", "cg"}, {"bc3", "bc3", "bc3"}},
      {{{"bpp", "5"}, {"packing", "bc7"}}, {"y", "co", "cg"}, {"bc4", "bc7", "bc7"}},
      {{{"bpp", "2"}, {"levels", "3"}}, {"y_level1", "y_level2", "y"}, {"bc1", "bc1", "bc3"}},
  };
  for (const Case& c : cases) {
    const FormatOptions options = options_with(c.options);
    const EncodedTexture texture = mavridis_format().encode(image, options, CodecContext{1, 1});
    const std::vector<GpuTexture> gpu = mavridis_format().gpu_textures(texture);
    ASSERT_EQ(gpu.size(), c.suffixes.size());
    std::vector<std::uint8_t> joined;
    for (std::size_t k = 0; k < gpu.size(); ++k) {
      EXPECT_EQ(gpu[k].suffix, c.suffixes[k]);
      EXPECT_EQ(gpu[k].texture.format, c.formats[k]);
      joined.insert(joined.end(), gpu[k].texture.blocks.begin(), gpu[k].texture.blocks.end());
    }
    // Y at 70 x 45: BC4 at full size, its first coefficient texture at half size (35 x 23); three levels end at 9 x 6.
    EXPECT_EQ(gpu[0].texture.width, c.formats[0] == "bc4" ? 70 : 35);
    EXPECT_EQ(gpu[0].texture.height, c.formats[0] == "bc4" ? 45 : 23);
    if (c.suffixes[0] == "y_level1") {
      EXPECT_EQ(gpu.back().texture.width, 9);
    }
    ASSERT_EQ(joined.size(), mavridis_payload_bytes(options, 70, 45));
    std::vector<std::uint8_t> stored(texture.blocks.begin(), texture.blocks.begin() + std::min(joined.size(), texture.blocks.size()));
    if (texture.side_data.count("tail_bytes"))
      for (double b : texture.side_data.at("tail_bytes")) stored.push_back(static_cast<std::uint8_t>(b));
    EXPECT_EQ(joined, stored);
  }
}

TEST(MavridisFormat, BadOptionValuesAreErrorsNamingTheOption) {
  try {
    options_with({{"bpp", "4"}});
    FAIL() << "bpp=4 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bpp"), std::string::npos) << e.what();
  }
  EXPECT_THROW(options_with({{"w", "0"}}), Error);
  EXPECT_THROW(options_with({{"space", "rgb"}}), Error);
  // BC7 packing drops HH, which the integer transforms need.
  for (const char* transform : {"s_transform", "plhaar"}) {
    const FormatOptions options = options_with({{"packing", "bc7"}, {"transform", transform}});
    try {
      mavridis_format().encode(test_image(8, 8), options, CodecContext{1, 1});
      FAIL() << transform << " with bc7 accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(transform), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(find_format("mavridis"));
}

}  // namespace
}  // namespace blocklab
