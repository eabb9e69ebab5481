// Published paper tables beside measured values (experiments/report.h): reading published.yaml, matching results
// records to its columns, the published / ours / delta table, and the README blocks generated from it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "experiments/report.h"
#include "experiments/results_writer.h"
#include "experiments/strict_yaml.h"

namespace fs = std::filesystem;

namespace blocklab {

namespace {

std::string escape_cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Published values keep the digits the paper printed ("40.0"); ours get one decimal more (at least two).
int decimals_of(const std::string& published) {
  const std::size_t dot = published.find('.');
  return dot == std::string::npos ? 0 : static_cast<int>(published.size() - dot - 1);
}

std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

bool record_matches(const nlohmann::json& record, const PublishedColumn& column) {
  // A swept variant's label carries its swept options ("banterle[bpp=4]"); the column names the base label.
  const std::string label = record.value("label", std::string());
  if (!column.label.empty() && label != column.label && label.rfind(column.label + "[", 0) != 0) return false;
  const nlohmann::json& options = record.contains("options") ? record["options"] : nlohmann::json::object();
  for (const auto& [key, value] : column.options)
    if (!options.contains(key) || !options[key].is_string() || options[key].get<std::string>() != value) return false;
  return true;
}

}  // namespace

std::string escape_markup(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string ReportTable::markdown() const {
  std::string out;
  if (!title.empty()) out += "**" + title + "**\n\n";
  out += "|";
  for (const std::string& cell : header) out += " " + escape_cell(cell) + " |";
  out += "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : rows) {
    out += "|";
    for (const std::string& cell : row) out += " " + escape_cell(cell) + " |";
    out += "\n";
  }
  if (!note.empty()) out += "\n" + note + "\n";
  return out;
}

std::string ReportTable::html() const {
  std::string out = "<table>\n";
  if (!title.empty()) out += "<caption>" + escape_markup(title) + "</caption>\n";
  out += "<thead><tr>";
  for (const std::string& cell : header) out += "<th>" + escape_markup(cell) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const std::string& cell : row) out += "<td>" + escape_markup(cell) + "</td>";
    out += "</tr>\n";
  }
  out += "</tbody></table>\n";
  if (!note.empty()) out += "<p class=\"note\">" + escape_markup(note) + "</p>\n";
  return out;
}

std::vector<PublishedTable> load_published_tables(const std::string& path) {
  const StrictYaml yaml(read_text(path), path);
  const YAML::Node& root = yaml.root();
  yaml.check_map(root, "the top level", {"paper", "tables"}, {"paper", "tables"});
  const std::string paper = yaml.scalar(StrictYaml::child(root, "paper"), "paper");
  std::vector<PublishedTable> tables;
  const YAML::Node list = yaml.sequence(StrictYaml::child(root, "tables"), "tables");
  for (std::size_t t = 0; t < list.size(); ++t) {
    const std::string where = "tables[" + std::to_string(t) + "]";
    const YAML::Node node = list[t];
    yaml.check_map(node, where, {"id", "title", "experiment", "note", "columns", "rows"},
                   {"id", "title", "experiment", "columns", "rows"});
    PublishedTable table;
    table.paper = paper;
    table.id = yaml.identifier(StrictYaml::child(node, "id"), where + ".id");
    table.title = yaml.scalar(StrictYaml::child(node, "title"), where + ".title");
    table.experiment = yaml.identifier(StrictYaml::child(node, "experiment"), where + ".experiment");
    if (node["note"]) table.note = yaml.scalar(StrictYaml::child(node, "note"), where + ".note");
    const YAML::Node columns = yaml.sequence(StrictYaml::child(node, "columns"), where + ".columns");
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string at = where + ".columns[" + std::to_string(c) + "]";
      yaml.check_map(columns[c], at, {"label", "options", "metric", "header"}, {"metric", "header"});
      PublishedColumn column;
      if (columns[c]["label"]) column.label = yaml.identifier(StrictYaml::child(columns[c], "label"), at + ".label");
      column.metric = yaml.identifier(StrictYaml::child(columns[c], "metric"), at + ".metric");
      column.header = yaml.scalar(StrictYaml::child(columns[c], "header"), at + ".header");
      if (columns[c]["options"]) {
        const YAML::Node options = StrictYaml::child(columns[c], "options");
        for (const std::string& key : yaml.map_keys(options, at + ".options"))
          column.options[key] = yaml.scalar(StrictYaml::child(options, key), at + ".options." + key);
      }
      table.columns.push_back(column);
    }
    const YAML::Node rows = yaml.sequence(StrictYaml::child(node, "rows"), where + ".rows");
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const std::string at = where + ".rows[" + std::to_string(r) + "]";
      yaml.check_map(rows[r], at, {"image", "name", "values"}, {"image", "name", "values"});
      PublishedRow row;
      row.image = yaml.scalar(StrictYaml::child(rows[r], "image"), at + ".image");
      row.name = yaml.scalar(StrictYaml::child(rows[r], "name"), at + ".name");
      const YAML::Node values = yaml.sequence(StrictYaml::child(rows[r], "values"), at + ".values");
      if (values.size() != table.columns.size())
        yaml.fail_at(values, at + ".values has " + std::to_string(values.size()) + " values for " +
                                 std::to_string(table.columns.size()) + " columns");
      for (std::size_t v = 0; v < values.size(); ++v) {
        if (values[v].IsNull()) {
          row.values.emplace_back();
          row.texts.emplace_back();
          continue;
        }
        const std::string text = yaml.scalar(values[v], at + ".values[" + std::to_string(v) + "]");
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') yaml.fail_at(values[v], "'" + text + "' is not a number");
        row.values.emplace_back(value);
        row.texts.push_back(text);
      }
      table.rows.push_back(row);
    }
    tables.push_back(std::move(table));
  }
  return tables;
}

ReportTable paper_table(const PublishedTable& table, const std::vector<nlohmann::json>& records) {
  ReportTable out;
  out.title = table.title;
  out.header = {"image", "quantity", "published", "ours", "delta"};
  std::vector<const nlohmann::json*> mine;
  for (const nlohmann::json& record : records)
    if (record.value("experiment", std::string()) == table.experiment &&
        record.value("status", std::string()) == "ok")
      mine.push_back(&record);
  std::size_t image_count = 0;
  {
    std::vector<std::string> images;
    for (const nlohmann::json* record : mine) images.push_back(record->value("image", std::string()));
    std::sort(images.begin(), images.end());
    image_count = static_cast<std::size_t>(std::unique(images.begin(), images.end()) - images.begin());
  }
  for (const PublishedRow& row : table.rows) {
    const std::string image_cell = row.image == "*" ? row.name + " (" + std::to_string(image_count) + " images)"
                                                    : row.name + " (" + row.image + ")";
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      const PublishedColumn& column = table.columns[c];
      std::vector<std::string> cells = {image_cell, column.header};
      double sum = 0.0;
      int finite = 0, matched = 0;
      for (const nlohmann::json* record : mine) {
        if (row.image != "*" && record->value("image", std::string()) != row.image) continue;
        if (!record_matches(*record, column)) continue;
        if (!(*record)["metrics"].contains(column.metric)) continue;
        const std::optional<double> parsed = metric_value_from_json((*record)["metrics"][column.metric]);
        if (!parsed.has_value()) continue;
        const double value = parsed.value();
        ++matched;
        if (std::isfinite(value)) {
          sum += value;
          ++finite;
        } else if (row.image != "*") {
          sum = value;
          finite = 1;
        }
      }
      const std::optional<double> published = row.values[c];
      const std::string published_text = c < row.texts.size() && !row.texts[c].empty()
                                             ? row.texts[c] : published ? fixed(*published, 3) : std::string();
      const int decimals = published ? std::max(decimals_of(published_text) + 1, 2) : 3;
      cells.push_back(published ? published_text : "-");
      if (finite == 0) {
        cells.push_back(matched > 0 ? "no finite value" : "not measured");
        cells.push_back("-");
        out.rows.push_back(std::move(cells));
        continue;
      }
      const double ours = sum / finite;
      std::string ours_text = fixed(ours, decimals);
      if (row.image == "*" && finite < matched)
        ours_text += " (" + std::to_string(finite) + " of " + std::to_string(matched) + " finite)";
      cells.push_back(ours_text);
      if (!published || !std::isfinite(ours)) {
        cells.push_back("-");
        out.rows.push_back(std::move(cells));
        continue;
      }
      const double delta = ours - *published;
      std::string delta_text = (delta >= 0 ? "+" : "") + fixed(delta, decimals);
      if (*published != 0.0) {
        char percent[32];
        std::snprintf(percent, sizeof percent, " (%+.0f %%)", 100.0 * delta / std::fabs(*published));
        delta_text += percent;
      }
      cells.push_back(delta_text);
      out.rows.push_back(std::move(cells));
    }
  }
  out.note = table.note;
  return out;
}

std::vector<nlohmann::json> read_records(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot read (a run folder holds results.jsonl)");
  std::vector<nlohmann::json> records;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    try {
      records.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::exception& e) {
      fail(path + ":" + std::to_string(number), std::string("not a JSON record: ") + e.what());
    }
  }
  return records;
}

std::string paper_readme_tables(const std::string& paper_dir) {
  const fs::path folder(paper_dir);
  const std::string paper = folder.filename().empty() ? folder.parent_path().filename().string()
                                                      : folder.filename().string();
  std::string out;
  for (const PublishedTable& table : load_published_tables((folder / "published.yaml").string())) {
    const fs::path measured = folder / "measured" / (table.id + ".jsonl");
    if (!fs::exists(measured)) continue;
    const std::vector<nlohmann::json> records = read_records(measured.string());
    std::string source = "measured/" + table.id + ".jsonl";
    if (!records.empty()) {
      const nlohmann::json& first = records.front();
      source += ": blocklab " + first.value("blocklab_version", std::string("?")) + ", commit " +
                first.value("git_sha", std::string("?")).substr(0, 12);
    }
    ReportTable rendered = paper_table(table, records);
    rendered.note += (rendered.note.empty() ? "" : " ") + std::string("(Published: ") + table.paper +
                     "; ours: " + source + ".)";
    out += "<!-- generated by blocklab report: " + paper + " " + table.id + " -->\n" + rendered.markdown() +
           "<!-- end generated: " + paper + " " + table.id + " -->\n";
  }
  return out;
}

}  // namespace blocklab
