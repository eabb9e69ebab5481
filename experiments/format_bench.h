// `blocklab bench formats`: every registered format at each of its presets, side by side with the peer encoders
// (experiments/peer_encoders.h: astcenc at 4x4, 6x6, 8x8; libsquish and NVTT 2.0 for BC1/BC3), on one core, on the
// images that suit each encoder, and the Pareto front of error against encode time at each bit rate.
//
// Which images suit a format: a format whose decoder returns values above 1 for an HDR input (a constant 16x16
// image of 4.0, encoded at its fast preset) is an HDR format and runs on the HDR images; any other (every LDR codec
// clamps to [0, 1]) runs on the LDR (PNG) images. astcenc runs on both (-ch on HDR, -cl on LDR); squish and NVTT on
// LDR only. An image is LDR when it is a PNG (told by its magic bytes), HDR otherwise.
//
// Protocol: the reference is the image after the clamp input policy. Every encoder runs on one core (our formats:
// CodecContext{1 thread}; process CPU time of the encode and the decode call; peers as peer_encoders.h says).
// Within a round every encoder of an image runs once, one after the other (alternating), so a slow drift of the
// machine's speed hits all of them alike; with repeat > 1 the times are medians over the rounds and our formats
// must give the same bytes in every round. The speed ratio of a row is its encode time over the reference
// encoder's (default astcenc-4x4-medium) on the same image in the same process: the median of the per-round
// ratios; empty when the reference did not run on that image.
//
// Metrics ("every metric the image's kind reads", metrics/): HDR: log2rgb (2^-24 floor rule), log2rgb_skip
// (log2rgb with zero_rule=skip), mpsnr (fixed stops -10..10), mpsnr_auto, pu21_psnr, psnr (code values clamped to
// [0, 1]); LDR: psnr, psnr_luma.
//
// Pareto front: per image kind and bit rate, each encoder's error (HDR: mean log2[RGB] over the images, lower is
// better; LDR: mean PSNR, higher is better) against its total encode seconds; an encoder is on the front when no
// other encoder at the same bit rate is at least as fast and at least as good, and strictly better in one.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace blocklab {

struct FormatBenchSettings {
  std::string data_root;
  std::vector<std::string> images;     // relative to data_root; empty: every image under <root>/hdr and <root>/ldr
  std::vector<std::string> formats;    // registered format names and peer format names (astcenc-4x4, squish-bc1,
                                       // nvtt-bc3); empty: every registered format and every available peer
  std::vector<std::string> presets = {"fast", "medium", "thorough"};
  std::string reference = "astcenc-4x4-medium";
  int repeat = 1;
  bool peers = true;
};

struct FormatBenchRow {
  std::string format, preset, image, kind;   // kind: "hdr" or "ldr"
  double bpp = 0.0;
  std::map<std::string, double> metrics;     // column name -> value
  double encode_seconds = 0.0, decode_seconds = 0.0;
  std::optional<double> speed_ratio;         // encode time / the reference's on the same image
  std::string name() const { return format + "-" + preset; }
};

// The metric columns of one image kind, in CSV order (see above).
const std::vector<std::string>& format_bench_metric_columns(const std::string& kind);

// True when `format_name` (a registered format) decodes HDR values (see above); memoised.
bool format_reads_hdr(const std::string& format_name);

using FormatBenchProgress = std::function<void(std::size_t done, std::size_t total, const std::string& current)>;

// Runs the benchmark; throws Error naming the image, format or preset that is wrong. Warnings (a peer tool that is
// missing, a reference that never ran) go to `warnings`.
std::vector<FormatBenchRow> run_format_bench(const FormatBenchSettings& settings, const FormatBenchProgress& progress,
                                             std::vector<std::string>* warnings);

// One CSV: format,preset,image,kind,bpp,<every HDR metric>,<every LDR metric not already listed>,encode_seconds,
// decode_seconds,speed_ratio (a metric the row's kind does not read is empty; inf/-inf/nan as words).
std::string format_bench_csv(const std::vector<FormatBenchRow>& rows);

struct ParetoPoint {
  std::string kind, name;
  double bpp = 0.0, error = 0.0, encode_seconds = 0.0;
  int images = 0;
  bool on_front = false;
};
// Every encoder's aggregate per kind and bit rate (sorted by kind, bpp, encode time), flagged when on the front.
std::vector<ParetoPoint> pareto_points(const std::vector<FormatBenchRow>& rows);
// The front as a Markdown table (kind, bpp, encoder, error metric, encode seconds).
std::string pareto_markdown(const std::vector<ParetoPoint>& points);

}  // namespace blocklab
