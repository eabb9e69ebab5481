// The `downscaled` Format (formats/downscaled/downscaled_format.h): Lanczos (3 lobes by default) downscale, the
// inner BCn encoder at the reduced size, inner decode and bilinear upscale: the equal-rate baseline of Mavridis &
// Papaioannou 2012, section 4.1 ("scaling down the DXTC encoded textures by the appropriate factors in order to match
// the bitrates of our method ... scaled back to their original size using the hardware bilinear filter").
//
// Stored texture: width x height are the true size; `blocks` are the inner format's blocks of the reduced image
// (row-major, ceil(w'/4) * ceil(h'/4) of them); side data `reduced_size` = [w', h'] (integers, 1 <= w' <= width,
// 1 <= h' <= height; Errors name the key). No other side data.
#include "formats/downscaled/downscaled_format.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/number_text.h"
#include "core/resample.h"
#include "formats/registry.h"

namespace blocklab {

namespace {

constexpr const char* kName = "downscaled";
constexpr const char* kReducedSizeKey = "reduced_size";

const std::vector<std::string> kInnerFormats = {"bc1", "bc3", "bc4", "bc7"};
const std::vector<std::string> kInnerPresets = {"fast", "medium", "thorough"};

// BT.601 luma weights of the gray source (the weights metrics/psnr_luma.cpp measures with).
constexpr double kLumaWeights[3] = {0.299, 0.587, 0.114};

const Format& inner_format(const FormatOptions& options) {
  const std::string& name = option_text(options, "inner");
  if (std::find(kInnerFormats.begin(), kInnerFormats.end(), name) == kInnerFormats.end())
    fail(kName, "option 'inner': '" + name + "' is not one of " + join_names(kInnerFormats));
  return find_format(name);
}

// The inner format's resolved options: its preset `inner_preset` and this texture's seed.
FormatOptions inner_options(const FormatOptions& options) {
  const Format& inner = inner_format(options);
  try {
    return resolve_format_options(inner, {{"preset", option_text(options, "inner_preset")},
                                          {"seed", std::to_string(option_int(options, "seed"))}});
  } catch (const Error& error) {
    fail(kName, std::string("option 'inner_preset': ") + error.what());
  }
}

double inner_bits_per_pixel(const FormatOptions& options) {
  return inner_format(options).bits_per_pixel(inner_options(options));
}

// The linear scale of each side: `scale`, or sqrt(bpp / inner bpp) when bpp > 0.
double effective_scale(const FormatOptions& options) {
  const double bpp = option_real(options, "bpp");
  if (bpp <= 0.0) return option_real(options, "scale");
  const double inner_bpp = inner_bits_per_pixel(options);
  if (bpp > inner_bpp)
    fail(kName, "option 'bpp': " + option_text(options, "bpp") + " is above the inner format's " +
                    exact_number_text(inner_bpp) + " bpp (the scale would exceed 1)");
  return std::sqrt(bpp / inner_bpp);
}

int reduced_side(int side, double scale) {
  return static_cast<int>(std::clamp(std::lround(side * scale), 1L, static_cast<long>(side)));
}

struct ReducedSize {
  int width = 0, height = 0;
};

// The `reduced_size` side data, checked against the true size.
ReducedSize stored_reduced_size(const EncodedTexture& texture) {
  const auto found = texture.side_data.find(kReducedSizeKey);
  if (found == texture.side_data.end()) fail(kName, std::string("side data '") + kReducedSizeKey + "' is missing");
  if (found->second.size() != 2)
    fail(kName, std::string("side data '") + kReducedSizeKey + "' holds " + std::to_string(found->second.size()) +
                    " values, expected 2 (width, height)");
  const int limits[2] = {texture.width, texture.height};
  int sides[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const double value = found->second[static_cast<std::size_t>(k)];
    if (!(value >= 1.0 && value <= limits[k] && value == std::floor(value)))
      fail(kName, std::string("side data '") + kReducedSizeKey + "'[" + std::to_string(k) + "] is " +
                      exact_number_text(value) + ", not an integer in [1, " + std::to_string(limits[k]) + "]");
    sides[k] = static_cast<int>(value);
  }
  for (const auto& entry : texture.side_data)
    if (entry.first != kReducedSizeKey)
      fail(kName, "unknown side data '" + entry.first + "'; expected " + kReducedSizeKey);
  return {sides[0], sides[1]};
}

// The image the inner format codes: the source, or its BT.601 luma as a one-channel image (R = G = B = Y').
Image coded_source(const Image& image, const std::string& source) {
  if (source == "rgb") return image;
  if (source != "bt601_luma") fail(kName, "option 'source': '" + source + "' is not one of rgb, bt601_luma");
  Image luma(image.width, image.height, 1);
  luma.metadata = image.metadata;
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    double y = 0.0;
    for (int c = 0; c < 3; ++c) y += kLumaWeights[c] * std::clamp(static_cast<double>(image.pixels[i * 4 + c]), 0.0, 1.0);
    for (int c = 0; c < 3; ++c) luma.pixels[i * 4 + c] = static_cast<float>(y);
  }
  return luma;
}

class DownscaledFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "Scaled-down BCn (Mavridis & Papaioannou 2012, Table 4's scaled DXTC): Lanczos-3 downscale, inner bc1 / "
           "bc3 / bc4 / bc7 blocks at the reduced size, bilinear upscale; inner bpp * scale^2";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        choice_option("inner", "bc1", kInnerFormats, "the BCn format coding the reduced image"),
        real_option("scale", 0.75, 0.01, 1.0,
                    "reduced side = round(side * scale), at least 1; rate = inner bpp * scale^2 (ignored when bpp > 0)"),
        real_option("bpp", 0.0, 0.0, 8.0,
                    "target rate; > 0 sets scale = sqrt(bpp / inner bpp) (at most the inner rate), 0 = use scale"),
        choice_option("source", "rgb", {"rgb", "bt601_luma"},
                      "what is coded: the RGB(A) texels, or BT.601 luma as a one-channel image (gray baselines)"),
        integer_option("lanczos_lobes", 3, 1, 8,
                       "lobes a of the Lanczos downscale filter (support a / scale source texels on each side)"),
        choice_option("inner_preset", kDefaultPreset, kInnerPresets, "the inner format's preset (its search effort)"),
    };
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"inner", "a block of the inner format at the reduced size (its own modes are not reported)"}};
  }
  // The inner format's presets, passed through.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("inner_preset", "fast", "medium", "thorough");
  }
  int block_bytes(const FormatOptions& options) const override {
    return inner_format(options).block_bytes(inner_options(options));
  }
  // The nominal rate: the inner rate times the area ratio (the stored blocks cover the reduced image; its rounding
  // to whole texels and blocks moves the exact rate of a given size slightly, README.md).
  double bits_per_pixel(const FormatOptions& options) const override {
    const double bpp = option_real(options, "bpp");
    if (bpp > 0.0) return bpp;
    const double scale = option_real(options, "scale");
    return inner_bits_per_pixel(options) * scale * scale;
  }
  std::size_t stored_block_count(const EncodedTexture& texture) const override {
    const ReducedSize reduced = stored_reduced_size(texture);
    return BlockGrid(reduced.width, reduced.height).block_count();
  }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const Format& inner = inner_format(options);
    const FormatOptions inner_resolved = inner_options(options);
    const double scale = effective_scale(options);
    const int width = reduced_side(image.width, scale), height = reduced_side(image.height, scale);

    Image reduced = coded_source(image, option_text(options, "source"));
    if (width != image.width || height != image.height) {
      reduced = lanczos_resize(reduced, width, height, static_cast<int>(option_int(options, "lanczos_lobes")));
      // The Lanczos lobes overshoot near edges; the inner formats code values in [0, 1].
      for (float& value : reduced.pixels) value = std::clamp(value, 0.0f, 1.0f);
    }
    const EncodedTexture coded = inner.encode(reduced, inner_resolved, context);
    if (!coded.side_data.empty()) fail(kName, "inner format '" + inner.name() + "' wrote side data, which is not stored");

    EncodedTexture texture;
    texture.format = kName;
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = coded.channels;
    texture.block_bytes = coded.block_bytes;
    texture.blocks = coded.blocks;
    texture.side_data[kReducedSizeKey] = {static_cast<double>(width), static_cast<double>(height)};
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    const EncodedTexture coded = inner_texture(texture);
    const Image reduced = find_format(coded.format).decode(coded, context);
    if (reduced.width == texture.width && reduced.height == texture.height) return reduced;
    return bilinear_resize(reduced, texture.width, texture.height);
  }

  // The inner texture at the reduced size: what a renderer samples (with bilinear filtering, magnified).
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override {
    return {{"", inner_texture(texture)}};
  }

 private:
  EncodedTexture inner_texture(const EncodedTexture& texture) const {
    validate_encoded_texture(*this, texture, kName);
    const ReducedSize reduced = stored_reduced_size(texture);
    EncodedTexture coded;
    coded.format = inner_format(texture.options).name();
    coded.options = inner_options(texture.options);
    coded.width = reduced.width;
    coded.height = reduced.height;
    coded.channels = texture.channels;
    coded.block_bytes = texture.block_bytes;
    coded.blocks = texture.blocks;
    validate_encoded_texture(find_format(coded.format), coded, kName);
    return coded;
  }
};

}  // namespace

const Format& downscaled_format() {
  static const DownscaledFormat format;
  return format;
}

}  // namespace blocklab
