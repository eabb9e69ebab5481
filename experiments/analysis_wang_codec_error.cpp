// Analysis wang_codec_error (Wang et al. 2007 section 3.5, the 1D codec against plain BC3), in the analysis registry
// (experiments/analysis.h). Per image and codec variant the image is encoded with the `wang` format and decoded as
// the section 3.4 shader does (formats/wang/wang_filtering.h fetch_textures, wang_shader.h shader_luminance), and
// the format's own luminance error is averaged over every texel of the image:
//   error        the error the encoder scores (wang_block_problem.h ResidualBlockError::texel_error): the shader's
//                clamped decode D = max(L' + S, 0) against the source L as |L - D| / (min(L, D) + c), i.e. eq. 9
//                where D >= L and the same ratio the other way where D < L
//   error_eq9    eq. 9 as printed, |L - D| / (L + c)
//   alpha_error  the L part: `error` of the alpha channels alone, the eq. 4 luminance tex0.a high + tex1.a low + tmin
//                (before the residual of tex1.rgb is added)
//   residual_gain  the S part: alpha_error - error, what the residual channels (eq. 5-7) take off the L part
//   black        texels with L > 0 that the shader shows black (D = 0); `error` charges each about L / c
// L is the source luminance as the format computes it (wang_color_space.h to_luminance_chroma: |RGB| for LUVW,
// R + 2G + B for LUV, of the image after the config's input policy); c is the variants' error_c (all variants must
// use the same c). The winner of an image is the variant with the smallest mean `error`.
// Its keys (all optional):
//   variants: {1d: {}, bc3: {codec: bc3}}   label -> wang options (the default: the format's defaults, i.e. the 1D
//                                           codec, and the plain BC3 encoder on the same channels)
// It writes codec_error_measured.csv (one row per image), config.yaml and analysis.json into the output folder and
// prints the per-image table and the totals over all texels of all images.
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_filtering.h"
#include "formats/wang/wang_format.h"

namespace blocklab {

namespace {

struct CodecErrorSettings {
  std::vector<AnalysisVariant> variants;
  double error_c = 0.0;
};

double option_number(const FormatOptions& options, const std::string& key) {
  const auto found = options.find(key);
  if (found == options.end()) fail("wang_codec_error", "the resolved wang options lack '" + key + "'");
  return std::strtod(found->second.c_str(), nullptr);
}

CodecErrorSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  CodecErrorSettings settings;
  settings.variants = analysis_format_variants(yaml, root, wang_format(), {{"1d", {}}, {"bc3", {{"codec", "bc3"}}}});
  const YAML::Node variants = StrictYaml::child(root, "variants");
  settings.error_c = option_number(settings.variants.front().options, "error_c");
  for (const AnalysisVariant& variant : settings.variants)
    if (option_number(variant.options, "error_c") != settings.error_c)
      yaml.fail_at(variants, "variants." + variant.label + ".error_c: every variant must use the same error_c (" +
                                 settings.variants.front().options.at("error_c") + " in variants." +
                                 settings.variants.front().label + "), the errors are compared");
  return settings;
}

// Sums of the per-texel errors over a set of texels.
struct ErrorSums {
  double error = 0.0, error_eq9 = 0.0, alpha_error = 0.0;
  std::size_t texels = 0, black = 0;
  void add(const ErrorSums& other) {
    error += other.error;
    error_eq9 += other.error_eq9;
    alpha_error += other.alpha_error;
    texels += other.texels;
    black += other.black;
  }
  double mean(double sum) const { return texels ? sum / static_cast<double>(texels) : 0.0; }
};

// The format's luminance errors of one encoded image against its source luminances.
ErrorSums measure(const Image& image, const EncodedTexture& texture, double error_c) {
  const wang::DecodeSetup setup = wang::decode_setup(texture);
  const wang::FetchedTextures fetched = wang::fetch_textures(texture);
  wang::ResidualBlockError scoring;   // only its texel_error (the encoder's error of a shown luminance)
  scoring.c = error_c;
  ErrorSums sums;
  const std::size_t count = image.texel_count();
  for (std::size_t i = 0; i < count; ++i) {
    const double source = wang::to_luminance_chroma(setup.space, &image.pixels[i * 4]).luminance;
    const float* t0 = &fetched.tex0[i * 4];
    const float* t1 = &fetched.tex1[i * 4];
    const double alpha_only =
        wang::shader_luminance<float>(setup.constants, wang::Residual::none, t0[3], t1[3], t1);
    const double decoded = wang::shader_luminance<float>(setup.constants, setup.residual, t0[3], t1[3], t1);
    const double shown = decoded > 0.0 ? decoded : 0.0;
    sums.error += scoring.texel_error(source, decoded);
    sums.error_eq9 += std::abs(source - shown) / (source + error_c);
    sums.alpha_error += scoring.texel_error(source, alpha_only);
    if (source > 0.0 && !(shown > 0.0)) ++sums.black;
  }
  sums.texels = count;
  return sums;
}

void run_wang_codec_error(const CodecErrorSettings& settings, const AnalysisRun& run) {
  std::string measured = "image,width,height,texels";
  for (const AnalysisVariant& variant : settings.variants)
    for (const char* column : {"error", "error_eq9", "alpha_error", "residual_gain", "black"})
      measured += "," + csv_field(variant.label + "_" + column);
  measured += ",winner\n";
  nlohmann::json record = analysis_base_record(run);
  record["error_c"] = settings.error_c;
  record["error"] = "|L - D| / (min(L, D) + c), D = max(L' + S, 0) (wang_block_problem.h texel_error)";
  for (const AnalysisVariant& variant : settings.variants) record["variants"][variant.label] = variant.options;
  std::printf("mean luminance error per texel, |L - D| / (min(L, D) + c), c = %g; alpha = eq. 4 alone\n",
              settings.error_c);
  std::printf("%-34s", "image");
  for (const AnalysisVariant& variant : settings.variants)
    std::printf(" %12s %12s", (variant.label + " error").c_str(), (variant.label + " alpha").c_str());
  std::printf("  winner\n");
  const Format& format = wang_format();
  std::map<std::string, ErrorSums> totals;
  std::map<std::string, int> wins;
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    nlohmann::json image_record = {{"image", relative}, {"sha256", sha256_file_hex(path)}};
    std::string row = csv_field(relative) + "," + std::to_string(image.width) + "," + std::to_string(image.height) +
                      "," + std::to_string(image.texel_count());
    std::printf("%-34s", relative.c_str());
    std::string winner;
    double best = 0.0;
    for (const AnalysisVariant& variant : settings.variants) {
      const EncodedTexture texture = format.encode(image, variant.options, CodecContext{0, 1});
      const ErrorSums sums = measure(image, texture, settings.error_c);
      totals[variant.label].add(sums);
      const double error = sums.mean(sums.error), alpha = sums.mean(sums.alpha_error);
      if (winner.empty() || error < best) {
        winner = variant.label;
        best = error;
      }
      row += "," + g17(error) + "," + g17(sums.mean(sums.error_eq9)) + "," + g17(alpha) + "," + g17(alpha - error) + "," +
             std::to_string(sums.black);
      std::printf(" %12.6g %12.6g", error, alpha);
      image_record["variants"][variant.label] = {{"error", error},
                                                 {"error_eq9", sums.mean(sums.error_eq9)},
                                                 {"alpha_error", alpha},
                                                 {"residual_gain", alpha - error},
                                                 {"black", sums.black}};
    }
    ++wins[winner];
    image_record["winner"] = winner;
    measured += row + "," + csv_field(winner) + "\n";
    std::printf("  %s\n", winner.c_str());
    record["images"].push_back(image_record);
  }
  for (const AnalysisVariant& variant : settings.variants) {
    const ErrorSums& total = totals[variant.label];
    std::printf("all images, %s: mean error %.6g (eq. 9 %.6g; alpha channels alone %.6g, residual takes off %.6g) "
                "over %zu texels, %zu shown black; smallest error on %d of %zu images\n",
                variant.label.c_str(), total.mean(total.error), total.mean(total.error_eq9),
                total.mean(total.alpha_error), total.mean(total.alpha_error) - total.mean(total.error), total.texels, total.black,
                wins[variant.label], run.images.size());
    record["all_images"][variant.label] = {{"error", total.mean(total.error)},
                                           {"error_eq9", total.mean(total.error_eq9)},
                                           {"alpha_error", total.mean(total.alpha_error)},
                                           {"texels", total.texels},
                                           {"black", total.black},
                                           {"wins", wins[variant.label]}};
  }
  write_analysis_folder(run, {{"codec_error_measured.csv", measured}}, record, "");
}

}  // namespace

Analysis wang_codec_error_analysis() {
  return {"wang_codec_error", {"variants"}, [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const CodecErrorSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_wang_codec_error(*settings, run); });
          }};
}

}  // namespace blocklab
