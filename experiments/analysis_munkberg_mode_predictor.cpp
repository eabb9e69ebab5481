// Analysis munkberg_mode_predictor (Munkberg et al. 2008 section 6: "each of the compression modes is tested, and the
// one with the smallest error ... is selected"; formats/munkberg/munkberg_modes.h encode_best_block), in the analysis
// registry (experiments/analysis.h). Checks an approximate mode choice (e.g. the option mode_predictor, which skips
// section 6's modes on a cheap estimate) against a reference search on the same blocks. Its keys:
//   options: {preset: medium, modes: all, mode_predictor: 1}   # required: the munkberg options under test
//   reference: {mode_predictor: 0}   # optional: overrides applied to `options` for the reference encode
//                                    # (default: mode_predictor 0, the full competition)
// Per image and pooled over all images ("all") it writes mode_predictor_summary.csv: blocks, the share of blocks where
// both encodes pick the same mode, the share with a higher block error under test, the mean per-block error (sum over
// 16 texels x 3 channels of squared log2[RGB] differences, munkberg::block_log2_error) of both and its relative
// increase, log2[RGB] (both zero rules, metrics/log2rgb) and mPSNR of both; and mode_predictor_confusion.csv: per
// image, the block count of each (reference mode, tested mode) pair. Both encodes run on one thread.
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "core/error.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace blocklab {

namespace {

struct ModePredictorSettings {
  FormatOptions options;
  FormatOptions reference = {{"mode_predictor", "0"}};
};

FormatOptions parse_option_map(const StrictYaml& yaml, const YAML::Node& node, const std::string& path) {
  FormatOptions out;
  for (const std::string& key : yaml.map_keys(node, path))
    out[key] = yaml.scalar(StrictYaml::child(node, key), path + "." + key);
  return out;
}

ModePredictorSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  ModePredictorSettings settings;
  const YAML::Node options = StrictYaml::child(root, "options");
  if (!options.IsDefined()) fail(yaml.source_name(), "munkberg_mode_predictor needs the key 'options'");
  settings.options = parse_option_map(yaml, options, "options");
  if (const YAML::Node n = StrictYaml::child(root, "reference"); n.IsDefined())
    settings.reference = parse_option_map(yaml, n, "reference");
  // Both option sets are checked before any image is read (unknown keys, bad values: an error naming them).
  const Format& format = find_format("munkberg");
  FormatOptions reference = settings.options;
  for (const auto& [key, value] : settings.reference) reference[key] = value;
  resolve_format_options(format, settings.options);
  resolve_format_options(format, reference);
  settings.reference = reference;
  return settings;
}

struct Tally {
  std::size_t blocks = 0, same_mode = 0, worse = 0;
  double test_error = 0.0, reference_error = 0.0;
  std::array<std::array<std::size_t, munkberg::kBlockModeCount>, munkberg::kBlockModeCount> confusion{};

  void add(const Tally& other) {
    blocks += other.blocks;
    same_mode += other.same_mode;
    worse += other.worse;
    test_error += other.test_error;
    reference_error += other.reference_error;
    for (std::size_t a = 0; a < munkberg::kBlockModeCount; ++a)
      for (std::size_t b = 0; b < munkberg::kBlockModeCount; ++b) confusion[a][b] += other.confusion[a][b];
  }
};

double metric(const char* name, const Image& reference, const Image& test, const char* zero_rule) {
  MetricOptions options;
  if (zero_rule != nullptr) options["zero_rule"] = zero_rule;
  return find_metric(name).compute(reference, test, options).value;
}

void run_mode_predictor(const ModePredictorSettings& settings, const AnalysisRun& run) {
  const Format& format = find_format("munkberg");
  const FormatOptions test_options = resolve_format_options(format, settings.options);
  const FormatOptions reference_options = resolve_format_options(format, settings.reference);
  const std::vector<std::string> modes = format.modes();
  std::string summary =
      "image,blocks,same_mode_share,worse_share,mean_block_error_test,mean_block_error_reference,"
      "relative_error_increase,log2rgb_test,log2rgb_reference,log2rgb_skip_test,log2rgb_skip_reference,"
      "mpsnr_test,mpsnr_reference\n";
  std::string confusion = "image,reference_mode,test_mode,blocks\n";
  nlohmann::json record = analysis_base_record(run);
  Tally pooled;
  const auto add_rows = [&](const std::string& name, const Tally& t, const std::string& metrics, nlohmann::json& json) {
    const double n = t.blocks > 0 ? static_cast<double>(t.blocks) : 1.0;
    const double increase = t.reference_error > 0.0 ? t.test_error / t.reference_error - 1.0 : 0.0;
    summary += csv_field(name) + "," + std::to_string(t.blocks) + "," + g17(t.same_mode / n) + "," +
               g17(t.worse / n) + "," + g17(t.test_error / n) + "," + g17(t.reference_error / n) + "," +
               g17(increase) + "," + metrics + "\n";
    for (std::size_t a = 0; a < munkberg::kBlockModeCount; ++a)
      for (std::size_t b = 0; b < munkberg::kBlockModeCount; ++b)
        if (t.confusion[a][b] > 0)
          confusion += csv_field(name) + "," + modes[a] + "," + modes[b] + "," + std::to_string(t.confusion[a][b]) + "\n";
    json["blocks"] = t.blocks;
    json["same_mode_share"] = t.same_mode / n;
    json["relative_error_increase"] = increase;
    std::printf("%-34s %8zu %9.2f%% %9.2f%% %+9.3f%%\n", name.c_str(), t.blocks, 100.0 * t.same_mode / n,
                100.0 * t.worse / n, 100.0 * increase);
  };
  std::printf("%-34s %8s %10s %10s %10s\n", "image", "blocks", "same mode", "worse", "error");
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    const EncodedTexture test = format.encode(image, test_options, CodecContext{1, 1});
    const EncodedTexture reference = format.encode(image, reference_options, CodecContext{1, 1});
    const Image test_decoded = format.decode(test, CodecContext{1, 1});
    const Image reference_decoded = format.decode(reference, CodecContext{1, 1});
    const BlockGrid grid(image.width, image.height);
    Tally tally;
    for (std::size_t b = 0; b < grid.block_count(); ++b) {
      const BlockTexels source = load_block(image, grid, b);
      const double e_test = munkberg::block_log2_error(source, load_block(test_decoded, grid, b));
      const double e_reference = munkberg::block_log2_error(source, load_block(reference_decoded, grid, b));
      const std::size_t mode_test = test.block_modes.at(b), mode_reference = reference.block_modes.at(b);
      ++tally.blocks;
      tally.same_mode += mode_test == mode_reference ? 1 : 0;
      tally.worse += e_test > e_reference ? 1 : 0;
      tally.test_error += e_test;
      tally.reference_error += e_reference;
      ++tally.confusion[mode_reference][mode_test];
    }
    const std::string metrics =
        g17(metric("log2rgb", image, test_decoded, nullptr)) + "," +
        g17(metric("log2rgb", image, reference_decoded, nullptr)) + "," +
        g17(metric("log2rgb", image, test_decoded, "skip")) + "," +
        g17(metric("log2rgb", image, reference_decoded, "skip")) + "," +
        g17(metric("mpsnr", image, test_decoded, nullptr)) + "," + g17(metric("mpsnr", image, reference_decoded, nullptr));
    nlohmann::json json = {{"image", relative}, {"sha256", sha256_file_hex(path)}};
    add_rows(relative, tally, metrics, json);
    record["images"].push_back(json);
    pooled.add(tally);
  }
  nlohmann::json all = {{"images", run.images.size()}};
  add_rows("all", pooled, ",,,,,", all);
  record["all"] = all;
  write_analysis_folder(run, {{"mode_predictor_summary.csv", summary}, {"mode_predictor_confusion.csv", confusion}},
                        record, "");
}

}  // namespace

Analysis munkberg_mode_predictor_analysis() {
  return {"munkberg_mode_predictor", {"options", "reference"},
          [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const ModePredictorSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_mode_predictor(*settings, run); });
          }};
}

}  // namespace blocklab
