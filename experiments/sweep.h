// Sweep expansion: format entries -> variants (cartesian product of list-valued options) -> treatments (each variant
// as baseline and once per applicable ablation patch). The order is part of the results contract (results.jsonl is
// written in this order); it is documented in experiments/config.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/config.h"

namespace blocklab {

// The variants of one entry, first option outermost. `seed` (when `seed_given`) is added as option `seed` if the
// format declares it and the entry does not set it. Options are resolved; errors name the entry and the values.
std::vector<FormatVariant> expand_format_entry(const FormatEntry& entry, std::size_t entry_index,
                                               const Format& format, bool seed_given, std::int64_t seed);

// Number of variants an entry expands to (product of the axis lengths).
std::size_t variant_count(const FormatEntry& entry);

// How many treatments (variants x (baseline + applicable ablations)) the config's entries expand to, known without
// expanding anything (saturating at UINT64_MAX), and where they come from, e.g.
// "formats[0] bc7: modes (9) x seed (1000) x (baseline + 1 ablation) = 18000; formats[1] fp16: 1".
struct SweepSize {
  std::uint64_t treatments = 0;
  std::string account;
};
SweepSize sweep_size(const ExperimentConfig& config, const Catalog& catalog);

// Throws Error(config: "... cells ... above the limit ...") when treatments x `images` exceeds `max_cells`, naming
// every list and the product. `images_text` says what `images` counts ("7 images", "at least 2 images").
void check_cell_limit(const ExperimentConfig& config, const SweepSize& size, std::uint64_t images,
                      const std::string& images_text, std::uint64_t max_cells);

// Fills config.variants and config.treatments from config.formats and config.ablations (formats already looked up
// in `catalog`). Rejects two variants with the same format and resolved options, and ablation keys that no format
// of the config declares.
void expand_experiment(ExperimentConfig& config, const Catalog& catalog);

}  // namespace blocklab
