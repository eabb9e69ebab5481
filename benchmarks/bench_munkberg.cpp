// Speed and quality of the `munkberg` presets (Munkberg et al. 2008; formats/munkberg) side by side with astcenc
// (Debian package astcenc, run as an external process through experiments/peer_encoders.h astcenc_peer:
// `astcenc -ch IN OUT 4x4 -fast|-medium|-thorough -j 1`), with
// log2[RGB] (eq. 1, metrics/log2rgb) and mPSNR (metrics/mpsnr) against the same reference: the image after the clamp
// input policy. astcenc gets that reference as a float32 EXR and its output is decoded with `astcenc -dh` (half EXR).
//
// Per image and encoder (each munkberg preset, each astcenc level): one-core CPU time (ours: process CPU time of the
// encode call at 1 thread; astcenc: user + sys of the child, getrusage) scaled to a 1024x1024 image (65,536 blocks),
// its ratio to astcenc -medium (the median of the per-round ratios), log2[RGB] with both zero rules (floor 2^-24,
// and skip: values <= 0 in either image left out) and mPSNR. With --rules, also the time
// and output of munkberg with each exact speed-up switched off (munkberg::ExactSpeedups: skip_constant,
// skip_mode_bound): the time the rule saves and whether the bytes are identical.
//
// Usage: bench_munkberg [--data DIR] [--images a,b,...] [--presets a,b] [--crop N] [--set key=value ...] [--rules]
//                       [--no-astcenc] [--repeat N] [--csv FILE]
//   --data     data root (default ../shared/data); images are read from DIR/hdr
//   --images   default Desk.exr,memorial.hdr,dani_cathedral_oBBC.hdr (the paper's desk, memorial, cathedral)
//   --presets  munkberg presets to run (default fast,medium,thorough; `paper` is slow)
//   --crop N   encode the top-left min(N, width) x min(N, height) part (default 1024: none of the three is 1024x1024
//              in both directions, so they are encoded whole)
//   --set      munkberg format option (repeatable) applied on top of every preset, e.g. --set solver=procrustes
//   --repeat N N rounds per image (default 3); within a round every encoder runs once, alternating, so a slow drift
//              of the machine's speed hits all of them alike. Times are medians over the rounds. On the shared VMs
//              we run on, one run can be 20 % off the next with nothing changed.
//   --csv FILE the table as CSV (image,encoder,seconds,seconds_per_1024x1024,ratio_to_astcenc_medium,log2rgb,
//              log2rgb_skip,mpsnr)
// Prints a Markdown table; asserts nothing (docs/benchmarks-munkberg.md has the results).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "benchmarks/bench_cpu_time.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "experiments/peer_encoders.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace {

using namespace blocklab;

using bench::process_cpu_seconds;

Image crop(const Image& image, int size) {
  const int width = std::min(size, image.width), height = std::min(size, image.height);
  if (width == image.width && height == image.height) return image;
  Image out(width, height, image.channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) std::memcpy(out.texel(x, y), image.texel(x, y), 4 * sizeof(float));
  return out;
}

double metric_value(const char* metric, const Image& reference, const Image& test, const MetricOptions& options = {}) {
  return find_metric(metric).compute(reference, test, options).value;
}

struct Encoded {
  double seconds = 0.0;
  EncodedTexture texture;
};

// Times of one measurement over the rounds.
struct Timings {
  std::vector<double> seconds;

  double median() const {
    std::vector<double> sorted = seconds;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  }
};

Encoded encode_one_core(const Image& image, const FormatOptions& given,
                        const munkberg::ExactSpeedups& speedups = munkberg::ExactSpeedups{}) {
  const Format& format = find_format("munkberg");
  const FormatOptions options = resolve_format_options(format, given);
  Encoded out;
  const double start = process_cpu_seconds();
  out.texture = munkberg::encode_with_speedups(image, options, CodecContext{1, 1}, speedups);
  out.seconds = process_cpu_seconds() - start;
  return out;
}

// One encoder of the comparison: a munkberg preset or an astcenc level.
struct Encoder {
  std::string label;             // "munkberg fast", "astcenc -medium"
  std::string preset;            // munkberg preset; empty for astcenc
  std::optional<PeerEncoder> astcenc;   // the astcenc level (experiments/peer_encoders.h); empty for ours
  Timings times;
  std::vector<double> ratios;    // per round, to astcenc -medium
  EncodedTexture texture;        // ours: round 0's
  Image peer_decoded;            // astcenc: round 0's decoded image
};

struct Row {
  std::string image, encoder;
  double seconds = 0.0, per_megapixel = 0.0, ratio = 0.0, log2rgb = 0.0, log2rgb_skip = 0.0, mpsnr = 0.0;
  bool has_ratio = false;
};

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", csv_path;
  std::vector<std::string> images = {"Desk.exr", "memorial.hdr", "dani_cathedral_oBBC.hdr"};
  std::vector<std::string> presets = {"fast", "medium", "thorough"};
  int crop_size = 1024;
  int repeat = 3;
  bool rules = false, astcenc = true;
  FormatOptions given;
  bench::CommandLine command_line(
      "bench_munkberg",
      "[--data DIR] [--images a,b,...] [--presets a,b] [--crop N] [--set key=value ...] [--rules] [--no-astcenc] "
      "[--repeat N] [--csv FILE]",
      "Speed and quality of the munkberg presets side by side with astcenc 4x4 -fast/-medium/-thorough.");
  command_line.add_data(data, "data root; images are read from DIR/hdr");
  command_line.add_list("--images", images, "the paper's desk, memorial, cathedral by default");
  command_line.add_list("--presets", presets, "munkberg presets to run (`paper` is slow)");
  command_line.add_integer("--crop", crop_size, 1, 65536,
                           "encode the top-left min(N, width) x min(N, height) part (none of the default three is "
                           "1024x1024 in both directions, so they are encoded whole)");
  command_line.add_settings(given, "munkberg format option (repeatable) applied on top of every preset, e.g. --set "
                                   "solver=procrustes");
  command_line.app().add_flag("--rules", rules, "also time munkberg with each exact speed-up switched off");
  command_line.add_no_astcenc(astcenc);
  command_line.add_repeat(repeat, "rounds per image; within a round every encoder runs once, alternating, so a slow "
                                  "drift of the machine's speed hits all of them alike. Times are medians over the "
                                  "rounds.");
  command_line.add_csv(csv_path, "the table as CSV (image,encoder,seconds,seconds_per_1024x1024,"
                                 "ratio_to_astcenc_medium,log2rgb,log2rgb_skip,mpsnr)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  astcenc = astcenc && bench::astcenc_found();
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "bench_munkberg";
  std::filesystem::create_directories(scratch);

  std::vector<Row> rows;
  std::vector<std::string> rule_rows;
  try {
    for (const std::string& name : images) {
      const std::string path = data + "/hdr/" + name;
      Image image = read_image(path);
      apply_input_policy(image, InputPolicy::clamp, path);
      image = crop(image, crop_size);
      const double blocks = static_cast<double>(((image.width + 3) / 4) * ((image.height + 3) / 4));
      const double per_megapixel = 65536.0 / blocks;

      std::vector<Encoder> encoders;
      for (const std::string& preset : presets) encoders.push_back({"munkberg " + preset, preset, {}, {}, {}, {}, {}});
      std::size_t astcenc_medium = encoders.size();
      if (astcenc)
        for (const char* level : {"fast", "medium", "thorough"}) {
          if (std::string(level) == "medium") astcenc_medium = encoders.size();
          const PeerEncoder peer = astcenc_peer("4x4", level, true);
          encoders.push_back({"astcenc " + peer.level, "", peer, {}, {}, {}, {}});
        }
      for (int round = 0; round < repeat; ++round) {
        for (Encoder& encoder : encoders) {
          if (!encoder.preset.empty()) {
            FormatOptions options = given;
            options["preset"] = encoder.preset;
            Encoded run = encode_one_core(image, options);
            encoder.times.seconds.push_back(run.seconds);
            if (round == 0) {
              encoder.texture = std::move(run.texture);
            } else if (run.texture.blocks != encoder.texture.blocks) {
              fail("bench_munkberg", name + ": round " + std::to_string(round) + " of " + encoder.label +
                                         " encoded other bytes than round 0");
            }
          } else {
            PeerRun run = encoder.astcenc->run(image, scratch);
            encoder.times.seconds.push_back(run.encode_seconds);
            if (round == 0) encoder.peer_decoded = std::move(run.decoded);
          }
        }
        if (astcenc_medium < encoders.size())
          for (Encoder& encoder : encoders)
            encoder.ratios.push_back(encoder.times.seconds.back() / encoders[astcenc_medium].times.seconds.back());
      }
      const Format& format = find_format("munkberg");
      for (Encoder& encoder : encoders) {
        Image decoded;
        if (!encoder.preset.empty()) {
          decoded = format.decode(encoder.texture, CodecContext{1, 1});
        } else {
          decoded = encoder.peer_decoded;
        }
        Row row;
        row.image = name;
        row.encoder = encoder.label;
        row.seconds = encoder.times.median();
        row.per_megapixel = row.seconds * per_megapixel;
        row.has_ratio = !encoder.ratios.empty();
        if (row.has_ratio) row.ratio = Timings{encoder.ratios}.median();
        row.log2rgb = metric_value("log2rgb", image, decoded);
        row.log2rgb_skip = metric_value("log2rgb", image, decoded, {{"zero_rule", "skip"}});
        row.mpsnr = metric_value("mpsnr", image, decoded);
        rows.push_back(row);
      }

      if (rules) {
        const Encoder& first = encoders.front();
        const double ours_seconds = first.times.median();
        for (const char* rule : {"skip_constant", "skip_mode_bound"}) {
          munkberg::ExactSpeedups speedups;
          (std::string(rule) == "skip_constant" ? speedups.skip_constant : speedups.skip_mode_bound) = false;
          FormatOptions options = given;
          options["preset"] = first.preset;
          Encoded without;
          Timings without_times;
          for (int round = 0; round < repeat; ++round) {
            Encoded run = encode_one_core(image, options, speedups);
            without_times.seconds.push_back(run.seconds);
            if (round == 0) without = std::move(run);
          }
          without.seconds = without_times.median();
          const bool identical = without.texture.blocks == first.texture.blocks;
          char row[512];
          std::snprintf(row, sizeof row, "| %s | %s | %s | %.2f | %.2f | %+.2f (%+.1f %%) | %s |", name.c_str(),
                        first.label.c_str(), rule, without.seconds, ours_seconds, without.seconds - ours_seconds,
                        100.0 * (without.seconds - ours_seconds) / without.seconds, identical ? "yes" : "no");
          rule_rows.push_back(row);
        }
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_munkberg: %s\n", e.what());
    return 1;
  }
  std::printf("Times: one core, median of %d rounds (every encoder once per round, alternating).\n\n", repeat);
  std::printf("| image | encoder | s (1 core) | s per 1024x1024 | / astcenc -medium | log2[RGB] | log2[RGB] skip | "
              "mPSNR (dB) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    char ratio[32] = "n/a";
    if (row.has_ratio) std::snprintf(ratio, sizeof ratio, "%.2f", row.ratio);
    std::printf("| %s | %s | %.2f | %.2f | %s | %.4f | %.4f | %.2f |\n", row.image.c_str(), row.encoder.c_str(),
                row.seconds, row.per_megapixel, ratio, row.log2rgb, row.log2rgb_skip, row.mpsnr);
  }
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "image,encoder,seconds,seconds_per_1024x1024,ratio_to_astcenc_medium,log2rgb,log2rgb_skip,mpsnr\n";
    for (const Row& row : rows) {
      char line[512];
      std::snprintf(line, sizeof line, "%s,%s,%.4f,%.4f,%s,%.6f,%.6f,%.4f\n", row.image.c_str(),
                    row.encoder.c_str(), row.seconds, row.per_megapixel,
                    row.has_ratio ? std::to_string(row.ratio).c_str() : "", row.log2rgb, row.log2rgb_skip, row.mpsnr);
      csv << line;
    }
    if (!csv) {
      std::fprintf(stderr, "bench_munkberg: cannot write %s\n", csv_path.c_str());
      return 1;
    }
  }
  if (rules) {
    std::printf("\n| image | encoder | rule | s with the rule off | s with it on | saved | bytes identical |\n"
                "|---|---|---|---|---|---|---|\n");
    for (const std::string& row : rule_rows) std::printf("%s\n", row.c_str());
  }
  return 0;
}
