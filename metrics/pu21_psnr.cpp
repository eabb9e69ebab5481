// PU21-PSNR (Mantiuk & Azimi, PCS 2021; gfxdisp/pu21 matlab/pu21_metric.m), SPECS.md section 1c:
// every R, G, B value is scaled to absolute luminance (option nits_per_unit, default 100: 1.0 in the texture is
// 100 cd/m^2 — HDR textures are relative, so the scale is a stated assumption), PU21-encoded separately with the
// banding_glare parameters (metrics/pu21.h; clamp to [0.005, 10000] cd/m^2), and
//     PU21-PSNR = 20 log10(256) - 10 log10(MSE),  MSE = mean over all R, G, B values of (V_ref - V_test)^2.
// Peak 256 as in pu21_metric.m. Alpha is ignored. Identical images give +inf.
// Error map: per pixel mean over R, G, B of (V_ref - V_test)^2 (PU units squared); its mean is the MSE.
#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/builtin_metrics.h"
#include "metrics/pu21.h"
#include "metrics/row_reduction.h"
#include "metrics/validation.h"

namespace blocklab {

namespace {

constexpr const char* kNitsOption = "nits_per_unit";
constexpr double kDefaultNitsPerUnit = 100.0;
constexpr double kPu21Peak = 256.0;   // pu21_metric.m: PSNR "peak" of the PU21 scale
constexpr Pu21Type kPu21Type = Pu21Type::banding_glare;

double pixel_squared_pu_error(const float* reference_texel, const float* test_texel, double nits_per_unit) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = pu21_encode(static_cast<double>(reference_texel[c]) * nits_per_unit, kPu21Type) -
                     pu21_encode(static_cast<double>(test_texel[c]) * nits_per_unit, kPu21Type);
    sum += d * d;
  }
  return sum;
}

class Pu21PsnrMetric final : public Metric {
 public:
  std::string name() const override { return "pu21_psnr"; }
  std::string description() const override {
    return "PU21-PSNR: R,G,B each PU21-encoded (banding_glare, absolute cd/m^2 = value x nits_per_unit), "
           "20 log10(256) - 10 log10(MSE) (Mantiuk & Azimi 2021; SPECS.md 1c)";
  }
  std::string unit() const override { return "dB"; }
  bool higher_is_better() const override { return true; }
  std::vector<std::string> option_names() const override { return {kNitsOption}; }

  MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const double nits = nits_per_unit_from(options);
    const double squared_sum = sum_rows_in_order(reference.height, [&](int y) {
      double row = 0.0;
      for (int x = 0; x < reference.width; ++x) row += pixel_squared_pu_error(reference.texel(x, y), test.texel(x, y), nits);
      return row;
    });
    const double mse = squared_sum / (3.0 * static_cast<double>(reference.texel_count()));
    MetricResult result;
    // MSE = 0: identical after encoding, +inf (explicit, not log10(0)).
    result.value = mse > 0.0 ? 20.0 * std::log10(kPu21Peak) - 10.0 * std::log10(mse)
                             : std::numeric_limits<double>::infinity();
    result.details = {
        {"variant", "PU21-PSNR on R, G, B separately, peak 256"},
        {"pu21_type", to_string(kPu21Type)},
        {"nits_per_unit", format_number(nits)},
        {"luminance_clamp", "[0.005, 10000] cd/m^2 after scaling (negative and NaN -> 0.005)"},
        {"channels", "RGB (alpha ignored)"},
        {"mse", format_number(mse)},
        {"error_map", "per pixel mean over R,G,B of (V_ref - V_test)^2; its mean is the MSE"},
    };
    return result;
  }

  Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const override {
    validate_metric_inputs(*this, reference, test, options);
    const double nits = nits_per_unit_from(options);
    return make_error_map(reference.width, reference.height, [&](int x, int y) {
      return pixel_squared_pu_error(reference.texel(x, y), test.texel(x, y), nits) / 3.0;
    });
  }

 private:
  double nits_per_unit_from(const MetricOptions& options) const {
    const double nits = option_double(name(), options, kNitsOption, kDefaultNitsPerUnit);
    // A zero or negative scale would map every value to the 0.005 cd/m^2 floor: refuse it.
    if (!(nits > 0.0)) fail(name() + ": option '" + kNitsOption + "'", "must be > 0, got " + format_number(nits));
    return nits;
  }
};

}  // namespace

const Metric& pu21_psnr_metric() {
  static const Pu21PsnrMetric metric;
  return metric;
}

}  // namespace blocklab
