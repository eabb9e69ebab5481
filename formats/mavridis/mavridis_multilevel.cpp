// Multi-level decomposition of a `mavridis` plane (mavridis_multilevel.h; paper section 3.4).
#include "formats/mavridis/mavridis_multilevel.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "formats/bc1/bc1_block.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {
namespace mavridis {

namespace {

// The scale coefficients of a level as the next level's plane (ceil(width / 2) x ceil(height / 2)).
Plane scale_plane(const Coefficients& c, int width, int height) {
  Plane ll;
  ll.width = (width + 1) / 2;
  ll.height = (height + 1) / 2;
  ll.values.resize(static_cast<std::size_t>(ll.width) * ll.height);
  for (int y = 0; y < ll.height; ++y)
    for (int x = 0; x < ll.width; ++x)
      ll.values[static_cast<std::size_t>(y) * ll.width + x] = c.bands[0][static_cast<std::size_t>(y) * c.groups_x + x];
  return ll;
}

// The three wavelet bands in the RGB of 4-colour DXT1 blocks (row-major over the groups).
std::vector<std::uint8_t> encode_detail_blocks(const Coefficients& c, const BandMapping& mapping, S3tcSearch search,
                                               int threads) {
  const int blocks_x = c.groups_x / 4, blocks_y = c.groups_y / 4;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(blocks_x) * blocks_y * 8, 0);
  ColorFitSettings fit;
  fit.search = search;
  fit.allow_three_color = false;
  const std::array<float, 3> unit_weights = {1.0f, 1.0f, 1.0f};
  parallel_for_index(static_cast<std::size_t>(blocks_x) * blocks_y, threads, [&](std::size_t index) {
    const int bx = static_cast<int>(index % static_cast<std::size_t>(blocks_x));
    const int by = static_cast<int>(index / static_cast<std::size_t>(blocks_x));
    BlockTexels texels{};
    for (int i = 0; i < 16; ++i) {
      const std::size_t g = static_cast<std::size_t>(by * 4 + i / 4) * c.groups_x + static_cast<std::size_t>(bx * 4 + i % 4);
      for (int k = 1; k < 4; ++k) texels.rgba[i][k - 1] = static_cast<float>(quantise(c.bands[k][g], mapping, k));
      texels.rgba[i][3] = 1.0f;
    }
    pack_bc1_block(canonicalise_bc1(fit_color_block(make_color_block(texels, unit_weights), fit)),
                   bytes.data() + index * 8);
  });
  return bytes;
}

// One detail level decoded onto its plane (width x height) from the decoded scale plane `ll`: eq. 3 per texel.
Plane decode_detail_level(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping, const Plane& ll,
                          Transform transform, double w, int threads) {
  Plane out = Plane::zeros(width, height);
  const int blocks_x = wavelet_blocks_x(width), blocks_y = wavelet_blocks_x(height);
  parallel_for_index(static_cast<std::size_t>(blocks_x) * blocks_y, threads, [&](std::size_t index) {
    const int bx = static_cast<int>(index % static_cast<std::size_t>(blocks_x));
    const int by = static_cast<int>(index / static_cast<std::size_t>(blocks_x));
    const BlockTexels stored = decode_bc1_params(unpack_bc1_block(bytes + index * 8));
    // DXT1 values are multiples of 1 / 1530 (thirds and halves of the bit-replicated 8-bit endpoints).
    auto exact = [](float value) { return std::round(static_cast<double>(value) * 1530.0) / 1530.0; };
    for (int i = 0; i < 16; ++i) {
      const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
      if (2 * gx >= width || 2 * gy >= height) continue;
      std::array<double, 4> band;
      band[0] = ll.at(gx, gy);
      for (int k = 1; k < 4; ++k)
        band[k] = dequantise<double>(exact(stored.rgba[i][k - 1]), mapping.centre[k], mapping.half_range[k],
                                     mapping.gamma);
      const std::array<double, 4> haar = transform == Transform::pi_haar ? haar_from_pi_haar(band, w) : band;
      for (int k = 0; k < 4; ++k) {
        const int x = 2 * gx + k % 2, y = 2 * gy + k / 2;
        if (x < width && y < height) out.values[static_cast<std::size_t>(y) * width + x] = reconstruct_texel(haar, k % 2, k / 2);
      }
    }
  });
  return out;
}

struct DetailLevel {
  std::vector<std::uint8_t> bytes;
  BandMapping mapping;
  double clamp = 0.0, squared_error = 0.0;
};

DetailLevel encode_detail_at(const Plane& plane, const Coefficients& c, const Plane& ll, const WaveletSettings& settings,
                             double clamp, double gamma, S3tcSearch search) {
  DetailLevel level;
  level.mapping = band_mapping(c, clamp, gamma);
  level.clamp = clamp;
  level.bytes = encode_detail_blocks(c, level.mapping, search, settings.threads);
  const Plane decoded = decode_detail_level(level.bytes.data(), plane.width, plane.height, level.mapping, ll,
                                            settings.transform, settings.w, settings.threads);
  level.squared_error = plane_squared_error(plane, decoded);
  return level;
}

}  // namespace

std::size_t multilevel_plane_bytes(int width, int height, int levels) {
  std::size_t bytes = 0;
  for (int k = 1; k < levels; ++k) bytes += detail_level_bytes(level_size(width, k - 1), level_size(height, k - 1));
  return bytes + wavelet_plane_bytes(level_size(width, levels - 1), level_size(height, levels - 1));
}

MultilevelPlane encode_multilevel_plane(const Plane& plane, const WaveletSettings& settings, int levels) {
  MultilevelPlane coded;
  WaveletSettings detail_settings = settings;
  detail_settings.packing = Packing::dxt5;   // the detail levels' bands are eq. 1 / eq. 2's three bands
  Plane current = plane;
  for (int k = 1; k < levels; ++k) {
    const Coefficients c = transform_plane(current, detail_settings);
    const Plane ll = scale_plane(c, current.width, current.height);
    // Section 3.2's grid search per level (as for the last level); the best point is re-encoded at the final search.
    const bool search = settings.clamps.size() > 1 || settings.gammas.size() > 1;
    const S3tcSearch effort = search ? settings.search_effort : settings.final_search;
    DetailLevel best;
    bool have_best = false;
    for (double clamp : settings.clamps)
      for (double gamma : settings.gammas) {
        DetailLevel candidate = encode_detail_at(current, c, ll, settings, clamp, gamma, effort);
        if (!have_best || candidate.squared_error < best.squared_error) {
          best = std::move(candidate);
          have_best = true;
        }
      }
    if (effort != settings.final_search)
      best = encode_detail_at(current, c, ll, settings, best.clamp, best.mapping.gamma, settings.final_search);
    coded.bytes.insert(coded.bytes.end(), best.bytes.begin(), best.bytes.end());
    coded.detail.push_back(best.mapping);
    coded.detail_clamp.push_back(best.clamp);
    coded.detail_error.push_back(best.squared_error);
    current = ll;
  }
  coded.last = encode_wavelet_plane(current, settings);
  coded.bytes.insert(coded.bytes.end(), coded.last.bytes.begin(), coded.last.bytes.end());
  return coded;
}

Plane decode_multilevel_plane(const std::uint8_t* bytes, int width, int height, const std::vector<BandMapping>& detail,
                              const BandMapping& last, Transform transform, double w, int threads, Packing packing) {
  const int levels = static_cast<int>(detail.size()) + 1;
  std::vector<std::size_t> offsets(1, 0);
  for (int k = 1; k < levels; ++k)
    offsets.push_back(offsets.back() + detail_level_bytes(level_size(width, k - 1), level_size(height, k - 1)));
  Plane current = decode_wavelet_plane(bytes + offsets.back(), level_size(width, levels - 1),
                                       level_size(height, levels - 1), last, transform, w, threads, packing);
  for (int k = levels - 1; k >= 1; --k)
    current = decode_detail_level(bytes + offsets[static_cast<std::size_t>(k - 1)], level_size(width, k - 1),
                                  level_size(height, k - 1), detail[static_cast<std::size_t>(k - 1)], current,
                                  transform, w, threads);
  return current;
}

}  // namespace mavridis
}  // namespace blocklab
