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

void write_file_atomically(const std::string& path, const std::string& content) {
  const std::string temp = path + ".tmp." + std::to_string(static_cast<long>(getpid()));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) fail(temp, "cannot create file");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::remove(temp.c_str());
      fail(temp, "write failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    std::remove(temp.c_str());
    fail(path, "cannot move the finished file into place: " + ec.message());
  }
}

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
  // A corrupt file (edited by hand, disk trouble) is recomputed rather than trusted.
  nlohmann::json record = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (record.is_discarded() || !record.is_object()) return std::nullopt;
  if (!record.contains("key") || record["key"] != key) return std::nullopt;
  return record;
}

void RunFolder::write_cell(const std::string& key, const nlohmann::json& record) const {
  const fs::path file = cell_path(key);
  make_directories(file.parent_path());
  write_file_atomically(file.string(), record.dump(2) + "\n");
}

std::size_t RunFolder::remove_stray_temp_files() const {
  std::size_t removed = 0;
  std::error_code ec;
  std::vector<fs::path> strays;
  for (fs::recursive_directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && is_temp_name(it->path().filename().string())) strays.push_back(it->path());
  }
  for (const fs::path& stray : strays) {
    if (fs::remove(stray, ec)) ++removed;
  }
  return removed;
}

std::string RunFolder::artifact_path(const std::string& subdir, const std::string& file_name) const {
  const fs::path folder = fs::path(dir_) / subdir;
  make_directories(folder);
  return (folder / file_name).string();
}

}  // namespace blocklab
