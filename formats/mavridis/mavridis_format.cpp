// The `mavridis` Format (formats/mavridis/mavridis_format.h): colour transform and chroma subsampling (section 3.5),
// each plane wavelet-coded (mavridis_plane_codec.h) or, for the 5 bpp luminance, BC4-coded; the payload laid out
// Y, Co, Cg; per-plane constants in side data.
//
// Side data (Errors name the key): `<p>_bands` (p = y, co, cg; 8 values: centre and half range of LL, HL, LH, HH,
// |centre| <= 1e6, 0 < half range <= 1e6), `<p>_gamma` (1 value in [0.1, 10]), `<p>_search` (clamp, gamma, squared
// error found by the section 3.2 search; a record, not decoded), `tail_bytes` (payload beyond the block capacity,
// integers 0..255). The keys present are exactly those of the coded planes.
#include "formats/mavridis/mavridis_format.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/color_spaces.h"
#include "core/error.h"
#include "core/parallel.h"
#include "formats/bc4/bc4_block.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/common/block_solver.h"
#include "formats/mavridis/mavridis_plane_codec.h"
#include "formats/mavridis/mavridis_presets.h"
#include "solvers/registry.h"

namespace blocklab {

namespace {

using mavridis::Plane;

constexpr const char* kName = "mavridis";

enum class Space { ycocg_r, ycocg, ycbcr };

struct Layout {
  bool gray = false;        // bpp = 2
  bool bc4_luma = false;    // bpp = 5
  int chroma_factor = 2;    // per axis
  int block_bytes = 4;
};

std::size_t choice_index(const FormatOptions& options, const std::string& key, const std::vector<std::string>& choices) {
  const auto found = options.find(key);
  if (found == options.end()) fail(kName, "option '" + key + "' is missing");
  for (std::size_t k = 0; k < choices.size(); ++k)
    if (found->second == choices[k]) return k;
  fail(kName, "option '" + key + "': '" + found->second + "' is not one of " + join_names(choices));
}

const std::vector<std::string> kRates = {"5", "3", "2.25", "2"};

Layout parse_layout(const FormatOptions& options) {
  Layout layout;
  switch (choice_index(options, "bpp", kRates)) {
    case 0: layout.bc4_luma = true; layout.block_bytes = 10; break;
    case 1: layout.block_bytes = 6; break;
    case 2: layout.chroma_factor = 4; layout.block_bytes = 5; break;
    default: layout.gray = true; layout.block_bytes = 4; break;
  }
  return layout;
}

Space parse_space(const FormatOptions& options) {
  const std::size_t k = choice_index(options, "space", {"ycocg_r", "ycocg", "ycbcr"});
  return k == 0 ? Space::ycocg_r : (k == 1 ? Space::ycocg : Space::ycbcr);
}

mavridis::Packing parse_packing(const FormatOptions& options) {
  const mavridis::Packing packing =
      choice_index(options, "packing", {"dxt5", "bc7"}) == 0 ? mavridis::Packing::dxt5 : mavridis::Packing::bc7;
  const auto transform = options.find("transform");
  if (packing == mavridis::Packing::bc7 && transform != options.end() && transform->second == "s_transform")
    fail(kName, "option 'packing': bc7 drops HH, which the integer S-transform needs (use transform=pi_haar or haar)");
  return packing;
}

mavridis::Transform parse_transform(const FormatOptions& options) {
  const std::size_t k = choice_index(options, "transform", {"pi_haar", "haar", "s_transform"});
  return k == 0 ? mavridis::Transform::pi_haar : (k == 1 ? mavridis::Transform::haar : mavridis::Transform::s_transform);
}

// Section 3.5 forward transform of one texel (RGB in [0, 1]) to (Y, Co, Cg) in 8-bit units.
std::array<double, 3> to_luma_chroma(Space space, const float* rgb) {
  double c[3];
  for (int k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<double>(rgb[k]), 0.0, 1.0) * 255.0;
  if (space == Space::ycocg_r) {
    const YCoCgR v = rgb_to_ycocg_r(static_cast<std::int32_t>(std::lround(c[0])), static_cast<std::int32_t>(std::lround(c[1])),
                                    static_cast<std::int32_t>(std::lround(c[2])));
    return {double(v.y), double(v.co), double(v.cg)};
  }
  if (space == Space::ycocg)
    return {0.25 * c[0] + 0.5 * c[1] + 0.25 * c[2], 0.5 * (c[0] - c[2]), -0.25 * c[0] + 0.5 * c[1] - 0.25 * c[2]};
  const double y = 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];   // BT.601 full range
  return {y, 0.564 * (c[2] - y), 0.713 * (c[0] - y)};
}

// The inverse, to RGB in [0, 1]. YCoCg-R: the decoded values are rounded to integers, then the paper's
// t = Y - (Cg >> 1); G = Cg + t; B = t - (Co >> 1); R = B + Co (core/color_spaces.h), clamped to 0..255.
std::array<float, 3> to_rgb(Space space, double y, double a, double b) {
  double rgb[3];
  if (space == Space::ycocg_r) {
    YCoCgR v;
    v.y = static_cast<std::int32_t>(std::lround(std::clamp(y, -1e6, 1e6)));
    v.co = static_cast<std::int32_t>(std::lround(std::clamp(a, -1e6, 1e6)));
    v.cg = static_cast<std::int32_t>(std::lround(std::clamp(b, -1e6, 1e6)));
    const Rgb<std::int32_t> c = ycocg_r_to_rgb(v);
    rgb[0] = c.r;
    rgb[1] = c.g;
    rgb[2] = c.b;
  } else if (space == Space::ycocg) {
    rgb[0] = y + a - b;
    rgb[1] = y + b;
    rgb[2] = y - a - b;
  } else {
    rgb[0] = y + b / 0.713;   // (a, b) = (Cb, Cr)
    rgb[2] = y + a / 0.564;
    rgb[1] = (y - 0.299 * rgb[0] - 0.114 * rgb[2]) / 0.587;
  }
  std::array<float, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::clamp(rgb[k], 0.0, 255.0) / 255.0);
  return out;
}

// Box average over factor x factor texels (edge replication beyond the plane).
Plane subsample(const Plane& plane, int factor) {
  Plane out;
  out.width = (plane.width + factor - 1) / factor;
  out.height = (plane.height + factor - 1) / factor;
  out.values.resize(static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      double sum = 0.0;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i)
          sum += plane.at(std::min(x * factor + i, plane.width - 1), std::min(y * factor + j, plane.height - 1));
      out.values[static_cast<std::size_t>(y) * out.width + x] = sum / (factor * factor);
    }
  return out;
}

// Bilinear upsampling to width x height: sample k sits at the centre of its factor x factor footprint.
double upsampled(const Plane& plane, int factor, int x, int y) {
  const double fx = (x + 0.5) / factor - 0.5, fy = (y + 0.5) / factor - 0.5;
  const double cx = std::clamp(fx, 0.0, double(plane.width - 1)), cy = std::clamp(fy, 0.0, double(plane.height - 1));
  const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
  const int x1 = std::min(x0 + 1, plane.width - 1), y1 = std::min(y0 + 1, plane.height - 1);
  const double tx = cx - x0, ty = cy - y0;
  return (1 - ty) * ((1 - tx) * plane.at(x0, y0) + tx * plane.at(x1, y0)) +
         ty * ((1 - tx) * plane.at(x0, y1) + tx * plane.at(x1, y1));
}

std::size_t bc4_plane_bytes(int width, int height) {
  return static_cast<std::size_t>((width + 3) / 4) * static_cast<std::size_t>((height + 3) / 4) * 8;
}

struct PlaneSlot {
  std::string key;            // "y", "co", "cg"
  int width = 0, height = 0;
  bool bc4 = false;
  std::size_t offset = 0, bytes = 0;
};

std::vector<PlaneSlot> plane_slots(const Layout& layout, int width, int height) {
  std::vector<PlaneSlot> slots;
  PlaneSlot y{"y", width, height, layout.bc4_luma, 0, 0};
  y.bytes = layout.bc4_luma ? bc4_plane_bytes(width, height) : mavridis::wavelet_plane_bytes(width, height);
  slots.push_back(y);
  if (layout.gray) return slots;
  const int cw = (width + layout.chroma_factor - 1) / layout.chroma_factor;
  const int ch = (height + layout.chroma_factor - 1) / layout.chroma_factor;
  for (const char* key : {"co", "cg"}) {
    PlaneSlot c{key, cw, ch, false, slots.back().offset + slots.back().bytes, mavridis::wavelet_plane_bytes(cw, ch)};
    slots.push_back(c);
  }
  return slots;
}

std::size_t payload_bytes(const std::vector<PlaneSlot>& slots) { return slots.back().offset + slots.back().bytes; }

std::size_t capacity_bytes(const Layout& layout, int width, int height) {
  return BlockGrid(width, height).block_count() * static_cast<std::size_t>(layout.block_bytes);
}

const std::vector<double>& side_values(const EncodedTexture& texture, const std::string& key, std::size_t count) {
  const auto found = texture.side_data.find(key);
  if (found == texture.side_data.end()) fail(kName, "side data '" + key + "' is missing");
  if (found->second.size() != count)
    fail(kName, "side data '" + key + "' holds " + std::to_string(found->second.size()) + " values, expected " +
                    std::to_string(count));
  return found->second;
}

class MavridisFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "Mavridis & Papaioannou 2012 wavelet texture compression: one-level (PI-)Haar coefficients in DXT5 at "
           "half resolution, YCoCg-R with chroma subsampling; 2 (gray), 2.25, 3, 5 bpp (Table 2)";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        choice_option("bpp", "3", kRates,
                      "Table 2 rate: 5 (Y in BC4, CoCg 2:1), 3 (CoCg 2:1), 2.25 (CoCg 4:1), 2 (gray, Y only)"),
        choice_option("transform", "pi_haar", {"pi_haar", "haar", "s_transform"},
                      "wavelet: PI-Haar (eq. 2), Haar (eq. 1) or the integer S-transform (Table 3)"),
        real_option("w", 0.4, 0.01, 1.0, "PI-Haar weight of HH in eq. 2 (0 < w <= 1)"),
        choice_option("space", "ycocg_r", {"ycocg_r", "ycocg", "ycbcr"},
                      "colour space (section 3.5, Table 3): YCoCg-R (integer lifting), YCoCg or YCbCr (BT.601)"),
        choice_option("packing", "dxt5", {"dxt5", "bc7"},
                      "coefficient packing (3.1): dxt5 = LL in alpha, HL' LH' HH' in RGB; bc7 = LL, HL+LH, HL-LH in "
                      "RGB, HH dropped, weights 0.6 / 0.2 / 0.2"),
        choice_option("effort", "medium", mavridis::preset_names(),
                      "section 3.2 clamp / gamma search grid and BC3 search effort, set by the presets "
                      "(mavridis_presets.h)"),
        text_option("coeff_solver", "grid",
                    "section 3.2 search: grid (the preset's brute-force grid) or a solver of the library (e.g. "
                    "coeff_search) on the clamp / gamma Problem (mavridis_coefficient_problem.h)"),
        text_option("coeff_solver_options", "", "options of that solver as 'key=value, key=value'"),
    };
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"wavelet", "one level of the wavelet transform per 2x2 texels, its bands in the packing's channels"}};
  }
  // The presets set the search effort (coefficient grid, BC3 search); the rate and transform are the user's.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("effort", "fast", "medium", "thorough");
  }
  int block_bytes(const FormatOptions& options) const override { return parse_layout(options).block_bytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const Layout layout = parse_layout(options);
    const Space space = parse_space(options);
    const mavridis::SearchEffort effort = mavridis::preset_effort(option_text(options, "effort"), kName);
    mavridis::WaveletSettings settings;
    settings.transform = parse_transform(options);
    settings.packing = parse_packing(options);
    settings.w = option_real(options, "w");
    settings.final_search = effort.final_search;
    settings.search_effort = S3tcSearch::fast;
    settings.clamps = effort.clamps;
    settings.gammas = effort.gammas;
    settings.threads = context.threads;
    settings.seed = static_cast<std::uint64_t>(option_int(options, "seed"));
    const std::string coeff_solver = option_text(options, "coeff_solver");
    if (coeff_solver != "grid") {
      try {
        find_solver(coeff_solver);
      } catch (const Error& e) {
        fail(kName, "option 'coeff_solver': " + std::string(e.what()) + " (or 'grid')");
      }
      settings.solver = coeff_solver;
      settings.solver_options =
          parse_solver_option_list(option_text(options, "coeff_solver_options"), "coeff_solver_options", kName);
    }

    // Planes in 8-bit units.
    std::array<Plane, 3> planes;
    for (Plane& p : planes) {
      p.width = image.width;
      p.height = image.height;
      p.values.resize(image.texel_count());
    }
    for (std::size_t i = 0; i < image.texel_count(); ++i) {
      const float* rgba = &image.pixels[i * 4];
      if (image.channels == 1) {
        planes[0].values[i] = std::clamp(static_cast<double>(rgba[0]), 0.0, 1.0) * 255.0;
        if (space == Space::ycocg_r) planes[0].values[i] = std::round(planes[0].values[i]);
        continue;
      }
      const std::array<double, 3> v = to_luma_chroma(space, rgba);
      for (int k = 0; k < 3; ++k) planes[k].values[i] = v[k];
    }

    const std::vector<PlaneSlot> slots = plane_slots(layout, image.width, image.height);
    std::vector<std::uint8_t> payload(payload_bytes(slots), 0);
    EncodedTexture texture;
    texture.format = kName;
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    // Gray textures decode to one channel; the colour rates to RGB (a one-channel source becomes R = G = B).
    texture.channels = layout.gray ? 1 : std::max(image.channels, 3);
    texture.block_bytes = layout.block_bytes;
    for (std::size_t s = 0; s < slots.size(); ++s) {
      const PlaneSlot& slot = slots[s];
      const Plane source = s == 0 ? planes[0] : subsample(planes[s], layout.chroma_factor);
      if (slot.bc4) {
        const BlockGrid grid(slot.width, slot.height);
        parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
          const int bx = static_cast<int>(index % static_cast<std::size_t>(grid.blocks_x));
          const int by = static_cast<int>(index / static_cast<std::size_t>(grid.blocks_x));
          float values[16];
          for (int i = 0; i < 16; ++i)
            values[i] = static_cast<float>(std::clamp(
                source.at(std::min(bx * 4 + i % 4, slot.width - 1), std::min(by * 4 + i / 4, slot.height - 1)), 0.0,
                255.0));
          pack_bc4_block(fit_bc4_block(values, effort.final_search), payload.data() + slot.offset + index * 8, kName);
        });
        continue;
      }
      const mavridis::WaveletPlane coded = mavridis::encode_wavelet_plane(source, settings);
      std::copy(coded.bytes.begin(), coded.bytes.end(), payload.begin() + static_cast<std::ptrdiff_t>(slot.offset));
      std::vector<double> bands;
      for (int k = 0; k < 4; ++k) {
        bands.push_back(coded.mapping.centre[k]);
        bands.push_back(coded.mapping.half_range[k]);
      }
      texture.side_data[slot.key + "_bands"] = bands;
      texture.side_data[slot.key + "_gamma"] = {coded.mapping.gamma};
      texture.side_data[slot.key + "_search"] = {coded.clamp, coded.mapping.gamma, coded.squared_error};
    }
    const std::size_t capacity = capacity_bytes(layout, image.width, image.height);
    texture.blocks.assign(capacity, 0);
    std::copy(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(std::min(capacity, payload.size())),
              texture.blocks.begin());
    if (payload.size() > capacity)
      texture.side_data["tail_bytes"] =
          std::vector<double>(payload.begin() + static_cast<std::ptrdiff_t>(capacity), payload.end());
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const Layout layout = parse_layout(texture.options);
    const Space space = parse_space(texture.options);
    const mavridis::Transform transform = parse_transform(texture.options);
    const mavridis::Packing packing = parse_packing(texture.options);
    const auto w_found = texture.options.find("w");
    if (w_found == texture.options.end()) fail(kName, "option 'w' is missing");
    const double w = option_real(texture.options, "w");
    if (!(w >= 0.01 && w <= 1.0)) fail(kName, "option 'w': " + w_found->second + " is outside [0.01, 1]");
    if (layout.gray != (texture.channels == 1))
      fail(kName, "bpp=2 (gray) textures have one channel, the others three or four; this one has " +
                      std::to_string(texture.channels));

    const std::vector<PlaneSlot> slots = plane_slots(layout, texture.width, texture.height);
    const std::size_t capacity = capacity_bytes(layout, texture.width, texture.height);
    const std::size_t payload_size = payload_bytes(slots);
    std::vector<std::uint8_t> payload(texture.blocks.begin(),
                                      texture.blocks.begin() + static_cast<std::ptrdiff_t>(std::min(capacity, payload_size)));
    std::vector<std::string> expected_keys;
    if (payload_size > capacity) {
      for (double byte : side_values(texture, "tail_bytes", payload_size - capacity)) {
        if (!(byte >= 0.0 && byte <= 255.0 && byte == std::floor(byte)))
          fail(kName, "side data 'tail_bytes' holds " + std::to_string(byte) + ", not an integer in 0..255");
        payload.push_back(static_cast<std::uint8_t>(byte));
      }
      expected_keys.push_back("tail_bytes");
    }

    std::array<Plane, 3> planes;
    for (std::size_t s = 0; s < slots.size(); ++s) {
      const PlaneSlot& slot = slots[s];
      const std::uint8_t* bytes = payload.data() + slot.offset;
      if (slot.bc4) {
        Plane& p = planes[s];
        p.width = slot.width;
        p.height = slot.height;
        p.values.assign(static_cast<std::size_t>(p.width) * p.height, 0.0);
        const BlockGrid grid(slot.width, slot.height);
        parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
          const std::array<float, 16> v = decode_bc4_params(unpack_bc4_block(bytes + index * 8));
          const int bx = static_cast<int>(index % static_cast<std::size_t>(grid.blocks_x));
          const int by = static_cast<int>(index / static_cast<std::size_t>(grid.blocks_x));
          for (int i = 0; i < 16; ++i) {
            const int x = bx * 4 + i % 4, y = by * 4 + i / 4;
            if (x < p.width && y < p.height) p.values[static_cast<std::size_t>(y) * p.width + x] = v[i] * 255.0;
          }
        });
        continue;
      }
      const std::vector<double>& bands = side_values(texture, slot.key + "_bands", 8);
      const double gamma = side_values(texture, slot.key + "_gamma", 1)[0];
      mavridis::BandMapping mapping;
      for (int k = 0; k < 4; ++k) {
        mapping.centre[k] = bands[2 * k];
        mapping.half_range[k] = bands[2 * k + 1];
        if (!(std::abs(mapping.centre[k]) <= 1e6 && mapping.half_range[k] > 0.0 && mapping.half_range[k] <= 1e6))
          fail(kName, "side data '" + slot.key + "_bands': band " + std::to_string(k) +
                          " needs |centre| <= 1e6 and 0 < half range <= 1e6, got " + std::to_string(mapping.centre[k]) +
                          ", " + std::to_string(mapping.half_range[k]));
      }
      if (!(gamma >= 0.1 && gamma <= 10.0))
        fail(kName, "side data '" + slot.key + "_gamma' is " + std::to_string(gamma) + ", outside [0.1, 10]");
      mapping.gamma = gamma;
      planes[s] = mavridis::decode_wavelet_plane(bytes, slot.width, slot.height, mapping, transform, w, context.threads,
                                                 packing);
      expected_keys.push_back(slot.key + "_bands");
      expected_keys.push_back(slot.key + "_gamma");
      expected_keys.push_back(slot.key + "_search");
    }
    for (const auto& entry : texture.side_data)
      if (std::find(expected_keys.begin(), expected_keys.end(), entry.first) == expected_keys.end())
        fail(kName, "unknown side data '" + entry.first + "'; expected " + join_names(expected_keys));

    Image image(texture.width, texture.height, layout.gray ? 1 : std::min(texture.channels, 3));
    parallel_for_index(static_cast<std::size_t>(texture.height), context.threads, [&](std::size_t row) {
      const int y = static_cast<int>(row);
      for (int x = 0; x < texture.width; ++x) {
        float* out = image.texel(x, y);
        const double luma = planes[0].at(x, y);
        if (layout.gray) {
          const double rounded = space == Space::ycocg_r ? std::round(luma) : luma;
          const float v = static_cast<float>(std::clamp(rounded, 0.0, 255.0) / 255.0);
          out[0] = out[1] = out[2] = v;
          continue;
        }
        const std::array<float, 3> rgb = to_rgb(space, luma, upsampled(planes[1], layout.chroma_factor, x, y),
                                                upsampled(planes[2], layout.chroma_factor, x, y));
        for (int k = 0; k < 3; ++k) out[k] = rgb[k];
      }
    });
    return image;
  }
};

}  // namespace

std::size_t mavridis_payload_bytes(const FormatOptions& options, int width, int height) {
  return payload_bytes(plane_slots(parse_layout(options), width, height));
}

const Format& mavridis_format() {
  static const MavridisFormat format;
  return format;
}

}  // namespace blocklab
