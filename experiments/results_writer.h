// Derived result files, regenerated from the cell records (in cell-expansion order) after every run:
//   results.jsonl : one record per line, exactly the cell files' JSON (less the cell file's record_sha256), compact.
//   results.csv   : RFC 4180, one row per cell, columns kCsvFixedColumns then one column per metric in config order.
// Column names equal the JSON keys (libjxl#3585 in ECOSYSTEM.md section 3). Nested values (options, ablation_patch)
// are compact JSON text in one cell; input_changed is input_report.changed.
//
// Metric values in JSON (results schema 2; the same in cell files, results.jsonl and `blocklab compare --json`):
// a finite value is a JSON number; +infinity, -infinity and NaN, which JSON numbers cannot hold, are the STRINGS
// "inf", "-inf" and "nan" (e.g. PSNR of identical images is "inf"; mpsnr_auto with no valid exposure range is
// "nan"). null never stands for a metric value. Python's float(), pandas' to_numeric and numpy parse all three
// strings; the CSV writes the same three words.
//
// Execution fields: encode_seconds, decode_seconds, host (the machine that computed the cell) and rank (its MPI
// rank; null outside MPI) say how and where a cell ran, not what it computed. Runs of one config agree on every
// other field whatever their thread count, shard split or MPI rank count (docs/cluster.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace blocklab {

extern const std::vector<std::string> kCsvFixedColumns;
extern const std::vector<std::string> kExecutionFields;

// `record` less kExecutionFields: what two runs of one config must agree on.
nlohmann::json without_execution_fields(nlohmann::json record);

std::string results_jsonl(const std::vector<nlohmann::json>& records);
std::string results_csv(const std::vector<nlohmann::json>& records, const std::vector<std::string>& metric_names);
// Writes <dir>/results<suffix>.jsonl and <dir>/results<suffix>.csv (atomically).
void write_results_files(const std::string& dir, const std::vector<nlohmann::json>& records,
                         const std::vector<std::string>& metric_names, const std::string& suffix = "");

// A metric value as JSON: the number, or "inf" / "-inf" / "nan".
nlohmann::json metric_value_json(double value);
// The value back from metric_value_json's encoding; nothing for anything else (null, other strings, objects).
std::optional<double> metric_value_from_json(const nlohmann::json& value);

// The display text of a metric value in a record: the number, "inf"/"-inf"/"nan" for non-finite ones, "" if absent.
std::string metric_text(const nlohmann::json& record, const std::string& metric, int significant_digits = 17);

}  // namespace blocklab
