// One channel ("plane") of `mavridis` coded the paper's 2 bpp way (sections 3.1-3.3): the plane, padded to a
// multiple of 8 by edge replication, is wavelet-decomposed one level (eq. 1, or PI-Haar eq. 2); the coefficients of
// each 2x2 group become one texel of a half-resolution DXT5 (BC3) texture, LL in alpha and the three wavelet bands
// in RGB, each band mapped into [0, 1] by its centre, half range and (wavelet bands) gamma (section 3.2):
//   n = clamp((x - c) / r, -1, 1),  s = (1 + sign(n) |n|^g) / 2;  decoded by mavridis_wavelet.h's dequantise.
// The half range of a wavelet band is (1 - clamp) times half its exact range (the "outliers" beyond it clamp);
// LL keeps its exact range and g = 1. The clamp and gamma are found per plane by a brute-force search over a grid
// on the real decoded error (sum of squared plane errors), as section 3.2 describes.
// Values are in 8-bit units (Y in [0, 255], chroma in [-255, 255]). BC3 blocks are row-major over the coefficient
// texture: ceil(w / 8) x ceil(h / 8) blocks of 16 bytes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/options.h"

#include "formats/common/s3tc_color_fit.h"
#include "formats/mavridis/mavridis_plhaar.h"
#include "formats/mavridis/mavridis_wavelet.h"

namespace blocklab {
namespace mavridis {

struct Plane {
  int width = 0, height = 0;
  std::vector<double> values;   // row-major
  double at(int x, int y) const { return values[static_cast<std::size_t>(y) * width + x]; }
  static Plane zeros(int width, int height) {
    Plane plane;
    plane.width = width;
    plane.height = height;
    plane.values.assign(static_cast<std::size_t>(width) * height, 0.0);
    return plane;
  }
};

// Per-band constants of section 3.2 (band order LL, HL, LH, HH).
struct BandMapping {
  std::array<double, 4> centre{}, half_range{};
  double gamma = 1.0;            // wavelet bands only
};

// dxt5: LL in alpha, three wavelet bands in RGB (16-byte BC3 blocks). bc7: LL, two bands in RGB, HH dropped,
// alpha 255, BC7 with channel weights 0.6 / 0.2 / 0.2 (16-byte BC7 blocks; Haar or PI-Haar only).
enum class Packing { dxt5, bc7 };

struct WaveletSettings {
  Transform transform = Transform::pi_haar;
  Packing packing = Packing::dxt5;
  double w = 0.4;                               // eq. 2
  PlhaarDomain domain = plhaar_luma_domain();   // transform = plhaar: the plane's signed range
  int bc7_partitions = 4, bc7_refine_iterations = 2;   // packing = bc7: the bc7 encoder's effort
  bool bc7_pbit_search = true;
  S3tcSearch final_search = S3tcSearch::standard;
  S3tcSearch search_effort = S3tcSearch::fast;  // the BC3 fits inside the clamp / gamma search
  std::vector<double> clamps{0.26};             // candidates, tried in order (strict improvements win)
  std::vector<double> gammas{0.86};
  // Empty: the grid above. Otherwise the name of a solver of the library (solvers/registry.h) run on the
  // CoefficientProblem (mavridis_coefficient_problem.h) from (clamps[0], gammas[0]), with these options and seed.
  std::string solver;
  Options solver_options;
  std::uint64_t seed = 1;
  int threads = 1;
};

struct WaveletPlane {
  std::vector<std::uint8_t> bytes;   // wavelet_plane_bytes(width, height)
  BandMapping mapping;
  double clamp = 0.0;                // the search's choice (recorded in side data, not decoded)
  double squared_error = 0.0;        // sum over the plane's texels of the decoded squared error
};

inline int wavelet_blocks_x(int width) { return (width + 7) / 8; }
inline std::size_t wavelet_plane_bytes(int width, int height) {
  return static_cast<std::size_t>(wavelet_blocks_x(width)) * static_cast<std::size_t>(wavelet_blocks_x(height)) * 16;
}

// The coefficients of a plane padded to whole 8x8 tiles: band k of group (gx, gy) at bands[k][gy * groups_x + gx]
// (LL, HL, LH, HH; PI-Haar's HL', LH', HH' for dxt5 packing, section 3.1's three BC7 bands for bc7).
struct Coefficients {
  int groups_x = 0, groups_y = 0;
  std::array<std::vector<double>, 4> bands;
};
Coefficients transform_plane(const Plane& plane, const WaveletSettings& settings);
// Section 3.2's mapping of each band from its exact range, the wavelet bands' half range shrunk by (1 - clamp).
BandMapping band_mapping(const Coefficients& c, double clamp, double gamma);
// Section 3.2's forward mapping of one value of band `band` to [0, 1].
double quantise(double x, const BandMapping& mapping, int band);
double plane_squared_error(const Plane& plane, const Plane& decoded);

WaveletPlane encode_wavelet_plane(const Plane& plane, const WaveletSettings& settings);
// The search's error at one (clamp, gamma): the plane's summed squared error after a settings.search_effort encode.
double wavelet_plane_error(const Plane& plane, const WaveletSettings& settings, double clamp, double gamma);
// The decode of one plane (width x height) from its BC3 blocks: the templated pieces of mavridis_wavelet.h at
// T = double, eq. 3 per texel.
Plane decode_wavelet_plane(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping,
                           Transform transform, double w, int threads, Packing packing = Packing::dxt5,
                           PlhaarDomain domain = plhaar_luma_domain());

// The oracle (mavridis_reference_decode.cpp): the same plane decoded straight from the paper's equations and the
// DXT5 text, reading the block bits itself and inverting with eq. 1 (its own inverse) instead of eq. 3 (PLHaar:
// by a table of its forward map over every pair of the domain).
Plane reference_decode_wavelet_plane(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping,
                                     Transform transform, double w, Packing packing = Packing::dxt5,
                                     PlhaarDomain domain = plhaar_luma_domain());

}  // namespace mavridis
}  // namespace blocklab
