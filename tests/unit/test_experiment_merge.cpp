// Sharded runs and `merge` (experiments/shard.h, experiments/run_merge.h) with the fake formats and metrics: shards
// in separate or shared folders merge into results equal to one process's apart from the execution fields, the
// merged folder is a complete cache, and folders of another plan or with missing cells are refused.
#include <set>

#include "core/error.h"
#include "experiments/results_writer.h"
#include "experiments/run_folder.h"
#include "experiments/run_merge.h"
#include "test_experiment_run_fixture.h"

namespace blocklab {
namespace {

using testing::ExperimentRunFixture;
namespace fs = std::filesystem;

const char* const kSweep =
    "schema: 1\n"
    "name: sweep\n"
    "images: [a.pfm, b.pfm, c.pfm]\n"
    "metrics: [fake_peak, fake_mae]\n"
    "formats:\n"
    "  - format: fake_quant\n"
    "    options: {step: [0.125, 0.5, 1], mode: [a, b]}\n"
    "  - format: fake_broken\n";

class ExperimentShards : public ExperimentRunFixture {
 protected:
  void SetUp() override {
    ExperimentRunFixture::SetUp();
    write_test_image("a.pfm", 6, 5, 0);
    write_test_image("b.pfm", 3, 7, 4);
    write_test_image("c.pfm", 8, 8, 9);
    config_ = write_config("sweep", kSweep);
  }

  RunSummary run_shard(const std::string& folder, std::size_t index, std::size_t count) const {
    RunOptions options = options_for(config_, folder);
    options.shard = {index, count};
    return run(options);
  }

  static std::vector<nlohmann::json> stripped(const std::vector<nlohmann::json>& records) {
    std::vector<nlohmann::json> out;
    for (const nlohmann::json& record : records) out.push_back(without_execution_fields(record));
    return out;
  }

  // results.csv with the execution columns emptied.
  static std::string csv_without_execution_fields(const std::string& csv) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream lines(csv);
    std::vector<std::size_t> drop;
    std::string out;
    for (std::string line; std::getline(lines, line);) {
      std::vector<std::string> fields;
      std::string field;
      bool quoted = false;
      for (char c : line) {
        if (c == '"') quoted = !quoted;
        if (c == ',' && !quoted) {
          fields.push_back(field);
          field.clear();
        } else {
          field += c;
        }
      }
      fields.push_back(field);
      if (drop.empty()) {
        for (std::size_t i = 0; i < fields.size(); ++i)
          for (const std::string& name : kExecutionFields)
            if (fields[i] == name) drop.push_back(i);
      }
      for (std::size_t i : drop) fields[i].clear();
      for (std::size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + fields[i];
      out += "\n";
    }
    return out;
  }

  std::string config_;
};

TEST_F(ExperimentShards, TwoShardsInTheirOwnFoldersMergeIntoTheSingleProcessResults) {
  const RunSummary whole = run(options_for(config_, "whole"));
  ASSERT_EQ(whole.total, 21u);   // 3 images x (6 fake_quant variants + fake_broken)
  const RunSummary first = run_shard("shard0", 0, 2);
  const RunSummary second = run_shard("shard1", 1, 2);
  EXPECT_EQ(first.total + second.total, 21u);
  EXPECT_EQ(first.experiment_cells, 21u);
  EXPECT_LE(first.total > second.total ? first.total - second.total : second.total - first.total, 1u);
  EXPECT_TRUE(fs::exists(root_ / "shard0" / "results.shard-0-of-2.jsonl"));
  EXPECT_TRUE(fs::exists(root_ / "shard1" / "results.shard-1-of-2.csv"));
  EXPECT_TRUE(fs::exists(root_ / "shard1" / "provenance.shard-1-of-2.json"));
  EXPECT_FALSE(fs::exists(root_ / "shard0" / "results.jsonl"));   // a shard never passes for the whole run

  const MergeSummary merged = merge_run_folders({(root_ / "shard0").string(), (root_ / "shard1").string()},
                                                (root_ / "merged").string(), 2);
  EXPECT_EQ(merged.cells, 21u);
  EXPECT_EQ(merged.failed, 3u);   // fake_broken on each image
  const std::vector<nlohmann::json> expected = read_jsonl(root_ / "whole" / "results.jsonl");
  const std::vector<nlohmann::json> actual = read_jsonl(root_ / "merged" / "results.jsonl");
  EXPECT_EQ(stripped(actual), stripped(expected));
  EXPECT_EQ(csv_without_execution_fields(read_file(root_ / "merged" / "results.csv")),
            csv_without_execution_fields(read_file(root_ / "whole" / "results.csv")));
  EXPECT_EQ(read_file(root_ / "merged" / "resolved.json"), read_file(root_ / "shard0" / "resolved.json"));
  const nlohmann::json provenance = nlohmann::json::parse(read_file(root_ / "merged" / "provenance.json"));
  EXPECT_EQ(provenance["merged_from"].size(), 2u);
  EXPECT_TRUE(provenance["sources"][(root_ / "shard1").string()].contains("provenance.shard-1-of-2.json"));
}

TEST_F(ExperimentShards, EveryRecordNamesTheHostThatComputedItAndNoRankOutsideMpi) {
  const RunSummary whole = run(options_for(config_, "whole"));
  for (const nlohmann::json& record : whole.records) {
    EXPECT_FALSE(record["host"].get<std::string>().empty());
    EXPECT_TRUE(record["rank"].is_null());
  }
  const std::string csv = read_file(root_ / "whole" / "results.csv");
  EXPECT_NE(csv.find(",git_sha,host,rank,mode_shares,"), std::string::npos) << csv.substr(0, 300);
}

TEST_F(ExperimentShards, ShardsSharingOneFolderMergeInPlaceAndTheFolderIsThenACompleteCache) {
  run(options_for(config_, "whole"));
  for (std::size_t i = 0; i < 3; ++i) run_shard("shared", i, 3);
  const MergeSummary merged = merge_run_folders({(root_ / "shared").string()}, (root_ / "shared").string(), 1);
  EXPECT_EQ(merged.cells, 21u);
  EXPECT_EQ(stripped(read_jsonl(root_ / "shared" / "results.jsonl")),
            stripped(read_jsonl(root_ / "whole" / "results.jsonl")));
  const RunSummary again = run(options_for(config_, "shared"));
  EXPECT_EQ(again.cached, 18u);   // every ok cell; the 3 failed ones are retried, as always
  EXPECT_EQ(again.computed, 0u);
}

TEST_F(ExperimentShards, ShardResultsAreItsCellsInExpansionOrder) {
  const RunSummary whole = run(options_for(config_, "whole"));
  const RunSummary shard = run_shard("shard", 1, 4);
  std::vector<std::string> expected;
  std::set<std::string> mine;
  for (const nlohmann::json& record : shard.records) mine.insert(record["key"]);
  for (const nlohmann::json& record : whole.records)
    if (mine.count(record["key"])) expected.push_back(record["key"]);
  std::vector<std::string> actual;
  for (const nlohmann::json& record : read_jsonl(root_ / "shard" / "results.shard-1-of-4.jsonl"))
    actual.push_back(record["key"]);
  EXPECT_EQ(actual, expected);
  EXPECT_EQ(mine.size(), shard.total);
}

TEST_F(ExperimentShards, MergeRefusesFoldersOfAnotherConfigNamingBothAndTheDifference) {
  run_shard("shard0", 0, 2);
  RunOptions other = options_for(write_config("other", std::string(kSweep) + "seed: 7\n"), "other");
  run(other);
  try {
    merge_run_folders({(root_ / "shard0").string(), (root_ / "other").string()}, (root_ / "merged").string(), 1);
    FAIL() << "merged folders of different configs";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((root_ / "other").string() + " is a run of another plan than " +
                           (root_ / "shard0").string()), std::string::npos) << message;
    EXPECT_NE(message.find("seed"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(root_ / "merged"));
}

TEST_F(ExperimentShards, MergeRefusesWhenAShardIsMissingNamingTheCountAndACell) {
  const RunSummary first = run_shard("shard0", 0, 2);
  try {
    merge_run_folders({(root_ / "shard0").string()}, (root_ / "merged").string(), 1);
    FAIL() << "merged an incomplete set of shards";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(std::to_string(21 - first.total) + " of 21 cells are in none of the 1 run folders"),
              std::string::npos) << message;
    EXPECT_NE(message.find(".pfm fake_"), std::string::npos) << message;
  }
  try {
    merge_run_folders({(root_ / "data").string()}, (root_ / "merged").string(), 1);
    FAIL() << "merged a folder that is no run folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a run folder (no resolved.json)"), std::string::npos) << e.what();
  }
}

TEST_F(ExperimentShards, MergePrefersAnOkRecordOverAFailedOneOfTheSameCell) {
  // The same cell failed in one folder (a damaged image there) and succeeded in another.
  run(options_for(config_, "good"));
  const std::vector<nlohmann::json> good = read_jsonl(root_ / "good" / "results.jsonl");
  fs::copy(root_ / "good", root_ / "bad", fs::copy_options::recursive);
  RunFolder bad((root_ / "bad").string());
  nlohmann::json failed = good[0];
  failed["status"] = "error";
  failed["error"] = "disk trouble";
  bad.write_cell(good[0]["key"], failed);
  const MergeSummary merged = merge_run_folders({(root_ / "bad").string(), (root_ / "good").string()},
                                                (root_ / "merged").string(), 1);
  EXPECT_EQ(merged.records[0]["status"], "ok");
  EXPECT_EQ(merged.records, good);
}

TEST_F(ExperimentShards, CachedCellsSendNoProgressEventsSoTheEtaCountsOnlyWorkLeft) {
  RunOptions options = options_for(config_, "whole");
  run(options);
  std::vector<ProgressEvent> events;
  options.on_progress = [&events](const ProgressEvent& e) { events.push_back(e); };
  run(options);
  ASSERT_EQ(events.size(), 4u);   // the 3 failed cells are retried, then the final event
  EXPECT_EQ(events[0].done, 18u);
  EXPECT_EQ(events[0].cached, 18u);
  EXPECT_EQ(events.back().done, 21u);
}

}  // namespace
}  // namespace blocklab
