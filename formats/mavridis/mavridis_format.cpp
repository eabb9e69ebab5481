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
#include "formats/registry.h"
#include "formats/mavridis/mavridis_chroma.h"
#include "formats/mavridis/mavridis_color_storage.h"
#include "formats/mavridis/mavridis_multilevel.h"
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
  int luma_levels = 1;      // section 3.4: wavelet levels of Y (levels - 1 DXT1 detail textures)
  double rate = 3.0;        // payload bits per texel (Table 2, section 3.4)
  // A rate of whole bytes per 4x4 block: the payload fills ceil(w/4) x ceil(h/4) blocks of block_bytes (the bytes of
  // larger padded textures in side data `tail_bytes`). Otherwise (2.25 bpp: 4.5 bytes; the levels rates 1.75,
  // 1.375, ...) the payload is stored at its true size in units of kUnitBytes (one BC1 block, half a BC3 / BC7 block).
  bool whole_bytes_per_block = true;
  int block_bytes = 4;
};

constexpr int kUnitBytes = 8;

std::size_t choice_index(const FormatOptions& options, const std::string& key, const std::vector<std::string>& choices) {
  const auto found = options.find(key);
  if (found == options.end()) fail(kName, "option '" + key + "' is missing");
  for (std::size_t k = 0; k < choices.size(); ++k)
    if (found->second == choices[k]) return k;
  fail(kName, "option '" + key + "': '" + found->second + "' is not one of " + join_names(choices));
}

const std::vector<std::string> kRates = {"5", "3", "2.25", "2"};
const std::vector<std::string> kTransforms = {"pi_haar", "haar", "s_transform", "plhaar"};

// Bits per texel of Y at `levels` wavelet levels (section 3.4): B_1 = 2, B_N = 1 + B_{N-1} / 4.
double luma_rate(int levels) { return levels <= 1 ? 2.0 : 1.0 + luma_rate(levels - 1) / 4.0; }

Layout parse_layout(const FormatOptions& options) {
  Layout layout;
  switch (choice_index(options, "bpp", kRates)) {
    case 0: layout.bc4_luma = true; break;
    case 1: break;
    case 2: layout.chroma_factor = 4; break;
    default: layout.gray = true; break;
  }
  const auto levels = options.find("levels");
  if (levels == options.end()) fail(kName, "option 'levels' is missing");
  layout.luma_levels = static_cast<int>(option_int(options, "levels"));
  if (layout.luma_levels < 1 || layout.luma_levels > 4)
    fail(kName, "option 'levels': " + levels->second + " is outside [1, 4]");
  if (layout.bc4_luma && layout.luma_levels > 1)
    fail(kName, "option 'levels': bpp=5 codes Y in BC4, not by the wavelet; levels > 1 needs bpp 3, 2.25 or 2");
  const auto transform = options.find("transform");
  if (layout.luma_levels > 1 && transform != options.end() &&
      (transform->second == "s_transform" || transform->second == "plhaar"))
    fail(kName, "option 'levels': the detail levels are stored as eq. 1 / eq. 2 bands; transform '" +
                    transform->second + "' supports levels=1 only");
  // Payload bits per texel: Y's rate plus two chroma planes at 2 bpp over 1 / factor^2 of the texels; stored in
  // whole bytes per 4x4 block (16 texels) where the rate allows, else in kUnitBytes units.
  layout.rate = (layout.bc4_luma ? 4.0 : luma_rate(layout.luma_levels)) +
                (layout.gray ? 0.0 : 2.0 * 2.0 / (layout.chroma_factor * layout.chroma_factor));
  const double bytes_per_block = layout.rate * 2.0;
  layout.whole_bytes_per_block = std::abs(bytes_per_block - std::round(bytes_per_block)) < 1e-9;
  layout.block_bytes = layout.whole_bytes_per_block ? static_cast<int>(std::round(bytes_per_block)) : kUnitBytes;
  return layout;
}

Space parse_space(const FormatOptions& options) {
  const std::size_t k = choice_index(options, "space", {"ycocg_r", "ycocg", "ycbcr"});
  return k == 0 ? Space::ycocg_r : (k == 1 ? Space::ycocg : Space::ycbcr);
}

const std::vector<std::string> kPackings = {"dxt5", "bc7", "best"};
const std::vector<std::string> kColorStorages = {"exact", "unorm8"};

// Option color_storage=unorm8: the colour-space planes as 8-bit textures before the wavelet
// (mavridis_color_storage.h); a one-channel source is Y itself.
void store_planes_unorm8(std::array<Plane, 3>& planes, Space space, bool gray_source) {
  if (space == Space::ycocg_r) {
    if (gray_source) return;   // Y is already rounded to 0..255
    mavridis::store_ycocg_r_chroma_unorm8(planes[1]);
    mavridis::store_ycocg_r_chroma_unorm8(planes[2]);
    return;
  }
  mavridis::store_unorm8(planes[0], 0.0);
  if (gray_source) return;
  mavridis::store_unorm8(planes[1], 128.0);
  mavridis::store_unorm8(planes[2], 128.0);
}

// The packing option: dxt5, bc7, or best (the encoder keeps the better of the two; side data `packing` says which).
std::size_t parse_packing_choice(const FormatOptions& options) {
  const std::size_t packing = choice_index(options, "packing", kPackings);
  const auto transform = options.find("transform");
  if (packing != 0 && transform != options.end() &&
      (transform->second == "s_transform" || transform->second == "plhaar"))
    fail(kName, "option 'packing': bc7 drops HH, which the integer transform '" + transform->second +
                    "' needs (use transform=pi_haar or haar)");
  return packing;
}

// The packing a texture was coded with: its option, or for packing=best its side data `packing` (0 dxt5, 1 bc7).
mavridis::Packing texture_packing(const EncodedTexture& texture) {
  const std::size_t choice = parse_packing_choice(texture.options);
  if (choice == 0) return mavridis::Packing::dxt5;
  if (choice == 1) return mavridis::Packing::bc7;
  const auto found = texture.side_data.find("packing");
  if (found == texture.side_data.end()) fail(kName, "side data 'packing' is missing (packing=best records the choice)");
  if (found->second.size() != 1 || !(found->second[0] == 0.0 || found->second[0] == 1.0))
    fail(kName, "side data 'packing' must be one value, 0 (dxt5) or 1 (bc7)");
  return found->second[0] == 0.0 ? mavridis::Packing::dxt5 : mavridis::Packing::bc7;
}

mavridis::Transform parse_transform(const FormatOptions& options) {
  switch (choice_index(options, "transform", kTransforms)) {
    case 0: return mavridis::Transform::pi_haar;
    case 1: return mavridis::Transform::haar;
    case 2: return mavridis::Transform::s_transform;
    default: return mavridis::Transform::plhaar;
  }
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
// With color_storage=unorm8 the real-valued spaces invert what 8-bit textures hold (Y a code 0..255, chroma a code
// offset by 128), as YCoCg-R's integer decoder does for its 8-bit Y and 9-bit Co, Cg.
std::array<float, 3> to_rgb(Space space, double y, double a, double b, bool unorm8) {
  if (unorm8 && space != Space::ycocg_r) {
    y = mavridis::unorm8_code(y, 0.0);
    a = mavridis::unorm8_code(a, 128.0);
    b = mavridis::unorm8_code(b, 128.0);
  }
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
  y.bytes = layout.bc4_luma ? bc4_plane_bytes(width, height)
                            : mavridis::multilevel_plane_bytes(width, height, layout.luma_levels);
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

// Bytes of the stored block stream: whole blocks of the 4x4 grid, or the payload itself (a multiple of kUnitBytes).
std::size_t capacity_bytes(const Layout& layout, int width, int height) {
  if (!layout.whole_bytes_per_block) return payload_bytes(plane_slots(layout, width, height));
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

// The coded planes' bytes: the block stream up to the payload size, then side data `tail_bytes` where the payload
// exceeds the stream's capacity.
std::vector<std::uint8_t> full_payload(const EncodedTexture& texture, const Layout& layout,
                                       const std::vector<PlaneSlot>& slots) {
  const std::size_t capacity = capacity_bytes(layout, texture.width, texture.height);
  const std::size_t payload_size = payload_bytes(slots);
  std::vector<std::uint8_t> payload(texture.blocks.begin(),
                                    texture.blocks.begin() + static_cast<std::ptrdiff_t>(std::min(capacity, payload_size)));
  if (payload_size > capacity)
    for (double byte : side_values(texture, "tail_bytes", payload_size - capacity)) {
      if (!(byte >= 0.0 && byte <= 255.0 && byte == std::floor(byte)))
        fail(kName, "side data 'tail_bytes' holds " + std::to_string(byte) + ", not an integer in 0..255");
      payload.push_back(static_cast<std::uint8_t>(byte));
    }
  return payload;
}

// One standard texture of the payload (bytes [offset, offset + size)), `format` at width x height.
GpuTexture gpu_texture(const std::string& suffix, const std::string& format, int width, int height, int channels,
                       const std::vector<std::uint8_t>& payload, std::size_t offset, std::size_t size) {
  GpuTexture gpu;
  gpu.suffix = suffix;
  EncodedTexture& t = gpu.texture;
  t.format = format;
  t.options = resolve_format_options(find_format(format), {});
  t.width = width;
  t.height = height;
  t.channels = channels;
  t.block_bytes = format == "bc1" || format == "bc4" ? 8 : 16;
  if (BlockGrid(width, height).block_count() * static_cast<std::size_t>(t.block_bytes) != size)
    fail(kName, "DDS export: the " + suffix + " texture's " + std::to_string(size) + " bytes do not fill " +
                    std::to_string(width) + "x" + std::to_string(height) + " " + format);
  t.blocks.assign(payload.begin() + static_cast<std::ptrdiff_t>(offset),
                  payload.begin() + static_cast<std::ptrdiff_t>(offset + size));
  return gpu;
}

// Section 3.2's constants of one coded level from side data `<key>_bands` (centre and half range of the bands from
// `first_band` on) and `<key>_gamma`; Errors name the key.
mavridis::BandMapping side_mapping(const EncodedTexture& texture, const std::string& key, int first_band) {
  const std::vector<double>& bands = side_values(texture, key + "_bands", static_cast<std::size_t>(2 * (4 - first_band)));
  const double gamma = side_values(texture, key + "_gamma", 1)[0];
  mavridis::BandMapping mapping;
  mapping.centre[0] = 0.0;
  mapping.half_range[0] = 1.0;
  for (int k = first_band; k < 4; ++k) {
    mapping.centre[k] = bands[2 * (k - first_band)];
    mapping.half_range[k] = bands[2 * (k - first_band) + 1];
    if (!(std::abs(mapping.centre[k]) <= 1e6 && mapping.half_range[k] > 0.0 && mapping.half_range[k] <= 1e6))
      fail(kName, "side data '" + key + "_bands': band " + std::to_string(k) +
                      " needs |centre| <= 1e6 and 0 < half range <= 1e6, got " + std::to_string(mapping.centre[k]) +
                      ", " + std::to_string(mapping.half_range[k]));
  }
  if (!(gamma >= 0.1 && gamma <= 10.0))
    fail(kName, "side data '" + key + "_gamma' is " + std::to_string(gamma) + ", outside [0.1, 10]");
  mapping.gamma = gamma;
  return mapping;
}

// Squared error of a decode against its source in 8-bit units: R, G, B for colour; for gray (one decoded channel) the
// luma of the chosen space (the source itself when it has one channel).
double decoded_error(const Image& source, const Image& decoded, Space space) {
  double sum = 0.0;
  for (std::size_t i = 0; i < source.texel_count(); ++i) {
    const float* s = &source.pixels[i * 4];
    const float* d = &decoded.pixels[i * 4];
    if (decoded.channels == 1) {
      const double luma = source.channels == 1 ? std::clamp(static_cast<double>(s[0]), 0.0, 1.0) * 255.0
                                               : to_luma_chroma(space, s)[0];
      const double e = d[0] * 255.0 - luma;
      sum += e * e;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const double e = 255.0 * (d[k] - std::clamp(static_cast<double>(s[k]), 0.0, 1.0));
      sum += e * e;
    }
  }
  return sum;
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
        choice_option("transform", "pi_haar", kTransforms,
                      "wavelet: PI-Haar (eq. 2), Haar (eq. 1) or the integer S-transform or PLHaar (Table 3)"),
        real_option("w", 0.4, 0.01, 1.0, "PI-Haar weight of HH in eq. 2 (0 < w <= 1)"),
        choice_option("space", "ycocg_r", {"ycocg_r", "ycocg", "ycbcr"},
                      "colour space (section 3.5, Table 3): YCoCg-R (integer lifting), YCoCg or YCbCr (BT.601)"),
        choice_option("color_storage", "exact", kColorStorages,
                      "Y, Co, Cg planes between the colour transform and the wavelet (section 3.5): exact, or unorm8 = "
                      "8-bit textures as the paper's GPU pipeline (YCoCg-R: Co / Cg lose one bit where they span "
                      "more than 256 values; YCoCg, YCbCr: rounded to 8-bit codes)"),
        choice_option("packing", "dxt5", kPackings,
                      "coefficient packing (3.1): dxt5 = LL in alpha, HL' LH' HH' in RGB; bc7 = LL, HL+LH, HL-LH in "
                      "RGB, HH dropped, weights 0.6 / 0.2 / 0.2; best = both, the lower RGB error kept (side data "
                      "'packing': 0 dxt5, 1 bc7)"),
        integer_option("levels", 1, 1, 4,
                       "wavelet levels of Y (section 3.4): the first levels - 1 as DXT1, the last as the packing; "
                       "Y at 2, 1.5, 1.375, 1.34 bpp (levels=2 with bpp=2.25: 1.75 bpp colour); Haar / PI-Haar"),
        choice_option("effort", "medium", mavridis::effort_names(),
                      "section 3.2 clamp / gamma search grid and BC3 / BC7 search effort, set by the presets "
                      "(mavridis_presets.h); none = no section 3.2 optimisation (clamp 0, gamma 1)"),
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
  // The payload's rate: Table 2's 5, 3, 2.25, 2 bpp; section 3.4's with levels > 1 (1.75 colour, 1.5 gray, ...).
  double bits_per_pixel(const FormatOptions& options) const override { return parse_layout(options).rate; }
  // Rates of whole bytes per 4x4 block: the 4x4 grid. The others: the payload's kUnitBytes units.
  std::size_t stored_block_count(const EncodedTexture& texture) const override {
    const Layout layout = parse_layout(texture.options);
    if (layout.whole_bytes_per_block) return Format::stored_block_count(texture);
    return capacity_bytes(layout, texture.width, texture.height) / kUnitBytes;
  }
  // 3: rates that are not whole bytes per 4x4 block (2.25 bpp, most levels > 1) store the payload at its true size
  // (no zero tail, no side data tail_bytes; block_bytes 8). 2: the BC7 packing's encoder effort follows the preset.
  // The default bytes (3 bpp) are those of revision 1.
  int revision() const override { return 3; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const std::size_t packing = parse_packing_choice(options);
    if (packing < 2) return encode_packed(image, options, context, packing == 0 ? mavridis::Packing::dxt5 : mavridis::Packing::bc7);
    // packing=best: both packings, the one whose decoded texture is closer to the source kept.
    EncodedTexture best;
    double best_error = 0.0;
    for (const mavridis::Packing candidate : {mavridis::Packing::dxt5, mavridis::Packing::bc7}) {
      EncodedTexture texture = encode_packed(image, options, context, candidate);
      texture.side_data["packing"] = {candidate == mavridis::Packing::dxt5 ? 0.0 : 1.0};
      const double error = decoded_error(image, decode(texture, context), parse_space(options));
      if (candidate == mavridis::Packing::dxt5 || error < best_error) {
        best = std::move(texture);
        best_error = error;
      }
    }
    return best;
  }

  EncodedTexture encode_packed(const Image& image, const FormatOptions& options, const CodecContext& context,
                               mavridis::Packing packing) const {
    const Layout layout = parse_layout(options);
    const Space space = parse_space(options);
    const mavridis::SearchEffort effort = mavridis::preset_effort(option_text(options, "effort"), kName);
    mavridis::WaveletSettings settings;
    settings.transform = parse_transform(options);
    settings.packing = packing;
    settings.bc7_partitions = effort.bc7_partitions;
    settings.bc7_refine_iterations = effort.bc7_refine_iterations;
    settings.bc7_pbit_search = effort.bc7_pbit_search;
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
    for (Plane& p : planes) p = Plane::zeros(image.width, image.height);
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
    if (choice_index(options, "color_storage", kColorStorages) == 1) store_planes_unorm8(planes, space, image.channels == 1);

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
      const Plane source = s == 0 ? planes[0] : mavridis::subsample(planes[s], layout.chroma_factor);
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
      settings.domain = s == 0 ? mavridis::plhaar_luma_domain() : mavridis::plhaar_chroma_domain();
      const mavridis::MultilevelPlane levels =
          mavridis::encode_multilevel_plane(source, settings, s == 0 ? layout.luma_levels : 1);
      std::copy(levels.bytes.begin(), levels.bytes.end(), payload.begin() + static_cast<std::ptrdiff_t>(slot.offset));
      for (std::size_t k = 0; k < levels.detail.size(); ++k) {
        const std::string key = slot.key + "_level" + std::to_string(k + 1);
        std::vector<double> bands;
        for (int b = 1; b < 4; ++b) {
          bands.push_back(levels.detail[k].centre[b]);
          bands.push_back(levels.detail[k].half_range[b]);
        }
        texture.side_data[key + "_bands"] = bands;
        texture.side_data[key + "_gamma"] = {levels.detail[k].gamma};
        texture.side_data[key + "_search"] = {levels.detail_clamp[k], levels.detail[k].gamma, levels.detail_error[k]};
      }
      const mavridis::WaveletPlane& coded = levels.last;
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

  // The textures the paper's shader samples, each at its own resolution (suffixes y, co, cg; y_level<k> for the
  // DXT1 detail levels); the constants of section 3.2 stay in the .blk beside them.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override;

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const Layout layout = parse_layout(texture.options);
    const Space space = parse_space(texture.options);
    const mavridis::Transform transform = parse_transform(texture.options);
    const mavridis::Packing packing = texture_packing(texture);
    const bool unorm8 = choice_index(texture.options, "color_storage", kColorStorages) == 1;
    const auto w_found = texture.options.find("w");
    if (w_found == texture.options.end()) fail(kName, "option 'w' is missing");
    const double w = option_real(texture.options, "w");
    if (!(w >= 0.01 && w <= 1.0)) fail(kName, "option 'w': " + w_found->second + " is outside [0.01, 1]");
    if (layout.gray != (texture.channels == 1))
      fail(kName, "bpp=2 (gray) textures have one channel, the others three or four; this one has " +
                      std::to_string(texture.channels));

    const std::vector<PlaneSlot> slots = plane_slots(layout, texture.width, texture.height);
    std::vector<std::string> expected_keys;
    const std::vector<std::uint8_t> payload = full_payload(texture, layout, slots);
    if (payload_bytes(slots) > capacity_bytes(layout, texture.width, texture.height)) expected_keys.push_back("tail_bytes");
    if (parse_packing_choice(texture.options) == 2) expected_keys.push_back("packing");

    std::array<Plane, 3> planes;
    for (std::size_t s = 0; s < slots.size(); ++s) {
      const PlaneSlot& slot = slots[s];
      const std::uint8_t* bytes = payload.data() + slot.offset;
      if (slot.bc4) {
        Plane& p = planes[s];
        p = Plane::zeros(slot.width, slot.height);
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
      const mavridis::BandMapping mapping = side_mapping(texture, slot.key, 0);
      expected_keys.push_back(slot.key + "_bands");
      expected_keys.push_back(slot.key + "_gamma");
      expected_keys.push_back(slot.key + "_search");
      const int levels = s == 0 ? layout.luma_levels : 1;
      if (levels == 1) {
        planes[s] = mavridis::decode_wavelet_plane(
            bytes, slot.width, slot.height, mapping, transform, w, context.threads, packing,
            s == 0 ? mavridis::plhaar_luma_domain() : mavridis::plhaar_chroma_domain());
        continue;
      }
      std::vector<mavridis::BandMapping> detail;
      for (int k = 1; k < levels; ++k) {
        const std::string key = slot.key + "_level" + std::to_string(k);
        detail.push_back(side_mapping(texture, key, 1));
        for (const char* part : {"_bands", "_gamma", "_search"}) expected_keys.push_back(key + part);
      }
      planes[s] = mavridis::decode_multilevel_plane(bytes, slot.width, slot.height, detail, mapping, transform, w,
                                                    context.threads, packing);
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
          const double rounded =
              space == Space::ycocg_r ? std::round(luma) : (unorm8 ? mavridis::unorm8_code(luma, 0.0) : luma);
          const float v = static_cast<float>(std::clamp(rounded, 0.0, 255.0) / 255.0);
          out[0] = out[1] = out[2] = v;
          continue;
        }
        const std::array<float, 3> rgb = to_rgb(space, luma, mavridis::upsampled(planes[1], layout.chroma_factor, x, y),
                                                mavridis::upsampled(planes[2], layout.chroma_factor, x, y), unorm8);
        for (int k = 0; k < 3; ++k) out[k] = rgb[k];
      }
    });
    return image;
  }
};

}  // namespace

std::vector<GpuTexture> MavridisFormat::gpu_textures(const EncodedTexture& texture) const {
  validate_encoded_texture(*this, texture, kName);
  const Layout layout = parse_layout(texture.options);
  const bool bc7 = texture_packing(texture) == mavridis::Packing::bc7;
  const std::vector<PlaneSlot> slots = plane_slots(layout, texture.width, texture.height);
  const std::vector<std::uint8_t> payload = full_payload(texture, layout, slots);
  std::vector<GpuTexture> textures;
  for (std::size_t s = 0; s < slots.size(); ++s) {
    const PlaneSlot& slot = slots[s];
    if (slot.bc4) {
      textures.push_back(gpu_texture(slot.key, "bc4", slot.width, slot.height, 1, payload, slot.offset, slot.bytes));
      continue;
    }
    // Each level's coefficient texture is half its plane's size: detail levels DXT1 (bc1), the last DXT5 or BC7.
    const int levels = s == 0 ? layout.luma_levels : 1;
    std::size_t offset = slot.offset;
    for (int k = 1; k <= levels; ++k) {
      const int width = mavridis::level_size(slot.width, k - 1), height = mavridis::level_size(slot.height, k - 1);
      const bool last = k == levels;
      const std::size_t size = last ? mavridis::wavelet_plane_bytes(width, height) : mavridis::detail_level_bytes(width, height);
      textures.push_back(gpu_texture(last ? slot.key : slot.key + "_level" + std::to_string(k),
                                     last ? (bc7 ? "bc7" : "bc3") : "bc1", (width + 1) / 2, (height + 1) / 2,
                                     last && !bc7 ? 4 : 3, payload, offset, size));
      offset += size;
    }
  }
  return textures;
}

std::size_t mavridis_payload_bytes(const FormatOptions& options, int width, int height) {
  return payload_bytes(plane_slots(parse_layout(options), width, height));
}

const Format& mavridis_format() {
  static const MavridisFormat format;
  return format;
}

}  // namespace blocklab
