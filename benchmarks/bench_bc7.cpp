// BC7 encoder quality and speed per preset (formats/bc7): mean per-image PSNR (SPECS.md 1d: 8-bit RGB code values,
// MSE over all R, G, B samples, 10 log10(255^2 / MSE), mean of the per-image values) on the Kodak set and on the
// LDR texture set, and encode throughput in megapixels per second at 1 thread (per CPU-second of the process, so a
// busy shared machine does not distort it) and at all threads (wall clock).
// Also checks that the output bytes are identical at 1 thread and at all threads.
//
// Usage: bench_bc7 [--presets fast,default,thorough] [--data DIR (default ../shared/data)] [--limit N images per
//                  set] [--set key=value ...extra bc7 options] [--markdown]
// Prints a Markdown table (copied into docs/benchmarks-bc7.md with the command line).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "formats/registry.h"

namespace {

using blocklab::Image;

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

struct SetResult {
  double mean_psnr = 0.0;
  double megapixels = 0.0;
  double seconds_one = 0.0;
  double seconds_all = 0.0;
  bool identical = true;
  int images = 0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CPU time of the whole process: for the 1-thread encode this is the time one core spent, independent of how busy
// the (shared) machine is; the all-threads figure stays wall-clock.
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return now.tv_sec + now.tv_nsec * 1e-9;
}

SetResult run_set(const std::vector<Image>& images, const blocklab::FormatOptions& options) {
  const blocklab::Format& format = blocklab::find_format("bc7");
  SetResult result;
  for (const Image& image : images) {
    const double cpu_start = process_cpu_seconds();
    const auto one = format.encode(image, options, blocklab::CodecContext{1, 1});
    result.seconds_one += process_cpu_seconds() - cpu_start;
    const auto start = std::chrono::steady_clock::now();
    const auto all = format.encode(image, options, blocklab::CodecContext{0, 1});
    result.seconds_all += seconds_since(start);
    if (one.blocks != all.blocks) result.identical = false;
    result.mean_psnr += psnr_rgb_8bit(image, format.decode(one, {}));
    result.megapixels += image.texel_count() / 1e6;
    ++result.images;
  }
  if (result.images > 0) result.mean_psnr /= result.images;
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = std::string(BLOCKLAB_SOURCE_DIR) + "/../shared/data";
  std::string presets = "fast,default,thorough";
  int limit = 0;
  blocklab::FormatOptions extra;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--presets") presets = value;
    else if (key == "--data") data = value;
    else if (key == "--limit") limit = std::stoi(value);
    else if (key == "--set" && value.find('=') != std::string::npos)
      extra[value.substr(0, value.find('='))] = value.substr(value.find('=') + 1);
    else {
      std::fprintf(stderr, "bench_bc7: unknown argument '%s'\n", key.c_str());
      return 2;
    }
  }
  try {
    const char* set_names[2] = {"kodak", "textures"};
    std::vector<Image> sets[2];
    for (int s = 0; s < 2; ++s)
      for (const std::string& path : png_files(data + "/ldr/" + set_names[s], limit)) sets[s].push_back(blocklab::read_image(path));
    std::printf("threads (all) = %d\n\n", blocklab::resolve_thread_count(0));
    std::printf("| preset | set | images | mean PSNR (dB) | MP/s 1 thread (CPU time) | MP/s all threads (wall) | bytes 1 == all threads | expanded options |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    std::size_t start = 0;
    while (start <= presets.size()) {
      const std::size_t comma = presets.find(',', start);
      const std::string preset = presets.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      start = comma == std::string::npos ? presets.size() + 1 : comma + 1;
      blocklab::FormatOptions given = extra;
      given["preset"] = preset;
      const blocklab::Format& format = blocklab::find_format("bc7");
      const auto options = blocklab::resolve_format_options(format, given);
      std::string expanded;
      if (!sets[0].empty()) {
        const Image& probe = sets[0][0];
        Image tiny(4, 4, probe.channels);
        for (const auto& [key, value] : format.encode(tiny, options, {}).options)
          if (key != "seed" && key != "solver") expanded += key + "=" + value + " ";
      }
      for (int s = 0; s < 2; ++s) {
        if (sets[s].empty()) continue;
        const SetResult r = run_set(sets[s], options);
        std::printf("| %s | %s | %d | %.2f | %.2f | %.2f | %s | %s|\n", preset.c_str(), set_names[s], r.images, r.mean_psnr,
                    r.megapixels / r.seconds_one, r.megapixels / r.seconds_all, r.identical ? "yes" : "NO",
                    expanded.c_str());
        std::fflush(stdout);
      }
    }
  } catch (const blocklab::Error& error) {
    std::fprintf(stderr, "bench_bc7: %s\n", error.what());
    return 1;
  }
  return 0;
}
