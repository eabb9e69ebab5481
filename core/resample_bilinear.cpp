// Bilinear resampling (core/resample.h): what a GPU's bilinear texture filter returns for a texture of the source's
// size sampled at the destination's texel centres with clamp-to-edge addressing (e.g. the OpenGL 4.6 specification,
// section 8.14.2, "Coordinate Wrapping and Texel Selection", LINEAR filter), evaluated in double precision.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/resample.h"

namespace blocklab {

namespace {

// Along one axis: the lower neighbour and the weight of the upper one for each destination index.
struct Neighbours {
  std::vector<int> lower;
  std::vector<double> upper_weight;
};

Neighbours axis_neighbours(int source_size, int size) {
  const double ratio = static_cast<double>(source_size) / size;
  Neighbours n;
  for (int x = 0; x < size; ++x) {
    const double u = std::clamp((x + 0.5) * ratio - 0.5, 0.0, static_cast<double>(source_size - 1));
    const int lower = std::min(static_cast<int>(std::floor(u)), source_size - 1);
    n.lower.push_back(lower);
    n.upper_weight.push_back(u - lower);
  }
  return n;
}

}  // namespace

Image bilinear_resize(const Image& source, int width, int height) {
  check_resize_arguments(source, width, height, "bilinear_resize");
  const Neighbours columns = axis_neighbours(source.width, width);
  const Neighbours rows = axis_neighbours(source.height, height);
  Image result(width, height, source.channels);
  result.metadata = source.metadata;
  for (int y = 0; y < height; ++y) {
    const int y0 = rows.lower[static_cast<std::size_t>(y)], y1 = std::min(y0 + 1, source.height - 1);
    const double ty = rows.upper_weight[static_cast<std::size_t>(y)];
    for (int x = 0; x < width; ++x) {
      const int x0 = columns.lower[static_cast<std::size_t>(x)], x1 = std::min(x0 + 1, source.width - 1);
      const double tx = columns.upper_weight[static_cast<std::size_t>(x)];
      const float* a = source.texel(x0, y0);
      const float* b = source.texel(x1, y0);
      const float* c = source.texel(x0, y1);
      const float* d = source.texel(x1, y1);
      float* out = result.texel(x, y);
      for (int k = 0; k < 4; ++k)
        out[k] = static_cast<float>((1.0 - ty) * ((1.0 - tx) * a[k] + tx * b[k]) + ty * ((1.0 - tx) * c[k] + tx * d[k]));
      if (!source.has_alpha()) out[3] = 1.0f;
    }
  }
  return result;
}

}  // namespace blocklab
