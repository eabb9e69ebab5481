// results.jsonl and results.csv writers (format in results_writer.h).
#include "experiments/results_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "core/atomic_write.h"

namespace blocklab {

const std::vector<std::string> kCsvFixedColumns = {
    "key",          "experiment",     "image",          "image_sha256", "width",        "height",
    "channels",     "format",         "label",          "ablation",     "options",      "ablation_patch",
    "bpp",          "encode_seconds", "decode_seconds", "threads",      "seed",         "input_policy",
    "input_changed", "status",        "error",          "blocklab_version", "git_sha",      "host",
    "rank",         "mode_shares"};

const std::vector<std::string> kExecutionFields = {"encode_seconds", "decode_seconds", "host", "rank"};

namespace {

std::string csv_field(const std::string& text) {
  // RFC 4180: quote a field holding a comma, a quote or a line break; double the quotes inside.
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string value_text(const nlohmann::json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  return value.dump();   // numbers keep JSON's shortest round-trip form; objects become compact JSON
}

std::string column_text(const nlohmann::json& record, const std::string& column) {
  if (column == "input_changed") {
    const auto report = record.find("input_report");
    if (report == record.end() || !report->is_object()) return "";
    return value_text(report->value("changed", nlohmann::json()));
  }
  if (column == "mode_shares") {
    // {"mode": share, ...} in the format's mode order -> "mode=share;mode=share" (no commas, so no CSV quoting).
    const auto shares = record.find("mode_shares");
    if (shares == record.end() || !shares->is_object()) return "";
    std::string text;
    for (const auto& [mode, share] : shares->items()) {
      char value[32];
      std::snprintf(value, sizeof value, "%.4f", share.get<double>());
      text += (text.empty() ? "" : ";") + mode + "=" + value;
    }
    return text;
  }
  const auto it = record.find(column);
  return it == record.end() ? "" : value_text(*it);
}

}  // namespace

nlohmann::json without_execution_fields(nlohmann::json record) {
  for (const std::string& field : kExecutionFields) record.erase(field);
  return record;
}

nlohmann::json metric_value_json(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;
}

std::optional<double> metric_value_from_json(const nlohmann::json& value) {
  if (value.is_number()) return value.get<double>();
  if (!value.is_string()) return std::nullopt;
  const std::string& text = value.get_ref<const std::string&>();
  if (text == "inf") return std::numeric_limits<double>::infinity();
  if (text == "-inf") return -std::numeric_limits<double>::infinity();
  if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
  return std::nullopt;
}

std::string metric_text(const nlohmann::json& record, const std::string& metric, int significant_digits) {
  const auto metrics = record.find("metrics");
  if (metrics == record.end() || !metrics->contains(metric)) return "";
  const nlohmann::json& value = (*metrics)[metric];
  if (value.is_string()) return metric_value_from_json(value) ? value.get<std::string>() : "";
  if (!value.is_number()) return "";
  if (significant_digits >= 17) return value.dump();
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant_digits, value.get<double>());
  return text;
}

std::string results_jsonl(const std::vector<nlohmann::json>& records) {
  std::string out;
  for (const nlohmann::json& record : records) out += record.dump() + "\n";
  return out;
}

std::string results_csv(const std::vector<nlohmann::json>& records, const std::vector<std::string>& metric_names) {
  std::string out;
  std::vector<std::string> header = kCsvFixedColumns;
  header.insert(header.end(), metric_names.begin(), metric_names.end());
  for (std::size_t i = 0; i < header.size(); ++i) out += (i ? "," : "") + csv_field(header[i]);
  out += "\n";
  for (const nlohmann::json& record : records) {
    std::string row;
    for (std::size_t i = 0; i < kCsvFixedColumns.size(); ++i) {
      row += (i ? "," : "") + csv_field(column_text(record, kCsvFixedColumns[i]));
    }
    for (const std::string& metric : metric_names) row += "," + csv_field(metric_text(record, metric));
    out += row + "\n";
  }
  return out;
}

void write_results_files(const std::string& dir, const std::vector<nlohmann::json>& records,
                         const std::vector<std::string>& metric_names, const std::string& suffix) {
  const std::filesystem::path folder(dir);
  write_file_atomically((folder / ("results" + suffix + ".jsonl")).string(), results_jsonl(records));
  write_file_atomically((folder / ("results" + suffix + ".csv")).string(), results_csv(records, metric_names));
}

}  // namespace blocklab
