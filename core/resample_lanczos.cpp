// Lanczos resampling (core/resample.h): the windowed-sinc filter of C. E. Duchon, "Lanczos filtering in one and two
// dimensions", J. Applied Meteorology 18 (1979), with a lobes (3 by default), applied separably (rows, then
// columns), stretched by 1 / f when shrinking by f < 1 so that it low-passes at the destination's Nyquist frequency.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "core/resample.h"

namespace blocklab {

namespace {

constexpr double kPi = 3.14159265358979323846;

double sinc(double t) { return t == 0.0 ? 1.0 : std::sin(kPi * t) / (kPi * t); }

double lanczos(double t, double lobes) { return std::abs(t) < lobes ? sinc(t) * sinc(t / lobes) : 0.0; }

// The taps of one destination index along one axis: source indices (already clamped to the edge) and normalised
// weights.
struct Taps {
  std::vector<int> index;
  std::vector<double> weight;
};

std::vector<Taps> axis_taps(int source_size, int size, double lobes) {
  const double ratio = static_cast<double>(source_size) / size;   // source texels per destination texel
  const double stretch = ratio > 1.0 ? ratio : 1.0;               // kernel widening when shrinking
  const double support = lobes * stretch;
  std::vector<Taps> taps(static_cast<std::size_t>(size));
  for (int x = 0; x < size; ++x) {
    const double centre = (x + 0.5) * ratio - 0.5;
    Taps& t = taps[static_cast<std::size_t>(x)];
    double sum = 0.0;
    for (int i = static_cast<int>(std::floor(centre - support)); i <= static_cast<int>(std::ceil(centre + support));
         ++i) {
      const double w = lanczos((i - centre) / stretch, lobes);
      if (w == 0.0) continue;
      const int clamped = i < 0 ? 0 : (i >= source_size ? source_size - 1 : i);
      // Taps beyond the edge read the edge texel: merge them into its weight.
      if (!t.index.empty() && t.index.back() == clamped) {
        t.weight.back() += w;
      } else {
        t.index.push_back(clamped);
        t.weight.push_back(w);
      }
      sum += w;
    }
    for (double& w : t.weight) w /= sum;
  }
  return taps;
}

}  // namespace

Image lanczos_resize(const Image& source, int width, int height, int lobes) {
  check_resize_arguments(source, width, height, "lanczos_resize");
  if (lobes < 1 || lobes > 8) fail("lanczos_resize", "lobes must be in 1..8, got " + std::to_string(lobes));
  const std::vector<Taps> columns = axis_taps(source.width, width, lobes);
  const std::vector<Taps> rows = axis_taps(source.height, height, lobes);

  // Rows first: width x source.height, in double.
  std::vector<double> horizontal(static_cast<std::size_t>(width) * source.height * 4, 0.0);
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < width; ++x) {
      const Taps& t = columns[static_cast<std::size_t>(x)];
      double* out = &horizontal[(static_cast<std::size_t>(y) * width + x) * 4];
      for (std::size_t k = 0; k < t.index.size(); ++k) {
        const float* texel = source.texel(t.index[k], y);
        for (int c = 0; c < 4; ++c) out[c] += t.weight[k] * texel[c];
      }
    }

  Image result(width, height, source.channels);
  result.metadata = source.metadata;
  for (int y = 0; y < height; ++y) {
    const Taps& t = rows[static_cast<std::size_t>(y)];
    for (int x = 0; x < width; ++x) {
      double sum[4] = {0.0, 0.0, 0.0, 0.0};
      for (std::size_t k = 0; k < t.index.size(); ++k) {
        const double* in = &horizontal[(static_cast<std::size_t>(t.index[k]) * width + x) * 4];
        for (int c = 0; c < 4; ++c) sum[c] += t.weight[k] * in[c];
      }
      float* texel = result.texel(x, y);
      for (int c = 0; c < 4; ++c) texel[c] = static_cast<float>(sum[c]);
      if (!source.has_alpha()) texel[3] = 1.0f;
    }
  }
  return result;
}

}  // namespace blocklab
