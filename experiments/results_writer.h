// Derived result files, regenerated from the cell records (in cell-expansion order) after every run:
//   results.jsonl : one record per line, exactly the cell files' JSON, compact.
//   results.csv   : RFC 4180, one row per cell, columns kCsvFixedColumns then one column per metric in config order.
// Column names equal the JSON keys (libjxl#3585 in ECOSYSTEM.md section 3). Nested values (options, ablation_patch)
// are compact JSON text in one cell; input_changed is input_report.changed; a metric that is +inf/-inf/NaN (null in
// JSON) is written as inf / -inf / nan, which pandas and numpy parse as floats.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace blocklab {

extern const std::vector<std::string> kCsvFixedColumns;

std::string results_jsonl(const std::vector<nlohmann::json>& records);
std::string results_csv(const std::vector<nlohmann::json>& records, const std::vector<std::string>& metric_names);

// The display text of a metric value in a record: the number, "inf"/"-inf"/"nan" for non-finite ones, "" if absent.
std::string metric_text(const nlohmann::json& record, const std::string& metric, int significant_digits = 17);

}  // namespace blocklab
