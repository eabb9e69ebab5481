// `blocklab bench formats` (experiments/format_bench.h): our formats at their presets against the peer encoders,
// one core, alternating runs, one CSV and the Pareto front of error against encode time per bit rate.
#include "experiments/format_bench.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>

#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "experiments/peer_encoders.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace fs = std::filesystem;

namespace blocklab {

const std::vector<std::string>& format_bench_metric_columns(const std::string& kind) {
  static const std::vector<std::string> hdr = {"log2rgb", "log2rgb_skip", "mpsnr", "mpsnr_auto", "pu21_psnr", "psnr"};
  static const std::vector<std::string> ldr = {"psnr", "psnr_luma"};
  return kind == "hdr" ? hdr : ldr;
}

bool format_reads_hdr(const std::string& format_name) {
  static std::mutex mutex;
  static std::map<std::string, bool> known;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto found = known.find(format_name);
  if (found != known.end()) return found->second;
  const Format& format = find_format(format_name);
  Image probe(16, 16, 3);
  for (std::size_t i = 0; i < probe.pixels.size(); ++i) probe.pixels[i] = i % 4 == 3 ? 1.0f : 4.0f;
  const EncodedTexture texture = format.encode(probe, resolve_format_options(format, {{"preset", "fast"}}), {1, 1});
  const Image decoded = format.decode(texture, {1, 1});
  float largest = 0.0f;
  for (std::size_t i = 0; i < decoded.pixels.size(); ++i)
    if (i % 4 != 3) largest = std::max(largest, decoded.pixels[i]);
  return known[format_name] = largest > 2.0f;
}

namespace {

bool is_png(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in.gcount() == 8 && std::string(magic, 8) == "\x89PNG\r\n\x1a\n";
}

std::vector<std::string> default_images(const std::string& root) {
  std::vector<std::string> images;
  for (const char* kind : {"hdr", "ldr"}) {
    const fs::path folder = fs::path(root) / kind;
    if (!fs::is_directory(folder)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      if (ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".png")
        images.push_back(fs::relative(entry.path(), root).generic_string());
    }
  }
  std::sort(images.begin(), images.end());
  if (images.empty()) fail("bench formats", "no images under " + root + "/hdr or " + root + "/ldr");
  return images;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// One encoder of the comparison: a registered format at a preset, or a peer.
struct Contender {
  std::string format, preset;
  const Format* ours = nullptr;
  FormatOptions options;
  std::optional<PeerEncoder> peer;
  double bpp = 0.0;
  std::vector<double> encode, decode;
  Image decoded;
  std::vector<std::uint8_t> first_bytes;
  std::string name() const { return format + "-" + preset; }
};

void run_once(Contender& contender, const Image& reference, const fs::path& scratch, bool first_round,
              const std::string& image) {
  if (contender.peer) {
    PeerRun run = contender.peer->run(reference, scratch);
    contender.encode.push_back(run.encode_seconds);
    contender.decode.push_back(run.decode_seconds);
    if (first_round) contender.decoded = std::move(run.decoded);
    return;
  }
  double start = process_cpu_seconds();
  EncodedTexture texture = contender.ours->encode(reference, contender.options, CodecContext{1, 1});
  contender.encode.push_back(process_cpu_seconds() - start);
  start = process_cpu_seconds();
  Image decoded = contender.ours->decode(texture, CodecContext{1, 1});
  contender.decode.push_back(process_cpu_seconds() - start);
  if (first_round) {
    contender.decoded = std::move(decoded);
    contender.first_bytes = std::move(texture.blocks);
  } else if (texture.blocks != contender.first_bytes) {
    fail("bench formats", image + ": " + contender.name() + " encoded other bytes than in its first round");
  }
}

std::vector<Contender> contenders_for(const std::string& kind, const FormatBenchSettings& settings,
                                      const std::vector<PeerEncoder>& peers) {
  const auto selected = [&](const std::string& name) {
    return settings.formats.empty() ||
           std::find(settings.formats.begin(), settings.formats.end(), name) != settings.formats.end();
  };
  std::vector<Contender> out;
  for (const Format* format : all_formats()) {
    if (!selected(format->name()) || format_reads_hdr(format->name()) != (kind == "hdr")) continue;
    for (const FormatPreset& preset : format->presets()) {
      if (std::find(settings.presets.begin(), settings.presets.end(), preset.name) == settings.presets.end()) continue;
      Contender c;
      c.format = format->name();
      c.preset = preset.name;
      c.ours = format;
      c.options = resolve_format_options(*format, {{"preset", preset.name}});
      c.bpp = format->bits_per_pixel(c.options);
      out.push_back(std::move(c));
    }
  }
  for (const PeerEncoder& peer : peers) {
    if (peer.hdr != (kind == "hdr") || !selected(peer.format_name())) continue;
    Contender c;
    c.format = peer.format_name();
    c.preset = peer.preset;
    c.peer = peer;
    c.bpp = peer.bits_per_pixel;
    out.push_back(std::move(c));
  }
  return out;
}

std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

std::vector<FormatBenchRow> run_format_bench(const FormatBenchSettings& settings, const FormatBenchProgress& progress,
                                             std::vector<std::string>* warnings) {
  if (settings.repeat < 1) fail("--repeat", "needs a count >= 1");
  for (const std::string& preset : settings.presets)
    if (preset != "fast" && preset != "medium" && preset != "thorough" && preset != "paper")
      fail("--presets", "unknown preset '" + preset + "'; valid: fast, medium, thorough, paper");
  const std::vector<std::string> images =
      settings.images.empty() ? default_images(settings.data_root) : settings.images;
  std::vector<PeerEncoder> peers;
  if (settings.peers) {
    for (const char* tool : {"astcenc", "squish", "nvtt"})
      if (!peer_tool_available(tool) && warnings != nullptr)
        warnings->push_back(std::string(tool) + " is not available here: its rows are skipped");
    for (bool hdr : {true, false})
      for (PeerEncoder& peer : available_peers(hdr, settings.presets)) peers.push_back(std::move(peer));
  }
  if (!settings.formats.empty()) {
    std::set<std::string> known;
    for (const Format* format : all_formats()) known.insert(format->name());
    for (const char* tool : {"astcenc-4x4", "astcenc-6x6", "astcenc-8x8", "squish-bc1", "squish-bc3", "nvtt-bc1",
                             "nvtt-bc3"})
      known.insert(tool);
    for (const std::string& name : settings.formats)
      if (known.count(name) == 0) fail("--formats", "unknown format '" + name + "' (see `blocklab list`; peers: "
                                                    "astcenc-4x4, astcenc-6x6, astcenc-8x8, squish-bc1, squish-bc3, "
                                                    "nvtt-bc1, nvtt-bc3)");
  }

  // Plan: the kind of each image (by magic bytes) and the contenders of that kind, so progress knows the total.
  std::vector<std::pair<std::string, std::string>> plan;   // (image, kind)
  std::size_t total = 0;
  std::map<std::string, std::size_t> per_kind;
  for (const std::string& image : images) {
    const fs::path path = fs::path(settings.data_root) / image;
    if (!fs::is_regular_file(path)) fail("--images", "no image file " + path.string());
    const std::string kind = is_png(path) ? "ldr" : "hdr";
    if (per_kind.count(kind) == 0) per_kind[kind] = contenders_for(kind, settings, peers).size();
    plan.emplace_back(image, kind);
    total += per_kind[kind] * static_cast<std::size_t>(settings.repeat);
  }

  const fs::path scratch = fs::temp_directory_path() / ("blocklab_bench_formats_" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  struct ScratchCleanup {
    fs::path path;
    ~ScratchCleanup() { std::error_code ignored; fs::remove_all(path, ignored); }
  } cleanup{scratch};

  std::vector<FormatBenchRow> rows;
  std::size_t done = 0;
  bool reference_ran = false;
  for (const auto& [image, kind] : plan) {
    const std::string path = (fs::path(settings.data_root) / image).string();
    Image reference = read_image(path);
    apply_input_policy(reference, InputPolicy::clamp, path);
    std::vector<Contender> contenders = contenders_for(kind, settings, peers);
    std::size_t reference_index = contenders.size();
    for (std::size_t i = 0; i < contenders.size(); ++i)
      if (contenders[i].name() == settings.reference) reference_index = i;
    std::vector<std::vector<double>> ratios(contenders.size());
    for (int round = 0; round < settings.repeat; ++round) {
      for (Contender& contender : contenders) {
        if (progress) progress(done, total, image + " " + contender.name());
        run_once(contender, reference, scratch, round == 0, image);
        ++done;
      }
      if (reference_index < contenders.size())
        for (std::size_t i = 0; i < contenders.size(); ++i)
          ratios[i].push_back(contenders[i].encode.back() / contenders[reference_index].encode.back());
    }
    reference_ran = reference_ran || reference_index < contenders.size();
    for (std::size_t i = 0; i < contenders.size(); ++i) {
      Contender& contender = contenders[i];
      FormatBenchRow row;
      row.format = contender.format;
      row.preset = contender.preset;
      row.image = image;
      row.kind = kind;
      row.bpp = contender.bpp;
      for (const std::string& column : format_bench_metric_columns(kind)) {
        MetricOptions options;
        std::string metric = column;
        if (column == "log2rgb_skip") {
          metric = "log2rgb";
          options["zero_rule"] = "skip";
        }
        row.metrics[column] = find_metric(metric).compute(reference, contender.decoded, options).value;
      }
      row.encode_seconds = median(contender.encode);
      row.decode_seconds = median(contender.decode);
      if (!ratios[i].empty()) row.speed_ratio = median(ratios[i]);
      rows.push_back(std::move(row));
    }
  }
  if (progress) progress(done, total, "done");
  if (!reference_ran && warnings != nullptr)
    warnings->push_back("the reference " + settings.reference + " ran on no image: the speed_ratio column is empty");
  return rows;
}

std::string format_bench_csv(const std::vector<FormatBenchRow>& rows) {
  std::vector<std::string> columns = format_bench_metric_columns("hdr");
  for (const std::string& column : format_bench_metric_columns("ldr"))
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) columns.push_back(column);
  std::string csv = "format,preset,image,kind,bpp";
  for (const std::string& column : columns) csv += "," + column;
  csv += ",encode_seconds,decode_seconds,speed_ratio\n";
  for (const FormatBenchRow& row : rows) {
    csv += row.format + "," + row.preset + "," + row.image + "," + row.kind + "," + number_text(row.bpp);
    for (const std::string& column : columns) {
      const auto found = row.metrics.find(column);
      csv += "," + (found == row.metrics.end() ? std::string() : number_text(found->second));
    }
    csv += "," + number_text(row.encode_seconds) + "," + number_text(row.decode_seconds) + "," +
           (row.speed_ratio ? number_text(*row.speed_ratio) : std::string()) + "\n";
  }
  return csv;
}

std::vector<ParetoPoint> pareto_points(const std::vector<FormatBenchRow>& rows) {
  std::map<std::tuple<std::string, long long, std::string>, ParetoPoint> by_encoder;
  for (const FormatBenchRow& row : rows) {
    const std::string metric = row.kind == "hdr" ? "log2rgb" : "psnr";
    ParetoPoint& point = by_encoder[{row.kind, std::llround(row.bpp * 1000.0), row.name()}];
    point.kind = row.kind;
    point.name = row.name();
    point.bpp = row.bpp;
    point.error += row.metrics.at(metric);
    point.encode_seconds += row.encode_seconds;
    point.images += 1;
  }
  std::vector<ParetoPoint> points;
  for (auto& [key, point] : by_encoder) {
    point.error /= point.images;
    points.push_back(point);
  }
  // Lower is better for log2rgb (hdr); psnr (ldr) is negated for the comparison.
  const auto better_or_equal = [](const ParetoPoint& a, const ParetoPoint& b) {
    const double ea = a.kind == "hdr" ? a.error : -a.error, eb = b.kind == "hdr" ? b.error : -b.error;
    return ea <= eb && a.encode_seconds <= b.encode_seconds && (ea < eb || a.encode_seconds < b.encode_seconds);
  };
  for (ParetoPoint& point : points) {
    point.on_front = true;
    for (const ParetoPoint& other : points)
      if (other.kind == point.kind && std::llround(other.bpp * 1000.0) == std::llround(point.bpp * 1000.0) &&
          better_or_equal(other, point))
        point.on_front = false;
  }
  std::sort(points.begin(), points.end(), [](const ParetoPoint& a, const ParetoPoint& b) {
    return std::tie(a.kind, a.bpp, a.encode_seconds, a.name) < std::tie(b.kind, b.bpp, b.encode_seconds, b.name);
  });
  return points;
}

std::string pareto_markdown(const std::vector<ParetoPoint>& points) {
  std::string out = "| kind | bpp | encoder (on the front) | error | encode s (sum over images) | images |\n"
                    "|---|---|---|---|---|---|\n";
  for (const ParetoPoint& point : points) {
    if (!point.on_front) continue;
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %.3g | %s | %s %.4g | %.3f | %d |\n", point.kind.c_str(), point.bpp,
                  point.name.c_str(), point.kind == "hdr" ? "log2[RGB]" : "PSNR dB", point.error,
                  point.encode_seconds, point.images);
    out += line;
  }
  return out;
}

}  // namespace blocklab
