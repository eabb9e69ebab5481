// Analysis banterle_filtering (Banterle et al. 2008 section 4.5, eqs. 5-7; formats/banterle/filtering_error.h), in
// the analysis registry (experiments/analysis.h). Its keys:
//   intervals: [[0.3, 0.6], [0, 1]]  required: [a, b] pairs, 0 <= a < b <= 1
//   samples: 101                     optional: points x per curve (2..100001), default 101
//   tmo: {fit: ceres_lm}             optional. Either options of the `banterle` format (every option except bpp and
//                                    search: fit, mean, ...), fitted per image exactly as the encoder does
//                                    (default: the format's defaults); or the given parameters
//                                    {alpha: A, l_white: W, mean_luminance: M} (all three) for every image.
// It writes into the output folder:
//   filtering_curves.csv    per image and interval, `samples` rows: x, the interpolated tone-mapped value, eq. 5,
//                           eq. 6, eq. 7 (through g and by the paper's closed form), eq. 7 / eq. 5
//   filtering_measured.csv  per image: the TMO parameters and the bilinear 2x magnification error of the image
//   config.yaml, analysis.json   the config as given; the resolved data root, images, parameters, versions
// The plot is drawn from the CSVs by configs/papers/banterle2008/plot_filtering.py (matplotlib).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/banterle/banterle_format.h"
#include "formats/banterle/filtering_error.h"
#include "formats/banterle/tmo_fit.h"

namespace blocklab {

namespace {

constexpr int kMaxCurveSamples = 100001;

struct ToneInterval {
  double a = 0.0, b = 1.0;
};

struct BanterleFilteringSettings {
  std::vector<ToneInterval> intervals;
  int samples = 101;
  bool tmo_given = false;
  ReinhardParameters given;      // tmo_given
  FormatOptions fit_options;     // !tmo_given: resolved banterle options
};

BanterleFilteringSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  BanterleFilteringSettings settings;
  const YAML::Node intervals = StrictYaml::child(root, "intervals");
  if (!intervals.IsDefined()) yaml.fail_at(root, "analysis banterle_filtering needs the key 'intervals'");
  yaml.sequence(intervals, "intervals");
  if (intervals.size() == 0) yaml.fail_at(intervals, "intervals must list at least one [a, b] pair");
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const std::string path = indexed_path("intervals", i);
    const YAML::Node pair = intervals[i];
    yaml.sequence(pair, path);
    if (pair.size() != 2) yaml.fail_at(pair, path + " must be a pair [a, b], got " + std::to_string(pair.size()) + " values");
    ToneInterval interval{analysis_number(yaml, pair[0], path + "[0]"), analysis_number(yaml, pair[1], path + "[1]")};
    if (!(interval.a >= 0.0 && interval.a < interval.b && interval.b <= 1.0))
      yaml.fail_at(pair, path + " must satisfy 0 <= a < b <= 1 (tone-mapped values), got [" + yaml.scalar(pair[0], path) +
                             ", " + yaml.scalar(pair[1], path) + "]");
    settings.intervals.push_back(interval);
  }
  if (const YAML::Node n = StrictYaml::child(root, "samples"); n.IsDefined()) {
    const std::int64_t samples = yaml.integer(n, "samples");
    if (samples < 2 || samples > kMaxCurveSamples)
      yaml.fail_at(n, "samples must be in [2, " + std::to_string(kMaxCurveSamples) + "], got " + std::to_string(samples));
    settings.samples = static_cast<int>(samples);
  }
  FormatOptions given_options;
  if (const YAML::Node tmo = StrictYaml::child(root, "tmo"); tmo.IsDefined()) {
    const std::vector<std::string> keys = yaml.map_keys(tmo, "tmo");
    const std::vector<std::string> given_keys = {"alpha", "l_white", "mean_luminance"};
    std::size_t given_count = 0;
    for (const std::string& key : keys) given_count += std::count(given_keys.begin(), given_keys.end(), key);
    if (given_count > 0) {
      yaml.check_map(tmo, "tmo", given_keys, given_keys);
      settings.tmo_given = true;
      double* const slots[] = {&settings.given.alpha, &settings.given.l_white, &settings.given.mean};
      for (std::size_t k = 0; k < given_keys.size(); ++k) {
        const YAML::Node value = StrictYaml::child(tmo, given_keys[k]);
        const double parsed = analysis_number(yaml, value, "tmo." + given_keys[k]);
        if (!(parsed > 0.0)) yaml.fail_at(value, "tmo." + given_keys[k] + " must be > 0");
        *slots[k] = parsed;
      }
    } else {
      for (const std::string& key : keys) {
        const YAML::Node value = StrictYaml::child(tmo, key);
        // bpp and search change the S3TC texture, not the TMO parameters: not meaningful here.
        if (key == "bpp" || key == "search")
          yaml.fail_at(value, "tmo." + key + " does not affect the TMO parameters; use the fit options or "
                              "alpha, l_white, mean_luminance");
        given_options[key] = yaml.scalar(value, "tmo." + key);
      }
      try {
        settings.fit_options = resolve_format_options(banterle_format(), given_options);
        // The fit's solver options are checked now, so a bad key is reported at the config's line.
        resolve_tmo_fit_options(parse_tmo_fit_method(settings.fit_options.at("fit"), "banterle"),
                                parse_tmo_fit_options(settings.fit_options.at("fit_options"), "banterle"), "banterle");
      } catch (const Error& e) {
        yaml.fail_at(tmo, std::string("tmo: ") + e.what());
      }
    }
  } else {
    settings.fit_options = resolve_format_options(banterle_format(), {});
  }
  return settings;
}

void run_banterle_filtering(const BanterleFilteringSettings& settings, const AnalysisRun& run) {
  std::string curves =
      "image,a,b,x,tone_mapped,hdr_filtered,tone_mapped_filtered,error,closed_form_error,relative_error\n";
  std::string measured =
      "image,width,height,tmo,alpha,l_white,mean,samples,mean_interval,max_interval,fraction_interval_above_0_3,"
      "rms_error,max_error,mean_signed_error,rms_relative_error,max_relative_error,"
      "fraction_relative_above_1_percent,rms_log2_error,max_log2_error\n";
  nlohmann::json record = analysis_base_record(run);
  record.erase("input_policy");   // this analysis's record has no input_policy field
  record["samples"] = settings.samples;
  for (const ToneInterval& interval : settings.intervals) record["intervals"].push_back({interval.a, interval.b});
  if (!settings.tmo_given) record["tmo_options"] = settings.fit_options;

  std::printf("%-36s %9s %9s %9s %10s %10s %10s %10s %10s\n", "image", "alpha", "l_white", "mean", "interval",
              "max eq.7", "at x", "max rel.", "rel. x");
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    ReinhardParameters parameters = settings.given;
    std::string tmo = "given";
    if (!settings.tmo_given) {
      try {
        parameters = banterle_fit_tmo(image, settings.fit_options).fitted;
      } catch (const Error& e) {
        fail(path, e.what());   // e.g. fit_options the fit's solver rejects
      }
      tmo = "fit=" + settings.fit_options.at("fit") + " mean=" + settings.fit_options.at("mean");
    }
    nlohmann::json image_record = {{"image", relative},
                                   {"sha256", sha256_file_hex(path)},
                                   {"alpha", parameters.alpha},
                                   {"l_white", parameters.l_white},
                                   {"mean", parameters.mean},
                                   {"tmo", tmo}};
    for (const ToneInterval& interval : settings.intervals) {
      const std::vector<FilteringCurvePoint> curve =
          filtering_error_curve(parameters, interval.a, interval.b, settings.samples);
      const FilteringCurvePoint* peak = &curve.front();
      const FilteringCurvePoint* peak_relative = &curve.front();
      for (const FilteringCurvePoint& p : curve) {
        curves += csv_field(relative) + "," + g17(interval.a) + "," + g17(interval.b) + "," + g17(p.x) + "," +
                  g17(p.tone_mapped) + "," + g17(p.hdr_filtered) + "," + g17(p.tone_mapped_filtered) + "," +
                  g17(p.error) + "," + g17(p.closed_form_error) + "," + g17(p.relative_error) + "\n";
        if (p.error > peak->error) peak = &p;
        if (p.relative_error > peak_relative->relative_error) peak_relative = &p;
      }
      char label[64];
      std::snprintf(label, sizeof label, "[%g, %g]", interval.a, interval.b);
      std::printf("%-36s %9.4g %9.4g %9.4g %10s %10.4g %10.3f %10.4g %10.3f\n", relative.c_str(), parameters.alpha,
                  parameters.l_white, parameters.mean, label, peak->error, peak->x, peak_relative->relative_error,
                  peak_relative->x);
      image_record["curves"].push_back({{"a", interval.a},
                                        {"b", interval.b},
                                        {"max_error", peak->error},
                                        {"max_error_x", peak->x},
                                        {"max_relative_error", peak_relative->relative_error},
                                        {"max_relative_error_x", peak_relative->x}});
    }
    FilteringMeasurement m;
    try {
      m = measure_bilinear_filtering_error(image, parameters);
    } catch (const Error& e) {
      fail(path, e.what());   // e.g. an image smaller than 2x2: name the file
    }
    measured += csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) + "," +
                csv_field(tmo) + "," + g17(parameters.alpha) + "," + g17(parameters.l_white) + "," +
                g17(parameters.mean) + "," + std::to_string(m.samples) + "," + g17(m.mean_interval) + "," +
                g17(m.max_interval) + "," + g17(m.fraction_interval_above_0_3) + "," + g17(m.rms_error) + "," +
                g17(m.max_error) + "," + g17(m.mean_signed_error) + "," + g17(m.rms_relative_error) + "," +
                g17(m.max_relative_error) + "," + g17(m.fraction_relative_above_1_percent) + "," +
                g17(m.rms_log2_error) + "," + g17(m.max_log2_error) + "\n";
    std::printf("  bilinear 2x on the image: %zu samples, mean interval %.4f (%.2f %% of quads wider than 0.3), "
                "relative error RMS %.3g max %.3g (%.3f %% above 1 %%), log2 error RMS %.3g max %.3g\n",
                m.samples, m.mean_interval, 100.0 * m.fraction_interval_above_0_3, m.rms_relative_error,
                m.max_relative_error, 100.0 * m.fraction_relative_above_1_percent, m.rms_log2_error, m.max_log2_error);
    image_record["measured"] = {{"samples", m.samples},
                                {"mean_interval", m.mean_interval},
                                {"rms_relative_error", m.rms_relative_error},
                                {"max_relative_error", m.max_relative_error},
                                {"rms_log2_error", m.rms_log2_error}};
    record["images"].push_back(image_record);
  }
  write_analysis_folder(run,
                        {{"filtering_curves.csv", curves},
                        {"filtering_measured.csv", measured}},
                        record, "configs/papers/banterle2008/plot_filtering.py");
}

}  // namespace

Analysis banterle_filtering_analysis() {
  return {"banterle_filtering", {"intervals", "samples", "tmo"}, [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const BanterleFilteringSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_banterle_filtering(*settings, run); });
          }};
}

}  // namespace blocklab
