// Section 4 of Munkberg et al. 2008 (eqs. 7-10 and the luminance normalisation); see logyuv_filtering.h.
#include "formats/munkberg/munkberg_color_spaces.h"
#include "formats/munkberg/analysis/logyuv_filtering.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace blocklab::munkberg {

namespace {

constexpr const char* kOwner = "munkberg filtering";

void check_footprint(const FilterTexel* texels, const double* weights, std::size_t n) {
  if (n == 0 || texels == nullptr || weights == nullptr) fail(kOwner, "a filter footprint needs at least one texel");
}

}  // namespace

ShiftRule shift_rule_from_string(const std::string& text) {
  if (text == "nearest") return ShiftRule::nearest;
  if (text == "exponent") return ShiftRule::exponent;
  if (text == "truncate") return ShiftRule::truncate;
  fail(kOwner, "unknown shift rule '" + text + "'; valid: nearest, exponent, truncate");
}

ShiftReference shift_reference_from_string(const std::string& text) {
  if (text == "first") return ShiftReference::first;
  if (text == "brightest") return ShiftReference::brightest;
  fail(kOwner, "unknown shift reference '" + text + "'; valid: first, brightest");
}

const char* to_string(ShiftRule rule) {
  switch (rule) {
    case ShiftRule::nearest: return "nearest";
    case ShiftRule::exponent: return "exponent";
    case ShiftRule::truncate: return "truncate";
  }
  return "?";
}
const char* to_string(ShiftReference reference) { return reference == ShiftReference::first ? "first" : "brightest"; }

FilterTexel filter_texel_from_rgb(const Rgb<double>& rgb) {
  const LogYuv<double> yuv = rgb_to_logyuv(rgb);
  // Linear luminance straight from eq. 2 (not 2^Ybar): a black texel keeps Y = 0 (the eq. 3 black level) instead
  // of the 2^-28 floor of the logarithm, so it decodes to exact black.
  const double luminance = kRec601WeightR * rgb.r + kRec601WeightG * rgb.g + kRec601WeightB * rgb.b;
  return FilterTexel{luminance, yuv.u, yuv.v};
}

Rgb<double> rgb_from_filter_texel(const FilterTexel& texel) {
  return logyuv_to_rgb_from_luminance(texel.luminance, texel.u, texel.v);
}

int normalisation_shift(double luminance, double reference_luminance, ShiftRule rule) {
  // A black texel (or black reference) has no magnitude to compare: no shift (Y' = 0 whatever c is).
  if (!(luminance > 0.0) || !(reference_luminance > 0.0)) return 0;
  // Infinite luminance (never after the input policy) has no finite exponent: no shift, no float-to-int overflow.
  if (!std::isfinite(luminance) || !std::isfinite(reference_luminance)) return 0;
  long k = 0;
  if (rule == ShiftRule::nearest) {
    // Difference of logarithms, not log2 of the ratio, so a ratio beyond the double range cannot overflow.
    k = std::lround(std::log2(luminance) - std::log2(reference_luminance));
  } else if (rule == ShiftRule::truncate) {
    k = static_cast<long>(std::trunc(std::log2(luminance) - std::log2(reference_luminance)));
  } else {
    int e_texel = 0, e_reference = 0;
    std::frexp(luminance, &e_texel);
    std::frexp(reference_luminance, &e_reference);
    k = static_cast<long>(e_texel) - static_cast<long>(e_reference);
  }
  // Clamp: 2^+-512 keeps Y / c and c u, c v finite for any double input (see kMaxShift).
  return static_cast<int>(std::clamp<long>(k, -kMaxShift, kMaxShift));
}

std::size_t normalisation_reference(const FilterTexel* texels, std::size_t n, ShiftReference reference) {
  if (n == 0 || texels == nullptr) fail(kOwner, "a filter footprint needs at least one texel");
  // `first` with a black texel 0 falls back to the brightest: every shift against a black reference would be 0.
  if (reference == ShiftReference::first && texels[0].luminance > 0.0) return 0;
  std::size_t best = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (texels[i].luminance > texels[best].luminance) best = i;
  return best;
}

Rgb<double> filter_after_transform(const FilterTexel* texels, const double* weights, std::size_t n) {
  check_footprint(texels, weights, n);
  // Eq. 8's form: the products v_i Y_i (etc.) are weighted and the constant 1 / w of the transform is applied once,
  // which equals sum_i w_i RGB_i (eq. 7) and rounds like eq. 9 does, so equal luminances give exactly equal results.
  double red = 0.0, green = 0.0, blue = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    red += weights[i] * (texels[i].v * texels[i].luminance);
    green += weights[i] * ((1.0 - texels[i].u - texels[i].v) * texels[i].luminance);
    blue += weights[i] * (texels[i].u * texels[i].luminance);
  }
  return Rgb<double>{red / kRec601WeightR, green / kRec601WeightG, blue / kRec601WeightB};
}

Rgb<double> filter_before_transform(const FilterTexel* texels, const double* weights, std::size_t n) {
  check_footprint(texels, weights, n);
  FilterTexel sum;
  for (std::size_t i = 0; i < n; ++i) {
    sum.luminance += weights[i] * texels[i].luminance;
    sum.u += weights[i] * texels[i].u;
    sum.v += weights[i] * texels[i].v;
  }
  return rgb_from_filter_texel(sum);
}

Rgb<double> filter_before_transform_normalised(const FilterTexel* texels, const double* weights, std::size_t n,
                                               ShiftRule rule, ShiftReference reference, int* shifts_out) {
  check_footprint(texels, weights, n);
  const double reference_luminance = texels[normalisation_reference(texels, n, reference)].luminance;
  double luminance = 0.0, u = 0.0, v = 0.0, c = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const int k = normalisation_shift(texels[i].luminance, reference_luminance, rule);
    if (shifts_out != nullptr) shifts_out[i] = k;
    // Bit shifts: exact scaling by a power of two (ldexp), so v' Y' = v Y exactly.
    luminance += weights[i] * std::ldexp(texels[i].luminance, -k);
    u += weights[i] * std::ldexp(texels[i].u, k);
    v += weights[i] * std::ldexp(texels[i].v, k);
    c += weights[i] * std::ldexp(1.0, k);
  }
  return Rgb<double>{v * luminance / kRec601WeightR, (c - u - v) * luminance / kRec601WeightG,
                     u * luminance / kRec601WeightB};
}

double red_error_closed_form(double v1, double v2, double y1, double y2, double alpha) {
  return alpha * (alpha - 1.0) * (v2 - v1) * (y2 - y1) / kRec601WeightR;
}

std::vector<Figure1Point> figure1_curve(const Figure1Setup& s) {
  if (s.samples < 2) fail(kOwner, "the Figure 1 curve needs at least 2 samples, got " + std::to_string(s.samples));
  const double inputs[] = {s.v1, s.v2, s.y1, s.y2_first, s.y2_last};
  for (double x : inputs)
    if (!std::isfinite(x) || x < 0.0) fail(kOwner, "v1, v2, Y1 and the Y2 range must be finite and >= 0");
  if (!(s.alpha >= 0.0 && s.alpha <= 1.0)) fail(kOwner, "alpha must be in [0, 1]");
  // Geometric spacing takes logarithms of the end points.
  if (s.geometric && !(s.y2_first > 0.0 && s.y2_last > 0.0)) fail(kOwner, "geometric spacing needs Y2 > 0");
  std::vector<Figure1Point> curve;
  curve.reserve(static_cast<std::size_t>(s.samples));
  const double weights[2] = {1.0 - s.alpha, s.alpha};
  for (int i = 0; i < s.samples; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(s.samples - 1);
    // The last sample is exactly y2_last (no drift from t * (last - first) rounding).
    const double y2 = i == s.samples - 1 ? s.y2_last
                      : s.geometric ? s.y2_first * std::pow(s.y2_last / s.y2_first, t)
                                    : s.y2_first + t * (s.y2_last - s.y2_first);
    // u is irrelevant for red; grey chrominance wb keeps G >= 0 for the v values of the figure.
    const FilterTexel texels[2] = {{s.y1, kRec601WeightB, s.v1}, {y2, kRec601WeightB, s.v2}};
    Figure1Point p;
    p.y2 = y2;
    p.correct_red = filter_after_transform(texels, weights, 2).r;
    p.plain_red = filter_before_transform(texels, weights, 2).r;
    p.plain_error = p.plain_red - p.correct_red;
    p.plain_closed_form = red_error_closed_form(s.v1, s.v2, s.y1, y2, s.alpha);
    int shifts[2] = {0, 0};
    p.normalised_red = filter_before_transform_normalised(texels, weights, 2, s.rule, s.reference, shifts).r;
    p.shift1 = shifts[0];
    p.shift2 = shifts[1];
    p.normalised_error = p.normalised_red - p.correct_red;
    p.normalised_closed_form =
        red_error_closed_form(std::ldexp(s.v1, shifts[0]), std::ldexp(s.v2, shifts[1]), std::ldexp(s.y1, -shifts[0]),
                              std::ldexp(y2, -shifts[1]), s.alpha);
    curve.push_back(p);
  }
  return curve;
}

}  // namespace blocklab::munkberg
