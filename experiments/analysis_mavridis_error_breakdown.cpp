// Analysis mavridis_error_breakdown (Mavridis & Papaioannou 2012, Table 1 and Table 6), in the analysis registry
// (experiments/analysis.h). Per image (8-bit RGB; the paper uses Lena for Table 1 and kodim23 for Table 6):
//
// Table 1, "compression error of the R channel (MSE_R) when compressing a single coefficient subband vs three of
// them in the RGB channels of a DXT1 texture": the luminance Y of YCoCg-R is Haar / PI-Haar (w) transformed one
// level; each band is mapped linearly from its exact range to [0, 255] (section 3.2 without clamp or gamma); a
// half-resolution texture holds HL (HL') in R and zero in G, B, or HL, LH, HH (HL', LH', HH') in R, G, B, and is
// DXT1-encoded (4-colour blocks, blocklab's S3TC fit at its default search, unit channel weights). MSE_R is the
// mean squared error of R in 8-bit texture units.
//
// Table 6, "breakdown of the error (PSNR) after each successive stage", rows 2:1 chroma, 4:1 chroma and gray:
//   ycocg_r     RGB -> YCoCg-R -> RGB. blocklab keeps the integer planes (lossless, reported as inf); the paper's
//               48.0 dB comes from storing Co, Cg in 8 bits ("one bit of chrominance precision will be lost"), given
//               as ycocg_r_8bit (Co, Cg mapped from their exact range to 0..255 and back).
//   chroma      + chroma subsampling (box down, bilinear up; formats/mavridis/mavridis_chroma.h)
//   pi_haar     + every plane's PI-Haar coefficients stored as 8-bit values (exact ranges, linear; no DXT)
//   drop_hh     + HH dropped: the BC7 packing's three bands (LL, HL' + LH', HL' - LH') stored as 8-bit values
//   bc7         the format at packing=bc7 (blocklab's BC7 encoder, effort medium)
//   dxt5        the format at packing=dxt5 (the default; not a column of Table 6)
// Colour rows: PSNR over R, G, B code values; gray: PSNR of Y (YCoCg-R luminance) against the source's Y.
// Keys (all optional): w: 0.4 (PI-Haar weight).
// Writes table1_band_mse.csv (image, transform, packing, mse_r) and table6_stages.csv (image, row, stage, psnr).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/color_spaces.h"
#include "experiments/analysis.h"
#include "experiments/sha256.h"
#include "formats/bc1/bc1_block.h"
#include "formats/common/s3tc_color_fit.h"
#include "formats/mavridis/mavridis_chroma.h"
#include "formats/mavridis/mavridis_plane_codec.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace blocklab {

namespace {

using mavridis::Plane;

struct BreakdownSettings {
  double w = 0.4;
};

BreakdownSettings parse_settings(const StrictYaml& yaml, const YAML::Node& root) {
  BreakdownSettings settings;
  if (const YAML::Node n = StrictYaml::child(root, "w"); n.IsDefined()) {
    settings.w = analysis_number(yaml, n, "w");
    if (!(settings.w >= 0.01 && settings.w <= 1.0)) yaml.fail_at(n, "w must be in [0.01, 1]");
  }
  return settings;
}

// inf when lossless (below 1e-6 per sample: the float source's rounding of its 8-bit code values).
double psnr_of(double squared_error, std::size_t samples) {
  if (squared_error <= 1e-6 * static_cast<double>(samples)) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 * static_cast<double>(samples) / squared_error);
}

// PSNR over R, G, B of planes (Y full size, chroma at 1 / factor per axis) against the image: the decoder's rounding
// and the paper's inverse YCoCg-R.
double colour_psnr(const Image& image, const std::array<Plane, 3>& planes, int factor) {
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      YCoCgR v;
      v.y = static_cast<std::int32_t>(std::lround(planes[0].at(x, y)));
      v.co = static_cast<std::int32_t>(std::lround(factor == 1 ? planes[1].at(x, y) : mavridis::upsampled(planes[1], factor, x, y)));
      v.cg = static_cast<std::int32_t>(std::lround(factor == 1 ? planes[2].at(x, y) : mavridis::upsampled(planes[2], factor, x, y)));
      const Rgb<std::int32_t> rgb = ycocg_r_to_rgb(v);
      const int decoded[3] = {rgb.r, rgb.g, rgb.b};
      const float* source = image.texel(x, y);
      for (int k = 0; k < 3; ++k) {
        const double d = std::clamp(decoded[k], 0, 255) - std::clamp(static_cast<double>(source[k]), 0.0, 1.0) * 255.0;
        sum += d * d;
      }
    }
  return psnr_of(sum, image.texel_count() * 3);
}

// A plane mapped from its exact range to 0..255 and back (8-bit storage).
Plane stored_in_8_bits(const Plane& plane) {
  const auto range = std::minmax_element(plane.values.begin(), plane.values.end());
  const double lo = *range.first, span = std::max(*range.second - lo, 1e-9);
  Plane out = plane;
  for (double& v : out.values) v = lo + std::round((v - lo) / span * 255.0) / 255.0 * span;
  return out;
}

// One level of (PI-)Haar with each band stored as 8-bit values over its exact range (bc7_bands: the BC7 packing's
// three bands, HH dropped), inverted back to the plane.
Plane coefficients_in_8_bits(const Plane& plane, double w, bool bc7_bands) {
  mavridis::WaveletSettings settings;
  settings.transform = mavridis::Transform::pi_haar;
  settings.packing = bc7_bands ? mavridis::Packing::bc7 : mavridis::Packing::dxt5;
  settings.w = w;
  const mavridis::Coefficients c = mavridis::transform_plane(plane, settings);
  const mavridis::BandMapping mapping = mavridis::band_mapping(c, 0.0, 1.0);
  Plane out = plane;
  for (int gy = 0; 2 * gy < plane.height; ++gy)
    for (int gx = 0; 2 * gx < plane.width; ++gx) {
      const std::size_t g = static_cast<std::size_t>(gy) * c.groups_x + gx;
      std::array<double, 4> bands;
      for (int k = 0; k < 4; ++k) {
        const double s = std::round(mavridis::quantise(c.bands[k][g], mapping, k) * 255.0) / 255.0;
        bands[k] = mavridis::dequantise<double>(s, mapping.centre[k], mapping.half_range[k], 1.0);
      }
      const std::array<double, 4> haar =
          bc7_bands ? mavridis::haar_from_bc7_bands(bands, true) : mavridis::haar_from_pi_haar(bands, w);
      for (int t = 0; t < 4; ++t) {
        const int x = 2 * gx + t % 2, y = 2 * gy + t / 2;
        if (x < plane.width && y < plane.height)
          out.values[static_cast<std::size_t>(y) * plane.width + x] = mavridis::reconstruct_texel(haar, t % 2, t / 2);
      }
    }
  return out;
}

// Table 1: MSE of R (8-bit texture units) of a DXT1 texture holding band 1 alone or bands 1..3 of the plane.
double band_mse_r(const Plane& plane, mavridis::Transform transform, double w, bool three_bands) {
  mavridis::WaveletSettings settings;
  settings.transform = transform;
  settings.w = w;
  const mavridis::Coefficients c = mavridis::transform_plane(plane, settings);
  const mavridis::BandMapping mapping = mavridis::band_mapping(c, 0.0, 1.0);
  ColorFitSettings fit;
  fit.allow_three_color = false;
  const std::array<float, 3> unit_weights = {1.0f, 1.0f, 1.0f};
  double sum = 0.0;
  std::size_t count = 0;
  for (int by = 0; by < c.groups_y / 4; ++by)
    for (int bx = 0; bx < c.groups_x / 4; ++bx) {
      BlockTexels texels{};
      for (int i = 0; i < 16; ++i) {
        const std::size_t g = static_cast<std::size_t>(by * 4 + i / 4) * c.groups_x + bx * 4 + i % 4;
        for (int k = 1; k < 4; ++k)
          texels.rgba[i][k - 1] =
              k == 1 || three_bands ? static_cast<float>(std::round(mavridis::quantise(c.bands[k][g], mapping, k) * 255.0) / 255.0) : 0.0f;
        texels.rgba[i][3] = 1.0f;
      }
      std::uint8_t bytes[8];
      pack_bc1_block(canonicalise_bc1(fit_color_block(make_color_block(texels, unit_weights), fit)), bytes);
      const BlockTexels decoded = decode_bc1_params(unpack_bc1_block(bytes));
      for (int i = 0; i < 16; ++i) {
        const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
        if (2 * gx >= plane.width || 2 * gy >= plane.height) continue;   // padding groups do not count
        const double d = 255.0 * (decoded.rgba[i][0] - texels.rgba[i][0]);
        sum += d * d;
        ++count;
      }
    }
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

double format_psnr(const Image& image, const std::array<Plane, 3>& planes, const FormatOptions& given) {
  const Format& format = find_format("mavridis");
  const Image decoded =
      format.decode(format.encode(image, resolve_format_options(format, given), CodecContext{0, 1}), CodecContext{0, 1});
  if (decoded.channels != 1) return find_metric("psnr").compute(image, decoded, {}).value;
  double sum = 0.0;
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const double d = std::round(decoded.pixels[i * 4] * 255.0) - planes[0].values[i];
    sum += d * d;
  }
  return psnr_of(sum, image.texel_count());
}


void run_breakdown(const BreakdownSettings& settings, const AnalysisRun& run) {
  std::string table1 = "image,transform,bands,mse_r\n";
  std::string table6 = "image,row,stage,psnr\n";
  nlohmann::json record = analysis_base_record(run);
  record["w"] = settings.w;
  auto cell = [](double v) { return std::isinf(v) ? std::string("inf") : g17(v); };
  for (const std::string& relative : run.images) {
    const std::string path = (std::filesystem::path(run.data_root) / relative).string();
    const Image image = load_analysis_image(run, relative);
    const std::array<Plane, 3> planes = mavridis::ycocg_r_planes(image);
    nlohmann::json json = {{"image", relative}, {"sha256", sha256_file_hex(path)}};

    std::printf("%s\n  Table 1 (MSE_R, DXT1):", relative.c_str());
    for (const auto& [name, transform] : {std::pair<const char*, mavridis::Transform>{"haar", mavridis::Transform::haar},
                                          {"pi_haar", mavridis::Transform::pi_haar}})
      for (const bool three : {false, true}) {
        const double mse = band_mse_r(planes[0], transform, settings.w, three);
        table1 += csv_field(relative) + "," + name + "," + (three ? "three" : "one") + "," + g17(mse) + "\n";
        json["table1"][name][three ? "three" : "one"] = mse;
        std::printf("  %s %s %.2f", name, three ? "HL LH HH" : "HL 0 0", mse);
      }
    std::printf("\n");

    // Table 6 colour rows.
    for (const int factor : {2, 4}) {
      const std::string row = std::to_string(factor) + ":1";
      std::vector<std::pair<std::string, double>> stages;
      stages.emplace_back("ycocg_r", colour_psnr(image, planes, 1));
      stages.emplace_back("ycocg_r_8bit",
                          colour_psnr(image, {planes[0], stored_in_8_bits(planes[1]), stored_in_8_bits(planes[2])}, 1));
      std::array<Plane, 3> sub = {planes[0], mavridis::subsample(planes[1], factor), mavridis::subsample(planes[2], factor)};
      stages.emplace_back("chroma", colour_psnr(image, sub, factor));
      std::array<Plane, 3> coded;
      for (int k = 0; k < 3; ++k) coded[k] = coefficients_in_8_bits(sub[k], settings.w, false);
      stages.emplace_back("pi_haar", colour_psnr(image, coded, factor));
      for (int k = 0; k < 3; ++k) coded[k] = coefficients_in_8_bits(sub[k], settings.w, true);
      stages.emplace_back("drop_hh", colour_psnr(image, coded, factor));
      const std::string bpp = factor == 2 ? "3" : "2.25";
      stages.emplace_back("bc7", format_psnr(image, planes, {{"bpp", bpp}, {"packing", "bc7"}, {"w", g17(settings.w)}}));
      stages.emplace_back("dxt5", format_psnr(image, planes, {{"bpp", bpp}, {"w", g17(settings.w)}}));
      std::printf("  Table 6 %s:", row.c_str());
      for (const auto& [stage, psnr] : stages) {
        table6 += csv_field(relative) + "," + row + "," + stage + "," + cell(psnr) + "\n";
        json["table6"][row][stage] = cell(psnr);
        std::printf("  %s %s", stage.c_str(), cell(psnr).c_str());
      }
      std::printf("\n");
    }
    // Table 6 gray row: Y alone.
    {
      std::vector<std::pair<std::string, double>> stages;
      auto gray_psnr = [&](const Plane& decoded) {
        double sum = 0.0;
        for (std::size_t i = 0; i < decoded.values.size(); ++i) {
          const double d = std::clamp(std::round(decoded.values[i]), 0.0, 255.0) - planes[0].values[i];
          sum += d * d;
        }
        return psnr_of(sum, decoded.values.size());
      };
      stages.emplace_back("pi_haar", gray_psnr(coefficients_in_8_bits(planes[0], settings.w, false)));
      stages.emplace_back("drop_hh", gray_psnr(coefficients_in_8_bits(planes[0], settings.w, true)));
      stages.emplace_back("bc7", format_psnr(image, planes, {{"bpp", "2"}, {"packing", "bc7"}, {"w", g17(settings.w)}}));
      stages.emplace_back("dxt5", format_psnr(image, planes, {{"bpp", "2"}, {"w", g17(settings.w)}}));
      std::printf("  Table 6 gray:");
      for (const auto& [stage, psnr] : stages) {
        table6 += csv_field(relative) + ",gray," + stage + "," + cell(psnr) + "\n";
        json["table6"]["gray"][stage] = cell(psnr);
        std::printf("  %s %s", stage.c_str(), cell(psnr).c_str());
      }
      std::printf("\n");
    }
    record["images"].push_back(json);
  }
  write_analysis_folder(run, {{"table1_band_mse.csv", table1}, {"table6_stages.csv", table6}}, record, "");
}

}  // namespace

Analysis mavridis_error_breakdown_analysis() {
  return {"mavridis_error_breakdown", {"w"}, [](const StrictYaml& yaml, const YAML::Node& root) {
            const auto settings = std::make_shared<const BreakdownSettings>(parse_settings(yaml, root));
            return AnalysisRunner([settings](const AnalysisRun& run) { run_breakdown(*settings, run); });
          }};
}

}  // namespace blocklab
