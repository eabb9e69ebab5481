// Banterle 2008 tone-mapping pieces: Reinhard's operator and its inverse (eqs. 1-2), the Reinhard 2002 estimate
// (SPECS.md section 3), the half-float inverse LUT (section 4.4), the luminance histogram and the eq. 3 Problems
// (Problem contract, fit behaviour, SPECS.md section 5's stall of plain LM).
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "formats/banterle/itmo_lut.h"
#include "formats/banterle/reinhard_estimate.h"
#include "formats/banterle/reinhard_operator.h"
#include "formats/banterle/tmo_fit.h"
#include "formats/banterle/tmo_fit_problem.h"
#include "tests/contract/problem_contract.h"

namespace blocklab {
namespace {

// A deterministic spread of luminances over ~22 stops (log-uniform plus a bright cluster and a few zeros).
std::vector<double> synthetic_luminances() {
  std::vector<double> values;
  for (int i = 0; i < 20000; ++i) {
    const double u = static_cast<double>((i * 7919) % 20000) / 20000.0;
    values.push_back(std::exp2(-12.0 + 18.0 * u * u));
  }
  for (int i = 0; i < 500; ++i) values.push_back(std::exp2(8.0 + 2.0 * i / 500.0));
  for (int i = 0; i < 50; ++i) values.push_back(0.0);
  return values;
}

TEST(ReinhardOperator, InverseUndoesTheForwardOperatorOverThirtyStops) {
  for (double l_white : {0.5, 3.0, 100.0, 1e5}) {
    for (double log2_x = -20.0; log2_x <= 10.0; log2_x += 0.25) {
      const double x = std::exp2(log2_x);
      const double tone_mapped = reinhard_forward_scaled(x, l_white);
      if (tone_mapped > 1.0) continue;   // beyond the white point: clipped by the quantiser, not inverted
      EXPECT_NEAR(reinhard_inverse_scaled(tone_mapped, l_white), x, 1e-12 * x + 1e-300)
          << "Lwhite " << l_white << ", x 2^" << log2_x;
    }
  }
}

TEST(ReinhardOperator, RationalisedInverseEqualsTheLiteralEquation2) {
  const double alpha = 0.3, mean = 0.05;
  for (double l_white : {1.5, 10.0, 1000.0}) {
    for (int k = 1; k <= 255; ++k) {
      const long double q = k / 255.0L, lw = l_white;
      const long double literal = (lw * lw * mean / (2.0L * alpha)) *
                                  (q - 1.0L + std::sqrt((1.0L - q) * (1.0L - q) + 4.0L * q / (lw * lw)));
      const double ours = reinhard_inverse(static_cast<double>(q), alpha, l_white, mean);
      EXPECT_NEAR(ours, static_cast<double>(literal), 1e-9 * static_cast<double>(literal)) << "Lwhite " << l_white
                                                                                            << " code " << k;
    }
    EXPECT_DOUBLE_EQ(reinhard_inverse(1.0, alpha, l_white, mean), l_white * mean / alpha);   // g(1) = Lwhite L_H / alpha
    EXPECT_EQ(reinhard_inverse(0.0, alpha, l_white, mean), 0.0);
  }
}

TEST(ReinhardEstimate, FollowsTheReinhard2002FormulasOnKnownLuminances) {
  std::vector<double> values;
  for (int i = 0; i < 1001; ++i) values.push_back(std::exp2(-5.0 + 10.0 * i / 1000.0));   // 2^-5 .. 2^5
  const ReinhardParameters p = estimate_reinhard_parameters(values, TmoMean::geometric);
  double log_sum = 0.0;
  for (double v : values) log_sum += std::log(1e-6 + v);
  const double mean = std::exp(log_sum / 1001.0);
  EXPECT_NEAR(p.mean, mean, 1e-12 * mean);
  // 1st / 99th percentiles: ranks floor(0.01 * 1000) = 10 and floor(0.99 * 1000) = 990.
  const double lo = -5.0 + 10.0 * 10 / 1000.0, hi = -5.0 + 10.0 * 990 / 1000.0;
  const double expected_alpha = 0.18 * std::pow(4.0, (2.0 * std::log2(mean) - lo - hi) / (hi - lo));
  EXPECT_NEAR(p.alpha, expected_alpha, 1e-9 * expected_alpha);
  EXPECT_NEAR(p.l_white, 1.5 * std::exp2(10.0 - 5.0), 1e-9);   // 1.5 * 2^(log2 range - 5)
}

TEST(ReinhardEstimate, HarmonicMeanIsBelowTheGeometricMeanAndABlackImageKeepsDefaults) {
  const std::vector<double> values = synthetic_luminances();
  const double geometric = estimate_reinhard_parameters(values, TmoMean::geometric).mean;
  const double harmonic = estimate_reinhard_parameters(values, TmoMean::harmonic).mean;
  EXPECT_LT(harmonic, geometric);   // HM <= GM for positive values, strictly for a non-constant set
  const ReinhardParameters black = estimate_reinhard_parameters(std::vector<double>(64, 0.0), TmoMean::geometric);
  EXPECT_EQ(black.alpha, 0.18);
  EXPECT_EQ(black.l_white, 1.0);
  EXPECT_THROW(parse_tmo_mean("arithmetic", "banterle"), Error);
}

TEST(ItmoLut, EntriesAreHalfRoundedScaledEquation2WithThePeakBelowHalfMax) {
  const double alpha = 0.4, l_white = 3000.0, mean = 2.5;   // peak g(1) = 18750
  const ItmoLut lut = build_itmo_lut(alpha, l_white, mean, "test");
  const double peak = l_white * mean / alpha;
  EXPECT_GE(std::ldexp(peak, -lut.exponent), 16384.0);
  EXPECT_LT(std::ldexp(peak, -lut.exponent), 32768.0);
  for (int k = 0; k < 256; ++k) {
    const double expected = std::ldexp(reinhard_inverse(k / 255.0, alpha, l_white, mean), -lut.exponent);
    Imath::half h;
    h.setBits(lut.half_bits[static_cast<std::size_t>(k)]);
    EXPECT_EQ(static_cast<float>(h), lut.values[static_cast<std::size_t>(k)]);
    // Round to nearest half: within half an ulp of the half format (2^-11 relative for normals).
    EXPECT_NEAR(lut.values[static_cast<std::size_t>(k)], expected, expected * std::exp2(-11.0) + std::exp2(-25.0));
    if (k > 0) {
      EXPECT_GE(lut.values[static_cast<std::size_t>(k)], lut.values[static_cast<std::size_t>(k - 1)]);
    }
  }
}

TEST(ItmoLut, LookupHitsEntriesOnTheGridAndInterpolatesBetween) {
  const ItmoLut lut = build_itmo_lut(0.18, 50.0, 0.3, "test");
  for (int k = 0; k < 256; ++k) {
    const float at_grid = itmo_lookup(lut, static_cast<float>(k) / 255.0f);
    // k / 255 * 255 may round to k - ulp; the interpolation then lands within a rounding of the entry.
    EXPECT_NEAR(at_grid, std::ldexp(lut.values[static_cast<std::size_t>(k)], lut.exponent),
                1e-5 * std::ldexp(lut.values[255], lut.exponent));
  }
  const float low = itmo_lookup(lut, 10.0f / 255.0f), high = itmo_lookup(lut, 11.0f / 255.0f);
  const float middle = itmo_lookup(lut, 10.5f / 255.0f);
  EXPECT_GT(middle, low);
  EXPECT_LT(middle, high);
  EXPECT_EQ(itmo_lookup(lut, -1.0f), 0.0f);                          // clamped to entry 0 = g(0) = 0
  EXPECT_EQ(itmo_lookup(lut, 2.0f), itmo_lookup(lut, 1.0f));          // clamped to the last entry
}

TEST(ItmoLut, RejectsParametersThatCannotBuildATable) {
  EXPECT_THROW(build_itmo_lut(std::nan(""), 1.0, 1.0, "t"), Error);
  EXPECT_THROW(build_itmo_lut(0.18, 0.0, 1.0, "t"), Error);
  EXPECT_THROW(build_itmo_lut(0.18, -3.0, 1.0, "t"), Error);
  EXPECT_THROW(build_itmo_lut(0.18, 1.0, INFINITY, "t"), Error);
  EXPECT_THROW(build_itmo_lut(1e-300, 1e10, 1e25, "t"), Error);   // peak beyond 1e30
}

TEST(LuminanceHistogram, WeightsSumToOneAndPixelsAtTheFloorAreNotCounted) {
  const std::vector<double> values = synthetic_luminances();
  const LuminanceHistogram histogram = build_luminance_histogram(values);
  EXPECT_EQ(histogram.total, values.size());
  EXPECT_EQ(histogram.counted, values.size() - 50);   // the 50 zeros
  double sum = 0.0;
  for (std::size_t b = 0; b < histogram.weight.size(); ++b) {
    sum += histogram.weight[b];
    EXPECT_GE(histogram.log2_luminance[b], histogram.log2_min - 1e-12);
    EXPECT_LE(histogram.log2_luminance[b], histogram.log2_max + 1e-12);
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

struct FitFixture {
  std::shared_ptr<LuminanceHistogram> histogram;
  ReinhardParameters estimate;
  // `sparse`: 48 distinct luminances (48 non-empty bins), so the Interval-heavy contract checks stay fast.
  explicit FitFixture(bool sparse = false) {
    std::vector<double> values = synthetic_luminances();
    if (sparse) {
      values.clear();
      for (int i = 0; i < 48; ++i) values.push_back(std::exp2(-10.0 + 0.4 * i));
    }
    histogram = std::make_shared<LuminanceHistogram>(build_luminance_histogram(values));
    estimate = clamp_to_fit_box(estimate_reinhard_parameters(values, TmoMean::geometric));
  }
};

TEST(TmoFitProblem, Eq3ErrorHoldsTheProblemContract) {
  const FitFixture f(true);
  const Bounds bounds{{std::log2(f.estimate.alpha) - 3, 1.0}, {std::log2(f.estimate.alpha) + 3, 12.0}};
  contract::ContractOptions options;
  options.point_count = 60;
  options.box_count = 40;
  options.samples_per_box = 20;
  options.min_checked_gradient_fraction = 0.2;   // the quantiser makes the error a staircase
  contract::check_problem_contract(make_problem(Eq3Error{f.histogram, std::log2(f.estimate.mean)}, bounds), options);
}

TEST(TmoFitProblem, SmoothSurrogateHoldsTheProblemContract) {
  const FitFixture f(true);
  const Bounds bounds{{std::log2(f.estimate.alpha) - 3, 1.0}, {std::log2(f.estimate.alpha) + 3, 12.0}};
  contract::ContractOptions options;
  options.point_count = 60;
  options.box_count = 40;
  options.samples_per_box = 20;
  contract::check_problem_contract(make_problem(Eq3Surrogate{f.histogram, std::log2(f.estimate.mean)}, bounds),
                                   options);
}

TEST(TmoFitProblem, HistogramErrorTracksTheAllPixelError) {
  const std::vector<double> values = synthetic_luminances();
  const FitFixture f;
  const auto logs = std::make_shared<std::vector<double>>(counted_log2_luminances(values));
  const Eq3AllPixelsError exact{logs, std::log2(f.estimate.mean)};
  const Eq3Error binned{f.histogram, std::log2(f.estimate.mean)};
  for (double da : {-2.0, 0.0, 2.0})
    for (double lw : {2.0, 6.0, 12.0}) {
      const double x[2] = {std::log2(f.estimate.alpha) + da, lw};
      const double e = exact(x), h = binned(x);
      EXPECT_NEAR(h, e, 0.05 * e + 1e-6) << "at (" << x[0] << ", " << x[1] << ")";
    }
}

TEST(TmoFit, EverySolverBeatsTheReinhardEstimateAndPlainLmStallsAboveTheSurrogateChain) {
  const FitFixture f;
  double errors[5] = {};
  for (const std::string& name : tmo_fit_method_names()) {
    TmoFitSettings settings;
    settings.method = parse_tmo_fit_method(name, "test");
    const TmoFitResult result = fit_tmo_parameters(*f.histogram, f.estimate, settings);
    errors[static_cast<int>(settings.method)] = result.fitted_error;
    EXPECT_LE(result.fitted_error, result.estimate_error) << name;
    EXPECT_NEAR(result.fitted_error, tmo_fit_error(*f.histogram, result.fitted), 1e-9) << name;
    if (settings.method == TmoFitMethod::none) continue;
    EXPECT_TRUE(result.solver_improved) << name;
    EXPECT_LT(result.fitted_error, 0.9 * result.estimate_error) << name;
    EXPECT_FALSE(result.summaries.empty()) << name;
  }
  // SPECS.md section 5: LM through the quantiser (codes frozen) ends well above the surrogate + polish chain.
  EXPECT_LT(errors[static_cast<int>(TmoFitMethod::ceres_lm)], errors[static_cast<int>(TmoFitMethod::ceres_lm_raw)]);
  EXPECT_THROW(parse_tmo_fit_method("lbfgs", "banterle"), Error);
}

}  // namespace
}  // namespace blocklab
