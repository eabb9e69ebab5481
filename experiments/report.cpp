// `blocklab report` (experiments/report.h): the HTML page and its Markdown twin from run folders.
#include "experiments/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "experiments/results_writer.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace fs = std::filesystem;

namespace blocklab {

namespace {

std::string read_text_if_present(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::string number(double value, int significant = 4) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant, value);
  return buffer;
}

std::string file_safe(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
  return out;
}

bool higher_is_better(const std::string& column) {
  for (const Metric* metric : all_metrics())
    if (metric->name() == column) return metric->higher_is_better();
  return column.find("psnr") != std::string::npos;
}

struct Run {
  fs::path dir;
  std::vector<nlohmann::json> records;   // status ok only
  std::size_t failed = 0;
  nlohmann::json provenance;
  std::string config_text, experiment;
  std::vector<std::string> metrics;      // metric columns, in the order of the first record's keys
};

Run load_run(const std::string& dir) {
  Run run;
  run.dir = dir;
  if (!fs::is_directory(dir)) fail(dir, "not a run folder (no such directory)");
  for (nlohmann::json& record : read_records((fs::path(dir) / "results.jsonl").string())) {
    if (record.value("status", std::string()) != "ok") {
      ++run.failed;
      continue;
    }
    run.records.push_back(std::move(record));
  }
  const std::string provenance = read_text_if_present(fs::path(dir) / "provenance.json");
  if (!provenance.empty()) {
    try {
      run.provenance = nlohmann::json::parse(provenance);
    } catch (const nlohmann::json::exception& e) {
      fail((fs::path(dir) / "provenance.json").string(), std::string("not JSON: ") + e.what());
    }
  }
  run.config_text = read_text_if_present(fs::path(dir) / "config.yaml");
  run.experiment = run.provenance.value("experiment", run.records.empty() ? std::string("?")
                                                                            : run.records.front().value("experiment", std::string("?")));
  std::set<std::string> seen;
  for (const nlohmann::json& record : run.records)
    for (const auto& [name, value] : record["metrics"].items())
      if (seen.insert(name).second) run.metrics.push_back(name);
  return run;
}

// Variant name of a record: its label, the options that differ between records of the same label, its ablation.
std::map<const nlohmann::json*, std::string> variant_names(const Run& run) {
  std::map<std::string, std::map<std::string, std::set<std::string>>> values;   // label -> option -> values
  for (const nlohmann::json& record : run.records)
    for (const auto& [key, value] : record["options"].items())
      values[record.value("label", std::string())][key].insert(value.dump());
  std::map<const nlohmann::json*, std::string> names;
  for (const nlohmann::json& record : run.records) {
    const std::string label = record.value("label", std::string());
    std::string name = label;
    for (const auto& [key, value] : record["options"].items())
      if (values[label][key].size() > 1)
        name += " " + key + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
    const std::string ablation = record.value("ablation", std::string("baseline"));
    if (ablation != "baseline") name += " [" + ablation + "]";
    names[&record] = name;
  }
  return names;
}

std::string primary_metric(const Run& run) {
  for (const char* preferred : {"log2rgb", "psnr"})
    if (std::find(run.metrics.begin(), run.metrics.end(), preferred) != run.metrics.end()) return preferred;
  return run.metrics.empty() ? std::string() : run.metrics.front();
}

struct VariantSummary {
  std::string name;
  double bpp = 0.0;
  int images = 0;
  std::map<std::string, std::pair<double, int>> metric_sums;   // sum, finite count
  double encode = 0.0, decode = 0.0;
};

std::vector<VariantSummary> summarise(const Run& run) {
  const auto names = variant_names(run);
  std::vector<VariantSummary> out;
  for (const nlohmann::json& record : run.records) {
    const std::string& name = names.at(&record);
    auto found = std::find_if(out.begin(), out.end(), [&](const VariantSummary& v) { return v.name == name; });
    if (found == out.end()) {
      out.push_back({name, record.value("bpp", 0.0), 0, {}, 0.0, 0.0});
      found = out.end() - 1;
    }
    found->images += 1;
    found->encode += record.value("encode_seconds", 0.0);
    found->decode += record.value("decode_seconds", 0.0);
    for (const std::string& metric : run.metrics) {
      const double value = record["metrics"].contains(metric)
                               ? metric_value_from_json(record["metrics"][metric]).value_or(std::nan(""))
                               : std::nan("");
      auto& [sum, count] = found->metric_sums[metric];
      if (std::isfinite(value)) {
        sum += value;
        ++count;
      }
    }
  }
  return out;
}

// Tone mapping of the thumbnails: exposure so the crop's log-average luminance is 0.18, x / (1 + x), gamma 2.2.
double exposure_of(const Image& image) {
  double log_sum = 0.0;
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const float* p = &image.pixels[i * 4];
    const double luminance = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    log_sum += std::log(1e-6 + std::max(luminance, 0.0));
  }
  const double log_average = std::exp(log_sum / static_cast<double>(std::max<std::size_t>(image.texel_count(), 1)));
  return 0.18 / std::max(log_average, 1e-9);
}

Image display_image(const Image& image, bool hdr, double exposure) {
  Image out(image.width, image.height, 3);
  for (std::size_t i = 0; i < image.texel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      double v = std::max(0.0, static_cast<double>(image.pixels[i * 4 + c]));
      if (hdr) {
        v *= exposure;
        v = std::pow(v / (1.0 + v), 1.0 / 2.2);
      }
      out.pixels[i * 4 + c] = static_cast<float>(std::min(v, 1.0));
    }
  return out;
}

// Grey error map: R of the metric's error map over its 99th percentile (white), clamped.
Image grey_error_map(const Image& map, double* scale) {
  std::vector<float> values(map.texel_count());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = map.pixels[i * 4];
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  *scale = sorted.empty() ? 1.0 : std::max(1e-12, static_cast<double>(sorted[sorted.size() * 99 / 100]));
  Image out(map.width, map.height, 3);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float v = static_cast<float>(std::min(1.0, std::max(0.0, values[i] / *scale)));
    for (int c = 0; c < 3; ++c) out.pixels[i * 4 + c] = v;
  }
  return out;
}

Image centred_crop(const Image& image, int size) {
  const int width = std::min(size, image.width), height = std::min(size, image.height);
  return crop_image(image, (image.width - width) / 2 & ~3, (image.height - height) / 2 & ~3, width, height);
}

struct Page {
  std::string html, markdown;
  void section(const std::string& title, int level) {
    html += "<h" + std::to_string(level) + ">" + escape_markup(title) + "</h" + std::to_string(level) + ">\n";
    markdown += std::string(static_cast<std::size_t>(level), '#') + " " + title + "\n\n";
  }
  void paragraph(const std::string& text) {
    html += "<p>" + escape_markup(text) + "</p>\n";
    markdown += text + "\n\n";
  }
  void table(const ReportTable& table) {
    html += table.html();
    markdown += table.markdown() + "\n";
  }
  void preformatted(const std::string& title, const std::string& text) {
    html += "<details><summary>" + escape_markup(title) + "</summary><pre>" + escape_markup(text) + "</pre></details>\n";
    markdown += "<details><summary>" + title + "</summary>\n\n```\n" + text + (text.empty() || text.back() == '\n' ? "" : "\n") +
                "```\n\n</details>\n\n";
  }
};

const char* const kStyle =
    "body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1em}caption{font-weight:bold;text-align:left;padding:0.3em 0}"
    "th,td{border:1px solid #bbb;padding:2px 6px;font-size:13px;text-align:right}th{background:#eee}"
    "td:first-child,th:first-child{text-align:left}.note{font-size:13px;color:#555;max-width:1000px}"
    "figure{display:inline-block;margin:4px;text-align:center;font-size:11px;vertical-align:top}"
    "figure img{image-rendering:pixelated;border:1px solid #999;display:block}pre{background:#f6f6f6;padding:6px;"
    "overflow:auto;font-size:12px}.thumbs{margin-bottom:1em}";

}  // namespace

void write_report(const ReportSettings& settings, const ReportProgress& progress) {
  if (settings.run_dirs.empty()) fail("report", "no run folder given");
  if (settings.out_dir.empty()) fail("report", "--out is required");
  std::vector<Run> runs;
  for (const std::string& dir : settings.run_dirs) runs.push_back(load_run(dir));
  const fs::path out(settings.out_dir), images_dir = fs::path(settings.out_dir) / "img";
  fs::create_directories(images_dir);

  Page page;
  page.section("blocklab report", 1);
  std::string run_list;
  for (const Run& run : runs)
    run_list += (run_list.empty() ? "" : ", ") + run.experiment + " (" + std::to_string(run.records.size()) +
                " cells" + (run.failed > 0 ? ", " + std::to_string(run.failed) + " failed" : std::string()) + ")";
  page.paragraph("Runs: " + run_list + ". Generated by `blocklab report` " + BLOCKLAB_VERSION + ".");

  // Paper tables: every published table whose experiment one of the runs is.
  std::vector<nlohmann::json> all_records;
  std::set<std::string> experiments;
  for (const Run& run : runs) {
    experiments.insert(run.experiment);
    all_records.insert(all_records.end(), run.records.begin(), run.records.end());
  }
  bool any_paper_table = false;
  if (fs::is_directory(settings.papers_dir)) {
    std::vector<fs::path> papers;
    for (const auto& entry : fs::directory_iterator(settings.papers_dir))
      if (fs::exists(entry.path() / "published.yaml")) papers.push_back(entry.path());
    std::sort(papers.begin(), papers.end());
    for (const fs::path& paper : papers)
      for (const PublishedTable& table : load_published_tables((paper / "published.yaml").string())) {
        if (experiments.count(table.experiment) == 0) continue;
        if (!any_paper_table) page.section("Paper tables: published against ours", 2);
        any_paper_table = true;
        page.paragraph(table.paper + " (" + (paper / "published.yaml").string() + ")");
        page.table(paper_table(table, all_records));
      }
  }

  // Thumbnails are the slow part: count them first for the progress display.
  std::size_t total = 0, done = 0;
  for (const Run& run : runs) {
    std::set<std::string> images;
    for (const nlohmann::json& record : run.records) {
      const std::string image = record["image"].get<std::string>();
      if (images.count(image) == 0 && static_cast<int>(images.size()) < settings.thumbnail_images) images.insert(image);
      if (images.count(image) != 0) ++total;
    }
  }

  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Run& run = runs[r];
    const std::string prefix = "run" + std::to_string(r + 1);
    page.section("Run " + std::to_string(r + 1) + ": " + run.experiment, 2);
    page.paragraph("Folder: " + run.dir.string());

    // Summary table.
    const std::vector<VariantSummary> summary = summarise(run);
    ReportTable table;
    table.title = "Mean over the images per variant (finite values; encode and decode seconds as recorded)";
    table.header = {"variant", "bpp", "images"};
    for (const std::string& metric : run.metrics) table.header.push_back(metric);
    table.header.push_back("encode s");
    table.header.push_back("decode s");
    for (const VariantSummary& v : summary) {
      std::vector<std::string> row = {v.name, number(v.bpp), std::to_string(v.images)};
      for (const std::string& metric : run.metrics) {
        const auto& [sum, count] = v.metric_sums.at(metric);
        row.push_back(count > 0 ? number(sum / count) + (count < v.images ? " (" + std::to_string(count) + " finite)"
                                                                            : std::string())
                                : "-");
      }
      row.push_back(number(v.encode / v.images));
      row.push_back(number(v.decode / v.images));
      table.rows.push_back(std::move(row));
    }
    page.table(table);

    // Plots: error against encode time per bit rate.
    const std::string metric = primary_metric(run);
    std::map<double, std::vector<PlotPoint>> by_bpp;
    for (const VariantSummary& v : summary) {
      const auto found = v.metric_sums.find(metric);
      if (found == v.metric_sums.end() || found->second.second == 0) continue;
      by_bpp[v.bpp].push_back({v.name, v.encode / v.images, found->second.first / found->second.second});
    }
    if (!metric.empty()) {
      page.section("Error against encode time", 3);
      for (const auto& [bpp, points] : by_bpp) {
        const std::string title = run.experiment + ": " + metric + " at " + number(bpp) + " bpp";
        const std::string svg = error_time_svg(title, metric, higher_is_better(metric), points);
        const std::string file = prefix + "_plot_" + file_safe(number(bpp)) + "bpp.svg";
        write_file_atomically((images_dir / file).string(), svg);
        page.html += "<figure class=\"plot\">" + svg + "</figure>\n";
        page.markdown += "![" + title + "](img/" + file + ")\n\n";
      }
    }

    // Thumbnails.
    page.section("Thumbnails", 3);
    page.paragraph("A centred " + std::to_string(settings.thumbnail_size) + "x" +
                   std::to_string(settings.thumbnail_size) +
                   " crop of each image, re-encoded with each variant's recorded options and seed: source (HDR "
                   "tone-mapped: log-average to 0.18, x/(1+x), gamma 2.2), decoded, and the per-pixel error map "
                   "(log2rgb for HDR, psnr for LDR; white = the crop's 99th percentile, printed below it); the "
                   "run's mode map when the cell wrote one. First " +
                   std::to_string(settings.thumbnail_images) + " images of the run.");
    const std::string data_root = run.provenance.value("data_root", std::string());
    std::vector<std::string> images;
    for (const nlohmann::json& record : run.records) {
      const std::string image = record["image"].get<std::string>();
      if (std::find(images.begin(), images.end(), image) == images.end() &&
          static_cast<int>(images.size()) < settings.thumbnail_images)
        images.push_back(image);
    }
    const auto names = variant_names(run);
    for (const std::string& image_name : images) {
      page.html += "<h4>" + escape_markup(image_name) + "</h4>\n<div class=\"thumbs\">\n";
      page.markdown += "#### " + image_name + "\n\n";
      const fs::path source_path = fs::path(data_root) / image_name;
      if (data_root.empty() || !fs::exists(source_path)) {
        page.paragraph("(source not found under the run's data root '" + data_root + "': no thumbnails)");
        page.html += "</div>\n";
        continue;
      }
      Image source = read_image(source_path.string());
      const bool hdr = source.metadata.is_hdr;
      std::string image_markdown;
      const std::string stem = prefix + "_" + file_safe(image_name);
      bool source_written = false;
      Image crop;
      double exposure = 1.0;
      for (const nlohmann::json& record : run.records) {
        if (record["image"].get<std::string>() != image_name) continue;
        if (progress) progress(done, total, run.experiment + " " + image_name + " " + names.at(&record));
        ++done;
        if (!source_written) {
          Image reference = source;
          apply_input_policy(reference, input_policy_from_string(record.value("input_policy", std::string("clamp"))),
                             source_path.string());
          if (record.contains("crop") && record["crop"].is_object())
            reference = crop_image(reference, record["crop"]["x"], record["crop"]["y"], record["crop"]["width"],
                                   record["crop"]["height"]);
          crop = centred_crop(reference, settings.thumbnail_size);
          exposure = exposure_of(crop);
          write_image((images_dir / (stem + "_source.png")).string(), display_image(crop, hdr, exposure));
          page.html += "<figure><img src=\"img/" + stem + "_source.png\" alt=\"source\" width=\"" +
                       std::to_string(crop.width) + "\" height=\"" + std::to_string(crop.height) +
                       "\"><figcaption>source</figcaption></figure>\n";
          image_markdown += "| source | ![source](img/" + stem + "_source.png) | |\n";
          source_written = true;
        }
        const std::string variant = names.at(&record);
        const std::string vstem = stem + "_" + file_safe(variant);
        const Format& format = find_format(record["format"].get<std::string>());
        FormatOptions options;
        for (const auto& [key, value] : record["options"].items())
          options[key] = value.is_string() ? value.get<std::string>() : value.dump();
        const std::uint64_t seed = record.value("seed", static_cast<std::uint64_t>(1));
        const EncodedTexture texture = format.encode(crop, options, CodecContext{0, seed});
        const Image decoded = format.decode(texture, CodecContext{0, seed});
        write_image((images_dir / (vstem + "_decoded.png")).string(), display_image(decoded, hdr, exposure));
        double scale = 1.0;
        const Metric& error_metric = find_metric(hdr ? "log2rgb" : "psnr");
        write_image((images_dir / (vstem + "_error.png")).string(),
                    grey_error_map(error_metric.error_map(crop, decoded, {}), &scale));
        page.html += "<figure><img src=\"img/" + vstem + "_decoded.png\" alt=\"decoded " + escape_markup(variant) +
                     "\" width=\"" + std::to_string(crop.width) + "\" height=\"" + std::to_string(crop.height) +
                     "\"><figcaption>" + escape_markup(variant) + "</figcaption></figure>\n<figure><img src=\"img/" +
                     vstem + "_error.png\" alt=\"error " + escape_markup(variant) + "\" width=\"" +
                     std::to_string(crop.width) + "\" height=\"" + std::to_string(crop.height) +
                     "\"><figcaption>error, white = " + number(scale, 3) + "</figcaption></figure>\n";
        image_markdown += "| " + variant + " | ![decoded](img/" + vstem + "_decoded.png) | ![error, white = " +
                          number(scale, 3) + "](img/" + vstem + "_error.png) |\n";
        if (record.contains("artifacts") && record["artifacts"].contains("mode_map")) {
          const fs::path mode_map = run.dir / record["artifacts"]["mode_map"].get<std::string>();
          if (fs::exists(mode_map)) {
            fs::copy_file(mode_map, images_dir / (vstem + "_modes.png"), fs::copy_options::overwrite_existing);
            page.html += "<figure><img src=\"img/" + vstem + "_modes.png\" alt=\"mode map " + escape_markup(variant) +
                         "\" height=\"" + std::to_string(crop.height) + "\"><figcaption>mode map (whole image)"
                         "</figcaption></figure>\n";
            image_markdown += "| " + variant + " mode map | ![mode map](img/" + vstem + "_modes.png) | |\n";
          }
        }
      }
      page.html += "</div>\n";
      page.markdown += "| | image | error map |\n|---|---|---|\n" + image_markdown + "\n";
    }

    // Provenance.
    page.section("Provenance", 3);
    const nlohmann::json& p = run.provenance;
    page.paragraph("Commit " + p.value("git_sha", std::string("unknown")) +
                   (p.contains("git_dirty") && p["git_dirty"] == true ? " (dirty)" : "") + ", blocklab " +
                   p.value("blocklab_version", std::string("?")) + ", " + p.value("compiler", std::string("?")) + " " +
                   p.value("build_type", std::string("")) + ", CPU " + p.value("cpu_model", std::string("?")) + " (" +
                   (p.contains("hardware_threads") ? p["hardware_threads"].dump() : std::string("?")) +
                   " hardware threads, " + (p.contains("threads_used") ? p["threads_used"].dump() : std::string("?")) +
                   " used), started " + p.value("start_time", std::string("?")) + ", data root " +
                   p.value("data_root", std::string("?")) + ".");
    ReportTable resolved;
    resolved.title = "Resolved options per variant";
    resolved.header = {"variant", "format", "revision", "options"};
    std::set<std::string> listed;
    for (const nlohmann::json& record : run.records) {
      const std::string& variant = names.at(&record);
      if (!listed.insert(variant).second) continue;
      resolved.rows.push_back({variant, record.value("format", std::string()),
                               record.contains("format_revision") ? record["format_revision"].dump() : "",
                               record["options"].dump()});
    }
    page.table(resolved);
    page.preformatted("provenance.json", p.is_null() ? std::string("(none)") : p.dump(2));
    page.preformatted("config.yaml", run.config_text.empty() ? std::string("(none)") : run.config_text);
  }
  if (progress) progress(done, total, "done");

  const std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>blocklab "
                           "report</title>\n<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n" +
                           page.html + "</body>\n</html>\n";
  write_file_atomically((out / "index.html").string(), html);
  write_file_atomically((out / "report.md").string(), page.markdown);
}

}  // namespace blocklab
