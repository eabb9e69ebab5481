// End-to-end experiment with the REAL registries (fp16, rgbe; log2rgb, mpsnr, psnr) on tiny images written to a
// temp folder: the run computes, the re-run is served from the cache with identical results files, and the values
// behave as the formats promise (fp16 stores an fp16-representable image exactly).
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "core/error.h"
#include "formats/registry.h"
#include "tests/unit/test_experiment_run_fixture.h"

namespace blocklab {
namespace {

using testing::ExperimentRunFixture;
namespace fs = std::filesystem;

class ExperimentRegistryRun : public ExperimentRunFixture {
 protected:
  RunSummary run_real(const RunOptions& options) const { return run_experiment(options); }
};

TEST_F(ExperimentRegistryRun, Fp16AndRgbeRunThenReRunFromTheCacheWithIdenticalResults) {
  // Values k/8 with k < 17 are exact in fp16 and positive (log-based metrics need no zero rule here).
  Image image(7, 5, 3);
  image.metadata.is_hdr = true;
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = static_cast<float>(1 + (x + 2 * y + c) % 16) / 8.0f;
    }
  }
  write_image((root_ / "data" / "tiny.exr").string(), image, WriteOptions{ExrPixelType::float32, 8});
  const std::string config = write_config(
      "real", "schema: 1\nname: real\nimages: [tiny.exr]\nmetrics: [log2rgb, mpsnr, psnr]\n"
              "formats:\n  - format: fp16\n  - format: rgbe\n    options: {decode_offset: [none, half]}\n");
  const RunOptions options = options_for(config);
  const RunSummary first = run_real(options);
  ASSERT_EQ(first.total, 3u);
  for (const nlohmann::json& r : first.records) ASSERT_EQ(r["status"], "ok") << r.dump(2);
  EXPECT_EQ(first.records[0]["format"], "fp16");
  EXPECT_DOUBLE_EQ(first.records[0]["bpp"].get<double>(), 48.0);
  EXPECT_DOUBLE_EQ(first.records[1]["bpp"].get<double>(), 32.0);
  EXPECT_EQ(first.records[1]["label"], "rgbe[decode_offset=none]");
  EXPECT_EQ(first.records[2]["label"], "rgbe[decode_offset=half]");
  // fp16 is lossless on this image: zero log error.
  EXPECT_EQ(first.records[0]["metrics"]["log2rgb"].get<double>(), 0.0);
  for (const nlohmann::json& r : first.records) {
    for (const char* metric : {"log2rgb", "mpsnr", "psnr"}) {
      EXPECT_TRUE(r["metrics"].contains(metric)) << metric;
      EXPECT_TRUE(r["metric_details"].contains(metric)) << metric;
    }
    EXPECT_EQ(r["metrics"].size(), 3u);   // only the requested metrics
  }

  const std::string jsonl = read_file(root_ / "run" / "results.jsonl");
  const std::string csv = read_file(root_ / "run" / "results.csv");
  RunOptions again = options;
  again.threads = 2;
  const RunSummary second = run_real(again);
  EXPECT_EQ(second.cached, 3u);
  EXPECT_EQ(second.computed, 0u);
  EXPECT_EQ(read_file(root_ / "run" / "results.jsonl"), jsonl);
  EXPECT_EQ(read_file(root_ / "run" / "results.csv"), csv);
}

TEST_F(ExperimentRegistryRun, LoadExperimentChecksNamesAgainstTheRealRegistries) {
  const std::string config = write_config(
      "bad", "schema: 1\nname: bad\nimages: [x.exr]\nmetrics: [log2rgb]\nformats:\n  - format: fp17\n");
  try {
    load_experiment(config);
    FAIL();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.yaml:6:13: unknown format 'fp17' in formats[0]; valid formats:"), std::string::npos)
        << message;
    EXPECT_NE(message.find("fp16"), std::string::npos) << message;
    EXPECT_NE(message.find("rgbe"), std::string::npos) << message;
  }
  const std::string option = write_config(
      "badopt", "schema: 1\nname: bad\nimages: [x.exr]\nmetrics: [log2rgb]\nformats:\n"
                "  - format: rgbe\n    options: {decode_ofset: half}\n");
  try {
    load_experiment(option);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown option 'decode_ofset' for format 'rgbe'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("decode_offset"), std::string::npos) << e.what();
  }
}

TEST_F(ExperimentRegistryRun, TheShippedQuickstartConfigIsValid) {
  const ExperimentConfig config = load_experiment(std::string(BLOCKLAB_SOURCE_DIR) + "/configs/quickstart.yaml");
  EXPECT_EQ(config.name, "quickstart");
  // A newcomer's first table has every registered format, each at its default preset.
  std::set<std::string> formats;
  for (const FormatVariant& variant : config.variants) {
    formats.insert(variant.format->name());
    EXPECT_EQ(variant.resolved.at("preset"), kDefaultPreset) << variant.label;
  }
  for (const Format* format : all_formats()) EXPECT_EQ(formats.count(format->name()), 1u) << format->name();
}

TEST_F(ExperimentRegistryRun, EveryShippedConfigLoadsAndValidates) {
  // Every YAML under configs/ (quick start, paper tables, solver comparisons) names real formats, options and
  // metrics: a renamed option breaks this test, not a user's run.
  int count = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(BLOCKLAB_SOURCE_DIR) + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string text = entry.path().string();
    // Analysis configs (`blocklab analyze`) have their own schema; experiment configs start with `schema:`.
    std::ifstream file(entry.path());
    std::string first_key;
    for (std::string line; std::getline(file, line);)
      if (!line.empty() && line[0] != '#') {
        first_key = line.substr(0, line.find(':'));
        break;
      }
    if (first_key != "schema") continue;
    EXPECT_NO_THROW(load_experiment(text));
    ++count;
  }
  EXPECT_GE(count, 4);
}

}  // namespace
}  // namespace blocklab
