// The wavelet stage and plane codec of `mavridis` (formats/mavridis/mavridis_wavelet.h, mavridis_plane_codec.h):
// eq. 1 / eq. 3 and eq. 2 invert exactly, the templated decoder is bit-identical to the spec-literal oracle on random
// textures (one and several levels), PLHaar is a bijection of its square, and the section 3.2 search does no worse
// than its fixed starting point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "formats/mavridis/mavridis_coefficient_problem.h"
#include "formats/mavridis/mavridis_multilevel.h"
#include "formats/mavridis/mavridis_plane_codec.h"
#include "formats/mavridis/mavridis_wavelet.h"

namespace blocklab {
namespace mavridis {
namespace {

TEST(MavridisWavelet, HaarThenEquationThreeReturnsEveryIntegerTexelExactly) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(-255, 255);
  for (int trial = 0; trial < 10000; ++trial) {
    const double a = value(rng), b = value(rng), c = value(rng), d = value(rng);
    const std::array<double, 4> haar = haar_forward(a, b, c, d);
    // Group texels: a = (0, 0), b = (1, 0), c = (0, 1), d = (1, 1); eq. 3 uses only the coordinates' parity.
    EXPECT_EQ(reconstruct_texel(haar, 0, 0), a);
    EXPECT_EQ(reconstruct_texel(haar, 1, 0), b);
    EXPECT_EQ(reconstruct_texel(haar, 2, 1), c);
    EXPECT_EQ(reconstruct_texel(haar, 5, 3), d);
  }
}

TEST(MavridisWavelet, PiHaarInvertsExactlyForDyadicWeightsAndClosely) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> value(-255, 255);
  for (double w : {0.25, 0.5, 1.0}) {
    for (int trial = 0; trial < 2000; ++trial) {
      const std::array<double, 4> haar = haar_forward<double>(value(rng), value(rng), value(rng), value(rng));
      const std::array<double, 4> back = haar_from_pi_haar(pi_haar_from_haar(haar, w), w);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(back[k], haar[k]) << "w " << w;
    }
  }
  const std::array<double, 4> haar = {10.0, -3.5, 7.25, 1.75};
  const std::array<double, 4> back = haar_from_pi_haar(pi_haar_from_haar(haar, 0.4), 0.4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(back[k], haar[k], 1e-12);
}

TEST(MavridisWavelet, STransformInvertsExactlyOnIntegers) {
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> value(-255, 255);
  for (int trial = 0; trial < 20000; ++trial) {
    const long long a = value(rng), b = value(rng), c = value(rng), d = value(rng);
    const std::array<long long, 4> back = s_transform_inverse(s_transform_forward(a, b, c, d));
    ASSERT_EQ(back[0], a);
    ASSERT_EQ(back[1], b);
    ASSERT_EQ(back[2], c);
    ASSERT_EQ(back[3], d);
  }
}

TEST(MavridisWavelet, PlhaarMapsEverySignedPairOntoTheSameRangeBijectivelyAndInverts) {
  for (int half : {128, 256}) {
    const int side = 2 * half;
    std::vector<char> hit(static_cast<std::size_t>(side) * side, 0);
    for (int a = -half; a < half; ++a)
      for (int b = -half; b < half; ++b) {
        const PlhaarPair lh = plhaar_forward(a, b);
        ASSERT_GE(lh.low, -half) << a << " " << b;
        ASSERT_LT(lh.low, half) << a << " " << b;
        ASSERT_GE(lh.high, -half) << a << " " << b;
        ASSERT_LT(lh.high, half) << a << " " << b;
        char& seen = hit[static_cast<std::size_t>(lh.low + half) * side + (lh.high + half)];
        ASSERT_EQ(seen, 0) << "two pairs map to (" << lh.low << ", " << lh.high << ")";
        seen = 1;
        const PlhaarPair back = plhaar_inverse(lh.low, lh.high);
        ASSERT_EQ(back.low, a);
        ASSERT_EQ(back.high, b);
      }
  }
}

TEST(MavridisWavelet, PlhaarIsHaarLikeOnSameSignPairsAndItsGroupsInvert) {
  // Same sign: the high band is the difference, the low band the value of larger magnitude.
  EXPECT_EQ(plhaar_forward(100, 40).low, 100);
  EXPECT_EQ(plhaar_forward(100, 40).high, 60);
  EXPECT_EQ(plhaar_forward(10, 10).high, 0);
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> value(-128, 127);
  for (int trial = 0; trial < 20000; ++trial) {
    const int a = value(rng), b = value(rng), c = value(rng), d = value(rng);
    const std::array<int, 4> bands = plhaar_group_forward(a, b, c, d);
    for (int band : bands) ASSERT_TRUE(band >= -128 && band < 128);
    const std::array<int, 4> back = plhaar_group_inverse(bands);
    ASSERT_EQ(back, (std::array<int, 4>{a, b, c, d}));
  }
}

TEST(MavridisWavelet, DequantiseInvertsTheGammaMapping) {
  for (double g : {0.6, 0.86, 1.0}) {
    for (double n = -1.0; n <= 1.0; n += 0.125) {
      const double s = 0.5 * (1.0 + (n < 0 ? -1.0 : 1.0) * std::pow(std::abs(n), g));
      EXPECT_NEAR(dequantise(s, 3.0, 20.0, g), 3.0 + 20.0 * n, 1e-9) << "gamma " << g << " n " << n;
    }
  }
}

BandMapping random_mapping(std::mt19937& rng) {
  std::uniform_real_distribution<double> centre(-50.0, 50.0), half(0.5, 300.0), gamma(0.5, 1.5);
  BandMapping mapping;
  for (int k = 0; k < 4; ++k) {
    mapping.centre[k] = centre(rng);
    mapping.half_range[k] = half(rng);
  }
  mapping.gamma = gamma(rng);
  return mapping;
}

TEST(MavridisWavelet, TemplatedDecodeAgreesWithTheOracleOnRandomTextures) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> size(1, 40), byte(0, 255);
  for (int trial = 0; trial < 200; ++trial) {
    const int width = size(rng), height = size(rng);
    std::vector<std::uint8_t> bytes(wavelet_plane_bytes(width, height));
    for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(rng));
    const BandMapping mapping = random_mapping(rng);
    const Transform kTransforms[4] = {Transform::haar, Transform::pi_haar, Transform::s_transform, Transform::plhaar};
    const Transform transform = kTransforms[trial % 4];
    const PlhaarDomain domain = trial % 8 < 4 ? plhaar_luma_domain() : plhaar_chroma_domain();
    const double w = trial % 4 == 0 ? 1.0 : 0.4;
    // BC7 packing (Haar and PI-Haar only) on every fourth texture; PLHaar in the luma and the chroma domain.
    const Packing packing = trial % 8 == 1 || trial % 8 == 4 ? Packing::bc7 : Packing::dxt5;
    const Plane decoded = decode_wavelet_plane(bytes.data(), width, height, mapping, transform, w, 1, packing, domain);
    const Plane oracle =
        reference_decode_wavelet_plane(bytes.data(), width, height, mapping, transform, w, packing, domain);
    ASSERT_EQ(decoded.values.size(), oracle.values.size());
    // The two reach the exact DXT5 fractions by different routes and reconstruct with eq. 3 vs eq. 1 (summed in eq. 3's
    // order): bit-identical.
    for (std::size_t i = 0; i < oracle.values.size(); ++i)
      ASSERT_EQ(decoded.values[i], oracle.values[i]) << "trial " << trial << " texel " << i;
  }
}

Plane smooth_plane(int width, int height) {
  Plane plane;
  plane.width = width;
  plane.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      plane.values.push_back(128.0 + 90.0 * std::sin(0.21 * x) * std::cos(0.13 * y) + ((x * 7 + y * 3) % 5));
  return plane;
}

TEST(MavridisWavelet, EncodedPlaneDecodesLikeTheOracleAndReportsItsError) {
  const Plane plane = smooth_plane(37, 21);
  WaveletSettings settings;
  const WaveletPlane coded = encode_wavelet_plane(plane, settings);
  ASSERT_EQ(coded.bytes.size(), wavelet_plane_bytes(37, 21));
  const Plane decoded = decode_wavelet_plane(coded.bytes.data(), 37, 21, coded.mapping, settings.transform, 0.4, 2);
  const Plane oracle = reference_decode_wavelet_plane(coded.bytes.data(), 37, 21, coded.mapping, settings.transform, 0.4);
  double error = 0.0;
  for (std::size_t i = 0; i < plane.values.size(); ++i) {
    EXPECT_EQ(decoded.values[i], oracle.values[i]);
    error += (decoded.values[i] - plane.values[i]) * (decoded.values[i] - plane.values[i]);
  }
  EXPECT_DOUBLE_EQ(error, coded.squared_error);
  EXPECT_LT(error / plane.values.size(), 30.0);   // PSNR above ~33 dB on this smooth plane
}

TEST(MavridisWavelet, PlhaarPlaneDecodesLikeTheOracleInBothDomains) {
  for (const PlhaarDomain domain : {plhaar_luma_domain(), plhaar_chroma_domain()}) {
    Plane plane = smooth_plane(37, 21);
    if (domain.offset == 0)
      for (double& v : plane.values) v = 1.8 * (v - 128.0);   // signed chroma, beyond 8 bits
    WaveletSettings settings;
    settings.transform = Transform::plhaar;
    settings.domain = domain;
    const WaveletPlane coded = encode_wavelet_plane(plane, settings);
    const Plane decoded =
        decode_wavelet_plane(coded.bytes.data(), 37, 21, coded.mapping, Transform::plhaar, 0.4, 2, Packing::dxt5, domain);
    const Plane oracle =
        reference_decode_wavelet_plane(coded.bytes.data(), 37, 21, coded.mapping, Transform::plhaar, 0.4, Packing::dxt5, domain);
    double error = 0.0;
    for (std::size_t i = 0; i < plane.values.size(); ++i) {
      ASSERT_EQ(decoded.values[i], oracle.values[i]);
      error += (decoded.values[i] - plane.values[i]) * (decoded.values[i] - plane.values[i]);
    }
    EXPECT_DOUBLE_EQ(error, coded.squared_error);
    EXPECT_LT(error / plane.values.size(), domain.offset == 0 ? 200.0 : 60.0);
  }
}

TEST(MavridisWavelet, MultilevelDecodeAgreesWithTheOracleOnRandomBytes) {
  std::mt19937 rng(29);
  std::uniform_int_distribution<int> size(1, 70), byte(0, 255);
  for (int trial = 0; trial < 120; ++trial) {
    const int width = size(rng), height = size(rng), levels = 2 + trial % 3;
    std::vector<std::uint8_t> bytes(multilevel_plane_bytes(width, height, levels));
    for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(rng));
    std::vector<BandMapping> detail;
    for (int k = 1; k < levels; ++k) detail.push_back(random_mapping(rng));
    const BandMapping last = random_mapping(rng);
    const Transform transform = trial % 2 == 0 ? Transform::pi_haar : Transform::haar;
    const Packing packing = trial % 5 == 0 ? Packing::bc7 : Packing::dxt5;
    const Plane decoded = decode_multilevel_plane(bytes.data(), width, height, detail, last, transform, 0.4, 2, packing);
    const Plane oracle = reference_decode_multilevel_plane(bytes.data(), width, height, detail, last, transform, 0.4, packing);
    ASSERT_EQ(decoded.values.size(), static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < oracle.values.size(); ++i)
      ASSERT_EQ(decoded.values[i], oracle.values[i]) << "trial " << trial << " texel " << i;
  }
}

TEST(MavridisWavelet, MultilevelRatesFollowSection34AndTwoLevelsDecodeLikeTheOracle) {
  // B_N = 1 + B_{N-1} / 4: 2, 1.5, 1.375 bpp on a 64 x 64 plane.
  EXPECT_EQ(multilevel_plane_bytes(64, 64, 1) * 8, 2u * 64 * 64);
  EXPECT_EQ(multilevel_plane_bytes(64, 64, 2) * 16, 3u * 64 * 64);
  EXPECT_EQ(multilevel_plane_bytes(64, 64, 3) * 8 * 8, 11u * 64 * 64);
  const Plane plane = smooth_plane(45, 38);
  WaveletSettings settings;
  const MultilevelPlane coded = encode_multilevel_plane(plane, settings, 2);
  ASSERT_EQ(coded.bytes.size(), multilevel_plane_bytes(45, 38, 2));
  ASSERT_EQ(coded.detail.size(), 1u);
  const Plane decoded = decode_multilevel_plane(coded.bytes.data(), 45, 38, coded.detail, coded.last.mapping,
                                                Transform::pi_haar, 0.4, 1, Packing::dxt5);
  const Plane oracle = reference_decode_multilevel_plane(coded.bytes.data(), 45, 38, coded.detail, coded.last.mapping,
                                                         Transform::pi_haar, 0.4, Packing::dxt5);
  double error = 0.0;
  for (std::size_t i = 0; i < plane.values.size(); ++i) {
    ASSERT_EQ(decoded.values[i], oracle.values[i]);
    error += (decoded.values[i] - plane.values[i]) * (decoded.values[i] - plane.values[i]);
  }
  // Two levels lose quality against one (Figure 5) but stay a usable picture of the smooth plane.
  const MultilevelPlane one = encode_multilevel_plane(plane, settings, 1);
  EXPECT_EQ(one.bytes, encode_wavelet_plane(plane, settings).bytes);
  EXPECT_GT(error, one.last.squared_error);
  EXPECT_LT(error / plane.values.size(), 100.0);
}

TEST(MavridisWavelet, GridSearchIsNoWorseThanItsFixedPoint) {
  const Plane plane = smooth_plane(64, 48);
  WaveletSettings fixed;
  fixed.final_search = S3tcSearch::fast;
  WaveletSettings searched = fixed;
  searched.clamps = {0.26, 0.0, 0.1, 0.4};
  searched.gammas = {0.86, 0.7, 1.0};
  const WaveletPlane a = encode_wavelet_plane(plane, fixed);
  const WaveletPlane b = encode_wavelet_plane(plane, searched);
  EXPECT_LE(b.squared_error, a.squared_error);
}

TEST(MavridisWavelet, CoeffSearchSolverIsNoWorseThanItsStartPoint) {
  const Plane plane = smooth_plane(48, 40);
  WaveletSettings fixed;
  fixed.final_search = S3tcSearch::fast;
  WaveletSettings solved = fixed;
  solved.solver = "coeff_search";
  solved.solver_options = {{"grid_points", "3"}, {"refinement_levels", "1"}, {"hill_climb_steps", "3"}};
  const WaveletPlane a = encode_wavelet_plane(plane, fixed);
  const WaveletPlane b = encode_wavelet_plane(plane, solved);
  EXPECT_LE(b.squared_error, a.squared_error);
}

TEST(MavridisWavelet, CoefficientProblemEvaluatesThePlaneErrorAndRefusesPointsOutsideItsBox) {
  const Plane plane = smooth_plane(24, 16);
  const WaveletSettings settings;
  const CoefficientProblem problem(plane, settings);
  const double x[2] = {0.2, 0.9};
  EXPECT_EQ(problem.eval(x), wavelet_plane_error(plane, settings, 0.2, 0.9));
  const double outside[2] = {0.7, 0.9};
  EXPECT_TRUE(std::isnan(problem.eval(outside)));
  const Interval box[2] = {Interval(0.0, 0.6), Interval(0.5, 1.2)};
  EXPECT_LE(problem.eval(box).lower(), problem.eval(x));
  EXPECT_GE(problem.eval(box).upper(), problem.eval(x));
}

TEST(MavridisWavelet, Bc7PackedPlaneDecodesLikeTheOracleAndKeepsItsError) {
  const Plane plane = smooth_plane(40, 24);
  WaveletSettings settings;
  settings.packing = Packing::bc7;
  const WaveletPlane coded = encode_wavelet_plane(plane, settings);
  const Plane decoded =
      decode_wavelet_plane(coded.bytes.data(), 40, 24, coded.mapping, settings.transform, 0.4, 1, Packing::bc7);
  const Plane oracle =
      reference_decode_wavelet_plane(coded.bytes.data(), 40, 24, coded.mapping, settings.transform, 0.4, Packing::bc7);
  double error = 0.0;
  for (std::size_t i = 0; i < plane.values.size(); ++i) {
    EXPECT_EQ(decoded.values[i], oracle.values[i]);
    error += (decoded.values[i] - plane.values[i]) * (decoded.values[i] - plane.values[i]);
  }
  EXPECT_DOUBLE_EQ(error, coded.squared_error);
  EXPECT_LT(error / plane.values.size(), 30.0);
}

TEST(MavridisWavelet, ConstantPlaneDecodesToItsValue) {
  Plane plane;
  plane.width = 13;
  plane.height = 9;
  plane.values.assign(13 * 9, 77.0);
  const WaveletPlane coded = encode_wavelet_plane(plane, WaveletSettings{});
  const Plane decoded = decode_wavelet_plane(coded.bytes.data(), 13, 9, coded.mapping, Transform::pi_haar, 0.4, 1);
  for (double v : decoded.values) EXPECT_NEAR(v, 77.0, 1e-3);
}

}  // namespace
}  // namespace mavridis
}  // namespace blocklab
