// Second-stage partition estimate (see bc7_partition_palette_estimate.h).
#include "formats/bc7/bc7_partition_palette_estimate.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

// Squared error of the values t (n of them) against the palette a + (w_k / 64)(b - a), each value at the entry
// whose index is nearest to its position along [a, b] scaled to the index range (the BC7 weights are within 1/64
// of uniform, so this is the nearest entry up to rounding); writes each value's entry weight to f[] (0..1).
float palette_error(const float* t, int n, const int* index_weight, int palette_size, float a, float b, float* f) {
  const float range = b - a;
  const float to_index = static_cast<float>(palette_size - 1) / range;
  const float top = static_cast<float>(palette_size - 1);
  float weight_fraction[16];
  for (int k = 0; k < palette_size; ++k) weight_fraction[k] = static_cast<float>(index_weight[k]) / 64.0f;
  float total = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float position = (t[i] - a) * to_index + 0.5f;
    const int index = position <= 0.0f ? 0 : (position >= top ? palette_size - 1 : static_cast<int>(position));
    f[i] = weight_fraction[index];
    const float difference = t[i] - (a + f[i] * range);
    total += difference * difference;
  }
  return total;
}

// Error of a 1-D palette along the axis: endpoints at the extremes, then one least-squares round for the indices
// they give, with the indices re-assigned (the smaller error of the two).
float axis_palette_error(const float* t, int n, int index_bits) {
  if (n <= 1) return 0.0f;
  float a = t[0], b = t[0];
  for (int i = 1; i < n; ++i) a = t[i] < a ? t[i] : a, b = t[i] > b ? t[i] : b;
  if (!(b - a > 1e-6f)) return 0.0f;
  const int* index_weight = index_weights(index_bits);
  const int palette_size = 1 << index_bits;
  float f[16];
  const float extremes_error = palette_error(t, n, index_weight, palette_size, a, b, f);
  float aa = 0.0f, ab = 0.0f, bb = 0.0f, right_a = 0.0f, right_b = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float g = 1.0f - f[i];
    aa += g * g, ab += g * f[i], bb += f[i] * f[i];
    right_a += g * t[i], right_b += f[i] * t[i];
  }
  const float determinant = aa * bb - ab * ab;
  if (std::fabs(determinant) < 1e-6f) return extremes_error;   // every value on one entry: nothing to solve
  a = (bb * right_a - ab * right_b) / determinant;
  b = (aa * right_b - ab * right_a) / determinant;
  if (!(std::fabs(b - a) > 1e-6f)) return extremes_error;
  if (b < a) std::swap(a, b);
  const float fitted_error = palette_error(t, n, index_weight, palette_size, a, b, f);
  return fitted_error < extremes_error ? fitted_error : extremes_error;
}

}  // namespace

namespace {

// project_partition on the kLanes lanes listed in lane[] (those with a positive weight), compiled per lane count.
template <int kLanes>
void project_on_lanes(const float (&texels)[16][4], const float weights[4], const int (&lane)[4],
                      const std::uint8_t* subsets, PartitionProjection& projection) {
  float scale[kLanes];
  for (int l = 0; l < kLanes; ++l) scale[l] = std::sqrt(weights[lane[l]]);
  for (int subset = 0; subset < projection.subset_count; ++subset) {
    float y[16][kLanes];
    float mean[kLanes] = {};
    int n = 0;
    for (int texel = 0; texel < 16; ++texel)
      if (subsets[texel] == subset) {
        for (int l = 0; l < kLanes; ++l) y[n][l] = texels[texel][lane[l]] * scale[l], mean[l] += y[n][l];
        ++n;
      }
    projection.count[subset] = n;
    if (n == 0) continue;
    for (float& value : mean) value /= static_cast<float>(n);
    float covariance[kLanes][kLanes] = {};
    float total = 0.0f;
    for (int i = 0; i < n; ++i) {
      for (int l = 0; l < kLanes; ++l) y[i][l] -= mean[l];
      for (int a = 0; a < kLanes; ++a) {
        total += y[i][a] * y[i][a];
        for (int b = a; b < kLanes; ++b) covariance[a][b] += y[i][a] * y[i][b];
      }
    }
    for (int a = 0; a < kLanes; ++a)
      for (int b = 0; b < a; ++b) covariance[a][b] = covariance[b][a];
    // Principal axis by power iteration from the row of the largest variance (as bc7_endpoint_fit's PCA start).
    int start = 0;
    for (int l = 1; l < kLanes; ++l)
      if (covariance[l][l] > covariance[start][start]) start = l;
    float axis[kLanes];
    for (int l = 0; l < kLanes; ++l) axis[l] = covariance[start][l];
    for (int iteration = 0; iteration < 3; ++iteration) {
      float next[kLanes] = {};
      float largest = 0.0f;
      for (int a = 0; a < kLanes; ++a) {
        for (int b = 0; b < kLanes; ++b) next[a] += covariance[a][b] * axis[b];
        const float magnitude = std::fabs(next[a]);
        largest = magnitude > largest ? magnitude : largest;
      }
      if (largest <= 1e-20f) break;   // constant subset: any axis, every projection 0
      const float inverse_largest = 1.0f / largest;
      for (int l = 0; l < kLanes; ++l) axis[l] = next[l] * inverse_largest;
    }
    float norm = 0.0f;
    for (float value : axis) norm += value * value;
    const float inverse_norm = norm > 1e-20f ? 1.0f / std::sqrt(norm) : 0.0f;
    float along = 0.0f;
    for (int i = 0; i < n; ++i) {
      float t = 0.0f;
      for (int l = 0; l < kLanes; ++l) t += y[i][l] * axis[l];
      t *= inverse_norm;
      projection.t[subset][i] = t;
      along += t * t;
    }
    projection.line_error += total > along ? total - along : 0.0f;
  }
}

}  // namespace

PartitionProjection project_partition(const float (&texels)[16][4], const float weights[4], int subset_count,
                                      int partition) {
  PartitionProjection projection;
  projection.subset_count = subset_count;
  projection.line_error = 0.0f;
  const std::uint8_t* subsets = partition_subsets(subset_count, partition);
  int lane[4] = {0, 0, 0, 0};
  int lane_count = 0;
  for (int l = 0; l < 4; ++l)
    if (weights[l] > 0.0f) lane[lane_count++] = l;
  switch (lane_count) {
    case 1: project_on_lanes<1>(texels, weights, lane, subsets, projection); break;
    case 2: project_on_lanes<2>(texels, weights, lane, subsets, projection); break;
    case 3: project_on_lanes<3>(texels, weights, lane, subsets, projection); break;
    case 4: project_on_lanes<4>(texels, weights, lane, subsets, projection); break;
    default:   // no lane counts: every texel at 0 on any axis
      for (int subset = 0; subset < subset_count; ++subset) {
        projection.count[subset] = 0;
        for (int texel = 0; texel < 16; ++texel)
          if (partition_subsets(subset_count, partition)[texel] == subset) projection.t[subset][projection.count[subset]++] = 0.0f;
      }
  }
  return projection;
}

float palette_line_estimate(const PartitionProjection& projection, int index_bits) {
  float estimate = projection.line_error;
  for (int subset = 0; subset < projection.subset_count; ++subset)
    estimate += axis_palette_error(projection.t[subset], projection.count[subset], index_bits);
  return estimate;
}

}  // namespace bc7
}  // namespace blocklab
