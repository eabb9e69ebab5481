// The wavelet plane codec of `mavridis` (mavridis_plane_codec.h; paper sections 3.1-3.3).
#include "formats/mavridis/mavridis_plane_codec.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "formats/bc3/bc3_block.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_mode_search.h"
#include "formats/mavridis/mavridis_coefficient_problem.h"
#include "solvers/registry.h"

namespace blocklab {
namespace mavridis {

Coefficients transform_plane(const Plane& plane, const WaveletSettings& settings) {
  Coefficients c;
  c.groups_x = wavelet_blocks_x(plane.width) * 4;
  c.groups_y = wavelet_blocks_x(plane.height) * 4;
  for (auto& band : c.bands) band.resize(static_cast<std::size_t>(c.groups_x) * c.groups_y);
  // Edge replication: a texel beyond the plane takes the nearest one inside it.
  auto texel = [&](int x, int y) { return plane.at(std::min(x, plane.width - 1), std::min(y, plane.height - 1)); };
  for (int gy = 0; gy < c.groups_y; ++gy)
    for (int gx = 0; gx < c.groups_x; ++gx) {
      std::array<double, 4> h;
      if (settings.transform == Transform::plhaar) {
        // Integer, range-preserving: the texels are rounded and offset into the domain's signed range.
        const int lo = -settings.domain.half, hi = settings.domain.half - 1;
        auto integer = [&](int x, int y) {
          return std::clamp(static_cast<int>(std::lround(texel(x, y))) - settings.domain.offset, lo, hi);
        };
        const std::array<int, 4> p = plhaar_group_forward(integer(2 * gx, 2 * gy), integer(2 * gx + 1, 2 * gy),
                                                          integer(2 * gx, 2 * gy + 1), integer(2 * gx + 1, 2 * gy + 1));
        for (int k = 0; k < 4; ++k) h[k] = static_cast<double>(p[k]);
      } else if (settings.transform == Transform::s_transform) {
        // Integer transform: the texels are rounded to integers first.
        auto integer = [&](int x, int y) { return static_cast<long long>(std::llround(texel(x, y))); };
        const std::array<long long, 4> s = s_transform_forward(integer(2 * gx, 2 * gy), integer(2 * gx + 1, 2 * gy),
                                                               integer(2 * gx, 2 * gy + 1), integer(2 * gx + 1, 2 * gy + 1));
        for (int k = 0; k < 4; ++k) h[k] = static_cast<double>(s[k]);
      } else {
        h = haar_forward(texel(2 * gx, 2 * gy), texel(2 * gx + 1, 2 * gy), texel(2 * gx, 2 * gy + 1),
                         texel(2 * gx + 1, 2 * gy + 1));
        if (settings.packing == Packing::bc7)
          h = bc7_bands_from_haar(h, settings.transform == Transform::pi_haar);
        else if (settings.transform == Transform::pi_haar)
          h = pi_haar_from_haar(h, settings.w);
      }
      for (int k = 0; k < 4; ++k) c.bands[k][static_cast<std::size_t>(gy) * c.groups_x + gx] = h[k];
    }
  return c;
}

BandMapping band_mapping(const Coefficients& c, double clamp, double gamma) {
  BandMapping mapping;
  mapping.gamma = gamma;
  for (int k = 0; k < 4; ++k) {
    const auto range = std::minmax_element(c.bands[k].begin(), c.bands[k].end());
    const double lo = *range.first, hi = *range.second;
    mapping.centre[k] = 0.5 * (lo + hi);
    const double half = 0.5 * (hi - lo) * (k == 0 ? 1.0 : 1.0 - clamp);
    mapping.half_range[k] = std::max(half, 1e-6);   // a flat band still decodes (to its centre)
  }
  return mapping;
}

double quantise(double x, const BandMapping& mapping, int band) {
  const double n = std::clamp((x - mapping.centre[band]) / mapping.half_range[band], -1.0, 1.0);
  const double g = band == 0 ? 1.0 : mapping.gamma;
  const double magnitude = std::pow(std::abs(n), g);
  return 0.5 * (1.0 + (n < 0.0 ? -magnitude : magnitude));
}

namespace {

void encode_blocks_with(const Coefficients& c, const BandMapping& mapping, S3tcSearch search,
                        const WaveletSettings& settings, std::vector<std::uint8_t>& bytes) {
  const int threads = settings.threads;
  const Packing packing = settings.packing;
  const int blocks_x = c.groups_x / 4, blocks_y = c.groups_y / 4;
  bytes.assign(static_cast<std::size_t>(blocks_x) * blocks_y * 16, 0);
  ColorFitSettings color_settings;
  color_settings.search = search;
  color_settings.allow_three_color = false;
  const std::array<float, 3> unit_weights = {1.0f, 1.0f, 1.0f};
  parallel_for_index(static_cast<std::size_t>(blocks_x) * blocks_y, threads, [&](std::size_t index) {
    const int bx = static_cast<int>(index % static_cast<std::size_t>(blocks_x));
    const int by = static_cast<int>(index / static_cast<std::size_t>(blocks_x));
    if (packing == Packing::bc7) {
      // Section 3.1: quantisation weights 0.6 for LL, 0.2 for the two wavelet bands.
      std::uint8_t rgba[16][4];
      for (int i = 0; i < 16; ++i) {
        const std::size_t g =
            static_cast<std::size_t>(by * 4 + i / 4) * c.groups_x + static_cast<std::size_t>(bx * 4 + i % 4);
        for (int k = 0; k < 3; ++k)
          rgba[i][k] = static_cast<std::uint8_t>(std::lround(quantise(c.bands[k][g], mapping, k) * 255.0));
        rgba[i][3] = 255;
      }
      bc7::EncoderSettings bc7_settings;
      bc7_settings.partitions_to_refine = settings.bc7_partitions;
      bc7_settings.refine_iterations = settings.bc7_refine_iterations;
      bc7_settings.pbit_search = settings.bc7_pbit_search;
      const float weights[4] = {0.6f, 0.2f, 0.2f, 1.0f};
      for (int k = 0; k < 4; ++k) bc7_settings.weights[k] = weights[k];
      bc7::pack(bc7::encode_block(rgba, bc7_settings), bytes.data() + index * 16);
      return;
    }
    BlockTexels texels{};
    float alpha[16];
    for (int i = 0; i < 16; ++i) {
      const std::size_t g = static_cast<std::size_t>(by * 4 + i / 4) * c.groups_x + static_cast<std::size_t>(bx * 4 + i % 4);
      for (int k = 1; k < 4; ++k) texels.rgba[i][k - 1] = static_cast<float>(quantise(c.bands[k][g], mapping, k));
      texels.rgba[i][3] = 1.0f;
      alpha[i] = static_cast<float>(quantise(c.bands[0][g], mapping, 0) * 255.0);
    }
    Bc3Params params;
    params.color = fit_color_block(make_color_block(texels, unit_weights), color_settings);
    params.alpha = fit_bc4_block(alpha, search);
    pack_bc3_block(params, bytes.data() + index * 16);
  });
}

}  // namespace

double plane_squared_error(const Plane& plane, const Plane& decoded) {
  double sum = 0.0;
  for (std::size_t i = 0; i < plane.values.size(); ++i) {
    const double d = plane.values[i] - decoded.values[i];
    sum += d * d;
  }
  return sum;
}

namespace {

WaveletPlane encode_at(const Plane& plane, const Coefficients& c, const WaveletSettings& settings, double clamp,
                       double gamma, S3tcSearch search) {
  WaveletPlane coded;
  coded.mapping = band_mapping(c, clamp, gamma);
  coded.clamp = clamp;
  encode_blocks_with(c, coded.mapping, search, settings, coded.bytes);
  const Plane decoded = decode_wavelet_plane(coded.bytes.data(), plane.width, plane.height, coded.mapping,
                                             settings.transform, settings.w, settings.threads, settings.packing,
                                             settings.domain);
  coded.squared_error = plane_squared_error(plane, decoded);
  return coded;
}

}  // namespace

double wavelet_plane_error(const Plane& plane, const WaveletSettings& settings, double clamp, double gamma) {
  return encode_at(plane, transform_plane(plane, settings), settings, clamp, gamma, settings.search_effort)
      .squared_error;
}

WaveletPlane encode_wavelet_plane(const Plane& plane, const WaveletSettings& settings) {
  const Coefficients c = transform_plane(plane, settings);
  if (!settings.solver.empty()) {
    const CoefficientProblem problem(plane, settings);
    const double start[2] = {std::clamp(settings.clamps.at(0), 0.0, kClampUpper),
                             std::clamp(settings.gammas.at(0), kGammaLower, kGammaUpper)};
    const SolveResult solved = find_solver(settings.solver).solve(problem, settings.solver_options, start, settings.seed);
    const bool found = solved.parameters.size() == 2 && !std::isnan(solved.summary.final_error);
    return encode_at(plane, c, settings, found ? solved.parameters[0] : start[0],
                     found ? solved.parameters[1] : start[1], settings.final_search);
  }
  const bool search = settings.clamps.size() > 1 || settings.gammas.size() > 1;
  const S3tcSearch effort = search ? settings.search_effort : settings.final_search;
  WaveletPlane best;
  bool have_best = false;
  for (double clamp : settings.clamps)
    for (double gamma : settings.gammas) {
      WaveletPlane candidate = encode_at(plane, c, settings, clamp, gamma, effort);
      if (!have_best || candidate.squared_error < best.squared_error) {
        best = std::move(candidate);
        have_best = true;
      }
    }
  if (effort != settings.final_search) best = encode_at(plane, c, settings, best.clamp, best.mapping.gamma, settings.final_search);
  return best;
}

Plane decode_wavelet_plane(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping,
                           Transform transform, double w, int threads, Packing packing, PlhaarDomain domain) {
  Plane out = Plane::zeros(width, height);
  const int blocks_x = wavelet_blocks_x(width), blocks_y = wavelet_blocks_x(height);
  parallel_for_index(static_cast<std::size_t>(blocks_x) * blocks_y, threads, [&](std::size_t index) {
    const int bx = static_cast<int>(index % static_cast<std::size_t>(blocks_x));
    const int by = static_cast<int>(index / static_cast<std::size_t>(blocks_x));
    BlockTexels stored{};
    int bc7_texels[16][4] = {};
    if (packing == Packing::bc7)
      bc7::decode(bc7::unpack(bytes + index * 16), bc7_texels);
    else
      stored = decode_bc3_params(unpack_bc3_block(bytes + index * 16));
    // Every DXT5 value is a multiple of 1 / (255 * 105) (thirds of the colour palette, fifths and sevenths of the
    // alpha palette); the floats are snapped back to those exact fractions.
    auto exact = [](float value) { return std::round(static_cast<double>(value) * 26775.0) / 26775.0; };
    for (int i = 0; i < 16; ++i) {
      std::array<double, 4> band;
      if (packing == Packing::bc7) {
        for (int k = 0; k < 3; ++k)
          band[k] = dequantise<double>(bc7_texels[i][k] / 255.0, mapping.centre[k], mapping.half_range[k],
                                       k == 0 ? 1.0 : mapping.gamma);
        band[3] = 0.0;
        const std::array<double, 4> haar = haar_from_bc7_bands(band, transform == Transform::pi_haar);
        for (int k = 0; k < 4; ++k) {
          const int x = (bx * 4 + i % 4) * 2 + k % 2, y = (by * 4 + i / 4) * 2 + k / 2;
          if (x < width && y < height)
            out.values[static_cast<std::size_t>(y) * width + x] = reconstruct_texel(haar, k % 2, k / 2);
        }
        continue;
      }
      band[0] = dequantise<double>(exact(stored.rgba[i][3]), mapping.centre[0], mapping.half_range[0], 1.0);
      for (int k = 1; k < 4; ++k)
        band[k] = dequantise<double>(exact(stored.rgba[i][k - 1]), mapping.centre[k], mapping.half_range[k],
                                     mapping.gamma);
      std::array<double, 4> texels;
      if (transform == Transform::plhaar) {
        std::array<int, 4> integers;
        for (int k = 0; k < 4; ++k)
          integers[k] = static_cast<int>(std::clamp(std::round(band[k]), -double(domain.half), domain.half - 1.0));
        const std::array<int, 4> abcd = plhaar_group_inverse(integers);
        for (int k = 0; k < 4; ++k) texels[k] = static_cast<double>(abcd[k] + domain.offset);
      } else if (transform == Transform::s_transform) {
        std::array<long long, 4> integers;
        for (int k = 0; k < 4; ++k) integers[k] = std::llround(std::clamp(band[k], -1e9, 1e9));
        const std::array<long long, 4> abcd = s_transform_inverse(integers);
        for (int k = 0; k < 4; ++k) texels[k] = static_cast<double>(abcd[k]);
      } else {
        const std::array<double, 4> haar = transform == Transform::pi_haar ? haar_from_pi_haar(band, w) : band;
        // Texel (u, v) of the group: eq. 3 takes the parity of the coordinates.
        for (int k = 0; k < 4; ++k) texels[k] = reconstruct_texel(haar, k % 2, k / 2);
      }
      for (int k = 0; k < 4; ++k) {
        const int x = (bx * 4 + i % 4) * 2 + k % 2, y = (by * 4 + i / 4) * 2 + k / 2;
        if (x < width && y < height) out.values[static_cast<std::size_t>(y) * width + x] = texels[k];
      }
    }
  });
  return out;
}

}  // namespace mavridis
}  // namespace blocklab
