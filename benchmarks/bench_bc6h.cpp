// Quality and speed of the `bc6h` (BC6H UF16) presets side by side with astcenc's HDR 4x4 ASTC (Debian package
// astcenc, external process: `astcenc -ch IN OUT 4x4 -fast|-medium|-thorough -j 1`, decoded with `astcenc -dh`),
// both at 8 bpp, one thread each, on every image of DATA/hdr (each cropped to its top-left N x N, default 512;
// --crop 0: whole images).
// Reference: the image after the clamp input policy; astcenc reads it as a float32 EXR.
// Per encoder: mean over the images of mPSNR (metrics/mpsnr), of log2[RGB] under the floor zero rule (the default,
// metrics/zero_rule.h) and under the skip rule, and the one-core CPU time (ours: process CPU time of the encode call
// at 1 thread; astcenc: user + sys of the child, getrusage) summed over the images, with its ratio to each astcenc
// level. Also checks that our bytes at all threads equal those at 1 thread.
//
// Usage: bench_bc6h [--data DIR (default ../shared/data)] [--crop N] [--images a,b,...] [--presets a,b]
//                   [--encoder 'PRESET KEY=VALUE ...']... [--format bc6h|bc6h_sf] [--astcenc fast,medium,thorough]
//                   [--no-astcenc] [--no-thread-check]
// --encoder adds one of our encoders: a preset with options set over it (e.g. 'medium error=mpsnr_weighted'); when
// given, --presets defaults to none. --astcenc chooses the astcenc levels run (default all three).
// Prints Markdown tables (formats/bc6h/README.md has the results); asserts nothing.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "benchmarks/bench_cpu_time.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace {

using namespace blocklab;

using bench::children_cpu_seconds;
using bench::process_cpu_seconds;


struct Scores {
  double mpsnr = 0.0, log2rgb = 0.0, log2rgb_skip = 0.0;
};

Scores score(const Image& reference, const Image& test) {
  Scores s;
  s.mpsnr = find_metric("mpsnr").compute(reference, test, {}).value;
  s.log2rgb = find_metric("log2rgb").compute(reference, test, {}).value;
  s.log2rgb_skip = find_metric("log2rgb").compute(reference, test, {{"zero_rule", "skip"}}).value;
  return s;
}

struct Encoder {
  std::string label, preset, astcenc_level;
  FormatOptions options;   // set over the preset
  double seconds = 0.0;
  Scores sum;
  int images = 0;
};

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", format_name = "bc6h";
  std::vector<std::string> images, presets = {"fast", "medium", "thorough"}, specs,
                           astcenc_levels = {"fast", "medium", "thorough"};
  bool thread_check = true;
  int crop_size = 512;
  bool astcenc = true;
  bench::CommandLine command_line(
      "bench_bc6h",
      "[--data DIR] [--crop N] [--images a,b,...] [--presets a,b] [--encoder 'PRESET KEY=VALUE ...']... "
      "[--format bc6h|bc6h_sf] [--astcenc fast,medium,thorough] [--no-astcenc] [--no-thread-check]",
      "Quality and speed of the bc6h presets side by side with astcenc -ch 4x4 (one thread each) on the HDR images.");
  command_line.add_data(data, "data root; every *.exr and *.hdr in DIR/hdr unless --images");
  command_line.add_integer("--crop", crop_size, 0, 65536,
                           "encode each image's top-left N x N (0: whole images; else at least 4)");
  command_line.add_list("--images", images, "file names under DIR/hdr");
  CLI::Option* presets_option =
      command_line.add_list("--presets", presets, "presets of our encoder (default none when --encoder is given)");
  command_line.app()
      .add_option("--encoder", specs,
                  "adds one of our encoders (repeatable): a preset with options set over it, e.g. 'medium "
                  "error=mpsnr_weighted'")
      ->type_name("'PRESET KEY=VALUE ...'");
  command_line.app().add_option("--format", format_name, "bc6h or bc6h_sf")->capture_default_str();
  command_line.add_list("--astcenc", astcenc_levels, "astcenc levels run");
  command_line.add_no_astcenc(astcenc);
  command_line.app().add_flag_callback("--no-thread-check", [&thread_check] { thread_check = false; },
                                       "skip the check that our bytes at all threads equal those at 1 thread");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  const bool presets_given = presets_option->count() > 0;
  if (crop_size != 0) crop_size = std::max(4, crop_size);
  astcenc = astcenc && bench::astcenc_found();
  if (images.empty()) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(data + "/hdr", error)) {
      const std::string extension = entry.path().extension().string();
      if (extension == ".exr" || extension == ".hdr") images.push_back(entry.path().filename().string());
    }
    std::sort(images.begin(), images.end());
  }
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "bench_bc6h";
  std::filesystem::create_directories(scratch);
  const std::string in = (scratch / "in.exr").string(), packed = (scratch / "out.astc").string(),
                    back = (scratch / "back.exr").string();

  std::vector<Encoder> encoders;
  if (!specs.empty() && !presets_given) presets.clear();
  for (const std::string& preset : presets) encoders.push_back({format_name + " " + preset, preset, "", {}, 0.0, {}, 0});
  for (const std::string& spec : specs) {
    std::istringstream words(spec);
    Encoder encoder{format_name + " " + spec, "", "", {}, 0.0, {}, 0};
    std::string word;
    while (words >> word) {
      const std::size_t equals = word.find('=');
      if (equals == std::string::npos) {
        encoder.preset = word;
      } else {
        encoder.options[word.substr(0, equals)] = word.substr(equals + 1);
      }
    }
    if (encoder.preset.empty()) encoder.preset = "medium";
    encoders.push_back(encoder);
  }
  if (astcenc)
    for (const std::string& level : astcenc_levels)
      encoders.push_back({"astcenc 4x4 -" + level, "", "-" + level, {}, 0.0, {}, 0});
  bool identical = true;
  std::printf("| image | encoder | s (1 core) | mPSNR (dB) | log2[RGB] floor | log2[RGB] skip |\n|---|---|---|---|---|---|\n");
  try {
    const Format& format = find_format(format_name);
    for (const std::string& name : images) {
      const std::string path = data + "/hdr/" + name;
      Image image = read_image(path);
      apply_input_policy(image, InputPolicy::clamp, path);
      if (crop_size > 0)
        image = crop_image(image, 0, 0, std::min(crop_size, image.width), std::min(crop_size, image.height));
      if (astcenc) {
        WriteOptions float32;
        float32.exr_pixel_type = ExrPixelType::float32;
        write_image(in, image, float32);
      }
      for (Encoder& encoder : encoders) {
        Image decoded;
        double seconds = 0.0;
        if (!encoder.preset.empty()) {
          FormatOptions requested = encoder.options;
          requested["preset"] = encoder.preset;
          const FormatOptions options = resolve_format_options(format, requested);
          const double start = process_cpu_seconds();
          const EncodedTexture texture = format.encode(image, options, CodecContext{1, 1});
          seconds = process_cpu_seconds() - start;
          if (thread_check) identical = identical && format.encode(image, options, CodecContext{0, 1}).blocks == texture.blocks;
          decoded = format.decode(texture, CodecContext{0, 1});
        } else {
          const double start = children_cpu_seconds();
          const std::string command =
              "astcenc -ch '" + in + "' '" + packed + "' 4x4 " + encoder.astcenc_level + " -j 1 > /dev/null 2>&1";
          if (std::system(command.c_str()) != 0) fail("bench_bc6h", "astcenc failed: " + command);
          seconds = children_cpu_seconds() - start;
          const std::string unpack = "astcenc -dh '" + packed + "' '" + back + "' > /dev/null 2>&1";
          if (std::system(unpack.c_str()) != 0) fail("bench_bc6h", "astcenc -dh failed: " + unpack);
          decoded = read_image(back);
        }
        const Scores s = score(image, decoded);
        encoder.seconds += seconds;
        encoder.sum.mpsnr += s.mpsnr;
        encoder.sum.log2rgb += s.log2rgb;
        encoder.sum.log2rgb_skip += s.log2rgb_skip;
        ++encoder.images;
        std::printf("| %s | %s | %.3f | %.2f | %.4f | %.4f |\n", name.c_str(), encoder.label.c_str(), seconds, s.mpsnr,
                    s.log2rgb, s.log2rgb_skip);
        std::fflush(stdout);
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_bc6h: %s\n", e.what());
    return 1;
  }
  std::printf("\nMeans over %zu images (crop %d), one thread; time summed. Bytes identical at all threads: %s\n\n",
              images.size(), crop_size, !thread_check ? "not checked" : identical ? "yes" : "NO");
  std::printf("| encoder | mean mPSNR (dB) | mean log2[RGB] floor | mean log2[RGB] skip | s (1 core) |");
  for (const Encoder& other : encoders)
    if (!other.astcenc_level.empty()) std::printf(" time / astcenc %s |", other.astcenc_level.c_str());
  std::printf("\n|---|---|---|---|---|");
  for (const Encoder& other : encoders)
    if (!other.astcenc_level.empty()) std::printf("---|");
  std::printf("\n");
  for (const Encoder& encoder : encoders) {
    const double n = std::max(encoder.images, 1);
    std::printf("| %s | %.3f | %.4f | %.4f | %.2f |", encoder.label.c_str(), encoder.sum.mpsnr / n,
                encoder.sum.log2rgb / n, encoder.sum.log2rgb_skip / n, encoder.seconds);
    for (const Encoder& other : encoders)
      if (!other.astcenc_level.empty()) std::printf(" %.2f |", encoder.seconds / std::max(other.seconds, 1e-9));
    std::printf("\n");
  }
  return 0;
}
