// Run folder + cell store (layout and atomicity contract in run_folder.h; layout idea from ECOSYSTEM.md section 3).
#include "experiments/run_folder.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "core/parallel.h"
#include "experiments/sha256.h"

namespace blocklab {
namespace fs = std::filesystem;

namespace {

bool is_temp_name(const std::string& name) {
  const std::size_t at = name.rfind(".tmp.");
  if (at == std::string::npos || at + 5 >= name.size()) return false;
  for (std::size_t i = at + 5; i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
  }
  return true;
}

void make_directories(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) fail(dir.string(), "cannot create directory: " + ec.message());
}

}  // namespace

RunFolder::RunFolder(const std::string& dir) : dir_(dir) {
  make_directories(fs::path(dir_));
  make_directories(fs::path(dir_) / "cells");
}

std::string RunFolder::path(const std::string& relative) const { return (fs::path(dir_) / relative).string(); }

std::string RunFolder::cell_path(const std::string& key) const {
  // Keys are 64 hex digits; two-digit fan-out keeps directories small for large sweeps.
  return (fs::path(dir_) / "cells" / key.substr(0, 2) / (key + ".json")).string();
}

std::optional<nlohmann::json> RunFolder::read_cell(const std::string& key) const {
  std::ifstream in(cell_path(key), std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  // A corrupt file (edited by hand, disk trouble) is recomputed rather than trusted: it must parse, hold this key,
  // and its content must still hash to the record_sha256 stored with it.
  nlohmann::json record = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (record.is_discarded() || !record.is_object()) return std::nullopt;
  if (!record.contains("key") || record["key"] != key) return std::nullopt;
  const auto stored = record.find(kRecordChecksumKey);
  if (stored == record.end() || !stored->is_string()) return std::nullopt;
  const std::string checksum = stored->get<std::string>();
  record.erase(kRecordChecksumKey);
  if (sha256_hex(record.dump()) != checksum) return std::nullopt;
  return record;
}

void RunFolder::write_cell(const std::string& key, const nlohmann::json& record) const {
  const fs::path file = cell_path(key);
  make_directories(file.parent_path());
  nlohmann::json stored = record;
  stored.erase(kRecordChecksumKey);
  stored[kRecordChecksumKey] = sha256_hex(stored.dump());   // of the compact, key-sorted dump without this field
  write_file_atomically(file.string(), stored.dump(2) + "\n");
}

std::vector<std::optional<nlohmann::json>> RunFolder::read_cells(const std::vector<std::string>& keys,
                                                                 int threads) const {
  std::vector<std::optional<nlohmann::json>> records(keys.size());
  parallel_for_index(keys.size(), threads, [&](std::size_t i) { records[i] = read_cell(keys[i]); });
  return records;
}

std::size_t RunFolder::remove_stray_temp_files(std::chrono::seconds untouched_for) const {
  std::size_t removed = 0;
  std::error_code ec;
  std::vector<fs::path> strays;
  const auto now = fs::file_time_type::clock::now();
  for (fs::recursive_directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec) || !is_temp_name(it->path().filename().string())) continue;
    std::error_code time_error;
    const auto changed = fs::last_write_time(it->path(), time_error);
    if (time_error || now - changed < untouched_for) continue;
    strays.push_back(it->path());
  }
  for (const fs::path& stray : strays) {
    if (fs::remove(stray, ec)) ++removed;
  }
  return removed;
}

void RunFolder::write_file_unless_same(const std::string& relative, const std::string& content) const {
  const std::string file = path(relative);
  std::ifstream in(file, std::ios::binary);
  if (in) {
    std::ostringstream existing;
    existing << in.rdbuf();
    if (existing.str() == content) return;
  }
  write_file_atomically(file, content);
}

std::string RunFolder::artifact_path(const std::string& subdir, const std::string& file_name) const {
  const fs::path folder = fs::path(dir_) / subdir;
  make_directories(folder);
  return (folder / file_name).string();
}

}  // namespace blocklab
