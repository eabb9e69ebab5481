// BC7 encoder quality and speed per preset (formats/bc7), side by side with astcenc 4x4 (the Debian package
// astcenc, run as an external process like benchmarks/bench_munkberg.cpp: `astcenc -cl IN.png OUT.astc 4x4 -medium
// -j 1`, decoded with `astcenc -dl OUT.astc BACK.png`; ASTC 4x4 is 8 bpp like BC7).
//
// Quality: mean per-image PSNR (SPECS.md 1d: 8-bit RGB code values, MSE over all R, G, B samples,
// 10 log10(255^2 / MSE), mean of the per-image values) on the Kodak set and on the LDR texture set, the same metric
// for both encoders. Speed: megapixels per CPU-second at one thread (ours: process CPU time of the encode call at 1
// thread; astcenc: user + sys CPU time of the child, getrusage, which also includes its PNG read and .astc write),
// so a busy shared machine distorts neither side much; per image every encoder runs once in turn (alternating), so
// a drift of the machine's speed hits all of them alike. Ours is also encoded at all threads (wall clock) to check
// that the bytes are identical at 1 thread and at all threads.
//
// Usage: bench_bc7 [--presets fast,medium,thorough] [--astcenc -medium,-thorough | none] [--data DIR (default
//                  ../shared/data)] [--limit N images per set] [--sets kodak,textures] [--set key=value ...extra bc7
//                  options] [--csv FILE]
// Prints a Markdown table and, per set and preset, the ratio lines to astcenc -medium (PSNR difference in dB,
// speed ratio); with --csv also the table as CSV (set,encoder,images,mean_psnr_db,megapixels,cpu_seconds,
// mp_per_cpu_second,mp_per_wall_second_all_threads,bytes_identical_1_vs_all_threads). Asserts nothing:
// docs/benchmarks-bc7.md has the results.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "benchmarks/bench_cpu_time.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "formats/registry.h"

namespace bench = blocklab::bench;

namespace {

using blocklab::Image;
using bench::children_cpu_seconds;
using bench::process_cpu_seconds;

double psnr_rgb_8bit(const Image& original, const Image& decoded) {
  double squared = 0.0;
  for (std::size_t i = 0; i < original.texel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = std::lround(std::fmin(std::fmax(original.pixels[i * 4 + c], 0.0f), 1.0f) * 255.0f);
      const double b = std::lround(std::fmin(std::fmax(decoded.pixels[i * 4 + c], 0.0f), 1.0f) * 255.0f);
      squared += (a - b) * (a - b);
    }
  const double mse = squared / (3.0 * original.texel_count());
  // Identical images: PSNR is infinite; report a cap so means stay finite (never happens on these sets).
  return mse == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

std::vector<std::string> png_files(const std::string& folder, int limit) {
  std::vector<std::string> files;
  if (!std::filesystem::is_directory(folder)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".png") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  if (limit > 0 && static_cast<int>(files.size()) > limit) files.resize(limit);
  return files;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One encoder of the comparison on one set: a bc7 preset or an astcenc level.
struct Encoder {
  std::string label;           // "bc7 medium", "astcenc -medium"
  std::string preset;          // bc7 preset; empty for astcenc
  std::string astcenc_level;   // "-medium", "-thorough"
  blocklab::FormatOptions options;
  std::string expanded;        // bc7: the resolved options as recorded in the result
  double psnr_sum = 0.0, megapixels = 0.0, cpu_seconds = 0.0, wall_seconds_all = 0.0;
  int images = 0;
  bool identical = true;

  double mean_psnr() const { return images > 0 ? psnr_sum / images : 0.0; }
  double speed() const { return megapixels / cpu_seconds; }
};

void run_bc7(Encoder& encoder, const Image& image) {
  const blocklab::Format& format = blocklab::find_format("bc7");
  const double cpu_start = process_cpu_seconds();
  const auto one = format.encode(image, encoder.options, blocklab::CodecContext{1, 1});
  encoder.cpu_seconds += process_cpu_seconds() - cpu_start;
  const auto start = std::chrono::steady_clock::now();
  const auto all = format.encode(image, encoder.options, blocklab::CodecContext{0, 1});
  encoder.wall_seconds_all += seconds_since(start);
  if (one.blocks != all.blocks) encoder.identical = false;
  encoder.psnr_sum += psnr_rgb_8bit(image, format.decode(one, {}));
}

void run_astcenc(Encoder& encoder, const std::string& path, const Image& image, const std::filesystem::path& scratch) {
  const std::string packed = (scratch / "out.astc").string(), back = (scratch / "back.png").string();
  const double before = children_cpu_seconds();
  const std::string command =
      "astcenc -cl '" + path + "' '" + packed + "' 4x4 " + encoder.astcenc_level + " -j 1 > /dev/null 2>&1";
  if (std::system(command.c_str()) != 0) blocklab::fail("bench_bc7", "astcenc failed: " + command);
  encoder.cpu_seconds += children_cpu_seconds() - before;
  const std::string unpack = "astcenc -dl '" + packed + "' '" + back + "' > /dev/null 2>&1";
  if (std::system(unpack.c_str()) != 0) blocklab::fail("bench_bc7", "astcenc -dl failed: " + unpack);
  encoder.psnr_sum += psnr_rgb_8bit(image, blocklab::read_image(back));
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = std::string(BLOCKLAB_SOURCE_DIR) + "/../shared/data", csv_path;
  std::vector<std::string> presets = {"fast", "medium", "thorough"};
  std::vector<std::string> astcenc_levels = {"-medium", "-thorough"};
  std::vector<std::string> set_names = {"kodak", "textures"};
  int limit = 0;
  blocklab::FormatOptions extra;
  bench::CommandLine command_line(
      "bench_bc7",
      "[--presets fast,medium,thorough] [--astcenc -medium,-thorough | none] [--data DIR] [--limit N images per set] "
      "[--sets kodak,textures] [--set key=value ...extra bc7 options] [--csv FILE]",
      "BC7 encoder quality (mean PSNR) and speed per preset, side by side with astcenc 4x4, on the Kodak and LDR "
      "texture sets.");
  command_line.add_list("--presets", presets, "bc7 presets");
  command_line.add_list("--astcenc", astcenc_levels, "astcenc quality levels (-fastest ... -exhaustive), or none");
  command_line.add_data(data, "data root; the sets are read from DIR/ldr/SET");
  command_line.add_integer("--limit", limit, 0, 100000, "images per set (0: all)");
  command_line.add_list("--sets", set_names, "image sets under DIR/ldr");
  command_line.add_settings(extra, "bc7 format option (repeatable) set over every preset");
  command_line.add_csv(csv_path, "the table as CSV (set,encoder,images,mean_psnr_db,megapixels,cpu_seconds,"
                                 "mp_per_cpu_second,mp_per_wall_second_all_threads,bytes_identical_1_vs_all_threads)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  if (astcenc_levels == std::vector<std::string>{"none"}) astcenc_levels.clear();
  for (const std::string& level : astcenc_levels)
    if (level != "-fastest" && level != "-fast" && level != "-medium" && level != "-thorough" && level != "-exhaustive") {
      std::fprintf(stderr, "bench_bc7: '--astcenc %s' is not an astcenc quality level (-fast, -medium, ...)\n",
                   level.c_str());
      return 2;
    }
  if (!astcenc_levels.empty() && !bench::astcenc_found()) astcenc_levels.clear();
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() / ("bench_bc7_" + std::to_string(getpid()));
  std::filesystem::create_directories(scratch);

  std::vector<std::pair<std::string, std::vector<Encoder>>> results;
  try {
    const blocklab::Format& format = blocklab::find_format("bc7");
    for (const std::string& set_name : set_names) {
      const std::vector<std::string> files = png_files(data + "/ldr/" + set_name, limit);
      if (files.empty()) continue;
      std::vector<Encoder> encoders;
      for (const std::string& preset : presets) {
        Encoder encoder;
        encoder.label = "bc7 " + preset;
        encoder.preset = preset;
        blocklab::FormatOptions given = extra;
        given["preset"] = preset;
        encoder.options = blocklab::resolve_format_options(format, given);
        Image tiny(4, 4, 3);
        for (const auto& [key, value] : format.encode(tiny, encoder.options, {}).options)
          if (key != "seed" && key != "solver") encoder.expanded += key + "=" + value + " ";
        encoders.push_back(encoder);
      }
      for (const std::string& level : astcenc_levels) {
        Encoder encoder;
        encoder.label = "astcenc " + level;
        encoder.astcenc_level = level;
        encoders.push_back(encoder);
      }
      for (const std::string& path : files) {
        const Image image = blocklab::read_image(path);
        for (Encoder& encoder : encoders) {   // alternating: every encoder once per image
          if (encoder.preset.empty()) run_astcenc(encoder, path, image, scratch);
          else run_bc7(encoder, image);
          encoder.megapixels += image.texel_count() / 1e6;
          ++encoder.images;
        }
      }
      results.emplace_back(set_name, std::move(encoders));
    }
  } catch (const blocklab::Error& error) {
    std::fprintf(stderr, "bench_bc7: %s\n", error.what());
    std::filesystem::remove_all(scratch);
    return 1;
  }
  std::filesystem::remove_all(scratch);

  std::printf("threads (all) = %d\n\n", blocklab::resolve_thread_count(0));
  std::printf("| encoder | set | images | mean PSNR (dB) | MP/s 1 thread (CPU time) | MP/s all threads (wall) | "
              "bytes 1 == all threads |\n|---|---|---|---|---|---|---|\n");
  for (const auto& [set_name, encoders] : results)
    for (const Encoder& e : encoders) {
      char all[32] = "-";
      if (!e.preset.empty()) std::snprintf(all, sizeof all, "%.2f", e.megapixels / e.wall_seconds_all);
      std::printf("| %s | %s | %d | %.2f | %.2f | %s | %s |\n", e.label.c_str(), set_name.c_str(), e.images,
                  e.mean_psnr(), e.speed(), all, e.preset.empty() ? "-" : (e.identical ? "yes" : "NO"));
    }
  std::printf("\nRatios to astcenc 4x4 (same images, same run; speed = CPU-time throughput ratio):\n");
  for (const auto& [set_name, encoders] : results)
    for (const Encoder& reference : encoders) {
      if (!reference.preset.empty()) continue;   // the references are the astcenc levels
      for (const Encoder& e : encoders) {
        if (e.preset.empty()) continue;
        std::printf("  %s %s: PSNR %+.2f dB vs astcenc %s (%.2f vs %.2f), speed %.2fx astcenc %s\n", set_name.c_str(),
                    e.label.c_str(), e.mean_psnr() - reference.mean_psnr(), reference.astcenc_level.c_str(),
                    e.mean_psnr(), reference.mean_psnr(), e.speed() / reference.speed(),
                    reference.astcenc_level.c_str());
      }
    }
  std::printf("\nExpanded options:\n");
  if (!results.empty())
    for (const Encoder& e : results.front().second)
      if (!e.preset.empty()) std::printf("  %s: %s\n", e.preset.c_str(), e.expanded.c_str());

  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "set,encoder,images,mean_psnr_db,megapixels,cpu_seconds,mp_per_cpu_second,mp_per_wall_second_all_threads,"
           "bytes_identical_1_vs_all_threads\n";
    for (const auto& [set_name, encoders] : results)
      for (const Encoder& e : encoders) {
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%d,%.4f,%.4f,%.4f,%.4f,%s,%s\n", set_name.c_str(), e.label.c_str(),
                      e.images, e.mean_psnr(), e.megapixels, e.cpu_seconds, e.speed(),
                      e.preset.empty() ? "" : std::to_string(e.megapixels / e.wall_seconds_all).c_str(),
                      e.preset.empty() ? "" : (e.identical ? "yes" : "no"));
        csv << line;
      }
    if (!csv) {
      std::fprintf(stderr, "bench_bc7: cannot write %s\n", csv_path.c_str());
      return 1;
    }
  }
  return 0;
}
