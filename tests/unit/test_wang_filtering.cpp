// Filtering of the `wang` textures (formats/wang/wang_filtering.h; Wang et al. 2007 section 4.4, Appendix B): the
// fetched channels reproduce the decoder, bilinear sampling weights, Appendix B's same-direction counts.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "formats/registry.h"
#include "formats/wang/wang_filtering.h"
#include "formats/wang/wang_format.h"

namespace blocklab {
namespace {

// A smooth HDR test image over a few stops, every channel positive.
Image hdr_ramp(int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      t[0] = static_cast<float>(std::exp2(0.3 * x - 2.0) * (1.0 + 0.2 * std::sin(y)));
      t[1] = static_cast<float>(std::exp2(0.2 * y - 1.0));
      t[2] = static_cast<float>(0.5 + 0.1 * ((x * 7 + y * 3) % 5));
    }
  return image;
}

TEST(WangFiltering, ShaderOnFetchedChannelsNearATexelCentreIsTheDecodedTexel) {
  const Image image = hdr_ramp(10, 9);
  const Format& format = wang_format();
  for (const char* residual : {"s", "ratio", "none"}) {
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, {{"residual", residual}}), CodecContext{1, 1});
    const Image decoded = format.decode(texture, CodecContext{1, 1});
    const wang::FetchedTextures fetched = wang::fetch_textures(texture);
    // Offset 1e-9: the sample is texel (x, y) up to a weight of 1e-9 on its neighbours.
    const Image shaded = wang::magnify_shaded(wang::decode_setup(texture), fetched, {1e-9});
    ASSERT_EQ(shaded.width, 9);
    ASSERT_EQ(shaded.height, 8);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 9; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(shaded.texel(x, y)[c], decoded.texel(x, y)[c], 1e-5 * (1.0 + decoded.texel(x, y)[c]))
              << residual << " texel " << x << "," << y;
  }
}

TEST(WangFiltering, MagnifiedRgbUsesBilinearWeightsBetweenTexelCentres) {
  Image image(2, 2, 3);
  const float corners[4] = {1.0f, 2.0f, 4.0f, 8.0f};   // (0,0), (1,0), (0,1), (1,1)
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) image.texel(k % 2, k / 2)[c] = corners[k] * static_cast<float>(c + 1);
  const Image magnified = wang::magnify_rgb(image, {0.25, 0.5});
  ASSERT_EQ(magnified.width, 2);
  ASSERT_EQ(magnified.height, 2);
  const double fx = 0.25, fy = 0.5;   // pixel (0, 1)
  const double expected = (1 - fx) * (1 - fy) * 1 + fx * (1 - fy) * 2 + (1 - fx) * fy * 4 + fx * fy * 8;
  EXPECT_NEAR(magnified.texel(0, 1)[0], expected, 1e-6);
  EXPECT_NEAR(magnified.texel(0, 1)[2], 3 * expected, 1e-5);
  EXPECT_THROW(wang::magnify_rgb(image, {1.0}), Error);
  EXPECT_THROW(wang::magnify_rgb(Image(1, 5, 3), {0.5}), Error);
}

TEST(WangFiltering, SameDirectionCountsEveryAdjacentPairOnce) {
  // R, G, B all grow with x and are constant in y: every pair goes in the same direction as L (vertical pairs have
  // dP = dL = 0, which counts as the same direction).
  Image image(5, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = static_cast<float>((x + 1) * (c + 1));
  const Format& format = wang_format();
  const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{1, 1});
  const wang::SameDirection counts =
      wang::same_direction(image, wang::decode_setup(texture), wang::fetch_textures(texture));
  const std::size_t pairs = 4 * 4 + 5 * 3;
  EXPECT_EQ(counts.rgb_pairs, 3 * pairs);
  EXPECT_EQ(counts.rgb_same, 3 * pairs);
  EXPECT_EQ(counts.s_pairs, pairs);
  EXPECT_LE(counts.s_same, pairs);
  EXPECT_DOUBLE_EQ(counts.rgb_fraction(), 1.0);
}

}  // namespace
}  // namespace blocklab
