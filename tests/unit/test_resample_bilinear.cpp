// Bilinear resampling (core/resample.h, core/resample_bilinear.cpp): hand-computed values of a 2-texel row enlarged
// to 4, a constant image stays constant, a linear ramp stays exactly linear where the sample lies inside the source,
// texels beyond the edge centres clamp to the edge texel, the same size is the identity, bad sizes are Errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/resample.h"

namespace blocklab {
namespace {

TEST(ResampleBilinear, TwoTexelsEnlargedToFourGiveTheHandComputedValues) {
  // u = (x + 0.5) * 2 / 4 - 0.5 = -0.25, 0.25, 0.75, 1.25, clamped to 0, 0.25, 0.75, 1: 1, 0.75, 0.25, 0.
  Image row(2, 1, 1);
  for (int c = 0; c < 3; ++c) {
    row.texel(0, 0)[c] = 1.0f;
    row.texel(1, 0)[c] = 0.0f;
  }
  const Image result = bilinear_resize(row, 4, 1);
  const float expected[4] = {1.0f, 0.75f, 0.25f, 0.0f};
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(result.texel(x, 0)[0], expected[x]) << x;
    EXPECT_EQ(result.texel(x, 0)[3], 1.0f);
  }
}

TEST(ResampleBilinear, AConstantImageStaysConstant) {
  Image constant(13, 9, 4);
  for (std::size_t i = 0; i < constant.pixels.size(); ++i) constant.pixels[i] = (i % 4 == 3) ? 0.5f : 0.37f;
  for (const int width : {13, 18, 29, 7}) {
    const Image result = bilinear_resize(constant, width, 20);
    for (std::size_t i = 0; i < result.pixels.size(); ++i)
      ASSERT_EQ(result.pixels[i], (i % 4 == 3) ? 0.5f : 0.37f) << "width " << width << " float " << i;
  }
}

TEST(ResampleBilinear, ALinearRampStaysLinearWhereTheSampleIsInsideAndClampsBeyond) {
  // R = x / 64 and G = y / 64 (exact in float); enlarged from 9 x 7 to 20 x 16.
  Image ramp(9, 7, 3);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) {
      ramp.texel(x, y)[0] = static_cast<float>(x) / 64.0f;
      ramp.texel(x, y)[1] = static_cast<float>(y) / 64.0f;
    }
  const Image result = bilinear_resize(ramp, 20, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 20; ++x) {
      const double u = (x + 0.5) * 9.0 / 20.0 - 0.5, v = (y + 0.5) * 7.0 / 16.0 - 0.5;
      // Inside: the ramp's value at (u, v); outside the texel centres: the edge value (clamp).
      const double clamped_u = std::min(std::max(u, 0.0), 8.0), clamped_v = std::min(std::max(v, 0.0), 6.0);
      EXPECT_NEAR(result.texel(x, y)[0], clamped_u / 64.0, 1e-7) << x << "," << y;
      EXPECT_NEAR(result.texel(x, y)[1], clamped_v / 64.0, 1e-7) << x << "," << y;
    }
  EXPECT_EQ(result.texel(0, 0)[0], 0.0f);            // u < 0: the edge texel exactly
  EXPECT_EQ(result.texel(19, 15)[0], 8.0f / 64.0f);   // u > 8
}

TEST(ResampleBilinear, TheSameSizeIsTheIdentity) {
  Image source(11, 5, 4);
  for (std::size_t i = 0; i < source.pixels.size(); ++i) source.pixels[i] = static_cast<float>((i * 37) % 101) / 100.0f;
  const Image result = bilinear_resize(source, 11, 5);
  EXPECT_EQ(result.pixels, source.pixels);
}

TEST(ResampleBilinear, BadSizesAreErrors) {
  const Image source(4, 4, 3);
  EXPECT_THROW(bilinear_resize(source, 0, 4), Error);
  EXPECT_THROW(bilinear_resize(source, 4, 70000), Error);
  EXPECT_THROW(bilinear_resize(Image(), 2, 2), Error);
}

}  // namespace
}  // namespace blocklab
