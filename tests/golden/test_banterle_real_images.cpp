// Required properties of the `banterle` format (Banterle et al. 2008) on real HDR images: the bundled samples/hdr crops, and
// (skipped when ../shared/data/hdr is missing) four small full images of the evaluation set.
//   * the eq. 3 fit (default fit = ceres_lm: surrogate LM + polish) beats the Reinhard 2002 estimate strictly;
//   * 8 bpp (with the eq. 4 residual) has lower log2[RGB] RMSE than 4 bpp (Banterle 2008 Table 1: 0.348 vs 0.581),
//     and rgbe (32 bpp) is lower than both -- except on samples/hdr/Desk.exr, where the measured order is
//     banterle 8 bpp 0.61 < rgbe 0.86 < banterle 4 bpp 0.90 (log2rgb). RGBE's shared
//     exponent floors every channel below 2^-8 of the texel's largest channel to 0 (Ward's byte = floor(c 256 / 2^e)),
//     and the 2^-24 zero rule makes each such zero cost ~(log2 c + 24)^2; Desk's crop has many strongly coloured
//     texels (stained glass), so this test checks rgbe < 4 bpp there and rgbe < both elsewhere.
// The full 28-image table is configs/papers/banterle2008/table1.yaml (README there has the measured averages).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/banterle/reinhard_estimate.h"
#include "formats/banterle/tmo_fit.h"
#include "formats/banterle/tmo_fit_problem.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

Image load(const std::string& path) {
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  return image;
}

double log2rgb_after(const Image& image, const std::string& format_name, const FormatOptions& given) {
  const Format& format = find_format(format_name);
  const CodecContext context;
  const Image decoded = format.decode(format.encode(image, resolve_format_options(format, given), context), context);
  return find_metric("log2rgb").compute(image, decoded, {}).value;
}

void check_image(const std::string& path, bool rgbe_beats_eight_bpp = true) {
  SCOPED_TRACE(path);
  const Image image = load(path);
  const std::vector<double> luminances = banterle_luminances(image);
  for (TmoMean mean : {TmoMean::geometric, TmoMean::harmonic}) {
    const TmoFitResult fit = fit_tmo_parameters(build_luminance_histogram(luminances),
                                                estimate_reinhard_parameters(luminances, mean), TmoFitSettings{});
    EXPECT_LT(fit.fitted_error, fit.estimate_error) << to_string(mean) << " mean";
    EXPECT_TRUE(fit.solver_improved) << to_string(mean) << " mean";
  }
  const double four = log2rgb_after(image, "banterle", {{"bpp", "4"}});
  const double eight = log2rgb_after(image, "banterle", {{"bpp", "8"}});
  const double rgbe = log2rgb_after(image, "rgbe", {});
  EXPECT_LT(eight, four);
  EXPECT_LT(rgbe, four);
  if (rgbe_beats_eight_bpp) {
    EXPECT_LT(rgbe, eight);
  }
  std::printf("%-60s log2rgb banterle 4 bpp %.4f, 8 bpp %.4f, rgbe %.4f\n", path.c_str(), four, eight, rgbe);
}

TEST(BanterleRealImages, SamplesFitBeatsReinhardAndEightBppBeatsFourBpp) {
  const std::string samples = std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/";
  check_image(samples + "Desk.exr", false);   // see the file comment: RGBE zeroes Desk's small channels
  check_image(samples + "blender_world_sunset.exr");
  check_image(samples + "hdr-rgb-arboretum.hdr");
}

TEST(BanterleRealImages, SharedDataFitBeatsReinhardAndEightBppBeatsFourBpp) {
  const std::string root = std::string(BLOCKLAB_TEST_SHARED_DATA) + "/hdr/";
  if (!std::filesystem::exists(root)) GTEST_SKIP() << root << " not found";
  // Small images (<= 256x512) with very different dynamic ranges: ~46 stops (grace), sun/lamp probes, a landscape.
  for (const char* name : {"grace.hdr", "ennis.hdr", "wells.hdr", "blender_world_city.exr"}) {
    if (!std::filesystem::exists(root + name)) continue;
    check_image(root + name);
  }
}

// On the whole evaluation set: the fit beats the Reinhard 2002 estimate on eq. 3 for every HDR
// image of ../shared/data/hdr, with both means (the encodes of all 28 images are configs/papers/banterle2008/
// table1.yaml; this checks the fit alone, a few seconds in all).
TEST(BanterleRealImages, FitBeatsReinhardOnEveryHdrImageOfTheSharedData) {
  const std::string root = std::string(BLOCKLAB_TEST_SHARED_DATA) + "/hdr/";
  if (!std::filesystem::exists(root)) GTEST_SKIP() << root << " not found";
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".exr" || ext == ".hdr") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  EXPECT_GE(paths.size(), 28u);
  for (const std::string& path : paths) {
    const std::vector<double> luminances = banterle_luminances(load(path));
    for (TmoMean mean : {TmoMean::geometric, TmoMean::harmonic}) {
      const TmoFitResult fit = fit_tmo_parameters(build_luminance_histogram(luminances),
                                                  estimate_reinhard_parameters(luminances, mean), TmoFitSettings{});
      EXPECT_LT(fit.fitted_error, fit.estimate_error) << path << " " << to_string(mean) << " mean";
      std::printf("%-50s %-9s eq. 3 estimate %.6g -> fitted %.6g (%.3f)\n", std::filesystem::path(path).filename().c_str(),
                  to_string(mean), fit.estimate_error, fit.fitted_error, fit.fitted_error / fit.estimate_error);
    }
  }
}

// A black background at 8 bpp: on this image (23 % exact-black texels) a residual zero code that decodes to ~2^-29
// instead of exactly 0 moves mPSNR's automatic exposure range to stop 29 (8 bpp 17.8 dB against 4 bpp 31.2;
// formats/banterle/README.md, "Exact zero residual").
TEST(BanterleRealImages, EightBppIsNoWorseThanFourBppInLog2AndMpsnrOnABlackBackground) {
  const std::string path = std::string(BLOCKLAB_TEST_SHARED_DATA) + "/hdr/v2_LowResLeftView_composited.exr";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  const Image image = load(path);
  const Format& format = find_format("banterle");
  const CodecContext context;
  double log2rgb[2], mpsnr[2];
  for (int i = 0; i < 2; ++i) {
    const FormatOptions options = resolve_format_options(format, {{"bpp", i == 0 ? "4" : "8"}});
    const Image decoded = format.decode(format.encode(image, options, context), context);
    log2rgb[i] = find_metric("log2rgb").compute(image, decoded, {}).value;
    mpsnr[i] = find_metric("mpsnr_auto").compute(image, decoded, {}).value;
  }
  EXPECT_LE(log2rgb[1], log2rgb[0]);
  EXPECT_GE(mpsnr[1], mpsnr[0]);
  std::printf("v2_LowResLeftView: log2rgb 4 bpp %.4f, 8 bpp %.4f; mpsnr_auto 4 bpp %.2f, 8 bpp %.2f\n", log2rgb[0],
              log2rgb[1], mpsnr[0], mpsnr[1]);
}

}  // namespace
}  // namespace blocklab
