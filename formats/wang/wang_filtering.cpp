// Filtering of the `wang` textures: fetched channels, magnified shader output and RGB, Appendix B's same-direction
// pairs (formats/wang/wang_filtering.h).
#include "formats/wang/wang_filtering.h"

#include <cmath>
#include <string>

#include "core/blocks.h"
#include "core/error.h"

namespace blocklab {
namespace wang {

namespace {

void check_magnification(int width, int height, const std::vector<double>& offsets) {
  if (width < 2 || height < 2)
    fail("wang filtering", "the image is " + std::to_string(width) + "x" + std::to_string(height) +
                               "; bilinear samples between texels need at least 2x2");
  if (offsets.empty()) fail("wang filtering", "no sample offsets");
  for (double offset : offsets)
    if (!(offset > 0.0 && offset < 1.0))
      fail("wang filtering", "sample offset " + std::to_string(offset) + " is not in (0, 1)");
}

// Bilinear mix of `count` floats of four texels (upper left a, upper right b, lower left c, lower right d).
void bilinear(const float* a, const float* b, const float* c, const float* d, double fx, double fy, int count,
              float* out) {
  const float w00 = static_cast<float>((1.0 - fx) * (1.0 - fy)), w10 = static_cast<float>(fx * (1.0 - fy));
  const float w01 = static_cast<float>((1.0 - fx) * fy), w11 = static_cast<float>(fx * fy);
  for (int k = 0; k < count; ++k) out[k] = ((w00 * a[k] + w10 * b[k]) + w01 * c[k]) + w11 * d[k];
}

// Calls sample(x, y, i, j, out) for every magnified pixel (x n + i, y n + j) of a width x height source.
template <typename Sample>
Image magnify(int width, int height, const std::vector<double>& offsets, Sample sample) {
  check_magnification(width, height, offsets);
  const int n = static_cast<int>(offsets.size());
  Image out((width - 1) * n, (height - 1) * n, 3);
  for (int y = 0; y + 1 < height; ++y)
    for (int x = 0; x + 1 < width; ++x)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          float* pixel = out.texel(x * n + i, y * n + j);
          sample(x, y, offsets[i], offsets[j], pixel);
          pixel[3] = 1.0f;
        }
  return out;
}

bool same_sign_or_zero(double dp, double dl) { return dp * dl >= 0.0; }

}  // namespace

FetchedTextures fetch_textures(const EncodedTexture& texture) {
  const BlockGrid grid(texture.width, texture.height);
  if (texture.blocks.size() != grid.block_count() * static_cast<std::size_t>(kBlockBytes))
    fail("wang filtering", "the texture holds " + std::to_string(texture.blocks.size()) + " bytes, expected " +
                               std::to_string(grid.block_count() * kBlockBytes));
  FetchedTextures out;
  out.width = texture.width;
  out.height = texture.height;
  out.tex0.resize(static_cast<std::size_t>(texture.width) * texture.height * 4);
  out.tex1.resize(out.tex0.size());
  for (std::size_t block = 0; block < grid.block_count(); ++block) {
    BlockTexels halves[2];
    fetch_block_bytes(texture.blocks.data() + block * kBlockBytes, halves);
    const int bx = static_cast<int>(block % static_cast<std::size_t>(grid.blocks_x)) * 4;
    const int by = static_cast<int>(block / static_cast<std::size_t>(grid.blocks_x)) * 4;
    for (int texel = 0; texel < kBlockTexels; ++texel) {
      const int x = bx + texel % 4, y = by + texel / 4;
      if (x >= texture.width || y >= texture.height) continue;
      const std::size_t at = (static_cast<std::size_t>(y) * texture.width + x) * 4;
      for (int k = 0; k < 4; ++k) {
        out.tex0[at + k] = halves[0].rgba[texel][k];
        out.tex1[at + k] = halves[1].rgba[texel][k];
      }
    }
  }
  return out;
}

Image magnify_shaded(const DecodeSetup& setup, const FetchedTextures& fetched, const std::vector<double>& offsets) {
  const std::size_t row = static_cast<std::size_t>(fetched.width) * 4;
  return magnify(fetched.width, fetched.height, offsets, [&](int x, int y, double fx, double fy, float* rgb) {
    const std::size_t at = static_cast<std::size_t>(y) * row + static_cast<std::size_t>(x) * 4;
    float t0[4], t1[4];
    const float* s0 = &fetched.tex0[at];
    const float* s1 = &fetched.tex1[at];
    bilinear(s0, s0 + 4, s0 + row, s0 + row + 4, fx, fy, 4, t0);
    bilinear(s1, s1 + 4, s1 + row, s1 + row + 4, fx, fy, 4, t1);
    shade_texel(setup.constants, setup.space, setup.residual, t0, t1, rgb);
  });
}

Image magnify_rgb(const Image& image, const std::vector<double>& offsets) {
  return magnify(image.width, image.height, offsets, [&](int x, int y, double fx, double fy, float* rgb) {
    bilinear(image.texel(x, y), image.texel(x + 1, y), image.texel(x, y + 1), image.texel(x + 1, y + 1), fx, fy, 3,
             rgb);
  });
}

SameDirection same_direction(const Image& source, const DecodeSetup& setup, const FetchedTextures& fetched) {
  if (source.width != fetched.width || source.height != fetched.height)
    fail("wang filtering", "the source image and the texture differ in size");
  const std::size_t count = source.texel_count();
  std::vector<double> luminance(count), residual(count), decoded(count);
  for (std::size_t i = 0; i < count; ++i) {
    luminance[i] = to_luminance_chroma(setup.space, &source.pixels[i * 4]).luminance;
    const float* t1 = &fetched.tex1[i * 4];
    decoded[i] = shader_luminance(setup.constants, Residual::none, fetched.tex0[i * 4 + 3], t1[3], t1);
    residual[i] = luminance[i] - decoded[i];
  }
  SameDirection out;
  const auto pair = [&](std::size_t a, std::size_t b) {
    const double dl = luminance[b] - luminance[a];
    for (int channel = 0; channel < 3; ++channel) {
      ++out.rgb_pairs;
      out.rgb_same += same_sign_or_zero(source.pixels[b * 4 + channel] - source.pixels[a * 4 + channel], dl);
    }
    ++out.s_pairs;
    out.s_same += same_sign_or_zero(residual[b] - residual[a], decoded[b] - decoded[a]);
  };
  const std::size_t width = static_cast<std::size_t>(source.width);
  for (std::size_t y = 0; y < static_cast<std::size_t>(source.height); ++y)
    for (std::size_t x = 0; x < width; ++x) {
      if (x + 1 < width) pair(y * width + x, y * width + x + 1);
      if (y + 1 < static_cast<std::size_t>(source.height)) pair(y * width + x, (y + 1) * width + x);
    }
  return out;
}

}  // namespace wang
}  // namespace blocklab
