// Encoder speed of `mavridis` (Mavridis & Papaioannou 2012; formats/mavridis): a 512x512 colour texture (the
// top-left 512x512 of a Kodak image) at 3 bpp, preset medium, one thread; goal < 1 s. Side by side with astcenc
// (Debian package astcenc, an external process: `astcenc -cl IN.png OUT.astc 4x4 -medium -j 1`, decoded with
// `astcenc -dl`). Times: ours the process CPU time of the encode call, astcenc the user + sys time of the child
// (getrusage); medians over the rounds, each round running both once. Also the PSNR (metrics/psnr) of both.
//
// Usage: bench_mavridis [--data DIR] [--image ldr/kodak/kodim03.png] [--size 512] [--repeat 3] [--set key=value ...]
//                       [--no-astcenc]
// Prints a Markdown table; asserts nothing (formats/mavridis/README.md, "Speed", has the results).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "benchmarks/bench_cpu_time.h"
#include "core/error.h"
#include "core/image_io.h"
#include "formats/registry.h"
#include "metrics/metric.h"

using namespace blocklab;
using bench::children_cpu_seconds;
using bench::median;
using bench::process_cpu_seconds;

int main(int argc, char** argv) {
  std::string data = "../shared/data", image_path = "ldr/kodak/kodim03.png";
  int size = 512, repeat = 3;
  bool astcenc = true;
  FormatOptions given = {{"bpp", "3"}, {"preset", "medium"}};
  bench::CommandLine command_line(
      "bench_mavridis",
      "[--data DIR] [--image ldr/kodak/kodim03.png] [--size 512] [--repeat 3] [--set key=value ...] [--no-astcenc]",
      "Encoder speed of mavridis (3 bpp, preset medium, one thread) on the top-left SIZE x SIZE of a colour image, "
      "side by side with astcenc 4x4 -medium.");
  command_line.add_data(data);
  command_line.app().add_option("--image", image_path, "the image, relative to the data root")
      ->type_name("REL")
      ->capture_default_str();
  command_line.add_integer("--size", size, 1, 65536, "side of the top-left crop");
  command_line.add_repeat(repeat, "rounds, each running both encoders once; times are medians over the rounds");
  command_line.add_settings(given, "mavridis format option (repeatable), over bpp=3 preset=medium");
  command_line.add_no_astcenc(astcenc);
  if (const auto status = command_line.parse(argc, argv)) return *status;
  try {
    const Image full = read_image((std::filesystem::path(data) / image_path).string());
    const int width = std::min(size, full.width), height = std::min(size, full.height);
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) std::memcpy(image.texel(x, y), full.texel(x, y), 4 * sizeof(float));
    astcenc = astcenc && bench::astcenc_found();
    const std::filesystem::path scratch =
        std::filesystem::temp_directory_path() / ("bench_mavridis_" + std::to_string(::getpid()));
    std::filesystem::create_directories(scratch);
    const std::string png = (scratch / "in.png").string(), astc = (scratch / "out.astc").string(),
                      back = (scratch / "back.png").string();
    write_image(png, image);

    const Format& format = find_format("mavridis");
    const FormatOptions options = resolve_format_options(format, given);
    std::vector<double> ours, theirs, ratios;
    EncodedTexture texture;
    for (int round = 0; round < repeat; ++round) {
      const double start = process_cpu_seconds();
      texture = format.encode(image, options, CodecContext{1, 1});
      ours.push_back(process_cpu_seconds() - start);
      if (astcenc) {
        const double before = children_cpu_seconds();
        const std::string command = "astcenc -cl '" + png + "' '" + astc + "' 4x4 -medium -j 1 > /dev/null 2>&1";
        if (std::system(command.c_str()) != 0) fail("bench_mavridis", "astcenc failed: " + command);
        theirs.push_back(children_cpu_seconds() - before);
        ratios.push_back(ours.back() / theirs.back());
      }
    }
    const double our_psnr = find_metric("psnr").compute(image, format.decode(texture, CodecContext{1, 1}), {}).value;
    std::string settings;
    for (const auto& [key, value] : given) settings += (settings.empty() ? "" : " ") + key + "=" + value;
    std::printf("%dx%d crop of %s, %d rounds, one thread (medians)\n\n", width, height, image_path.c_str(), repeat);
    std::printf("| encoder | bpp | s (1 core) | / astcenc -medium | PSNR (dB) |\n|---|---|---|---|---|\n");
    std::printf("| mavridis %s | %.3g | %.3f | %s | %.2f |\n", settings.c_str(), format.bits_per_pixel(options),
                median(ours), astcenc ? std::to_string(median(ratios)).substr(0, 5).c_str() : "-", our_psnr);
    if (astcenc) {
      const std::string command = "astcenc -dl '" + astc + "' '" + back + "' > /dev/null 2>&1";
      if (std::system(command.c_str()) != 0) fail("bench_mavridis", "astcenc -dl failed: " + command);
      Image decoded = read_image(back);
      const double psnr = find_metric("psnr").compute(image, decoded, {}).value;
      std::printf("| astcenc 4x4 -medium | 8 | %.3f | 1 | %.2f |\n", median(theirs), psnr);
    }
    std::filesystem::remove_all(scratch);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_mavridis: %s\n", e.what());
    return 1;
  }
  return 0;
}
