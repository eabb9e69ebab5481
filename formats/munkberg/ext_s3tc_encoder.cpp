// Encoder of the extended-S3TC mode (formats/munkberg/ext_s3tc_encoder.h; Munkberg et al. 2008, section 6.1).
#include "formats/munkberg/ext_s3tc_encoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "formats/munkberg/munkberg_encoder.h"

namespace blocklab::munkberg {

namespace {

constexpr int kPaletteSize = kExtS3tcLevelsMinusOne + 1;

int channel_max(int c) { return (1 << kExtS3tcChannelBits[static_cast<std::size_t>(c)]) - 1; }

// Working-space coordinates of a colour: linear RGB, or (Ybar / 8, u, v) for logyuv (Ybar scaled so that a stop of
// luminance weighs like 1/8 of the chroma triangle in the principal-axis fit).
std::array<double, 3> working_point(const float* rgba, ExtS3tcSpace space) {
  const double r = rgba[0], g = rgba[1], b = rgba[2];
  if (space == ExtS3tcSpace::rgb) return {r, g, b};
  const LogYuv<double> yuv = rgb_to_logyuv(Rgb<double>{r, g, b});
  // True black (and anything below the half range) sits at the bottom of the log-luminance range.
  const double ybar = (r == 0.0 && g == 0.0 && b == 0.0) ? kLogLumMin : std::min(kLogLumMax, std::max(kLogLumMin, yuv.log_luminance));
  return {ybar / 8.0, std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))};
}

// Codes of a working-space point (inverse of working_point + the dequantisation of ext_s3tc_block.h).
std::array<int, 3> quantise(const std::array<double, 3>& point, ExtS3tcSpace space) {
  std::array<int, 3> code{};
  for (int c = 0; c < 3; ++c) {
    const double m = channel_max(c);
    double q = 0.0;
    if (space == ExtS3tcSpace::rgb) {
      // Zero or below the half range: code 0 (true zero); otherwise the nearest log code, at least 1.
      q = point[static_cast<std::size_t>(c)] <= 0.0
              ? 0.0
              : std::max(1.0, std::round((std::log2(point[static_cast<std::size_t>(c)]) - kLogLumMin) * m / kLogLumRange));
    } else if (c == 0) {
      q = std::round((point[0] * 8.0 - kLogLumMin) * m / kLogLumRange);
    } else {
      q = std::round(point[static_cast<std::size_t>(c)] * m);
    }
    code[static_cast<std::size_t>(c)] = static_cast<int>(std::min(m, std::max(0.0, q)));   // clamp to the field
  }
  return code;
}

// A palette's decoded values and their log2. A coordinate-descent trial moves one channel of one endpoint of the
// best block so far, so in RGB space two of the three channels decode as in the best block's palette and their log2
// is reused from it (metric_log2 of an equal float is the same double).
struct PaletteLog2 {
  bool filled = false;
  float value[kPaletteSize][3] = {};
  double log2[kPaletteSize][3] = {};
};

// assign_ext_s3tc_indices with the source's log2 given, fitting texels only while the error so far is below `bound`:
// at or above it, it returns early with a partial error >= bound (the full error is >= bound too: every texel adds
// a square) and partial indices; below it, the full result bit for bit.
// `reference`: a palette whose log2 may be reused (or nullptr); `palette` receives this one's.
double assign_indices(const TexelLog2& source_log2, ExtS3tcSpace space, ExtS3tcParams* params, double bound,
                      const PaletteLog2* reference, PaletteLog2* palette) {
  // The 32 palette entries through the decoder itself (two 16-texel decodes), so the error is exactly the error of
  // the decoded block.
  const double (&palette_log2)[kPaletteSize][3] = palette->log2;
  for (int half = 0; half < 2; ++half) {
    ExtS3tcParams probe = *params;
    for (int i = 0; i < kTexels; ++i) probe.index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(16 * half + i);
    const BlockTexels decoded = decode_ext_s3tc_params(probe, space);
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c) {
        const int l = 16 * half + i;
        const float value = decoded.rgba[i][c];
        palette->value[l][c] = value;
        // A NaN never equals the reference: it is recomputed (and stays NaN).
        palette->log2[l][c] = reference != nullptr && reference->filled && reference->value[l][c] == value
                                  ? reference->log2[l][c]
                                  : metric_log2(value);
      }
  }
  palette->filled = true;
  double total = 0.0;
  for (int i = 0; i < kTexels; ++i) {
    const std::array<double, 3>& s = source_log2[static_cast<std::size_t>(i)];
    int best = 0;
    double best_error = 0.0;
    for (int l = 0; l < kPaletteSize; ++l) {
      double e = 0.0;
      for (int c = 0; c < 3; ++c) e += (palette_log2[l][c] - s[static_cast<std::size_t>(c)]) * (palette_log2[l][c] - s[static_cast<std::size_t>(c)]);
      if (l == 0 || e < best_error) {   // ties keep the lower index
        best = l;
        best_error = e;
      }
    }
    params->index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(best);
    total += best_error;
    if (total >= bound) return total;   // cannot end below the bound (a NaN total never stops early)
  }
  return total;
}

}  // namespace

double assign_ext_s3tc_indices(const BlockTexels& texels, ExtS3tcSpace space, ExtS3tcParams* params) {
  PaletteLog2 palette;
  return assign_indices(texel_log2(texels), space, params, std::numeric_limits<double>::infinity(), nullptr,
                        &palette);
}

ExtS3tcParams encode_ext_s3tc(const BlockTexels& texels, const ExtS3tcSettings& settings, double* error) {
  const ExtS3tcSpace space = settings.space;
  std::array<std::array<double, 3>, kTexels> p{};
  std::array<double, 3> mean{};
  for (int i = 0; i < kTexels; ++i) {
    p[static_cast<std::size_t>(i)] = working_point(texels.rgba[i], space);
    for (int c = 0; c < 3; ++c) mean[static_cast<std::size_t>(c)] += p[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] / kTexels;
  }
  // Principal axis by power iteration on the covariance (start: the diagonal, a fixed deterministic vector).
  double cov[3][3] = {};
  for (const auto& q : p)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] += (q[static_cast<std::size_t>(a)] - mean[static_cast<std::size_t>(a)]) * (q[static_cast<std::size_t>(b)] - mean[static_cast<std::size_t>(b)]);
  std::array<double, 3> axis = {1.0, 1.0, 1.0};
  for (int iteration = 0; iteration < 16; ++iteration) {
    std::array<double, 3> next{};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) next[static_cast<std::size_t>(a)] += cov[a][b] * axis[static_cast<std::size_t>(b)];
    const double norm = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
    if (!(norm > 1e-300)) break;   // constant block (zero covariance): keep the current axis, extremes coincide
    for (int a = 0; a < 3; ++a) axis[static_cast<std::size_t>(a)] = next[static_cast<std::size_t>(a)] / norm;
  }
  double lo = 0.0, hi = 0.0;
  int darkest = 0, brightest = 0;
  double dark_y = 0.0, bright_y = 0.0;
  for (int i = 0; i < kTexels; ++i) {
    const auto& q = p[static_cast<std::size_t>(i)];
    const double t = (q[0] - mean[0]) * axis[0] + (q[1] - mean[1]) * axis[1] + (q[2] - mean[2]) * axis[2];
    lo = i == 0 ? t : std::min(lo, t);
    hi = i == 0 ? t : std::max(hi, t);
    const double y = kRec601WeightR * texels.rgba[i][0] + kRec601WeightG * texels.rgba[i][1] + kRec601WeightB * texels.rgba[i][2];
    if (i == 0 || y < dark_y) { darkest = i; dark_y = y; }
    if (i == 0 || y > bright_y) { brightest = i; bright_y = y; }
  }
  std::array<double, 3> a{}, b{};
  for (int c = 0; c < 3; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c);
    a[cc] = mean[cc] + lo * axis[cc];
    b[cc] = mean[cc] + hi * axis[cc];
  }
  // Two starts: the principal-axis extremes and the darkest / brightest texels; the better one is refined.
  ExtS3tcParams best;
  best.endpoint = {quantise(a, space), quantise(b, space)};
  // Every trial below only replaces the best when strictly lower: it is fitted only while it can still be.
  const TexelLog2 source_log2 = texel_log2(texels);
  PaletteLog2 best_palette, trial_palette;
  double best_error =
      assign_indices(source_log2, space, &best, std::numeric_limits<double>::infinity(), nullptr, &best_palette);
  {
    ExtS3tcParams alt;
    alt.endpoint = {quantise(p[static_cast<std::size_t>(darkest)], space), quantise(p[static_cast<std::size_t>(brightest)], space)};
    const double e = assign_indices(source_log2, space, &alt, best_error, &best_palette, &trial_palette);
    if (e < best_error) {
      best = alt;
      best_error = e;
      std::swap(best_palette, trial_palette);
    }
  }
  // Coordinate descent on the six codes (steps 4 then 1), accepting strict improvements only (deterministic).
  for (int pass = 0; pass < settings.refine_passes; ++pass) {
    bool improved = false;
    for (const int step : {4, 1})
      for (int e = 0; e < 2; ++e)
        for (int c = 0; c < 3; ++c)
          for (const int sign : {-1, 1}) {
            ExtS3tcParams trial = best;
            int& code = trial.endpoint[static_cast<std::size_t>(e)][static_cast<std::size_t>(c)];
            const int moved = code + sign * step;
            if (moved < 0 || moved > channel_max(c)) continue;   // outside the field
            code = moved;
            const double err = assign_indices(source_log2, space, &trial, best_error, &best_palette, &trial_palette);
            if (err < best_error) {
              best = trial;
              best_error = err;
              std::swap(best_palette, trial_palette);
              improved = true;
            }
          }
    if (!improved) break;
  }
  canonicalize_ext_s3tc(&best);
  if (error != nullptr) *error = best_error;
  return best;
}

}  // namespace blocklab::munkberg
