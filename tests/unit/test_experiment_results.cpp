// Result files and the text table (experiments/results_writer.h, format_results_table in experiments/runner.h).
#include <gtest/gtest.h>

#include <cmath>

#include <sstream>

#include "experiments/results_writer.h"
#include "experiments/runner.h"

namespace blocklab {
namespace {

nlohmann::json record(const std::string& label, double mae, const nlohmann::json& peak, const std::string& status) {
  nlohmann::json r;
  r["key"] = std::string(64, 'c');
  r["experiment"] = "t";
  r["image"] = "hdr/a, b.exr";
  r["image_sha256"] = std::string(64, 'd');
  r["width"] = 5;
  r["height"] = 3;
  r["channels"] = 3;
  r["format"] = "fake_quant";
  r["label"] = label;
  r["ablation"] = "baseline";
  r["options"] = {{"step", "0.5"}, {"seed", "1"}};
  r["ablation_patch"] = nlohmann::json::object();
  r["bpp"] = 128.0;
  r["encode_seconds"] = 0.25;
  r["decode_seconds"] = 0.125;
  r["threads"] = 2;
  r["seed"] = 1;
  r["input_policy"] = "clamp";
  r["input_report"] = {{"changed", 4}};
  r["status"] = status;
  if (status == "error") r["error"] = "it said \"no\"";
  r["blocklab_version"] = "0.1.0";
  r["git_sha"] = "unknown";
  r["host"] = "node7";
  r["rank"] = 3;
  r["mode_shares"] = {{"three_colour", 0.25}, {"four_colour", 0.75}};
  r["metrics"] = {{"fake_mae", mae}, {"fake_peak", peak}};
  r["metric_details"] = {{"fake_mae", nlohmann::json::object()}, {"fake_peak", nlohmann::json::object()}};
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ExperimentResults, JsonLinesHoldOneCompactRecordPerLineInOrder) {
  const std::vector<nlohmann::json> records = {record("a", 0.5, 2.0, "ok"), record("b", 0.25, "inf", "ok")};
  const std::vector<std::string> lines = lines_of(results_jsonl(records));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(lines[0]), records[0]);
  EXPECT_EQ(nlohmann::json::parse(lines[1]), records[1]);
  EXPECT_EQ(nlohmann::json::parse(lines[1])["metrics"]["fake_peak"], "inf");
}

TEST(ExperimentResults, CsvHasFixedColumnsThenMetricsInConfigOrder) {
  const std::string csv = results_csv({record("a", 0.5, 2.0, "ok")}, {"fake_peak", "fake_mae"});
  const std::vector<std::string> lines = lines_of(csv);
  ASSERT_EQ(lines.size(), 2u);
  std::string expected_header;
  for (const std::string& c : kCsvFixedColumns) expected_header += c + ",";
  expected_header += "fake_peak,fake_mae";
  EXPECT_EQ(lines[0], expected_header);
  // The same names as the JSON keys.
  for (const std::string& c : kCsvFixedColumns) {
    if (c != "input_changed") {
      EXPECT_TRUE(record("a", 0.5, 2.0, "error").contains(c)) << c;
    }
  }
  EXPECT_EQ(lines[1].substr(lines[1].size() - 8), ",2.0,0.5");   // numbers in JSON's round-trip spelling
}

TEST(ExperimentResults, CsvQuotesCommasQuotesAndNestedJson) {
  const std::string csv = results_csv({record("a", 0.5, 2.0, "error")}, {"fake_mae"});
  EXPECT_NE(csv.find(",\"hdr/a, b.exr\","), std::string::npos) << csv;
  EXPECT_NE(csv.find(",\"it said \"\"no\"\"\","), std::string::npos) << csv;
  EXPECT_NE(csv.find(",\"{\"\"seed\"\":\"\"1\"\",\"\"step\"\":\"\"0.5\"\"}\","), std::string::npos) << csv;
  EXPECT_NE(csv.find(",clamp,4,error,"), std::string::npos) << csv;   // input_changed from input_report.changed
}

TEST(ExperimentResults, CsvWritesModeSharesAsNameEqualsShareListAndEmptyWhenAbsent) {
  nlohmann::json r = record("a", 0.5, 2.0, "ok");
  EXPECT_NE(results_csv({r}, {}).find(",four_colour=0.7500;three_colour=0.2500"), std::string::npos);
  r["mode_shares"] = nullptr;   // a format that records no block modes
  EXPECT_NE(results_csv({r}, {}).find(",unknown,node7,3,\n"), std::string::npos) << results_csv({r}, {});
}

TEST(ExperimentResults, ExecutionFieldsAreTimingsHostAndRankAndOnlyThoseAreStripped) {
  const nlohmann::json r = record("a", 0.5, 2.0, "ok");
  const nlohmann::json stripped = without_execution_fields(r);
  for (const char* field : {"encode_seconds", "decode_seconds", "host", "rank"}) {
    EXPECT_TRUE(r.contains(field)) << field;
    EXPECT_FALSE(stripped.contains(field)) << field;
  }
  EXPECT_EQ(stripped.size() + 4, r.size());
  const std::string csv = results_csv({r}, {});
  EXPECT_NE(csv.find(",git_sha,host,rank,mode_shares"), std::string::npos) << csv;
}

TEST(ExperimentResults, NonFiniteMetricIsTheStringInfInJsonAndInfInCsv) {
  const nlohmann::json r = record("a", 0.5, metric_value_json(HUGE_VAL), "ok");
  EXPECT_EQ(r["metrics"]["fake_peak"], "inf");
  EXPECT_EQ(metric_text(r, "fake_peak"), "inf");
  EXPECT_EQ(metric_text(r, "fake_mae"), "0.5");
  EXPECT_EQ(metric_text(r, "absent"), "");
  const std::string csv = results_csv({r}, {"fake_mae", "fake_peak"});
  EXPECT_EQ(lines_of(csv)[1].substr(lines_of(csv)[1].size() - 8), ",0.5,inf");
}

TEST(ExperimentResults, EveryNonFiniteValueHasItsOwnStringAndReadsBack) {
  EXPECT_EQ(metric_value_json(HUGE_VAL), "inf");
  EXPECT_EQ(metric_value_json(-HUGE_VAL), "-inf");
  EXPECT_EQ(metric_value_json(std::nan("")), "nan");
  EXPECT_EQ(metric_value_json(1.5), 1.5);
  EXPECT_EQ(*metric_value_from_json("inf"), HUGE_VAL);
  EXPECT_EQ(*metric_value_from_json("-inf"), -HUGE_VAL);
  EXPECT_TRUE(std::isnan(*metric_value_from_json("nan")));
  EXPECT_EQ(*metric_value_from_json(2.25), 2.25);
  EXPECT_FALSE(metric_value_from_json(nullptr).has_value());   // null is never a metric value
  EXPECT_FALSE(metric_value_from_json("+inf").has_value());
  nlohmann::json r = record("a", 0.5, "-inf", "ok");
  EXPECT_EQ(metric_text(r, "fake_peak"), "-inf");
  r["metrics"]["fake_peak"] = "nan";
  EXPECT_EQ(metric_text(r, "fake_peak", 6), "nan");
}

TEST(ExperimentResults, TableAlignsColumnsAndListsErrors) {
  RunSummary summary;
  summary.metric_names = {"fake_mae", "fake_peak"};
  summary.records = {record("short", 0.5, 2.0, "ok"), record("a_much_longer_label", 0.123456789, "inf", "error")};
  summary.records[1]["ablation"] = "flagged";
  const std::vector<std::string> lines = lines_of(format_results_table(summary));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("format", 0), 0u);
  EXPECT_NE(lines[0].find("fake_mae"), std::string::npos);
  EXPECT_NE(lines[0].find("encode s"), std::string::npos);
  // Every table line has the same width up to the status column.
  EXPECT_EQ(lines[0].find("status"), lines[1].find("ok"));
  EXPECT_EQ(lines[0].find("status"), lines[2].find("error"));
  EXPECT_NE(lines[2].find("a_much_longer_label +flagged"), std::string::npos);
  EXPECT_NE(lines[2].find("0.123457"), std::string::npos);
  EXPECT_NE(lines[2].find("inf"), std::string::npos);
  EXPECT_NE(lines[1].find("128.00"), std::string::npos);
  EXPECT_EQ(lines[3], "error: hdr/a, b.exr a_much_longer_label +flagged: it said \"no\"");
  // Explicit columns replace the summary's.
  EXPECT_EQ(lines_of(format_results_table(summary, {"fake_peak"}))[0].find("fake_mae"), std::string::npos);
}

}  // namespace
}  // namespace blocklab
