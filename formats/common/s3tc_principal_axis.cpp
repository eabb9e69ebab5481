// Principal axis of a block's colours (formats/common/s3tc_color_fit.h, step 2): the dominant eigenvector of the
// 3x3 covariance of the channel-weighted colours sqrt(w_c) x_c, found by power iteration (the covariance is
// symmetric positive semi-definite, so iteration from a vector with a component along the dominant eigenvector
// converges to it; the start is the covariance row of largest diagonal, which has such a component whenever the
// covariance is non-zero). The returned vector is the projection direction in RGB space,
// p_c = sqrt(w_c) v_c, so that dot(x, p) orders texels along the weighted principal axis.
#include <cmath>

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

std::array<float, 3> principal_axis(const ColorBlock& block) {
  float scale[3];
  for (int channel = 0; channel < 3; ++channel) scale[channel] = std::sqrt(block.weights[channel]);
  float mean[3] = {0, 0, 0};
  for (int texel = 0; texel < 16; ++texel)
    for (int channel = 0; channel < 3; ++channel) mean[channel] += scale[channel] * block.texels[texel][channel];
  for (float& value : mean) value /= 16.0f;
  float covariance[3][3] = {};
  for (int texel = 0; texel < 16; ++texel) {
    float d[3];
    for (int channel = 0; channel < 3; ++channel) d[channel] = scale[channel] * block.texels[texel][channel] - mean[channel];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) covariance[r][c] += d[r] * d[c];
  }
  int start_row = 0;
  for (int r = 1; r < 3; ++r)
    if (covariance[r][r] > covariance[start_row][start_row]) start_row = r;
  float vector[3] = {covariance[start_row][0], covariance[start_row][1], covariance[start_row][2]};
  // (Almost) no variance: any axis orders the texels equally well; use the grey diagonal.
  const float trace = covariance[0][0] + covariance[1][1] + covariance[2][2];
  if (!(trace > 1e-6f)) return {scale[0], scale[1], scale[2]};
  for (int iteration = 0; iteration < 8; ++iteration) {
    float next[3];
    for (int r = 0; r < 3; ++r)
      next[r] = covariance[r][0] * vector[0] + covariance[r][1] * vector[1] + covariance[r][2] * vector[2];
    const float norm = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
    // The start row can be orthogonal to the dominant eigenvector only if the covariance vanishes along it
    // (checked above via the trace); a zero product here means numerical underflow: keep the last vector.
    if (!(norm > 1e-20f)) break;
    for (int r = 0; r < 3; ++r) vector[r] = next[r] / norm;
  }
  return {scale[0] * vector[0], scale[1] * vector[1], scale[2] * vector[2]};
}

}  // namespace blocklab
