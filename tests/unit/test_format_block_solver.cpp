// The `solver` / `solver_options` format options (formats/common/block_solver.h, s3tc_solver_fit.h): BC1, BC3 and
// BC4 blocks searched by solvers of the library. Checks that a certifying solver reaches the exhaustive optimum, that
// stochastic solvers are reproducible from the seed at any thread count, and that bad settings are rejected with the
// key and the valid values named.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/image_io.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

// A 24x20 crop of the bundled Kodak sample (always present): real texture, edges that need partial blocks.
Image sample_crop() {
  const Image full = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/ldr/kodak/kodim03.png");
  Image crop(24, 20, 3);
  for (int y = 0; y < crop.height; ++y)
    for (int x = 0; x < crop.width; ++x)
      for (int c = 0; c < 4; ++c) crop.texel(x, y)[c] = full.texel(100 + x, 150 + y)[c];
  return crop;
}

EncodedTexture encode(const std::string& format, const FormatOptions& given, int threads = 1) {
  const Format& f = find_format(format);
  CodecContext context;
  context.threads = threads;
  return f.encode(sample_crop(), resolve_format_options(f, given), context);
}

// Sum of squared differences in 8-bit units over the stored channels (R for BC4).
double squared_error(const std::string& format, const EncodedTexture& texture) {
  const Image source = sample_crop();
  const Image decoded = find_format(format).decode(texture, CodecContext{});
  const int channels = format == "bc4" ? 1 : 3;
  double sum = 0.0;
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x)
      for (int c = 0; c < channels; ++c) {
        const double d = 255.0 * (source.texel(x, y)[c] - decoded.texel(x, y)[c]);
        sum += d * d;
      }
  return sum;
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(FormatBlockSolver, Bc4IntervalBranchAndBoundMatchesTheExhaustiveSearchError) {
  const double exhaustive = squared_error("bc4", encode("bc4", {{"search", "exhaustive"}}));
  const double certified = squared_error("bc4", encode("bc4", {{"solver", "interval_bb"}}));
  const double enumerated = squared_error("bc4", encode("bc4", {{"solver", "exhaustive"}}));
  // Every block is solved to its proven optimum in each mode, so the image errors agree to float rounding.
  EXPECT_NEAR(certified, exhaustive, 1e-6 * exhaustive);
  EXPECT_NEAR(enumerated, exhaustive, 1e-6 * exhaustive);
}

TEST(FormatBlockSolver, Bc1AnnealIsReproducibleFromTheSeedAtAnyThreadCount) {
  const FormatOptions options = {{"solver", "anneal"}, {"seed", "7"}};
  const EncodedTexture one = encode("bc1", options, 1);
  const EncodedTexture two = encode("bc1", options, 2);
  EXPECT_EQ(one.blocks, two.blocks);
  EXPECT_EQ(one.options.at("solver"), "anneal");
  // A real search lands close to the builtin cluster fit (a broken one would not).
  const double builtin = squared_error("bc1", encode("bc1", {}));
  const double annealed = squared_error("bc1", one);
  EXPECT_LT(annealed, 1.25 * builtin);   // measured on kodim03: 37.26 dB vs 37.30 dB builtin
  EXPECT_GT(annealed, 0.0);
}

TEST(FormatBlockSolver, Bc1NloptLocalSearchStartsFromTheFastAnswerAndNeverLeavesTheLattice) {
  const FormatOptions options = {{"solver", "nlopt"}, {"solver_options", "algorithm=LN_NELDERMEAD, max_evaluations=200"}};
  const EncodedTexture texture = encode("bc1", options);
  const double fast = squared_error("bc1", encode("bc1", {{"search", "fast"}}));
  // Nelder-Mead from the fast answer, snapped to the lattice: a valid block, close to the fast error (measured on kodim03: 37.08 dB vs 36.87 dB fast).
  const double searched = squared_error("bc1", texture);
  EXPECT_TRUE(std::isfinite(searched));
  EXPECT_LT(searched, 1.5 * fast);
}

TEST(FormatBlockSolver, Bc3SolverSearchesColourAndAlpha) {
  const EncodedTexture builtin = encode("bc3", {});
  const EncodedTexture bb = encode("bc3", {{"solver", "anneal"}, {"solver_options", "iterations=500"}});
  EXPECT_EQ(builtin.blocks.size(), bb.blocks.size());
  EXPECT_LT(squared_error("bc3", bb), 4.0 * squared_error("bc3", builtin));
}

TEST(FormatBlockSolver, UnknownSolverIsRejectedWithTheValidNames) {
  const std::string message = error_of([] { encode("bc1", {{"solver", "gradient_magic"}}); });
  EXPECT_NE(message.find("gradient_magic"), std::string::npos) << message;
  EXPECT_NE(message.find("interval_bb"), std::string::npos) << message;
}

TEST(FormatBlockSolver, UnknownSolverOptionNamesTheSolverAndTheKey) {
  const std::string message =
      error_of([] { encode("bc4", {{"solver", "anneal"}, {"solver_options", "temperature_of_mars=3"}}); });
  EXPECT_NE(message.find("bc4"), std::string::npos) << message;
  EXPECT_NE(message.find("anneal"), std::string::npos) << message;
  EXPECT_NE(message.find("temperature_of_mars"), std::string::npos) << message;
}

TEST(FormatBlockSolver, MalformedSolverOptionsAreRejected) {
  EXPECT_NE(error_of([] { encode("bc4", {{"solver", "anneal"}, {"solver_options", "iterations"}}); })
                .find("not key=value"),
            std::string::npos);
  EXPECT_NE(error_of([] { encode("bc4", {{"solver", "anneal"}, {"solver_options", "iterations=5,,"}}); })
                .find("empty item"),
            std::string::npos);
  EXPECT_NE(error_of([] { encode("bc4", {{"solver_options", "iterations=5"}}); }).find("builtin"), std::string::npos);
}

TEST(FormatBlockSolver, CeresLmOnThePaletteErrorFailsWithTheReason) {
  // The palette error is a min over entries with no least-squares form: ceres_lm must say so, not crash.
  const std::string message = error_of([] { encode("bc4", {{"solver", "ceres_lm"}}); });
  EXPECT_NE(message.find("ceres_lm"), std::string::npos) << message;
}

}  // namespace
}  // namespace blocklab
