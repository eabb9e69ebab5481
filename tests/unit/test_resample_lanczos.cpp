// Lanczos resampling (core/resample.h, core/resample_lanczos.cpp): a constant image stays constant, a linear ramp
// stays linear away from the edges (exactly where the taps sit symmetrically around the centre, as at a 2x shrink,
// and within a stated fraction of a texel step otherwise), the same size reproduces the source, edges clamp (the
// result equals the interior of resizing the source padded by replicating its border), and bad sizes are Errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/resample.h"

namespace blocklab {
namespace {

// R = slope * x, G = slope * y, B = 0.3 + 0.4 slope x - 0.3 slope y (source texel coordinates).
constexpr double kSlope = 0.01;

Image ramp(int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* texel = image.texel(x, y);
      texel[0] = static_cast<float>(kSlope * x);
      texel[1] = static_cast<float>(kSlope * y);
      texel[2] = static_cast<float>(0.3 + 0.4 * kSlope * x - 0.3 * kSlope * y);
    }
  return image;
}

Image pattern(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < (channels == 4 ? 4 : 3); ++c)
        image.texel(x, y)[c] = static_cast<float>(0.5 + 0.5 * std::sin(0.9 * x + 1.7 * y + 2.1 * c));
  return image;
}

// Largest deviation from the ramp, in texel steps (deviation / kSlope), over destination texels whose Lanczos
// support (3 source texels stretched by the shrink factor) lies inside the source.
double interior_ramp_deviation_in_texel_steps(int source_width, int source_height, int width, int height) {
  const Image result = lanczos_resize(ramp(source_width, source_height), width, height);
  const double rx = static_cast<double>(source_width) / width, ry = static_cast<double>(source_height) / height;
  const double support_x = 3.0 * std::max(1.0, rx), support_y = 3.0 * std::max(1.0, ry);
  double worst = 0.0;
  int checked = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) * rx - 0.5, v = (y + 0.5) * ry - 0.5;
      if (u < support_x || u > source_width - 1 - support_x || v < support_y || v > source_height - 1 - support_y)
        continue;
      const float* texel = result.texel(x, y);
      const double expected[3] = {kSlope * u, kSlope * v, 0.3 + 0.4 * kSlope * u - 0.3 * kSlope * v};
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(texel[c] - expected[c]) / kSlope);
      ++checked;
    }
  EXPECT_GT(checked, 100);
  return worst;
}

TEST(ResampleLanczos, AConstantImageStaysConstantAtEveryScaleAndLobeCount) {
  for (const int lobes : {2, 3, 4}) {
    for (const int width : {71, 50, 86, 1, 140}) {
      Image constant(100, 60, 4);
      for (std::size_t i = 0; i < constant.pixels.size(); ++i) constant.pixels[i] = (i % 4 == 3) ? 0.25f : 0.6f;
      const Image result = lanczos_resize(constant, width, 37, lobes);
      ASSERT_EQ(result.width, width);
      ASSERT_EQ(result.height, 37);
      EXPECT_EQ(result.channels, 4);
      for (std::size_t i = 0; i < result.pixels.size(); ++i)
        ASSERT_FLOAT_EQ(result.pixels[i], (i % 4 == 3) ? 0.25f : 0.6f)
            << "lobes " << lobes << " width " << width << " float " << i;
    }
  }
}

TEST(ResampleLanczos, ALinearRampStaysLinearAwayFromTheEdges) {
  // At a 2x shrink every destination centre sits halfway between two source texels: symmetric taps, exact.
  EXPECT_LT(interior_ramp_deviation_in_texel_steps(100, 60, 50, 30), 1e-4);
  // At other factors the taps are asymmetric and the discrete kernel's first moment is not exactly zero: the
  // ramp is reproduced to a few hundredths of a texel step (measured 0.003 at 71 %, 0.024 at 86 %, 0.038 at 140 %).
  EXPECT_LT(interior_ramp_deviation_in_texel_steps(100, 60, 71, 43), 0.01);
  EXPECT_LT(interior_ramp_deviation_in_texel_steps(100, 60, 86, 52), 0.05);
  EXPECT_LT(interior_ramp_deviation_in_texel_steps(100, 60, 140, 84), 0.05);
}

TEST(ResampleLanczos, TheSameSizeReproducesTheSource) {
  const Image source = pattern(23, 17, 3);
  const Image result = lanczos_resize(source, 23, 17);
  for (std::size_t i = 0; i < source.pixels.size(); ++i) ASSERT_NEAR(result.pixels[i], source.pixels[i], 1e-6) << i;
}

TEST(ResampleLanczos, EdgesClampAsIfTheBorderWereReplicated) {
  // Shrinking by 2 the source padded by 12 replicated texels on each side gives the unpadded result plus 6
  // destination texels on each side: the taps beyond the edge read the edge texel.
  constexpr int kPad = 12;
  const Image source = pattern(30, 22, 3);
  Image padded(30 + 2 * kPad, 22 + 2 * kPad, 3);
  for (int y = 0; y < padded.height; ++y)
    for (int x = 0; x < padded.width; ++x) {
      const int sx = std::clamp(x - kPad, 0, 29), sy = std::clamp(y - kPad, 0, 21);
      std::copy(source.texel(sx, sy), source.texel(sx, sy) + 4, padded.texel(x, y));
    }
  const Image result = lanczos_resize(source, 15, 11);
  const Image padded_result = lanczos_resize(padded, 15 + kPad, 11 + kPad);
  for (int y = 0; y < 11; ++y)
    for (int x = 0; x < 15; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(result.texel(x, y)[c], padded_result.texel(x + kPad / 2, y + kPad / 2)[c], 1e-6)
            << x << "," << y << " channel " << c;
}

TEST(ResampleLanczos, OneChannelImagesKeepGreyTexelsAndAlphaOne) {
  Image grey(40, 30, 1);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      float* texel = grey.texel(x, y);
      texel[0] = texel[1] = texel[2] = static_cast<float>((x * 7 + y * 3) % 11) / 10.0f;
    }
  const Image result = lanczos_resize(grey, 29, 21);
  EXPECT_EQ(result.channels, 1);
  for (int y = 0; y < 21; ++y)
    for (int x = 0; x < 29; ++x) {
      const float* texel = result.texel(x, y);
      ASSERT_EQ(texel[0], texel[1]);
      ASSERT_EQ(texel[0], texel[2]);
      ASSERT_EQ(texel[3], 1.0f);
    }
}

TEST(ResampleLanczos, BadSizesAreErrors) {
  const Image source = pattern(8, 8, 3);
  EXPECT_THROW(lanczos_resize(source, 0, 4), Error);
  EXPECT_THROW(lanczos_resize(source, 4, -1), Error);
  EXPECT_THROW(lanczos_resize(Image(), 4, 4), Error);
  Image short_pixels = source;
  short_pixels.pixels.pop_back();
  EXPECT_THROW(lanczos_resize(short_pixels, 4, 4), Error);
  EXPECT_THROW(lanczos_resize(source, 4, 4, 0), Error);
  EXPECT_THROW(lanczos_resize(source, 4, 4, 9), Error);
}

}  // namespace
}  // namespace blocklab
