// Data-root resolution and image globbing (see image_set.h for the rules).
#include "experiments/image_set.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <system_error>

#include "core/error.h"

namespace blocklab {
namespace fs = std::filesystem;

namespace {

bool has_wildcard(const std::string& component) { return component.find_first_of("*?") != std::string::npos; }

std::vector<std::string> split_components(const std::string& pattern) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : pattern) {
    if (c == '/') {
      if (!current.empty()) parts.push_back(current);   // "a//b" is "a/b"
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) parts.push_back(current);
  return parts;
}

// Expands one pattern: returns relative paths (unsorted) of the regular files it matches.
void expand(const fs::path& root, const fs::path& relative, const std::vector<std::string>& parts, std::size_t index,
            std::vector<std::string>& out) {
  const fs::path here = root / relative;
  std::error_code ec;
  if (index == parts.size()) {
    if (fs::is_regular_file(here, ec)) out.push_back(relative.lexically_normal().generic_string());
    return;
  }
  const std::string& part = parts[index];
  if (!has_wildcard(part)) {
    expand(root, relative / part, parts, index + 1, out);
    return;
  }
  if (!fs::is_directory(here, ec)) return;
  std::vector<std::string> names;
  for (fs::directory_iterator it(here, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // Hidden entries only match a component that asks for them (shell convention).
    if (name.front() == '.' && part.front() != '.') continue;
    if (glob_component_matches(part, name)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) expand(root, relative / name, parts, index + 1, out);
}

}  // namespace

bool glob_component_matches(const std::string& pattern, const std::string& name) {
  // Iterative wildcard match with single backtracking point (the last '*'): O(|pattern| * |name|) worst case.
  std::size_t p = 0, n = 0, star = std::string::npos, star_n = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p;
      ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      star_n = n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++star_n;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::string resolve_data_root(const ExperimentConfig& config, const std::string& override_root) {
  fs::path root;
  std::string origin;
  const char* env = std::getenv("BLOCKLAB_DATA_ROOT");
  if (!override_root.empty()) {
    root = override_root;
    origin = "--data-root";
  } else if (env != nullptr && *env != '\0') {
    root = env;
    origin = "BLOCKLAB_DATA_ROOT";
  } else if (!config.data_root.empty()) {
    // Config-relative roots are relative to the repository, so a config means the same thing from any directory.
    root = fs::path(config.data_root).is_absolute() ? fs::path(config.data_root)
                                                     : fs::path(BLOCKLAB_SOURCE_DIR) / config.data_root;
    origin = config.source_path + ": data_root";
  } else {
    root = BLOCKLAB_SOURCE_DIR;
    origin = "the repository root (no data_root in " + config.source_path + ")";
  }
  std::error_code ec;
  root = fs::absolute(root, ec).lexically_normal();
  if (ec || !fs::is_directory(root, ec)) fail(root.string(), "data root (from " + origin + ") is not a directory");
  std::string text = root.string();
  if (text.size() > 1 && text.back() == '/') text.pop_back();   // lexically_normal keeps a trailing separator
  return text;
}

std::vector<std::string> resolve_images(const ExperimentConfig& config, const std::string& data_root) {
  std::vector<std::string> images;
  std::map<std::string, std::size_t> matched_by;
  for (std::size_t i = 0; i < config.images.size(); ++i) {
    const std::string& pattern = config.images[i];
    const std::string where = config.source_path + ": images[" + std::to_string(i) + "]";
    // Resolved lexically before anything is opened: a pattern whose '..' components climb above the data root is
    // refused (absolute patterns are refused by the config loader). Symbolic links inside the root are followed
    // wherever they point: whoever can place a link in the data root chose that file.
    const fs::path normal = fs::path(pattern).lexically_normal();
    if (normal.is_absolute() || (!normal.empty() && *normal.begin() == "..")) {
      fail(where, "'" + pattern + "' leads outside the data root " + data_root +
                      " (image paths are relative to the data root and may not leave it with '..')");
    }
    std::vector<std::string> found;
    expand(fs::path(data_root), fs::path(), split_components(normal.generic_string()), 0, found);
    if (found.empty()) {
      fail(where, (has_wildcard(pattern) ? "pattern '" + pattern + "' matches no file" : "'" + pattern + "' not found") +
                      " under data root " + data_root);
    }
    std::sort(found.begin(), found.end());
    for (const std::string& path : found) {
      const auto [it, inserted] = matched_by.emplace(path, i);
      if (!inserted) {
        fail(where, "'" + path + "' is already listed by images[" + std::to_string(it->second) +
                        "] (an image appears once per experiment)");
      }
      images.push_back(path);
    }
  }
  return images;
}

}  // namespace blocklab
