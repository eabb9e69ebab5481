// Endpoint fitting for one BC7 subset (see bc7_endpoint_fit.h): PCA start, quantisation with P-bits, index
// assignment and least-squares refinement.
#include "formats/bc7/bc7_endpoint_fit.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "formats/bc7/bc7_endpoint_polish.h"
#include "formats/bc7/bc7_endpoint_rounding.h"
#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

namespace {

// nearest_index[bits][t] = index whose weight is nearest to t (0..64); ties to the lower index.
struct NearestIndexTable {
  std::uint8_t nearest[5][65];
  NearestIndexTable() {
    for (int bits = 2; bits <= 4; ++bits) {
      const int* weights = index_weights(bits);
      for (int t = 0; t <= 64; ++t) {
        int best = 0;
        for (int i = 1; i < (1 << bits); ++i)
          if (std::abs(weights[i] - t) < std::abs(weights[best] - t)) best = i;
        nearest[bits][t] = static_cast<std::uint8_t>(best);
      }
    }
  }
};

const NearestIndexTable& nearest_index_table() {
  static const NearestIndexTable table;
  return table;
}

// PCA start: the line through the mean along the principal axis of the weighted texels, cut at the extreme
// projections. Lanes with zero weight follow the axis by regression, so every stored lane gets endpoints.
void principal_axis_endpoints(const float (*texels)[4], int count, const float weights[4], float (&ideal)[2][4]) {
  float mean[4] = {0, 0, 0, 0};
  for (int i = 0; i < count; ++i)
    for (int lane = 0; lane < 4; ++lane) mean[lane] += texels[i][lane];
  for (float& value : mean) value /= static_cast<float>(count);
  float scale[4];
  for (int lane = 0; lane < 4; ++lane) scale[lane] = std::sqrt(weights[lane]);
  float covariance[4][4] = {};
  for (int i = 0; i < count; ++i) {
    float y[4];
    for (int lane = 0; lane < 4; ++lane) y[lane] = (texels[i][lane] - mean[lane]) * scale[lane];
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) covariance[a][b] += y[a] * y[b];
  }
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < a; ++b) covariance[a][b] = covariance[b][a];
  // Power iteration from the row of the largest variance.
  int start_lane = 0;
  for (int lane = 1; lane < 4; ++lane)
    if (covariance[lane][lane] > covariance[start_lane][start_lane]) start_lane = lane;
  float axis[4];
  for (int lane = 0; lane < 4; ++lane) axis[lane] = covariance[start_lane][lane];
  for (int iteration = 0; iteration < 6; ++iteration) {
    float next[4] = {0, 0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) next[a] += covariance[a][b] * axis[b];
    float largest = 0.0f;
    for (float value : next) largest = std::max(largest, std::fabs(value));
    // Zero covariance (all texels equal under the weights): keep the current axis; both endpoints end at the mean.
    if (largest <= 1e-20f) break;
    for (int lane = 0; lane < 4; ++lane) axis[lane] = next[lane] / largest;
  }
  // Projections t_i on the axis in the weighted space.
  float t[16];
  float t_min = 0.0f, t_max = 0.0f, t_square_sum = 0.0f;
  for (int i = 0; i < count; ++i) {
    float projection = 0.0f;
    for (int lane = 0; lane < 4; ++lane) projection += (texels[i][lane] - mean[lane]) * scale[lane] * axis[lane];
    t[i] = projection;
    t_min = i == 0 ? projection : std::min(t_min, projection);
    t_max = i == 0 ? projection : std::max(t_max, projection);
    t_square_sum += projection * projection;
  }
  for (int lane = 0; lane < 4; ++lane) {
    float direction = 0.0f;
    // A degenerate projection (constant colour, or an axis orthogonal to the data) gives direction 0: both
    // endpoints at the mean.
    if (t_square_sum > 1e-12f) {
      for (int i = 0; i < count; ++i) direction += (texels[i][lane] - mean[lane]) * t[i];
      direction /= t_square_sum;
    }
    ideal[0][lane] = std::clamp(mean[lane] + t_min * direction, 0.0f, 255.0f);
    ideal[1][lane] = std::clamp(mean[lane] + t_max * direction, 0.0f, 255.0f);
  }
}

struct Candidate {
  QuantisedEndpoints endpoints;
  std::uint8_t indices[16];
  float error;
};

// Quantises `ideal` with each P-bit candidate and keeps the best after index assignment.
Candidate evaluate_ideal(const float (*texels)[4], int count, const float ideal[2][4],
                         const SubsetFitSettings& settings, bool search_all_pbits) {
  int combos[4][2];
  const int combo_count = pbit_candidates(ideal, settings.lattice, settings.weights, search_all_pbits, combos);
  Candidate best;
  best.error = INFINITY;
  for (int c = 0; c < combo_count; ++c) {
    Candidate candidate;
    candidate.endpoints = quantise_endpoints(ideal, settings.lattice, combos[c][0], combos[c][1]);
    candidate.error =
        assign_indices(texels, count, candidate.endpoints, settings.index_bits, settings.weights, candidate.indices);
    if (candidate.error < best.error) best = candidate;
  }
  return best;
}

}  // namespace

namespace {

// Index assignment over the kLanes lanes listed in lane[] (the lanes with a positive weight), compiled once per
// lane count so the inner loops are fixed-length.
template <int kLanes>
float assign_indices_on_lanes(const float (*texels)[4], int count, const QuantisedEndpoints& endpoints,
                              int index_bits, const float weights[4], const int (&lane)[4], std::uint8_t* indices) {
  const int* index_weight = index_weights(index_bits);
  const int palette_size = 1 << index_bits;
  float w[kLanes], e0[kLanes], direction[kLanes];
  float palette[16][kLanes];
  float direction_square = 0.0f;
  for (int l = 0; l < kLanes; ++l) {
    w[l] = weights[lane[l]];
    e0[l] = static_cast<float>(endpoints.expanded[0][lane[l]]);
    direction[l] = static_cast<float>(endpoints.expanded[1][lane[l]]) - e0[l];
    direction_square += w[l] * direction[l] * direction[l];
    for (int k = 0; k < palette_size; ++k)
      palette[k][l] = static_cast<float>(
          interpolate(endpoints.expanded[0][lane[l]], endpoints.expanded[1][lane[l]], index_weight[k]));
  }
  const std::uint8_t* nearest = nearest_index_table().nearest[index_bits];
  const float to_weight = direction_square > 0.0f ? 64.0f / direction_square : 0.0f;
  const auto entry_error = [&](const float (&x)[kLanes], int k) {
    float error = 0.0f;
    for (int l = 0; l < kLanes; ++l) {
      const float difference = x[l] - palette[k][l];
      error += w[l] * difference * difference;
    }
    return error;
  };
  float total = 0.0f;
  for (int i = 0; i < count; ++i) {
    float x[kLanes];
    for (int l = 0; l < kLanes; ++l) x[l] = texels[i][lane[l]];
    int first = 0, last = palette_size - 1;
    if (direction_square <= 0.0f) {
      last = 0;   // equal endpoints (under the weights): every entry decodes alike, index 0
    } else if (palette_size > 4) {
      // Larger palettes: the projection t on the endpoint line picks the nearest entry, and the neighbour on the
      // other side of t is tried too, because the rounded palette is not exactly on the line (the distance along
      // the line is convex, so farther entries cannot win by more than the rounding). Small palettes try all.
      float projection = 0.0f;
      for (int l = 0; l < kLanes; ++l) projection += w[l] * (x[l] - e0[l]) * direction[l];
      const float t = std::clamp(projection * to_weight, 0.0f, 64.0f);
      const int centre = nearest[static_cast<int>(t + 0.5f)];
      const int other = t > static_cast<float>(index_weight[centre]) ? std::min(palette_size - 1, centre + 1)
                                                                    : std::max(0, centre - 1);
      // The two entries directly (no loop): ties keep the lower index.
      const float centre_error = entry_error(x, centre), other_error = entry_error(x, other);
      const bool take_other = other < centre ? !(centre_error < other_error) : other_error < centre_error;
      indices[i] = static_cast<std::uint8_t>(take_other ? other : centre);
      total += take_other ? other_error : centre_error;
      continue;
    }
    float best_error = INFINITY;
    int best_index = first;
    for (int k = first; k <= last; ++k) {
      const float error = entry_error(x, k);
      if (error < best_error) {   // strict: ties keep the lower index
        best_error = error;
        best_index = k;
      }
    }
    indices[i] = static_cast<std::uint8_t>(best_index);
    total += best_error;
  }
  return total;
}

}  // namespace

float assign_indices(const float (*texels)[4], int count, const QuantisedEndpoints& endpoints, int index_bits,
                     const float weights[4], std::uint8_t* indices) {
  int lane[4] = {0, 0, 0, 0};
  int lane_count = 0;
  for (int l = 0; l < 4; ++l)
    if (weights[l] > 0.0f) lane[lane_count++] = l;
  switch (lane_count) {
    case 1: return assign_indices_on_lanes<1>(texels, count, endpoints, index_bits, weights, lane, indices);
    case 2: return assign_indices_on_lanes<2>(texels, count, endpoints, index_bits, weights, lane, indices);
    case 3: return assign_indices_on_lanes<3>(texels, count, endpoints, index_bits, weights, lane, indices);
    case 4: return assign_indices_on_lanes<4>(texels, count, endpoints, index_bits, weights, lane, indices);
    default:
      // No lane counts: every index is equally good; index 0, error 0.
      for (int i = 0; i < count; ++i) indices[i] = 0;
      return 0.0f;
  }
}

bool least_squares_endpoints(const float (*texels)[4], int count, const std::uint8_t* indices, int index_bits,
                             float (&ideal)[2][4]) {
  const int* index_weight = index_weights(index_bits);
  float a = 0.0f, b = 0.0f, c = 0.0f;
  float right0[4] = {0, 0, 0, 0}, right1[4] = {0, 0, 0, 0};
  for (int i = 0; i < count; ++i) {
    const float f = static_cast<float>(index_weight[indices[i]]) / 64.0f;
    const float g = 1.0f - f;
    a += g * g;
    b += g * f;
    c += f * f;
    for (int lane = 0; lane < 4; ++lane) {
      right0[lane] += g * texels[i][lane];
      right1[lane] += f * texels[i][lane];
    }
  }
  const float determinant = a * c - b * b;
  // All texels on one weight: the 2x2 normal equations are singular; keep the previous endpoints.
  if (std::fabs(determinant) < 1e-6f) return false;
  for (int lane = 0; lane < 4; ++lane) {
    ideal[0][lane] = std::clamp((c * right0[lane] - b * right1[lane]) / determinant, 0.0f, 255.0f);
    ideal[1][lane] = std::clamp((a * right1[lane] - b * right0[lane]) / determinant, 0.0f, 255.0f);
  }
  return true;
}

void swap_endpoints(SubsetFit& fit, int index_bits, int count) {
  QuantisedEndpoints& e = fit.endpoints;
  for (int lane = 0; lane < 4; ++lane) {
    std::swap(e.codes[0][lane], e.codes[1][lane]);
    std::swap(e.expanded[0][lane], e.expanded[1][lane]);
  }
  std::swap(e.pbits[0], e.pbits[1]);
  const int top = (1 << index_bits) - 1;
  for (int i = 0; i < count; ++i) fit.indices[i] = static_cast<std::uint8_t>(top - fit.indices[i]);
}

SubsetFit fit_subset(const float (*texels)[4], int count, const SubsetFitSettings& settings) {
  float ideal[2][4];
  principal_axis_endpoints(texels, count, settings.weights, ideal);
  Candidate best = evaluate_ideal(texels, count, ideal, settings, false);
  float best_ideal[2][4];
  std::copy(&ideal[0][0], &ideal[0][0] + 8, &best_ideal[0][0]);
  for (int iteration = 0; iteration < settings.refine_iterations && best.error > 0.0f; ++iteration) {
    if (!least_squares_endpoints(texels, count, best.indices, settings.index_bits, ideal)) break;
    // Lattice codes and P-bits chosen for the indices the least squares assumed, then the indices re-assigned.
    Candidate candidate;
    float rounded_error;
    candidate.endpoints = round_endpoints_for_indices(texels, count, best.indices, settings.index_bits, ideal,
                                                      settings.lattice, settings.weights, settings.pbit_search,
                                                      &rounded_error);
    candidate.error = assign_indices(texels, count, candidate.endpoints, settings.index_bits, settings.weights,
                                     candidate.indices);
    if (!(candidate.error < best.error)) break;   // converged (or got worse): keep the best so far
    best = candidate;
    std::copy(&ideal[0][0], &ideal[0][0] + 8, &best_ideal[0][0]);
  }
  // P-bit search on the final ideal endpoints: every combination, each with one least-squares round of its own.
  if (settings.pbit_search && settings.lattice.pbit != PbitKind::none && !settings.lattice.force_pbit_one &&
      best.error > 0.0f) {
    const Candidate searched = evaluate_ideal(texels, count, best_ideal, settings, true);
    if (searched.error < best.error) best = searched;
    if (least_squares_endpoints(texels, count, best.indices, settings.index_bits, ideal)) {
      const int p0 = best.endpoints.pbits[0], p1 = best.endpoints.pbits[1];
      Candidate refit;
      refit.endpoints = quantise_endpoints(ideal, settings.lattice, p0, p1);
      refit.error = assign_indices(texels, count, refit.endpoints, settings.index_bits, settings.weights, refit.indices);
      if (refit.error < best.error) best = refit;
    }
  }
  if (settings.polish_passes > 0 && best.error > 0.0f)
    polish_endpoints(texels, count, settings.index_bits, settings.lattice, settings.weights, settings.polish_passes,
                     best.endpoints, best.indices, best.error);
  SubsetFit fit;
  fit.endpoints = best.endpoints;
  std::copy(best.indices, best.indices + count, fit.indices);
  fit.error = best.error;
  return fit;
}

}  // namespace bc7
}  // namespace blocklab
