// Encoder speed of the `wang` presets (Wang et al. 2007, LUVW in two DXT5; formats/wang) on the HDR images, side by
// side with astcenc 4x4 -medium (Debian package astcenc, an external process: `astcenc -ch IN OUT 4x4 -medium -j 1`,
// given the same reference, the image after the clamp input policy, as a float32 EXR). Goal: preset medium below
// 1 s per megapixel on one core.
//
// Per image and encoder: one-core CPU time (ours: process CPU time of the encode call at 1 thread; astcenc: user +
// sys of the child, getrusage), seconds per megapixel (10^6 texels), the ratio to astcenc -medium on the same image
// (median of the per-round ratios), and log2[RGB] (metrics/log2rgb) of the decoded image. The summary row per encoder
// adds the times over all images and divides by their megapixels.
//
// Usage: bench_wang [--data DIR] [--images a,b,...] [--presets a,b] [--repeat N] [--no-astcenc] [--csv FILE]
//   --data     data root (default ../shared/data); every *.exr and *.hdr in DIR/hdr unless --images
//   --images   file names under DIR/hdr
//   --presets  wang presets (default fast,medium,thorough)
//   --repeat N rounds (default 1); within a round every encoder runs once, alternating, so a drift of the shared
//              machine's speed hits all of them alike. Times are medians over the rounds.
//   --csv FILE the per-image rows as CSV (image,megapixels,encoder,seconds,seconds_per_megapixel,ratio,log2rgb)
// Prints Markdown tables; asserts nothing (docs/benchmarks-wang.md has the results).

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
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
using bench::median;
using bench::process_cpu_seconds;

// One encoder of the comparison: a wang preset or astcenc -medium.
struct Encoder {
  std::string label;    // "wang medium", "astcenc -medium"
  std::string preset;   // empty for astcenc
  std::vector<double> seconds;
  EncodedTexture texture;   // ours: round 0's
};

struct Row {
  std::string image, encoder;
  double megapixels = 0.0, seconds = 0.0, ratio = 0.0, log2rgb = 0.0;
  bool has_ratio = false;
};

std::vector<std::string> hdr_images(const std::string& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string extension = entry.path().extension().string();
    if (extension == ".exr" || extension == ".hdr") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", csv_path;
  std::vector<std::string> images;
  std::vector<std::string> presets = {"fast", "medium", "thorough"};
  int repeat = 1;
  bool astcenc = true;
  bench::CommandLine command_line("bench_wang",
                                  "[--data DIR] [--images a,b,...] [--presets a,b] [--repeat N] [--no-astcenc] "
                                  "[--csv FILE]",
                                  "Encoder speed of the wang presets on the HDR images, side by side with astcenc 4x4 "
                                  "-medium.");
  command_line.add_data(data, "data root; every *.exr and *.hdr in DIR/hdr unless --images");
  command_line.add_list("--images", images, "file names under DIR/hdr");
  command_line.add_list("--presets", presets, "wang presets");
  command_line.add_repeat(repeat, "rounds; within a round every encoder runs once, alternating, so a drift of the "
                                  "shared machine's speed hits all of them alike. Times are medians over the rounds.");
  command_line.add_no_astcenc(astcenc);
  command_line.add_csv(csv_path, "the per-image rows as CSV (image,megapixels,encoder,seconds,seconds_per_megapixel,"
                                 "ratio,log2rgb)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  astcenc = astcenc && bench::astcenc_found();
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "bench_wang";
  std::vector<Row> rows;
  std::map<std::string, double> total_seconds;   // per encoder label, over all images
  std::vector<std::string> labels;
  double total_megapixels = 0.0;
  try {
    std::filesystem::create_directories(scratch);
    if (images.empty()) images = hdr_images(data + "/hdr");
    if (images.empty()) fail(data + "/hdr", "no .exr or .hdr images");
    const Format& format = find_format("wang");
    for (const std::string& name : images) {
      const std::string path = data + "/hdr/" + name;
      Image image = read_image(path);
      apply_input_policy(image, InputPolicy::clamp, path);
      const double megapixels = static_cast<double>(image.texel_count()) * 1e-6;
      total_megapixels += megapixels;

      std::vector<Encoder> encoders;
      for (const std::string& preset : presets) encoders.push_back({"wang " + preset, preset, {}, {}});
      const std::size_t astcenc_medium = encoders.size();
      if (astcenc) encoders.push_back({"astcenc -medium", "", {}, {}});
      if (labels.empty())
        for (const Encoder& encoder : encoders) labels.push_back(encoder.label);
      const std::string in = (scratch / "in.exr").string(), packed = (scratch / "out.astc").string(),
                        back = (scratch / "back.exr").string();
      if (astcenc) {
        WriteOptions float32;
        float32.exr_pixel_type = ExrPixelType::float32;
        write_image(in, image, float32);
      }
      std::vector<std::vector<double>> ratios(encoders.size());
      for (int round = 0; round < repeat; ++round) {
        for (Encoder& encoder : encoders) {
          if (!encoder.preset.empty()) {
            const FormatOptions options = resolve_format_options(format, {{"preset", encoder.preset}});
            const double start = process_cpu_seconds();
            EncodedTexture texture = format.encode(image, options, CodecContext{1, 1});
            encoder.seconds.push_back(process_cpu_seconds() - start);
            if (round == 0) {
              encoder.texture = std::move(texture);
            } else if (texture.blocks != encoder.texture.blocks) {
              fail("bench_wang", name + ": round " + std::to_string(round) + " of " + encoder.label +
                                     " encoded other bytes than round 0");
            }
          } else {
            const double before = children_cpu_seconds();
            const std::string command = "astcenc -ch '" + in + "' '" + packed + "' 4x4 -medium -j 1 > /dev/null 2>&1";
            if (std::system(command.c_str()) != 0) fail("bench_wang", "astcenc failed: " + command);
            encoder.seconds.push_back(children_cpu_seconds() - before);
          }
        }
        if (astcenc)
          for (std::size_t e = 0; e < encoders.size(); ++e)
            ratios[e].push_back(encoders[e].seconds.back() / encoders[astcenc_medium].seconds.back());
      }
      for (std::size_t e = 0; e < encoders.size(); ++e) {
        Encoder& encoder = encoders[e];
        Image decoded;
        if (!encoder.preset.empty()) {
          decoded = format.decode(encoder.texture, CodecContext{1, 1});
        } else {
          const std::string unpack = "astcenc -dh '" + packed + "' '" + back + "' > /dev/null 2>&1";
          if (std::system(unpack.c_str()) != 0) fail("bench_wang", "astcenc -dh failed: " + unpack);
          decoded = read_image(back);
        }
        Row row;
        row.image = name;
        row.encoder = encoder.label;
        row.megapixels = megapixels;
        row.seconds = median(encoder.seconds);
        row.has_ratio = !ratios[e].empty();
        if (row.has_ratio) row.ratio = median(ratios[e]);
        row.log2rgb = find_metric("log2rgb").compute(image, decoded, {}).value;
        total_seconds[encoder.label] += row.seconds;
        rows.push_back(row);
        std::fprintf(stderr, "%s %s: %.2f s\n", name.c_str(), encoder.label.c_str(), row.seconds);
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_wang: %s\n", e.what());
    return 1;
  }
  std::printf("Times: one core, median of %d round(s) (every encoder once per round, alternating).\n\n", repeat);
  std::printf("| image | MP | encoder | s (1 core) | s per MP | / astcenc -medium | log2[RGB] |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    char ratio[32] = "n/a";
    if (row.has_ratio) std::snprintf(ratio, sizeof ratio, "%.2f", row.ratio);
    std::printf("| %s | %.2f | %s | %.2f | %.2f | %s | %.4f |\n", row.image.c_str(), row.megapixels,
                row.encoder.c_str(), row.seconds, row.seconds / row.megapixels, ratio, row.log2rgb);
  }
  std::printf("\nAll %zu images, %.2f MP:\n\n| encoder | s (1 core) | s per MP | / astcenc -medium |\n"
              "|---|---|---|---|\n",
              images.size(), total_megapixels);
  for (const std::string& label : labels) {
    char ratio[32] = "n/a";
    if (astcenc) std::snprintf(ratio, sizeof ratio, "%.2f", total_seconds[label] / total_seconds["astcenc -medium"]);
    std::printf("| %s | %.1f | %.2f | %s |\n", label.c_str(), total_seconds[label],
                total_seconds[label] / total_megapixels, ratio);
  }
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "image,megapixels,encoder,seconds,seconds_per_megapixel,ratio_to_astcenc_medium,log2rgb\n";
    for (const Row& row : rows) {
      char line[512];
      std::snprintf(line, sizeof line, "%s,%.6f,%s,%.4f,%.4f,%s,%.6f\n", row.image.c_str(), row.megapixels,
                    row.encoder.c_str(), row.seconds, row.seconds / row.megapixels,
                    row.has_ratio ? std::to_string(row.ratio).c_str() : "", row.log2rgb);
      csv << line;
    }
    if (!csv) {
      std::fprintf(stderr, "bench_wang: cannot write %s\n", csv_path.c_str());
      return 1;
    }
  }
  return 0;
}
