// The `downscaled` Format (formats/downscaled/downscaled_format.h): the rate of scale and bpp, an exact decode of a
// hand-built texture (BC4 codes of 0 and 1 upscaled bilinearly, expected values computed by hand, no oracle), scale 1
// is the inner format itself, the BT.601 luma source, bit-exact round trips through the .blk container and the DDS of
// gpu_textures, thread-count independence, and Errors naming bad options and side data.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "core/error.h"
#include "formats/common/container.h"
#include "formats/common/dds.h"
#include "formats/downscaled/downscaled_format.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

FormatOptions options_with(const std::map<std::string, std::string>& given) {
  return resolve_format_options(downscaled_format(), given);
}

Image test_image(int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      t[0] = static_cast<float>(0.5 + 0.4 * std::sin(0.2 * x + 0.1 * y));
      t[1] = static_cast<float>(0.5 + 0.3 * std::cos(0.15 * y));
      t[2] = static_cast<float>((x * 5 + y * 3) % 64 / 255.0 + 0.3);
    }
  return image;
}

std::vector<double> reduced_size(const EncodedTexture& texture) { return texture.side_data.at("reduced_size"); }

TEST(DownscaledFormat, TheRateIsTheInnerRateTimesTheAreaRatioOrTheGivenBpp) {
  const Format& format = downscaled_format();
  EXPECT_DOUBLE_EQ(format.bits_per_pixel(options_with({{"scale", "0.75"}})), 2.25);
  EXPECT_DOUBLE_EQ(format.bits_per_pixel(options_with({{"scale", "0.5"}, {"inner", "bc7"}})), 2.0);
  EXPECT_DOUBLE_EQ(format.bits_per_pixel(options_with({{"bpp", "2"}, {"inner", "bc4"}})), 2.0);
  EXPECT_EQ(format.block_bytes(options_with({{"inner", "bc3"}})), 16);
  // 768 x 512 (the Kodak size) at bpp = 2 with BC4: scale sqrt(1/2), round(543.06) x round(362.04).
  const EncodedTexture texture =
      format.encode(test_image(768, 512), options_with({{"bpp", "2"}, {"inner", "bc4"}}), CodecContext{2, 1});
  EXPECT_EQ(reduced_size(texture), (std::vector<double>{543, 362}));
  EXPECT_EQ(texture.blocks.size(), static_cast<std::size_t>((543 + 3) / 4) * ((362 + 3) / 4) * 8);
  EXPECT_EQ(texture.width, 768);
  EXPECT_EQ(texture.height, 512);
}

TEST(DownscaledFormat, AHandBuiltTextureDecodesToTheBilinearValuesComputedByHand) {
  // One BC4 block holding the 2 x 2 reduced image [[1, 0], [0, 1]]: red0 = 255, red1 = 0 (eight-value mode),
  // index 0 (red0) for texels 0 and 5, index 1 (red1) for texels 1 and 4 (3-bit indices, texel t at bit 3t).
  EncodedTexture texture;
  texture.format = "downscaled";
  texture.options = options_with({{"inner", "bc4"}});
  texture.width = 4;
  texture.height = 4;
  texture.channels = 1;
  texture.block_bytes = 8;
  texture.blocks = {255, 0, 0x08, 0x10, 0, 0, 0, 0};
  texture.side_data["reduced_size"] = {2, 2};
  const Image decoded = downscaled_format().decode(texture, CodecContext{1, 1});
  ASSERT_EQ(decoded.width, 4);
  ASSERT_EQ(decoded.height, 4);
  EXPECT_EQ(decoded.channels, 1);
  // Destination texel x samples u = (x + 0.5) / 2 - 0.5 = -0.25, 0.25, 0.75, 1.25, clamped: weights of the second
  // texel 0, 1/4, 3/4, 1. The value is (1 - tx)(1 - ty) * 1 + tx ty * 1.
  const double weight[4] = {0.0, 0.25, 0.75, 1.0};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const float expected = static_cast<float>((1 - weight[x]) * (1 - weight[y]) + weight[x] * weight[y]);
      EXPECT_EQ(decoded.texel(x, y)[0], expected) << x << "," << y;
      EXPECT_EQ(decoded.texel(x, y)[1], expected) << x << "," << y;
      EXPECT_EQ(decoded.texel(x, y)[3], 1.0f);
    }
}

TEST(DownscaledFormat, ScaleOneIsTheInnerFormatItself) {
  const Image image = test_image(21, 13);
  for (const char* inner : {"bc1", "bc4", "bc7"}) {
    const EncodedTexture texture =
        downscaled_format().encode(image, options_with({{"inner", inner}, {"scale", "1"}}), CodecContext{1, 1});
    const Format& inner_format = find_format(inner);
    const EncodedTexture plain = inner_format.encode(image, resolve_format_options(inner_format, {}), CodecContext{1, 1});
    EXPECT_EQ(texture.blocks, plain.blocks) << inner;
    EXPECT_EQ(downscaled_format().decode(texture, CodecContext{1, 1}).pixels,
              inner_format.decode(plain, CodecContext{1, 1}).pixels)
        << inner;
  }
}

TEST(DownscaledFormat, TheLumaSourceCodesBt601LumaAsOneChannel) {
  const Image image = test_image(16, 8);
  const EncodedTexture texture = downscaled_format().encode(
      image, options_with({{"inner", "bc4"}, {"scale", "1"}, {"source", "bt601_luma"}}), CodecContext{1, 1});
  EXPECT_EQ(texture.channels, 1);
  Image luma(16, 8, 1);
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const double y = 0.299 * image.pixels[i * 4] + 0.587 * image.pixels[i * 4 + 1] + 0.114 * image.pixels[i * 4 + 2];
    for (int c = 0; c < 3; ++c) luma.pixels[i * 4 + c] = static_cast<float>(y);
  }
  const Format& bc4 = find_format("bc4");
  const EncodedTexture plain = bc4.encode(luma, resolve_format_options(bc4, {}), CodecContext{1, 1});
  EXPECT_EQ(texture.blocks, plain.blocks);
}

TEST(DownscaledFormat, ContainerAndDdsRoundTripsAreBitExactAndTheDdsHoldsTheReducedInnerTexture) {
  const Image image = test_image(37, 22);
  const EncodedTexture texture =
      downscaled_format().encode(image, options_with({{"scale", "0.71"}}), CodecContext{2, 1});
  EXPECT_EQ(reduced_size(texture), (std::vector<double>{26, 16}));
  const Image decoded = downscaled_format().decode(texture, CodecContext{2, 1});

  const std::string path = (std::filesystem::temp_directory_path() /
                            ("blocklab_test_downscaled_" + std::to_string(::getpid()) + ".blk")).string();
  write_container(path, texture);
  const EncodedTexture read = read_container(path);
  std::remove(path.c_str());
  EXPECT_EQ(read.blocks, texture.blocks);
  EXPECT_EQ(read.side_data, texture.side_data);
  EXPECT_EQ(read.options, texture.options);
  EXPECT_EQ(downscaled_format().decode(read, CodecContext{1, 1}).pixels, decoded.pixels);

  const std::vector<GpuTexture> gpu = downscaled_format().gpu_textures(texture);
  ASSERT_EQ(gpu.size(), 1u);
  EXPECT_EQ(gpu[0].texture.format, "bc1");
  EXPECT_EQ(gpu[0].texture.width, 26);
  EXPECT_EQ(gpu[0].texture.height, 16);
  const EncodedTexture from_dds = parse_dds(dds_bytes(gpu[0].texture, "test.dds"), "test.dds");
  EXPECT_EQ(from_dds.blocks, texture.blocks);
  // The DDS texture, magnified bilinearly, is the decoded image.
  const Image reduced = find_format("bc1").decode(from_dds, CodecContext{1, 1});
  EXPECT_EQ(reduced.width, 26);
}

TEST(DownscaledFormat, BytesDoNotDependOnTheThreadCount) {
  const Image image = test_image(45, 30);
  const FormatOptions options = options_with({{"scale", "0.86"}, {"inner", "bc7"}, {"preset", "fast"}});
  const EncodedTexture one = downscaled_format().encode(image, options, CodecContext{1, 1});
  const EncodedTexture two = downscaled_format().encode(image, options, CodecContext{2, 1});
  EXPECT_EQ(one.blocks, two.blocks);
  EXPECT_EQ(downscaled_format().decode(one, CodecContext{1, 1}).pixels,
            downscaled_format().decode(two, CodecContext{2, 1}).pixels);
}

void expect_error_naming(const std::function<void()>& action, const std::string& name) {
  try {
    action();
    ADD_FAILURE() << "no Error; expected one naming " << name;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
  }
}

TEST(DownscaledFormat, BadOptionsAndSideDataAreErrorsNamingThem) {
  expect_error_naming([] { options_with({{"scale", "0"}}); }, "scale");
  expect_error_naming([] { options_with({{"inner", "mavridis"}}); }, "inner");
  expect_error_naming(
      [] { downscaled_format().encode(test_image(8, 8), options_with({{"bpp", "5"}}), CodecContext{1, 1}); }, "bpp");

  const EncodedTexture good = downscaled_format().encode(test_image(20, 12), options_with({}), CodecContext{1, 1});
  const auto decode_with = [&](const std::function<void(EncodedTexture&)>& change) {
    EncodedTexture texture = good;
    change(texture);
    downscaled_format().decode(texture, CodecContext{1, 1});
  };
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data.erase("reduced_size"); }); },
                      "reduced_size");
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data["reduced_size"] = {15.5, 9}; }); },
                      "reduced_size");
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data["reduced_size"] = {21, 9}; }); },
                      "reduced_size");
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data["reduced_size"] = {15}; }); },
                      "reduced_size");
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data["scale"] = {1}; }); }, "scale");
  // A consistent size with the wrong number of blocks.
  expect_error_naming([&] { decode_with([](EncodedTexture& t) { t.side_data["reduced_size"] = {20, 12}; }); },
                      "block data");
}

}  // namespace
}  // namespace blocklab
