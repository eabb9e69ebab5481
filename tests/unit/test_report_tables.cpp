// experiments/format_bench.h pareto_points and experiments/report.h paper_table on synthetic rows and records: the
// front keeps exactly the encoders no other encoder of the same kind and bit rate beats in both time and error, and
// a published table matches records by label (a swept label "name[k=v]" counts as "name"), options and metric, and
// averages finite values over the images for a "*" row.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "experiments/format_bench.h"
#include "experiments/report.h"

namespace blocklab {
namespace {

FormatBenchRow row(const std::string& format, const std::string& kind, double bpp, double error, double seconds) {
  FormatBenchRow r;
  r.format = format;
  r.preset = "fast";
  r.image = "img";
  r.kind = kind;
  r.bpp = bpp;
  r.metrics[kind == "hdr" ? "log2rgb" : "psnr"] = error;
  r.encode_seconds = seconds;
  return r;
}

bool on_front(const std::vector<ParetoPoint>& points, const std::string& name) {
  for (const ParetoPoint& p : points)
    if (p.name == name) return p.on_front;
  ADD_FAILURE() << name << " missing";
  return false;
}

TEST(ParetoFront, KeepsOnlyEncodersNotBeatenInBothTimeAndErrorAtTheSameBitRate) {
  const std::vector<FormatBenchRow> rows = {
      row("fast_bad", "hdr", 8, 0.5, 1.0), row("slow_good", "hdr", 8, 0.1, 5.0),
      row("dominated", "hdr", 8, 0.6, 2.0), row("other_rate", "hdr", 4, 0.9, 9.0),
      row("ldr_high_psnr", "ldr", 8, 40.0, 1.0), row("ldr_low_psnr", "ldr", 8, 30.0, 2.0)};
  const std::vector<ParetoPoint> points = pareto_points(rows);
  EXPECT_TRUE(on_front(points, "fast_bad-fast"));
  EXPECT_TRUE(on_front(points, "slow_good-fast"));
  EXPECT_FALSE(on_front(points, "dominated-fast"));
  EXPECT_TRUE(on_front(points, "other_rate-fast"));       // alone at 4 bpp
  EXPECT_TRUE(on_front(points, "ldr_high_psnr-fast"));    // PSNR: higher is better
  EXPECT_FALSE(on_front(points, "ldr_low_psnr-fast"));
  const std::string markdown = pareto_markdown(points);
  EXPECT_NE(markdown.find("slow_good-fast"), std::string::npos);
  EXPECT_EQ(markdown.find("dominated-fast"), std::string::npos);
}

nlohmann::json record(const std::string& image, const std::string& label, const std::string& bpp, double value) {
  nlohmann::json r;
  r["experiment"] = "paper_table";
  r["status"] = "ok";
  r["image"] = image;
  r["label"] = label;
  r["options"] = {{"bpp", bpp}};
  r["metrics"]["log2rgb"] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json("inf");
  return r;
}

TEST(PaperTable, MatchesSweptLabelsAndOptionsAndAveragesFiniteValues) {
  PublishedTable table;
  table.paper = "paper";
  table.experiment = "paper_table";
  table.columns = {{"codec", {{"bpp", "4"}}, "log2rgb", "4 bpp"}, {"codec", {{"bpp", "8"}}, "log2rgb", "8 bpp"}};
  table.rows = {{"*", "average", {0.5, 0.25}, {"0.5", "0.25"}}, {"a.exr", "a", {std::nullopt, 0.2}, {"", "0.20"}}};
  const std::vector<nlohmann::json> records = {
      record("a.exr", "codec[bpp=4]", "4", 1.0), record("b.exr", "codec[bpp=4]", "4", 0.5),
      record("a.exr", "codec[bpp=8]", "8", 0.3), record("b.exr", "codec[bpp=8]", "8",
                                                        std::numeric_limits<double>::infinity()),
      record("a.exr", "other", "4", 9.0)};
  const ReportTable out = paper_table(table, records);
  ASSERT_EQ(out.rows.size(), 4u);
  EXPECT_EQ(out.rows[0][0], "average (2 images)");
  EXPECT_EQ(out.rows[0][2], "0.5");
  EXPECT_EQ(out.rows[0][3], "0.75");                       // (1.0 + 0.5) / 2, "other" not counted
  EXPECT_EQ(out.rows[0][4], "+0.25 (+50 %)");
  EXPECT_EQ(out.rows[1][3], "0.300 (1 of 2 finite)");        // the infinite value left out and counted
  EXPECT_EQ(out.rows[2][2], "-");                           // not published
  EXPECT_EQ(out.rows[3][2], "0.20");                       // the published text as printed
  EXPECT_EQ(out.rows[3][3], "0.300");
  EXPECT_EQ(out.rows[3][4], "+0.100 (+50 %)");
  EXPECT_NE(out.markdown().find("| a (a.exr) | 8 bpp | 0.20 | 0.300 |"), std::string::npos);
  EXPECT_NE(out.html().find("<td>average (2 images)</td>"), std::string::npos);
}

}  // namespace
}  // namespace blocklab
