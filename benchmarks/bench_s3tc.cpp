// BC1 / BC3 quality and speed against the reference encoders available on Debian 12:
//   * blocklab `bc1` / `bc3` (search = fast, default, exhaustive), single thread and all threads;
//   * libsquish 1.15 (squish::CompressImage with kColourRangeFit, kColourClusterFit, kColourIterativeClusterFit;
//     single-threaded library);
//   * NVIDIA Texture Tools 2.0 `nvcompress -fast -bc1|-bc3 -nomips` run as a command on the PNG (its own
//     "time taken" report is used as its compression time, which excludes process start and PNG loading).
// Every encoder's blocks are decoded by blocklab's reference decoder (formats/common/s3tc_common.h: bit-replicated
// endpoints, exact-fraction interpolants), so the PSNR columns compare encoders, not decoders; libsquish's own
// integer decoder (squish::DecompressImage) is reported as an extra column. PSNR as SPECS.md 1d: RGB code values,
// MSE over all R, G, B samples of an image, mean of the per-image PSNR; BC3 also reports the alpha PSNR for sources
// with alpha. Throughput is megapixels per second of encoding (blocks only; image loading excluded); single-thread
// rows (threads = 1, libsquish) are timed in process CPU time so that other jobs on a shared machine do not skew the
// ratios, multi-thread rows in wall-clock time, NVTT by its own wall-clock report. libsquish gets alpha = 255 for
// bc1 (blocklab's bc1 ignores alpha; squish's DXT1 would make texels with alpha < 128 transparent).
//
// libsquish and NVTT run through experiments/peer_encoders.h (squish_peer, nvtt_peer), shared with
// `blocklab bench formats`.
//
// Usage: bench_s3tc [--data DIR] [--set kodak|textures|all] [--no-exhaustive] [--no-nvtt] [--no-squish] [--limit N]
// DIR defaults to <source>/../shared/data/ldr. The output is a Markdown table (docs/benchmarks-s3tc.md).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/bench_args.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "experiments/peer_encoders.h"
#include "formats/registry.h"

namespace fs = std::filesystem;
using namespace blocklab;

namespace {

struct Measurement {
  double psnr_sum = 0.0, alpha_psnr_sum = 0.0, own_decoder_psnr_sum = 0.0;
  int images = 0, alpha_images = 0;
  double seconds = 0.0, megapixels = 0.0;
  bool has_own_decoder = false;
};

double psnr(const Image& reference, const Image& test, int first_channel, int channel_count) {
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.texel_count(); ++i)
    for (int c = first_channel; c < first_channel + channel_count; ++c) {
      const double a = std::clamp(static_cast<double>(reference.pixels[i * 4 + c]), 0.0, 1.0);
      const double b = std::clamp(static_cast<double>(test.pixels[i * 4 + c]), 0.0, 1.0);
      sum += (a - b) * (a - b);
    }
  const double mse = sum / (static_cast<double>(reference.texel_count()) * channel_count);
  return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 99.0;   // identical: capped for the mean
}

void add_quality(Measurement& m, const Image& source, const Image& decoded, bool with_alpha) {
  m.psnr_sum += psnr(source, decoded, 0, 3);
  m.images += 1;
  if (with_alpha && source.channels == 4) {
    m.alpha_psnr_sum += psnr(source, decoded, 3, 1);
    m.alpha_images += 1;
  }
}

// Single-threaded runs are timed in process CPU time, which a machine shared with other jobs does not inflate;
// multi-threaded runs in wall-clock time.
class Stopwatch {
 public:
  explicit Stopwatch(bool cpu_time) : cpu_time_(cpu_time), wall_start_(std::chrono::steady_clock::now()) {
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu_start_);
  }
  double seconds() const {
    if (!cpu_time_) return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
    timespec now;
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec - cpu_start_.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec - cpu_start_.tv_nsec);
  }

 private:
  bool cpu_time_;
  std::chrono::steady_clock::time_point wall_start_;
  timespec cpu_start_{};
};

struct Row {
  std::string format, encoder, threads;
  Measurement m;
};

std::string fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = std::string(BLOCKLAB_SOURCE_DIR) + "/../shared/data/ldr";
  std::string set = "all";
  bool exhaustive = true, nvtt = true, use_squish = true;
  int limit = 0;   // 0: every image of the set
  bench::CommandLine command_line(
      "bench_s3tc", "[--data DIR] [--set kodak|textures|all] [--no-exhaustive] [--no-nvtt] [--no-squish] [--limit N]",
      "BC1 / BC3 quality and speed of blocklab, libsquish and NVTT on the LDR sets (Markdown table).");
  command_line.add_data(data, "the LDR image root (DIR/kodak, DIR/textures)");
  command_line.app()
      .add_option("--set", set, "image set: a folder under DIR, or all (kodak and textures)")
      ->type_name("kodak|textures|all")
      ->capture_default_str();
  command_line.app().add_flag_callback("--no-exhaustive", [&exhaustive] { exhaustive = false; },
                                       "leave out search=exhaustive");
  command_line.app().add_flag_callback("--no-nvtt", [&nvtt] { nvtt = false; }, "no NVTT rows");
  command_line.app().add_flag_callback("--no-squish", [&use_squish] { use_squish = false; }, "no libsquish rows");
  command_line.add_integer("--limit", limit, 0, 100000, "images per set (0: all)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  if (use_squish && !peer_tool_available("squish")) {
    std::fprintf(stderr, "libsquish not linked: squish rows skipped\n");
    use_squish = false;
  }
  if (nvtt && !peer_tool_available("nvtt")) {
    std::fprintf(stderr, "nvcompress not found: NVTT rows skipped\n");
    nvtt = false;
  }
  const int all_threads = resolve_thread_count(0);
  const fs::path temp = fs::temp_directory_path() / ("bench_s3tc_" + std::to_string(::getpid()));
  fs::create_directories(temp);

  std::vector<std::string> sets = set == "all" ? std::vector<std::string>{"kodak", "textures"}
                                               : std::vector<std::string>{set};
  for (const std::string& image_set : sets) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(fs::path(data) / image_set))
      if (entry.path().extension() == ".png") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    if (limit > 0 && files.size() > static_cast<std::size_t>(limit)) files.resize(static_cast<std::size_t>(limit));
    if (files.empty()) {
      std::fprintf(stderr, "no PNG images in %s/%s\n", data.c_str(), image_set.c_str());
      continue;
    }
    std::vector<Row> rows;
    std::map<std::string, std::size_t> row_index;
    const auto row = [&](const std::string& format, const std::string& encoder, const std::string& threads) -> Measurement& {
      const std::string key = format + "|" + encoder + "|" + threads;
      auto found = row_index.find(key);
      if (found == row_index.end()) {
        row_index[key] = rows.size();
        rows.push_back({format, encoder, threads, {}});
        return rows.back().m;
      }
      return rows[found->second].m;
    };

    for (const fs::path& file : files) {
      const Image source = read_image(file.string());
      const double megapixels = static_cast<double>(source.texel_count()) / 1e6;
      std::fprintf(stderr, "%s (%dx%d)\n", file.filename().c_str(), source.width, source.height);
      for (const std::string format : {"bc1", "bc3"}) {
        const Format& f = find_format(format);
        std::vector<std::string> searches = {"fast", "default"};
        if (exhaustive) searches.push_back("exhaustive");
        for (const std::string& search : searches) {
          for (const int threads : {1, all_threads}) {
            // Exhaustive is slow: measured with all threads only.
            if (search == "exhaustive" && threads == 1 && all_threads > 1) continue;
            const FormatOptions options = resolve_format_options(f, {{"search", search}});
            const Stopwatch stopwatch(threads == 1);
            const EncodedTexture texture = f.encode(source, options, CodecContext{threads, 1});
            const double seconds = stopwatch.seconds();
            Measurement& m = row(format, "blocklab " + search, std::to_string(threads));
            m.seconds += seconds;
            m.megapixels += megapixels;
            add_quality(m, source, f.decode(texture, CodecContext{0, 1}), format == "bc3");
          }
        }
        if (use_squish) {
          const std::pair<const char*, const char*> fits[] = {{"fast", "squish range fit"},
                                                              {"medium", "squish cluster fit"},
                                                              {"thorough", "squish iterative cluster fit"}};
          for (const auto& [preset, label] : fits) {
            const PeerRun run = squish_peer(format, preset).run(source, temp);
            Measurement& m = row(format, label, "1");
            m.seconds += run.encode_seconds;
            m.megapixels += megapixels;
            m.has_own_decoder = true;
            m.own_decoder_psnr_sum += psnr(source, *run.own_decoded, 0, 3);
            add_quality(m, source, run.decoded, format == "bc3");
          }
        }
        if (nvtt) {
          try {
            const PeerRun run = nvtt_peer(format, "fast").run(source, temp);
            Measurement& m = row(format, "nvcompress -fast", "1");
            m.seconds += run.encode_seconds;
            m.megapixels += megapixels;
            add_quality(m, source, run.decoded, format == "bc3");
          } catch (const Error& error) {
            std::fprintf(stderr, "nvcompress failed: %s\n", error.what());
          }
        }
      }
    }

    std::printf("\n### %s (%zu images, %s)\n\n", image_set.c_str(), files.size(), (data + "/" + image_set).c_str());
    std::printf("| format | encoder | threads | PSNR RGB (dB) | PSNR own decoder | PSNR alpha | MP/s | speed vs squish ICF |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
      const Measurement* icf = nullptr;
      for (const Row& other : rows)
        if (other.format == r.format && other.encoder == "squish iterative cluster fit") icf = &other.m;
      const double rate = r.m.megapixels / r.m.seconds;
      const std::string ratio = icf != nullptr ? fixed(rate / (icf->megapixels / icf->seconds), 2) + "x" : "-";
      std::printf("| %s | %s | %s | %s | %s | %s | %s | %s |\n", r.format.c_str(), r.encoder.c_str(), r.threads.c_str(),
                  fixed(r.m.psnr_sum / r.m.images, 3).c_str(),
                  r.m.has_own_decoder ? fixed(r.m.own_decoder_psnr_sum / r.m.images, 3).c_str() : "-",
                  r.m.alpha_images > 0 ? fixed(r.m.alpha_psnr_sum / r.m.alpha_images, 3).c_str() : "-",
                  fixed(rate, 3).c_str(), ratio.c_str());
    }
    std::fflush(stdout);
  }
  fs::remove_all(temp);
  return 0;
}
