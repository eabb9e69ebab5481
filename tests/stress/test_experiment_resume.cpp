// Resuming interrupted experiments: whatever a killed run left behind (some cell files, stray temp files, corrupt or
// foreign cell files, a subset of the cells), the next run computes exactly the missing cells and results.jsonl
// holds every planned cell exactly once, in expansion order, with the same values as an uninterrupted run.
#include <set>

#include "tests/unit/test_experiment_run_fixture.h"

namespace blocklab {
namespace {

using testing::ExperimentRunFixture;
namespace fs = std::filesystem;

// 3 images x (3 steps x 2 modes) variants x (baseline + 1 ablation) = 36 cells.
const char* const kSweep =
    "schema: 1\n"
    "name: resume\n"
    "images: [\"*.pfm\"]\n"
    "metrics: [fake_mae, fake_peak]\n"
    "formats:\n"
    "  - format: fake_quant\n"
    "    options: {step: [0.125, 0.5, 2], mode: [a, b]}\n"
    "ablations:\n"
    "  flagged: {flag: true}\n";

class ExperimentResume : public ExperimentRunFixture {
 protected:
  void SetUp() override {
    ExperimentRunFixture::SetUp();
    for (int i = 0; i < 3; ++i) write_test_image("img" + std::to_string(i) + ".pfm", 9 + i, 6 + 2 * i, i);
  }

  // results.jsonl must list exactly the planned cells, each once, in order; returns the records.
  std::vector<nlohmann::json> expect_every_cell_once(const fs::path& dir) const {
    const std::vector<nlohmann::json> records = read_jsonl(dir / "results.jsonl");
    const std::vector<std::string> planned = planned_keys(dir);
    std::vector<std::string> keys;
    for (const auto& r : records) keys.push_back(r["key"]);
    EXPECT_EQ(keys, planned);
    EXPECT_EQ(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size()) << "a cell appears twice";
    return records;
  }

  static void expect_same_values(const std::vector<nlohmann::json>& a, const std::vector<nlohmann::json>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i]["metrics"], b[i]["metrics"]) << i;
      EXPECT_EQ(a[i]["options"], b[i]["options"]) << i;
      EXPECT_EQ(a[i]["key"], b[i]["key"]) << i;
    }
  }
};

TEST_F(ExperimentResume, RunWithDeletedCellsAndStrayTempFilesComputesOnlyTheMissingOnes) {
  const RunOptions options = options_for(write_config("resume", kSweep));
  const RunSummary full = run(options);
  ASSERT_EQ(full.total, 36u);
  const fs::path dir = root_ / "run";
  const std::vector<nlohmann::json> uninterrupted = expect_every_cell_once(dir);

  // Simulate a run killed part-way: every third cell missing, temp files from interrupted writes, and a results
  // file from an older state.
  std::size_t deleted = 0;
  const std::vector<fs::path> files = cell_files(dir);
  for (std::size_t i = 0; i < files.size(); i += 3, ++deleted) fs::remove(files[i]);
  const fs::path stray_cell = files[0].string() + ".tmp.4242";
  std::ofstream(stray_cell) << "{\"key\": \"half a rec";
  std::ofstream(dir / "results.jsonl.tmp.777") << "partial";
  std::ofstream(dir / "results.jsonl") << uninterrupted[0].dump() << "\n" << uninterrupted[0].dump() << "\n";

  const RunSummary resumed = run(options);
  EXPECT_EQ(resumed.computed, deleted);
  EXPECT_EQ(resumed.cached, 36u - deleted);
  EXPECT_EQ(resumed.failed, 0u);
  EXPECT_FALSE(fs::exists(stray_cell));
  EXPECT_FALSE(fs::exists(dir / "results.jsonl.tmp.777"));
  EXPECT_EQ(cell_files(dir).size(), 36u);
  expect_same_values(expect_every_cell_once(dir), uninterrupted);
}

TEST_F(ExperimentResume, SubsetRunThenFullRunReusesTheSubsetsCells) {
  std::string subset = kSweep;
  subset.replace(subset.find("\"*.pfm\""), 7, "img1.pfm");
  const RunSummary first = run(options_for(write_config("subset", subset)));
  EXPECT_EQ(first.total, 12u);
  const RunSummary full = run(options_for(write_config("resume", kSweep)));
  EXPECT_EQ(full.total, 36u);
  EXPECT_EQ(full.cached, 12u);
  EXPECT_EQ(full.computed, 24u);
  const std::vector<nlohmann::json> records = expect_every_cell_once(root_ / "run");
  // The subset's cells sit in the middle of the full expansion (img1 is the second image).
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(records[12 + i]["key"], first.records[i]["key"]);

  // A fresh folder gives the same values.
  const RunSummary clean = run(options_for(write_config("resume", kSweep), "clean"));
  expect_same_values(read_jsonl(root_ / "clean" / "results.jsonl"), records);
  EXPECT_EQ(clean.computed, 36u);
}

TEST_F(ExperimentResume, CorruptOrForeignCellFilesAreRecomputedNotTrusted) {
  const RunOptions options = options_for(write_config("resume", kSweep));
  const RunSummary first = run(options);
  const fs::path dir = root_ / "run";
  const std::string key0 = first.records[0]["key"], key1 = first.records[1]["key"];
  const fs::path file0 = dir / "cells" / key0.substr(0, 2) / (key0 + ".json");
  const fs::path file1 = dir / "cells" / key1.substr(0, 2) / (key1 + ".json");
  std::ofstream(file0, std::ios::trunc) << "{\"key\": ";        // truncated JSON
  nlohmann::json foreign = first.records[2];                     // a valid record under the wrong name
  std::ofstream(file1, std::ios::trunc) << foreign.dump();
  const RunSummary second = run(options);
  EXPECT_EQ(second.computed, 2u);
  EXPECT_EQ(second.cached, 34u);
  expect_same_values(expect_every_cell_once(dir), first.records);
}

TEST_F(ExperimentResume, HandEditedWellFormedCellIsRecomputedByItsChecksum) {
  const RunOptions options = options_for(write_config("resume", kSweep));
  const RunSummary first = run(options);
  const fs::path dir = root_ / "run";
  const std::string key = first.records[3]["key"];
  const fs::path file = dir / "cells" / key.substr(0, 2) / (key + ".json");
  nlohmann::json edited = nlohmann::json::parse(read_file(file));
  ASSERT_TRUE(edited.contains("record_sha256"));
  edited["metrics"]["fake_mae"] = 1e-9;                    // still valid JSON, right key, status ok
  std::ofstream(file, std::ios::trunc) << edited.dump(2);
  const RunSummary second = run(options);
  EXPECT_EQ(second.computed, 1u);
  EXPECT_EQ(second.cached, 35u);
  const std::vector<nlohmann::json> records = expect_every_cell_once(dir);
  expect_same_values(records, first.records);
  EXPECT_FALSE(records[3].contains("record_sha256")) << "results.jsonl holds the records without their checksum";
  // A cell file whose checksum field is missing (written by an older blocklab) is recomputed too.
  nlohmann::json unsigned_record = nlohmann::json::parse(read_file(file));
  unsigned_record.erase("record_sha256");
  std::ofstream(file, std::ios::trunc) << unsigned_record.dump(2);
  EXPECT_EQ(run(options).computed, 1u);
}

TEST_F(ExperimentResume, EditedImageInvalidatesOnlyItsOwnCells) {
  const RunOptions options = options_for(write_config("resume", kSweep));
  run(options);
  write_test_image("img2.pfm", 11, 10, 5);   // new bytes under the same name
  const RunSummary second = run(options);
  EXPECT_EQ(second.computed, 12u);
  EXPECT_EQ(second.cached, 24u);
  expect_every_cell_once(root_ / "run");
}

TEST_F(ExperimentResume, RepeatedInterruptionsConvergeToTheUninterruptedResult) {
  const RunOptions options = options_for(write_config("resume", kSweep));
  const RunSummary reference = run(options);
  const fs::path dir = root_ / "run";
  for (int round = 0; round < 4; ++round) {
    const std::vector<fs::path> files = cell_files(dir);
    for (std::size_t i = static_cast<std::size_t>(round); i < files.size(); i += 5) fs::remove(files[i]);
    run(options);
    expect_same_values(expect_every_cell_once(dir), reference.records);
  }
}

}  // namespace
}  // namespace blocklab
