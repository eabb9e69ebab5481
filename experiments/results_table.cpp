// The aligned text table `blocklab run` prints: one row per cell, text columns left-aligned, numbers right-aligned,
// followed by one line per failed cell with its error message.
#include <algorithm>
#include <cstdio>

#include "experiments/results_writer.h"
#include "experiments/runner.h"

namespace blocklab {
namespace {

std::string fixed(const nlohmann::json& value, int decimals) {
  if (!value.is_number()) return "-";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value.get<double>());
  return text;
}

std::string display_format(const nlohmann::json& record) {
  std::string text = record.value("label", record.value("format", std::string("?")));
  const std::string ablation = record.value("ablation", std::string(kBaselineAblation));
  if (ablation != kBaselineAblation) text += " +" + ablation;
  return text;
}

}  // namespace

std::string format_results_table(const RunSummary& summary, const std::vector<std::string>& metric_columns) {
  const std::vector<std::string>& metrics = metric_columns.empty() ? summary.metric_names : metric_columns;
  std::vector<std::string> header = {"format", "image", "bpp"};
  header.insert(header.end(), metrics.begin(), metrics.end());
  header.insert(header.end(), {"encode s", "decode s", "status"});
  const std::size_t first_numeric = 2, last_numeric = header.size() - 2;   // bpp .. decode s

  std::vector<std::vector<std::string>> rows;
  for (const nlohmann::json& record : summary.records) {
    std::vector<std::string> row = {display_format(record), record.value("image", std::string()),
                                    fixed(record.value("bpp", nlohmann::json()), 2)};
    for (const std::string& metric : metrics) {
      const std::string text = metric_text(record, metric, 6);
      row.push_back(text.empty() ? "-" : text);
    }
    row.push_back(fixed(record.value("encode_seconds", nlohmann::json()), 3));
    row.push_back(fixed(record.value("decode_seconds", nlohmann::json()), 3));
    row.push_back(record.value("status", std::string("?")));
    rows.push_back(std::move(row));
  }

  std::vector<std::size_t> width(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string out;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string pad(width[c] - cells[c].size(), ' ');
      const bool numeric = c >= first_numeric && c <= last_numeric;
      out += (c ? "  " : "") + (numeric ? pad + cells[c] : cells[c] + (c + 1 < cells.size() ? pad : ""));
    }
    return out + "\n";
  };
  std::string out = line(header);
  for (const auto& row : rows) out += line(row);
  for (const nlohmann::json& record : summary.records) {
    if (record.value("status", std::string()) != "error") continue;
    out += "error: " + record.value("image", std::string()) + " " + display_format(record) + ": " +
           record.value("error", std::string()) + "\n";
  }
  return out;
}

}  // namespace blocklab
