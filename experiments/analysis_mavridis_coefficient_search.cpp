// Analysis mavridis_coefficient_search (Mavridis & Papaioannou 2012, section 3.2: "for most images the
// optimization process is converging around the same point in the search space, clamping 26% of the outliers and
// encoding the wavelet subbands with a gamma value of 0.86"), in the analysis registry (experiments/analysis.h).
// Each image is encoded by the `mavridis` format at `options` once per effort of `efforts`; the clamp fraction and
// gamma the section 3.2 search chose for each wavelet plane are read from side data `<plane>_search` (clamp, gamma,
// squared error) with the share of the plane's wavelet coefficients that clamp makes saturate (YCoCg-R, one level),
// and the PSNR of the decode (the `psnr` metric, RGB code values; `psnr_luma` for gray) is compared
// with effort `none` (clamp 0, gamma 1: no optimisation). Keys (all optional):
//   options: {bpp: "3"}              # mavridis options besides effort (strings)
//   efforts: [none, medium, thorough]  # efforts to run; `none` (the baseline of the gain) is always run
// Writes coefficient_search.csv (image, effort, plane, clamp, gamma, clamped_share, squared_error, psnr, gain_db) and
// coefficient_search_summary.csv (effort, plane, mean / median / min / max of clamp and gamma, mean clamped share,
// mean gain).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/mavridis/mavridis_chroma.h"
#include "formats/mavridis/mavridis_plane_codec.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace blocklab {

namespace {

struct SearchSettings {
  FormatOptions options = {{"bpp", "3"}};
  std::vector<std::string> efforts = {"none", "medium", "thorough"};
};

SearchSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  SearchSettings settings;
  if (const YAML::Node n = StrictYaml::child(root, "options"); n.IsDefined()) {
    settings.options.clear();
    for (const std::string& key : yaml.map_keys(n, "options")) {
      if (key == "effort" || key == "preset") yaml.fail_at(n, "options: '" + key + "' is set by efforts");
      settings.options[key] = yaml.scalar(StrictYaml::child(n, key), "options." + key);
    }
  }
  if (const YAML::Node list = StrictYaml::child(root, "efforts"); list.IsDefined()) {
    yaml.sequence(list, "efforts");
    settings.efforts = {"none"};
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string effort = yaml.scalar(list[i], indexed_path("efforts", i));
      if (std::find(settings.efforts.begin(), settings.efforts.end(), effort) == settings.efforts.end())
        settings.efforts.push_back(effort);
    }
  }
  // Every error before any image is read: the options must resolve at each effort.
  for (const std::string& effort : settings.efforts) {
    FormatOptions given = settings.options;
    given["effort"] = effort;
    try {
      resolve_format_options(find_format("mavridis"), given);
    } catch (const Error& e) {
      yaml.fail_at(root, std::string("options / efforts: ") + e.what());
    }
  }
  return settings;
}

// The YCoCg-R planes the format codes at these options (Y; Co, Cg box-subsampled by the rate's factor), keyed by the
// side-data plane name; empty for other colour spaces (the share of clamped coefficients is then not reported).
std::map<std::string, mavridis::Plane> coded_planes(const Image& image, const FormatOptions& options) {
  std::map<std::string, mavridis::Plane> planes;
  if (options.at("space") != "ycocg_r" || image.channels == 1) return planes;
  const std::array<mavridis::Plane, 3> full = mavridis::ycocg_r_planes(image);
  const std::string& bpp = options.at("bpp");
  planes["y"] = full[0];
  if (bpp == "3" || bpp == "2.25") {
    const int factor = bpp == "3" ? 2 : 4;
    planes["co"] = mavridis::subsample(full[1], factor);
    planes["cg"] = mavridis::subsample(full[2], factor);
  }
  return planes;
}

// Share of a plane's wavelet coefficients (HL, LH, HH bands) that the mapping in side data `bands` (centre, half
// range per band) clamps: |x - c| > r.
double clamped_share(const mavridis::Plane& plane, const FormatOptions& options, const std::vector<double>& bands) {
  mavridis::WaveletSettings settings;
  const std::string& transform = options.at("transform");
  settings.transform = transform == "haar" ? mavridis::Transform::haar : mavridis::Transform::pi_haar;
  settings.w = std::stod(options.at("w"));
  const mavridis::Coefficients c = mavridis::transform_plane(plane, settings);
  std::size_t clamped = 0, total = 0;
  for (int gy = 0; 2 * gy < plane.height; ++gy)
    for (int gx = 0; 2 * gx < plane.width; ++gx)
      for (int k = 1; k < 4; ++k) {
        const double x = c.bands[k][static_cast<std::size_t>(gy) * c.groups_x + gx];
        clamped += std::abs(x - bands[2 * k]) > bands[2 * k + 1] * (1.0 + 1e-12);
        ++total;
      }
  return total == 0 ? 0.0 : static_cast<double>(clamped) / static_cast<double>(total);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void run_search(const SearchSettings& settings, const AnalysisRun& run) {
  const Format& format = find_format("mavridis");
  std::string rows = "image,effort,plane,clamp,gamma,clamped_share,squared_error,psnr,gain_db\n";
  nlohmann::json record = analysis_base_record(run);
  record["options"] = settings.options;
  record["efforts"] = settings.efforts;
  // (effort, plane) -> the chosen clamps, gammas; effort -> PSNR gains.
  std::map<std::pair<std::string, std::string>, std::pair<std::vector<double>, std::vector<double>>> chosen;
  std::map<std::pair<std::string, std::string>, std::vector<double>> shares;
  std::map<std::string, std::vector<double>> gains;
  std::printf("%-24s %-9s %-50s %8s %8s\n", "image", "effort", "clamp / gamma / clamped share per plane", "PSNR", "gain");
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    double baseline = 0.0;
    nlohmann::json json = {{"image", relative}, {"sha256", sha256_file_hex(path)}};
    for (const std::string& effort : settings.efforts) {
      FormatOptions given = settings.options;
      given["effort"] = effort;
      const FormatOptions options = resolve_format_options(format, given);
      const EncodedTexture texture = format.encode(image, options, CodecContext{0, 1});
      const Image decoded = format.decode(texture, CodecContext{0, 1});
      const std::map<std::string, mavridis::Plane> planes = coded_planes(image, options);
      const Metric& metric = find_metric(decoded.channels == 1 ? "psnr_luma" : "psnr");
      const double psnr = metric.compute(image, decoded, {}).value;
      if (effort == "none") baseline = psnr;
      const double gain = psnr - baseline;
      gains[effort].push_back(gain);
      std::string line;
      for (const auto& [key, values] : texture.side_data) {
        if (key.size() < 7 || key.compare(key.size() - 7, 7, "_search") != 0 || values.size() != 3) continue;
        const std::string plane = key.substr(0, key.size() - 7);
        // Only one-level planes: the multi-level side data names its levels differently.
        const bool has_share = planes.count(plane) && options.at("levels") == "1";
        const double share = has_share ? clamped_share(planes.at(plane), options, texture.side_data.at(plane + "_bands")) : 0.0;
        if (has_share) shares[{effort, plane}].push_back(share);
        rows += csv_field(relative) + "," + effort + "," + plane + "," + g17(values[0]) + "," + g17(values[1]) + "," +
                (has_share ? g17(share) : std::string()) + "," + g17(values[2]) + "," + g17(psnr) + "," + g17(gain) + "\n";
        chosen[{effort, plane}].first.push_back(values[0]);
        chosen[{effort, plane}].second.push_back(values[1]);
        char cell[64];
        std::snprintf(cell, sizeof cell, " %s %.2f/%.2f/%.1f%%", plane.c_str(), values[0], values[1], 100.0 * share);
        line += cell;
        json[effort][plane] = {{"clamp", values[0]}, {"gamma", values[1]}, {"squared_error", values[2]}};
      }
      json[effort]["psnr"] = psnr;
      std::printf("%-24s %-9s %-50s %8.3f %+8.3f\n", relative.c_str(), effort.c_str(), line.c_str(), psnr, gain);
    }
    record["images"].push_back(json);
  }
  std::string summary = "effort,plane,images,clamp_mean,clamp_median,clamp_min,clamp_max,gamma_mean,gamma_median,"
                        "gamma_min,gamma_max,clamped_share_mean,mean_gain_db\n";
  std::printf("\n%-9s %-10s %6s %13s %13s %9s %10s\n", "effort", "plane", "images", "clamp mean/med", "gamma mean/med",
              "clamped", "mean gain");
  for (const auto& [key, values] : chosen) {
    const auto& [clamps, gammas] = values;
    auto mean = [](const std::vector<double>& v) {
      double sum = 0.0;
      for (double x : v) sum += x;
      return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
    };
    const double gain = mean(gains[key.first]);
    const double share = mean(shares[key]);
    summary += key.first + "," + key.second + "," + std::to_string(clamps.size()) + "," + g17(mean(clamps)) + "," +
               g17(median(clamps)) + "," + g17(*std::min_element(clamps.begin(), clamps.end())) + "," +
               g17(*std::max_element(clamps.begin(), clamps.end())) + "," + g17(mean(gammas)) + "," +
               g17(median(gammas)) + "," + g17(*std::min_element(gammas.begin(), gammas.end())) + "," +
               g17(*std::max_element(gammas.begin(), gammas.end())) + "," + g17(share) + "," + g17(gain) + "\n";
    std::printf("%-9s %-10s %6zu %6.3f/%6.3f %6.3f/%6.3f %8.2f%% %+10.3f\n", key.first.c_str(), key.second.c_str(),
                clamps.size(), mean(clamps), median(clamps), mean(gammas), median(gammas), 100.0 * share, gain);
  }
  write_analysis_folder(run, {{"coefficient_search.csv", rows}, {"coefficient_search_summary.csv", summary}}, record,
                        "");
}

}  // namespace

Analysis mavridis_coefficient_search_analysis() {
  return {"mavridis_coefficient_search", {"options", "efforts"}, [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const SearchSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_search(*settings, run); });
          }};
}

}  // namespace blocklab
