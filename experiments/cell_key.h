// Content-addressed cell keys: SHA-256 of a canonical JSON document holding everything that can change a cell's
// result, and nothing that cannot.
//
// In the key: the results schema version, the image path relative to the data root and the SHA-256 of its bytes,
// the format name + revision() + resolved options, the codec seed, the requested metrics with their options (as a
// name-keyed object, so reordering the metric list keeps the cache), the
// input policy, the ablation name and applied patch, the artifacts the cell writes (save_decoded, error maps: a
// cached cell must have them), and the blocklab version.
// Not in the key: thread count (formats are byte-identical at any thread count, which tests/cli/
// test_cli_threads_identical.sh checks; eqasim-france#438 in ECOSYSTEM.md section 3), the run folder, the data root
// location, labels, the experiment name and description (display only), timings.
// Canonical form: nlohmann::json objects are std::map-backed, so keys are sorted, and dump() without indentation is
// compact; the same document always gives the same bytes.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "experiments/config.h"

namespace blocklab {

// 2: non-finite metric values are the strings "inf" / "-inf" / "nan" (experiments/results_writer.h) and cell files
// carry record_sha256 (experiments/run_folder.h).
constexpr int kResultsSchemaVersion = 2;

struct ImageIdentity {
  std::string relative_path;     // as resolved from the config's patterns, relative to the data root
  std::string sha256;            // of the file's bytes
};

// The seed the codec gets: the resolved `seed` option when the format declares one, else the experiment seed.
std::uint64_t effective_seed(const ExperimentConfig& config, const Treatment& treatment);

// The config's crop as written (centred, or at x, y), for cell keys and resolved.json.
nlohmann::json crop_json(const ImageCrop& crop);

nlohmann::json cell_key_document(const ExperimentConfig& config, const ImageIdentity& image, const Treatment& treatment);
std::string cell_key(const nlohmann::json& key_document);   // lowercase hex SHA-256 of the canonical dump

}  // namespace blocklab
