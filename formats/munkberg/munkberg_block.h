// One `munkberg` block (Munkberg et al. 2008, sections 3.1, 5 and 7.1): the symbolic parameters, packing to / from
// the 16 bytes (layout: munkberg_layout.h), the templated decoder used by searches and Format::decode, and the
// spec-literal reference decoder (munkberg_reference_decode.cpp, kept apart; tests compare the two bit for bit).
//
// DECODING (the normative arithmetic, all in double, rounded once to float at the end):
//   luminance   n = 15 (shape II) or 7 (shape I); texel index l in [0, n]; integer numerator q = (n - l) e0 + l e1;
//               Ybar = kLogLumMin + (kLogLumRange * q) / (255 n);  Y = 0 when q == 0 (eq. 3: Ybar == Ybar_min is
//               true black), otherwise Y = exp2(Ybar).
//   chroma      base values u0 = c0 / 127, v0 = c1 / 127, u1 = c2 / 127, v1 = c3 / 127; du = u1 - u0, dv = v1 - v0;
//               landmark k of the block's shape (along a_k, across b_k; formats/munkberg/shape_fit/shape_fit_problem.h
// frame):
//               Lu = (u0 + a_k du) - b_k dv,  Lv = (v0 + a_k dv) + b_k du, each clamped to [0, 1];
//               texel i takes landmark chroma_index[group(i)] (group: munkberg_layout.h).
//   RGB (eq. 2) R = (v Y) / wr,  G = (max(0, 1 - u - v) Y) / wg,  B = (u Y) / wb  (Rec. 601 weights,
// core/color_spaces.h;
//               the max keeps G non-negative when a clamped landmark has u + v > 1). Alpha = 1.
#pragma once

#include <array>
#include <cstdint>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/scalar.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_shapes.h"

namespace blocklab::munkberg {

struct Params {
  Mode mode = Mode::shape_ii;
  int shape = 0;                                   // 0 .. kShapeCount - 1
  std::array<int, kBaseCoordinateCount> base{};    // codes of u0, v0, u1, v1, 0 .. 127
  std::array<int, kLumEndpointCount> lum{};        // log-luminance endpoint codes e0, e1, 0 .. 255
  std::array<std::uint8_t, kTexels> lum_index{};   // 0 .. n per texel
  // One 2-bit index per chroma group; groups >= chroma_groups(mode) are unused and must be 0.
  std::array<std::uint8_t, kTexels> chroma_index{};

  bool operator==(const Params& other) const;
  bool operator!=(const Params& other) const { return !(*this == other); }
};

// Writes the 16 bytes. Throws Error("munkberg: <field>: ...") when a field is out of range.
void pack_block(const Params& params, std::uint8_t* bytes);
// Reads the 16 bytes of a shape II or shape I block (block_mode_of(bytes) is one of them; otherwise an Error).
// Every such bit pattern is valid: pack(unpack(b)) == b.
Params unpack_block(const std::uint8_t* bytes);
// Shape I anchor convention (munkberg_layout.h): when lum_index[0] > 3, swaps e0/e1 and mirrors every luminance index
// (l -> 7 - l); the decoded texels do not change. No-op for shape II. The encoder calls it before pack_block.
void canonicalize_anchor(Params* params);

// Dequantised values (the decoding rules above).
inline double base_value(int code) { return static_cast<double>(code) / static_cast<double>(kBaseCoordinateMax); }
inline double log_luminance_of_numerator(std::int64_t q, int n) {
  return kLogLumMin + (kLogLumRange * static_cast<double>(q)) / (255.0 * static_cast<double>(n));
}
inline double log_luminance_of_code(int code) { return log_luminance_of_numerator(code, 1); }

// The 4 landmarks of `shape` for base points (u0, v0, u1, v1) as scalars, clamped to [0, 1] (decoding rule above).
template <typename T>
void decode_landmarks(const ShapeTemplate& shape, const T base[4], T u[kShapeLandmarkCount], T v[kShapeLandmarkCount]) {
  const T du = base[2] - base[0];
  const T dv = base[3] - base[1];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    const T a(shape.along(k)), b(shape.across(k));
    u[k] = clamp((base[0] + a * du) - b * dv, T(0.0), T(1.0));
    v[k] = clamp((base[1] + a * dv) + b * du, T(0.0), T(1.0));
  }
}

// The templated decoder: x = (e0, e1, u0, v0, u1, v1) as scalars (double, ceres::Jet or blocklab::Interval; e in
// code units, u/v as values in [0, 1]). The integer fields (mode, shape, indices) come from `params`; the true-black
// rule is decided on the INTEGER codes params.lum (eq. 3 compares stored codes), never on T.
// decode_block's two steps per texel, also used on their own by the encoder's index assignment (which decodes every
// texel on every landmark): the decoded luminance of texel i, and the linear RGB of a texel on landmark (u, v).
template <typename T>
T decode_texel_luminance(const Params& params, const T x[6], int i) {
  const int n = lum_levels_minus_one(params.mode);
  const int l = params.lum_index[static_cast<std::size_t>(i)];
  const std::int64_t q_code = static_cast<std::int64_t>(n - l) * params.lum[0] + static_cast<std::int64_t>(l) * params.lum[1];
  const T q = T(static_cast<double>(n - l)) * x[0] + T(static_cast<double>(l)) * x[1];
  const T log_luminance = T(kLogLumMin) + (T(kLogLumRange) * q) / T(255.0 * static_cast<double>(n));
  // Eq. (3): q == 0 is Ybar == Ybar_min, true black.
  return logyuv_luminance_from_code(q_code, std::int64_t{0}, log_luminance);
}
template <typename T>
void decode_texel_rgb(const T& u, const T& v, const T& luminance, T rgb[3]) {
  rgb[0] = (v * luminance) / T(kRec601WeightR);
  rgb[1] = (max(T(0.0), T(1.0) - u - v) * luminance) / T(kRec601WeightG);
  rgb[2] = (u * luminance) / T(kRec601WeightB);
}

template <typename T>
void decode_block(const Params& params, const ShapeSet& shapes, const T x[6], T rgb[kTexels][3]) {
  T landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  decode_landmarks(shapes.shapes[static_cast<std::size_t>(params.shape)], x + 2, landmark_u, landmark_v);
  for (int i = 0; i < kTexels; ++i) {
    const T luminance = decode_texel_luminance(params, x, i);
    const int k = params.chroma_index[static_cast<std::size_t>(chroma_group_of_texel(params.mode, i))];
    decode_texel_rgb(landmark_u[k], landmark_v[k], luminance, rgb[i]);
  }
}

// The parameter vector of decode_block for a Params value: (e0, e1, u0, v0, u1, v1) as doubles.
std::array<double, 6> decode_parameters(const Params& params);

// decode_block<double> of a Params value, as float texels (alpha = 1): what Format::decode writes.
BlockTexels decode_params(const Params& params, const ShapeSet& shapes);

// The decoded linear RGB of every mode's templated decoder (double) as float texels with alpha 1: what
// Format::decode writes.
BlockTexels texels_from_rgb(const double (&rgb)[kTexels][3]);

// The oracle: straight from the decoding rules and the layout table, bits read one at a time from the bytes.
BlockTexels reference_decode_block(const std::uint8_t* bytes, const ShapeSet& shapes);

}  // namespace blocklab::munkberg
