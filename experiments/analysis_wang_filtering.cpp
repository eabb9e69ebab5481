// Analysis wang_filtering (Wang et al. 2007 section 4.4, Fig. 5 and Appendix B eqs. 17-18;
// formats/wang/wang_filtering.h), in the analysis registry (experiments/analysis.h). Per image and variant the image
// is encoded with the `wang` format and sampled between texels three ways:
//   source    the source RGB filtered bilinearly (the reference)
//   shader    the shader of section 3.4 on the bilinearly filtered tex0 / tex1 channels (what the GPU renders)
//   decoded   the per-texel decoded RGB filtered bilinearly (an ideal filter after decoding)
// and compared with psnr peak=reference_max (Wang 2007 Table 2's PSNR, metrics/psnr.cpp) and log2rgb
// (SPECS.md 1a): shader vs source, decoded vs source, and shader vs decoded (the filtering artefact alone). Also
// Appendix B's "same direction" rates over adjacent texel pairs (paper: 97.5 % for RGB, 76.1 % for S).
// Its keys (all optional):
//   variants: {residual_s: {}, residual_ratio: {residual: ratio}}   label -> wang options (the default: Fig. 5's
//                                    residual S and residual ratio T; every other option at the format's default)
//   offsets: [0.25, 0.5, 0.75]       sample positions x + f, y + f between texel centres, each in (0, 1)
// It writes filtering_measured.csv (one row per image x variant), config.yaml and analysis.json into the output
// folder; configs/papers/wang2007/plot_filtering.py draws the shader-vs-decoded errors per image.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/registry.h"
#include "formats/wang/wang_filtering.h"
#include "formats/wang/wang_format.h"
#include "metrics/metric.h"

namespace blocklab {

namespace {

struct WangFilteringSettings {
  std::vector<AnalysisVariant> variants;
  std::vector<double> offsets = {0.25, 0.5, 0.75};
};

WangFilteringSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  WangFilteringSettings settings;
  settings.variants = analysis_format_variants(yaml, root, wang_format(),
                                               {{"residual_s", {}}, {"residual_ratio", {{"residual", "ratio"}}}});
  if (const YAML::Node offsets = StrictYaml::child(root, "offsets"); offsets.IsDefined()) {
    yaml.sequence(offsets, "offsets");
    if (offsets.size() == 0 || offsets.size() > 16) yaml.fail_at(offsets, "offsets must list 1 to 16 values");
    settings.offsets.clear();
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      const double offset = analysis_number(yaml, offsets[i], indexed_path("offsets", i));
      if (!(offset > 0.0 && offset < 1.0))
        yaml.fail_at(offsets[i], indexed_path("offsets", i) + " must be in (0, 1) (between texel centres)");
      settings.offsets.push_back(offset);
    }
  }
  return settings;
}

struct Comparison {
  double psnr = 0.0, log2rgb = 0.0;
};

Comparison compare(const Image& reference, const Image& test) {
  return {find_metric("psnr").compute(reference, test, {{"peak", "reference_max"}}).value,
          find_metric("log2rgb").compute(reference, test, {}).value};
}

void run_wang_filtering(const WangFilteringSettings& settings, const AnalysisRun& run) {
  std::string measured =
      "image,width,height,variant,samples,shader_psnr,decoded_psnr,shader_vs_decoded_psnr,shader_log2rgb,"
      "decoded_log2rgb,shader_vs_decoded_log2rgb,rgb_pairs,rgb_same_direction,s_pairs,s_same_direction\n";
  nlohmann::json record = analysis_base_record(run);
  record["offsets"] = settings.offsets;
  for (const AnalysisVariant& variant : settings.variants) record["variants"][variant.label] = variant.options;
  std::printf("%-34s %-16s %21s %21s %21s %8s %8s\n", "image", "variant", "shader: psnr / log2", "decoded",
              "shader vs decoded", "RGB same", "S same");
  const Format& format = wang_format();
  // Totals over images per variant (pair counts), for the summary line.
  std::map<std::string, wang::SameDirection> totals;
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    Image source_filtered;
    try {
      source_filtered = wang::magnify_rgb(image, settings.offsets);
    } catch (const Error& e) {
      fail(path, e.what());   // e.g. an image smaller than 2x2
    }
    nlohmann::json image_record = {{"image", relative}, {"sha256", sha256_file_hex(path)}};
    for (const AnalysisVariant& variant : settings.variants) {
      const EncodedTexture texture = format.encode(image, variant.options, CodecContext{0, 1});
      const wang::DecodeSetup setup = wang::decode_setup(texture);
      const wang::FetchedTextures fetched = wang::fetch_textures(texture);
      const Image shaded = wang::magnify_shaded(setup, fetched, settings.offsets);
      const Image decoded_filtered = wang::magnify_rgb(format.decode(texture, CodecContext{0, 1}), settings.offsets);
      const Comparison shader = compare(source_filtered, shaded);
      const Comparison decoded = compare(source_filtered, decoded_filtered);
      const Comparison artefact = compare(decoded_filtered, shaded);
      const wang::SameDirection direction = wang::same_direction(image, setup, fetched);
      wang::SameDirection& total = totals[variant.label];
      total.rgb_pairs += direction.rgb_pairs;
      total.rgb_same += direction.rgb_same;
      total.s_pairs += direction.s_pairs;
      total.s_same += direction.s_same;
      measured += csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) +
                  "," + csv_field(variant.label) + "," + std::to_string(shaded.texel_count()) + "," +
                  g17(shader.psnr) + "," + g17(decoded.psnr) + "," + g17(artefact.psnr) + "," + g17(shader.log2rgb) +
                  "," + g17(decoded.log2rgb) + "," + g17(artefact.log2rgb) + "," +
                  std::to_string(direction.rgb_pairs) + "," + std::to_string(direction.rgb_same) + "," +
                  std::to_string(direction.s_pairs) + "," + std::to_string(direction.s_same) + "\n";
      std::printf("%-34s %-16s %10.2f / %8.4f %10.2f / %8.4f %10.2f / %8.4f %7.2f%% %7.2f%%\n", relative.c_str(),
                  variant.label.c_str(), shader.psnr, shader.log2rgb, decoded.psnr, decoded.log2rgb, artefact.psnr,
                  artefact.log2rgb, 100.0 * direction.rgb_fraction(), 100.0 * direction.s_fraction());
      image_record["variants"][variant.label] = {
          {"shader_psnr", shader.psnr},         {"decoded_psnr", decoded.psnr},
          {"shader_vs_decoded_psnr", artefact.psnr}, {"shader_log2rgb", shader.log2rgb},
          {"decoded_log2rgb", decoded.log2rgb}, {"shader_vs_decoded_log2rgb", artefact.log2rgb},
          {"rgb_same_direction", direction.rgb_fraction()}, {"s_same_direction", direction.s_fraction()}};
    }
    record["images"].push_back(image_record);
  }
  for (const AnalysisVariant& variant : settings.variants) {
    const wang::SameDirection& total = totals[variant.label];
    std::printf("all images, %s: same direction %.2f %% of %zu RGB pairs (paper 97.5 %%), %.2f %% of %zu S pairs "
                "(paper 76.1 %%)\n",
                variant.label.c_str(), 100.0 * total.rgb_fraction(), total.rgb_pairs, 100.0 * total.s_fraction(),
                total.s_pairs);
    record["same_direction_all_images"][variant.label] = {{"rgb", total.rgb_fraction()},
                                                          {"s", total.s_fraction()},
                                                          {"rgb_pairs", total.rgb_pairs},
                                                          {"s_pairs", total.s_pairs}};
  }
  write_analysis_folder(run, {{"filtering_measured.csv", measured}}, record,
                        "configs/papers/wang2007/plot_filtering.py");
}

}  // namespace

Analysis wang_filtering_analysis() {
  return {"wang_filtering", {"variants", "offsets"}, [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const WangFilteringSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_wang_filtering(*settings, run); });
          }};
}

}  // namespace blocklab
