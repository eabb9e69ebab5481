// A format registered at run time (formats/registry.h register_format) gets the table-driven coverage without an
// edit to any test or to the bench: this binary registers `tiny_grey`, a one-byte-per-block format with one block
// problem, and shows that the names the contract and soundness tests are instantiated over include its problem,
// that the very checks those tests run (tests/contract/registered_problem_checks.h) pass on it, and that
// `blocklab bench solvers`' entry point (experiments/solver_bench.h) benchmarks it and certifies every block.
//
// tiny_grey: each block stores the 8-bit code of its mean grey (R + G + B) / 3 and decodes to that constant grey.
// Its block problem `level`: the stored level x on the 256-point lattice of [0, 1], error = sum over the 16 texels
// of (grey - x)^2 (smooth; the least-squares form has 16 residuals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/problem.h"
#include "experiments/solver_bench.h"
#include "experiments/strict_yaml.h"
#include "formats/common/block_codec.h"
#include "formats/registry.h"
#include "tests/contract/registered_problem_checks.h"

namespace blocklab {
namespace {

double texel_grey(const float* rgba) { return (rgba[0] + rgba[1] + rgba[2]) / 3.0; }

struct GreyLevelError {
  static constexpr int kDim = 1;
  static constexpr bool kSmooth = true;
  static constexpr int kResiduals = kBlockTexels;
  double grey[kBlockTexels] = {};

  template <typename T>
  void residuals(const T* x, T* r) const {
    for (int t = 0; t < kBlockTexels; ++t) r[t] = x[0] - T(grey[t]);
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

std::unique_ptr<Problem> make_grey_level_problem(const BlockTexels& block, std::uint64_t) {
  GreyLevelError error;
  for (int t = 0; t < kBlockTexels; ++t) error.grey[t] = std::clamp(texel_grey(block.rgba[t]), 0.0, 1.0);
  return std::make_unique<ErrorProblem<GreyLevelError>>(
      make_problem(error, Bounds{{0.0}, {1.0}}, {Lattice::uniform(0.0, 1.0, 256)}));
}

class TinyGreyFormat final : public Format {
 public:
  std::string name() const override { return "tiny_grey"; }
  std::string description() const override { return "test format: one 8-bit mean grey per block"; }
  std::vector<OptionSpec> option_specs() const override { return {}; }
  std::vector<ModeSpec> mode_table() const override { return {{"grey", "the block's mean grey, 8 bits"}}; }
  std::vector<BlockProblem> block_problems() const override {
    return {{"level", "the stored grey level on [0, 1] (256 points), squared error of the texels' grey",
             BlockImageKind::ldr, make_grey_level_problem}};
  }
  int block_bytes(const FormatOptions&) const override { return 1; }
  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    const auto encode_block = [](const BlockTexels& texels, std::size_t, std::uint8_t* out) {
      double sum = 0.0;
      for (int t = 0; t < kBlockTexels; ++t) sum += std::clamp(texel_grey(texels.rgba[t]), 0.0, 1.0);
      out[0] = static_cast<std::uint8_t>(std::lround(255.0 * sum / kBlockTexels));
      return 0;
    };
    return encode_blocks(*this, image, options, context, 1, encode_block);
  }
  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    return decode_blocks(*this, texture, context, 3, [](const std::uint8_t* bytes, std::size_t) {
      BlockTexels texels;
      for (auto& texel : texels.rgba) {
        std::fill(texel, texel + 3, bytes[0] / 255.0f);
        texel[3] = 1.0f;
      }
      return texels;
    });
  }
};

const Format& tiny_grey_format() {
  static const TinyGreyFormat format;
  static std::once_flag registered;
  std::call_once(registered, [] { register_format(format); });
  return format;
}

TEST(RegisteredTinyFormat, ItsProblemJoinsTheNamesTheTableDrivenTestsIterate) {
  tiny_grey_format();
  const std::vector<std::string> names = contract::registered_problem_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "tiny_grey.level"), names.end());
  EXPECT_EQ(&find_format("tiny_grey"), &tiny_grey_format());
  EXPECT_EQ(find_block_problem("tiny_grey.level").format, &tiny_grey_format());
}

TEST(RegisteredTinyFormat, RegisteringATakenNameIsAnError) {
  tiny_grey_format();
  EXPECT_THROW(register_format(tiny_grey_format()), Error);
}

TEST(RegisteredTinyFormat, ItsProblemHoldsTheContractOnRealBlocks) {
  tiny_grey_format();
  contract::check_registered_problem_contract(find_block_problem("tiny_grey.level"));
}

TEST(RegisteredTinyFormat, ItsProblemIsIntervalSoundOnRealBlocks) {
  tiny_grey_format();
  contract::check_registered_problem_soundness(find_block_problem("tiny_grey.level"));
}

TEST(RegisteredTinyFormat, TheSolverBenchCertifiesItsProblemOnEveryBlock) {
  tiny_grey_format();
  SolverBenchSettings settings;
  settings.data_root = BLOCKLAB_TEST_SAMPLES;
  settings.problems = {"tiny_grey"};   // a format name: all of its problems
  settings.solvers = {"exhaustive", "interval_bb", "nlopt"};
  settings.blocks = 6;
  std::ostringstream table;
  run_solver_bench(settings, table);
  const std::string text = table.str();
  // The certified optimum of a 256-point lattice is exhaustive's, and both certifying solvers find it everywhere.
  EXPECT_NE(text.find("| tiny_grey.level | (certification: exhaustive) |"), std::string::npos) << text;
  for (const char* solver : {"exhaustive", "interval_bb"}) {
    const std::string row = std::string("| tiny_grey.level | ") + solver + " | ";
    const std::size_t begin = text.find(row);
    ASSERT_NE(begin, std::string::npos) << text;
    const std::string line = text.substr(begin, text.find('\n', begin) - begin);
    EXPECT_NE(line.find("(6/6 blocks)"), std::string::npos) << line;
    EXPECT_NE(line.find("| 1.0000 | 100.0% |"), std::string::npos) << line;
  }
  EXPECT_NE(text.find("| tiny_grey.level | nlopt | "), std::string::npos) << text;
}

TEST(RegisteredFormatTables, EveryModeAndBlockProblemHasAUniqueNameAndADescription) {
  tiny_grey_format();
  for (const Format* format : all_formats()) {
    std::set<std::string> modes, problems;
    for (const ModeSpec& mode : format->mode_table()) {
      EXPECT_TRUE(modes.insert(mode.name).second) << format->name() << ": mode " << mode.name << " twice";
      EXPECT_FALSE(mode.description.empty()) << format->name() << "." << mode.name;
    }
    for (const BlockProblem& problem : format->block_problems()) {
      EXPECT_TRUE(is_identifier(problem.name) && problem.name.find('.') == std::string::npos)
          << format->name() << ": problem name '" << problem.name << "'";
      EXPECT_TRUE(problems.insert(problem.name).second) << format->name() << ": problem " << problem.name << " twice";
      EXPECT_FALSE(problem.description.empty()) << format->name() << "." << problem.name;
      EXPECT_TRUE(static_cast<bool>(problem.make)) << format->name() << "." << problem.name;
    }
  }
  EXPECT_THROW(find_block_problem("bc1.no_such_problem"), Error);
}

TEST(RegisteredTinyFormat, EncodesAndDecodesThroughTheRegistry) {
  const Format& format = (tiny_grey_format(), find_format("tiny_grey"));
  Image image(6, 5, 3);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x)
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = 0.5f;
  const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), {});
  EXPECT_EQ(texture.blocks.size(), 4u);
  const Image decoded = format.decode(texture, {});
  EXPECT_NEAR(decoded.texel(5, 4)[1], 128.0f / 255.0f, 1e-7);
}

}  // namespace
}  // namespace blocklab
