// Which images an experiment reads: the data root (RunOptions.data_root > env BLOCKLAB_DATA_ROOT > config data_root,
// relative to the repository root > the repository root) and the config's image patterns expanded under it.
// Glob syntax: `*` (any run of characters) and `?` (one character) inside ONE path component; `[` and every other
// character are literal. Names starting with '.' match only a pattern component that starts with '.'. Each
// pattern's matches are sorted by byte order; patterns keep their config order.
#pragma once

#include <string>
#include <vector>

#include "experiments/config.h"

namespace blocklab {

// Absolute, lexically normal data root; throws Error naming where the root came from if it is not a directory.
std::string resolve_data_root(const ExperimentConfig& config, const std::string& override_root);

// Relative paths (generic '/' form, lexically normal) of the images, in config order. A pattern matching nothing,
// a missing file, an image matched twice, or a pattern that leads outside the data root ("../x", "a/../../x") is an
// Error naming the config and the pattern. The check is lexical, made before any file is opened: a symbolic link
// inside the data root is followed wherever it points (whoever can write the data root chose that file).
std::vector<std::string> resolve_images(const ExperimentConfig& config, const std::string& data_root);

// Whole-string match of one path component against a pattern with `*` and `?`.
bool glob_component_matches(const std::string& pattern, const std::string& name);

}  // namespace blocklab
