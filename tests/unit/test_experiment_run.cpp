// End-to-end runs of tiny experiments (experiments/runner.h) with the fake formats and metrics: the run folder's
// files, cell records, the cache (second run all cached, identical results; threads not in the key), failed cells,
// non-finite metrics, artifacts and progress events.
#include <cmath>

#include "core/error.h"
#include "test_experiment_run_fixture.h"

namespace blocklab {
namespace {

using testing::ExperimentRunFixture;
namespace fs = std::filesystem;

const char* const kTwoImagesTwoSteps =
    "schema: 1\n"
    "name: tiny\n"
    "images: [b.pfm, \"dir/*.pfm\"]\n"
    "metrics: [fake_mae, fake_peak]\n"
    "formats:\n"
    "  - format: fake_quant\n"
    "    options: {step: [0.125, 1]}\n";

class ExperimentRun : public ExperimentRunFixture {
 protected:
  void SetUp() override {
    ExperimentRunFixture::SetUp();
    write_test_image("b.pfm", 6, 5, 0);
    write_test_image("dir/a.pfm", 3, 7, 4);
  }
};

TEST_F(ExperimentRun, WritesTheRunFolderAndOneRecordPerCellInExpansionOrder) {
  const std::string config = write_config("tiny", kTwoImagesTwoSteps);
  const RunSummary summary = run(options_for(config));
  const fs::path dir = root_ / "run";
  EXPECT_EQ(summary.run_dir, dir.string());
  EXPECT_EQ(summary.total, 4u);
  EXPECT_EQ(summary.computed, 4u);
  EXPECT_EQ(summary.cached, 0u);
  EXPECT_EQ(summary.failed, 0u);
  EXPECT_EQ(read_file(dir / "config.yaml"), kTwoImagesTwoSteps);
  ASSERT_TRUE(fs::exists(dir / "provenance.json"));
  const nlohmann::json provenance = nlohmann::json::parse(read_file(dir / "provenance.json"));
  for (const char* field : {"git_sha", "git_dirty", "compiler", "build_type", "invariant_build", "sanitize_build",
                            "libraries", "cpu_model", "hardware_threads", "threads_used", "seed", "start_time",
                            "finish_time", "blocklab_version"}) {
    EXPECT_TRUE(provenance.contains(field)) << field;
  }
  EXPECT_TRUE(provenance["libraries"].contains("eigen"));
  EXPECT_EQ(provenance["threads_used"], 1);

  // Image-major, then variants in sweep order.
  const std::vector<nlohmann::json> records = read_jsonl(dir / "results.jsonl");
  ASSERT_EQ(records.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"b.pfm", "0.125"}, {"b.pfm", "1"}, {"dir/a.pfm", "0.125"}, {"dir/a.pfm", "1"}};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(records[i]["image"], expected[i].first) << i;
    EXPECT_EQ(records[i]["options"]["step"], expected[i].second) << i;
    EXPECT_EQ(records[i], summary.records[i]) << i;
  }
  EXPECT_EQ(planned_keys(dir), (std::vector<std::string>{records[0]["key"], records[1]["key"], records[2]["key"],
                                                          records[3]["key"]}));
  const nlohmann::json& r = records[1];
  EXPECT_EQ(r["status"], "ok");
  EXPECT_EQ(r["experiment"], "tiny");
  EXPECT_EQ(r["width"], 6);
  EXPECT_EQ(r["height"], 5);
  EXPECT_EQ(r["channels"], 3);
  EXPECT_EQ(r["format"], "fake_quant");
  EXPECT_EQ(r["label"], "fake_quant[step=1]");
  EXPECT_EQ(r["ablation"], "baseline");
  EXPECT_DOUBLE_EQ(r["bpp"].get<double>(), 128.0);   // 256 bytes per 4x4 block
  EXPECT_EQ(r["threads"], 1);
  EXPECT_EQ(r["seed"], 1);
  EXPECT_EQ(r["input_policy"], "clamp");
  EXPECT_EQ(r["input_report"]["changed"], 0);
  EXPECT_EQ(r["image_sha256"].get<std::string>().size(), 64u);
  EXPECT_TRUE(r["encode_seconds"].is_number());
  EXPECT_TRUE(r["decode_seconds"].is_number());
  EXPECT_GT(r["metrics"]["fake_mae"].get<double>(), 0.0);   // step 1 loses the eighths
  EXPECT_TRUE(fs::exists(dir / "cells" / r["key"].get<std::string>().substr(0, 2) /
                         (r["key"].get<std::string>() + ".json")));

  const std::string csv = read_file(dir / "results.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_NE(csv.find(",fake_mae,fake_peak\n"), std::string::npos);
}

TEST_F(ExperimentRun, LosslessCellHasInfiniteMetricWrittenAsTheStringInf) {
  const RunSummary summary = run(options_for(write_config("tiny", kTwoImagesTwoSteps)));
  const nlohmann::json& lossless = summary.records[0];   // step 0.125 keeps every eighth exactly
  EXPECT_EQ(lossless["metrics"]["fake_mae"].get<double>(), 0.0);
  EXPECT_EQ(lossless["metrics"]["fake_peak"], "inf");
  const std::string jsonl = read_file(root_ / "run" / "results.jsonl");
  EXPECT_NE(jsonl.find("\"fake_peak\":\"inf\""), std::string::npos) << jsonl;
  const std::string csv = read_file(root_ / "run" / "results.csv");
  EXPECT_NE(csv.find(",0.0,inf\n"), std::string::npos) << csv;
}

TEST_F(ExperimentRun, SecondRunServesEveryCellFromTheCacheWithIdenticalResults) {
  const RunOptions options = options_for(write_config("tiny", kTwoImagesTwoSteps));
  const RunSummary first = run(options);
  const std::string jsonl = read_file(root_ / "run" / "results.jsonl");
  const std::string csv = read_file(root_ / "run" / "results.csv");
  const RunSummary second = run(options);
  EXPECT_EQ(second.total, 4u);
  EXPECT_EQ(second.cached, 4u);
  EXPECT_EQ(second.computed, 0u);
  EXPECT_EQ(read_file(root_ / "run" / "results.jsonl"), jsonl);
  EXPECT_EQ(read_file(root_ / "run" / "results.csv"), csv);
  EXPECT_EQ(second.records, first.records);
}

TEST_F(ExperimentRun, ThreadCountDoesNotInvalidateTheCache) {
  RunOptions options = options_for(write_config("tiny", kTwoImagesTwoSteps));
  run(options);
  options.threads = 2;
  const RunSummary again = run(options);
  EXPECT_EQ(again.cached, again.total);
}

TEST_F(ExperimentRun, FreshRecomputesEveryCell) {
  RunOptions options = options_for(write_config("tiny", kTwoImagesTwoSteps));
  run(options);
  options.fresh = true;
  const RunSummary again = run(options);
  EXPECT_EQ(again.computed, 4u);
  EXPECT_EQ(again.cached, 0u);
  // The computed values are deterministic: only timings may differ.
  for (std::size_t i = 0; i < again.records.size(); ++i) {
    EXPECT_EQ(again.records[i]["key"], read_jsonl(root_ / "run" / "results.jsonl")[i]["key"]);
  }
}

TEST_F(ExperimentRun, FailedCellIsRecordedOtherCellsContinueAndItIsRetriedNextRun) {
  const std::string config = write_config(
      "broken", "schema: 1\nname: broken\nimages: [b.pfm]\nmetrics: [fake_mae]\n"
                "formats:\n  - format: fake_broken\n  - format: fake_quant\n");
  const RunSummary first = run(options_for(config));
  EXPECT_EQ(first.total, 2u);
  EXPECT_EQ(first.failed, 1u);
  EXPECT_EQ(first.computed, 1u);
  EXPECT_EQ(first.records[0]["status"], "error");
  EXPECT_EQ(first.records[0]["error"], "fake_broken: this encoder always fails");
  EXPECT_DOUBLE_EQ(first.records[0]["bpp"].get<double>(), 4.0);
  EXPECT_EQ(first.records[1]["status"], "ok");
  const RunSummary second = run(options_for(config));
  EXPECT_EQ(second.cached, 1u);   // the good cell
  EXPECT_EQ(second.failed, 1u);   // the failed one ran again
  EXPECT_EQ(read_jsonl(root_ / "run" / "results.jsonl").size(), 2u);
}

TEST_F(ExperimentRun, UnreadableImageFailsOnlyItsOwnCells) {
  std::ofstream(root_ / "data" / "dir" / "c.pfm") << "not an image";
  const RunSummary summary = run(options_for(write_config("tiny", kTwoImagesTwoSteps)));
  ASSERT_EQ(summary.total, 6u);
  EXPECT_EQ(summary.failed, 2u);
  EXPECT_EQ(summary.computed, 4u);
  for (std::size_t i = 4; i < 6; ++i) {
    EXPECT_EQ(summary.records[i]["image"], "dir/c.pfm");
    EXPECT_EQ(summary.records[i]["status"], "error");
    EXPECT_NE(summary.records[i]["error"].get<std::string>().find("c.pfm"), std::string::npos);
    EXPECT_TRUE(summary.records[i]["width"].is_null());
  }
}

TEST_F(ExperimentRun, InvalidConfigOrMissingImageStopsBeforeTheRunFolderIsCreated) {
  EXPECT_THROW(run(options_for(write_config("bad", "schema: 1\nname: bad\nimages: [b.pfm]\nmetrics: [nope]\n"
                                                   "formats: [{format: fake_quant}]\n"))),
               Error);
  EXPECT_FALSE(fs::exists(root_ / "run"));
  try {
    run(options_for(write_config("missing", "schema: 1\nname: m\nimages: [b.pfm, zz.pfm]\nmetrics: [fake_mae]\n"
                                            "formats: [{format: fake_quant}]\n")));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("images[1]: 'zz.pfm' not found"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(root_ / "run"));
}

TEST_F(ExperimentRun, SavedDecodedImagesAndErrorMapsAreNamedByCellKey) {
  const RunSummary summary = run(options_for(write_config(
      "artifacts", "schema: 1\nname: art\nimages: [b.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n"
                   "save_decoded: true\nerror_maps: [fake_mae]\n")));
  ASSERT_EQ(summary.records.size(), 1u);
  const nlohmann::json& r = summary.records[0];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  const std::string key = r["key"];
  EXPECT_EQ(r["artifacts"]["decoded"], "decoded/" + key + ".exr");   // HDR source -> EXR
  EXPECT_EQ(r["artifacts"]["error_maps"]["fake_mae"], "error_maps/" + key + ".fake_mae.exr");
  const Image decoded = read_image((root_ / "run" / "decoded" / (key + ".exr")).string());
  EXPECT_EQ(decoded.width, 6);
  EXPECT_EQ(decoded.height, 5);
  EXPECT_TRUE(fs::exists(root_ / "run" / "error_maps" / (key + ".fake_mae.exr")));
}

TEST_F(ExperimentRun, CropIsCentredAndClippedOrAtXYAndRecordedAndChangesTheCellKey) {
  const std::string base = "schema: 1\nname: crop\nimages: [b.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n";
  const RunSummary whole = run(options_for(write_config("whole", base), "whole"));
  const RunSummary centred = run(options_for(write_config("centred", base + "crop: {width: 4, height: 2}\n"), "c"));
  const RunSummary clipped = run(options_for(write_config("clipped", base + "crop: {width: 100, height: 3}\n"), "k"));
  const RunSummary at = run(options_for(write_config("at", base + "crop: {x: 2, y: 3, width: 4, height: 2}\n"), "a"));
  const nlohmann::json& c = centred.records.at(0);
  ASSERT_EQ(c["status"], "ok") << c.dump();
  EXPECT_EQ(c["width"], 4);
  EXPECT_EQ(c["height"], 2);
  EXPECT_EQ(c["crop"], (nlohmann::json{{"x", 1}, {"y", 1}, {"width", 4}, {"height", 2}}));   // (6-4)/2, (5-2)/2
  const nlohmann::json& k = clipped.records.at(0);
  EXPECT_EQ(k["crop"], (nlohmann::json{{"x", 0}, {"y", 1}, {"width", 6}, {"height", 3}}));   // 100 clipped to 6
  EXPECT_EQ(at.records.at(0)["crop"], (nlohmann::json{{"x", 2}, {"y", 3}, {"width", 4}, {"height", 2}}));
  EXPECT_FALSE(whole.records.at(0).contains("crop"));
  EXPECT_NE(whole.records.at(0)["key"], c["key"]);
  EXPECT_NE(c["key"], k["key"]);
  const RunSummary outside = run(options_for(write_config("out", base + "crop: {x: 3, y: 0, width: 4, height: 2}\n"), "o"));
  const nlohmann::json& o = outside.records.at(0);
  EXPECT_EQ(o["status"], "error");
  EXPECT_NE(o["error"].get<std::string>().find("b.pfm: crop 4x2 at (3, 0) does not fit the 6x5 image"),
            std::string::npos) << o.dump();
}

TEST_F(ExperimentRun, ProgressReportsEachCellBeforeItRunsThenAFinalEvent) {
  RunOptions options = options_for(write_config("tiny", kTwoImagesTwoSteps));
  std::vector<ProgressEvent> events;
  options.on_progress = [&events](const ProgressEvent& e) { events.push_back(e); };
  run(options);
  ASSERT_EQ(events.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(events[i].done, i);
    EXPECT_EQ(events[i].total, 4u);
  }
  EXPECT_EQ(events[0].current, "b.pfm fake_quant[step=0.125]");
  EXPECT_EQ(events[3].current, "a.pfm fake_quant[step=1]");
  EXPECT_EQ(events[4].done, 4u);
  EXPECT_EQ(events[4].current, "");
  events.clear();
  run(options);
  EXPECT_EQ(events.back().cached, 4u);
}

TEST_F(ExperimentRun, DefaultRunFolderIsRunsSlashNameUnderTheCurrentDirectory) {
  RunOptions options = options_for(write_config("tiny", kTwoImagesTwoSteps));
  options.out_dir.clear();
  const fs::path previous = fs::current_path();
  fs::current_path(root_);
  const RunSummary summary = run(options);
  fs::current_path(previous);
  EXPECT_EQ(summary.run_dir, (root_ / "runs" / "tiny").string());
  EXPECT_TRUE(fs::exists(root_ / "runs" / "tiny" / "results.jsonl"));
}

}  // namespace
}  // namespace blocklab
