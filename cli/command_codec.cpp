// `blocklab encode`, `decode` and `convert`.
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/common/container.h"
#include "formats/common/dds.h"
#include "formats/common/mode_map.h"
#include "formats/registry.h"

namespace blocklab::cli {

std::pair<std::string, std::string> split_setting(const std::string& setting, const std::string& flag) {
  const auto eq = setting.find('=');
  if (eq == std::string::npos || eq == 0) fail(flag, "expected key=value, got '" + setting + "'");
  return {setting.substr(0, eq), setting.substr(eq + 1)};
}

namespace {

bool has_extension(const std::string& path, const std::string& ext) {
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

Image load_sanitised(const std::string& path, const std::string& policy_name) {
  const InputPolicy policy = input_policy_from_string(policy_name);
  Image image = read_image(path);
  const InputReport report = apply_input_policy(image, policy, path);
  if (report.changed_count() > 0) {
    std::fprintf(stderr, "blocklab: %s: input policy '%s' changed %zu values (NaN %zu, +Inf %zu, -Inf %zu, negative %zu)\n",
                 path.c_str(), policy_name.c_str(), report.changed_count(), report.nan_count,
                 report.positive_inf_count, report.negative_inf_count, report.negative_count);
  }
  return image;
}

// Says on stderr what a half-float EXR output loses (library code never prints; the CLI warns).
void warn_if_half_loses_values(const std::string& path, const Image& image, const WriteOptions& options) {
  std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".exr") return;   // write_image picks the EXR writer by this extension, in any case
  if (options.exr_pixel_type != ExrPixelType::half) return;
  const HalfConversionLoss loss = half_conversion_loss(image);
  if (!loss.any()) return;
  std::fprintf(stderr,
               "blocklab: warning: %s: half-float output: %zu values beyond +-65504 become infinite, %zu non-zero "
               "values below 2^-24 become 0 (--float keeps them)\n",
               path.c_str(), loss.overflowed, loss.flushed_to_zero);
}

// OUT.dds: a one-texture format writes OUT.dds; a format of several textures writes OUT.<suffix>.dds for each, and
// OUT.blk beside them, the container that keeps the shader constants the DDS files cannot hold.
void write_gpu_textures(const std::string& output, const Format& format, const EncodedTexture& texture) {
  const std::vector<GpuTexture> textures = format.gpu_textures(texture);
  if (textures.size() == 1 && textures[0].suffix.empty()) {
    write_dds(output, textures[0].texture);
    return;
  }
  const std::string stem = output.substr(0, output.size() - 4);
  for (const GpuTexture& gpu : textures) {
    const std::string path = stem + "." + gpu.suffix + ".dds";
    write_dds(path, gpu.texture);
    std::fprintf(stderr, "blocklab: wrote %s (%s)\n", path.c_str(), gpu.texture.format.c_str());
  }
  write_container(stem + ".blk", texture);
  std::fprintf(stderr, "blocklab: wrote %s (the %s container: its constants and side data)\n",
               (stem + ".blk").c_str(), format.name().c_str());
}

}  // namespace

int run_encode(const EncodeArgs& args) {
  const Format& format = find_format(args.format);
  FormatOptions given;
  for (const std::string& s : args.settings) {
    auto [key, value] = split_setting(s, "--set");
    if (given.count(key)) fail("--set", "option '" + key + "' given twice");
    given[key] = value;
  }
  const FormatOptions options = resolve_format_options(format, given);
  const bool dds = has_extension(args.output, ".dds");
  if (!dds && !has_extension(args.output, ".blk"))
    fail(args.output, "unknown output type; use .blk (blocklab container, any format) or .dds (formats with GPU "
                      "textures: see blocklab list)");
  // Refused before the encode, whose time would be lost: the DDS form is a property of the format.
  if (dds && !format.has_gpu_textures())
    fail(args.output, "format '" + format.name() + "' has no DDS form (it is not made of standard BCn textures); use .blk");
  const Image image = load_sanitised(args.input, args.input_policy);
  CodecContext context;
  context.threads = args.threads;
  context.seed = static_cast<std::uint64_t>(option_int(options, "seed"));
  const EncodedTexture texture = format.encode(image, options, context);
  if (dds) {
    write_gpu_textures(args.output, format, texture);
  } else {
    write_container(args.output, texture);
  }
  std::fprintf(stderr, "blocklab: %s -> %s (%s, %dx%d, %.3g bpp, %zu bytes of blocks)\n", args.input.c_str(),
               args.output.c_str(), format.name().c_str(), texture.width, texture.height,
               format.bits_per_pixel(options), texture.blocks.size());
  if (!args.mode_map.empty()) {
    const std::vector<std::string> names = format.modes();
    write_image(args.mode_map, mode_map_image(texture, names, &image));
    std::printf("mode map %s (block shares; colours: formats/common/mode_map.h)\n%s", args.mode_map.c_str(),
                mode_map_legend(mode_shares(texture, names), names).c_str());
  }
  return 0;
}

// The packed file's type is decided by its magic bytes ("DDS " or the .blk magic), not by its extension.
EncodedTexture read_packed(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, "cannot open file");
  char magic[4] = {};
  file.read(magic, 4);
  if (file.gcount() == 4 && std::memcmp(magic, "DDS ", 4) == 0) return read_dds(path);
  return read_container(path);
}

Image read_image_or_decode(const std::string& path, int threads) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, "cannot open file");
  char magic[8] = {};
  file.read(magic, 8);
  const bool dds = file.gcount() >= 4 && std::memcmp(magic, "DDS ", 4) == 0;
  const bool container = file.gcount() == 8 && std::memcmp(magic, "BLKLAB\r\n", 8) == 0;
  if (!dds && !container) return read_image(path);
  const EncodedTexture texture = read_packed(path);
  CodecContext context;
  context.threads = threads;
  return find_format(texture.format).decode(texture, context);
}

int run_decode(const DecodeArgs& args) {
  const EncodedTexture texture = read_packed(args.input);   // decode accepts packed files only
  CodecContext context;
  context.threads = args.threads;
  const Image decoded = find_format(texture.format).decode(texture, context);
  warn_if_half_loses_values(args.output, decoded, WriteOptions{});
  write_image(args.output, decoded);
  return 0;
}

int run_convert(const ConvertArgs& args) {
  // --raw keeps NaN/Inf/negative values as read (e.g. to crop test images that must keep them).
  Image image = args.raw ? read_image(args.input) : load_sanitised(args.input, args.input_policy);
  if (!args.crop.empty()) {
    int x = 0, y = 0, w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(args.crop.c_str(), "%d,%d,%d,%d%c", &x, &y, &w, &h, &tail) != 4)
      fail("--crop", "expected x,y,width,height, got '" + args.crop + "'");
    if (x < 0 || y < 0 || w <= 0 || h <= 0 || x + w > image.width || y + h > image.height)
      fail("--crop", "rectangle " + args.crop + " is not inside the " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " image " + args.input);
    image = crop_image(image, x, y, w, h);
  }
  // The input's precision is kept: a half-float EXR stays half, every other input (float EXR, PFM, RGBE, PNG)
  // becomes 32-bit float EXR, and 16-bit PNG stays 16-bit; --float / --half force the EXR pixel type.
  if (args.float_exr && args.half_exr) fail("--half", "cannot be combined with --float");
  WriteOptions options;
  const bool half = args.half_exr || (!args.float_exr && image.metadata.pixel_type == "half");
  options.exr_pixel_type = half ? ExrPixelType::half : ExrPixelType::float32;
  options.png_bits = image.metadata.pixel_type == "uint16" ? 16 : 8;
  warn_if_half_loses_values(args.output, image, options);
  write_image(args.output, image, options);
  return 0;
}

}  // namespace blocklab::cli
