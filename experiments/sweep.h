// Sweep expansion: format entries -> variants (cartesian product of list-valued options) -> treatments (each variant
// as baseline and once per applicable ablation patch). The order is part of the results contract (results.jsonl is
// written in this order); it is documented in experiments/config.h.
#pragma once

#include <cstddef>
#include <vector>

#include "experiments/config.h"

namespace blocklab {

// The variants of one entry, first option outermost. `seed` (when `seed_given`) is added as option `seed` if the
// format declares it and the entry does not set it. Options are resolved; errors name the entry and the values.
std::vector<FormatVariant> expand_format_entry(const FormatEntry& entry, std::size_t entry_index,
                                               const Format& format, bool seed_given, std::int64_t seed);

// Number of variants an entry expands to (product of the axis lengths).
std::size_t variant_count(const FormatEntry& entry);

// Fills config.variants and config.treatments from config.formats and config.ablations (formats already looked up
// in `catalog`). Rejects two variants with the same format and resolved options, and ablation keys that no format
// of the config declares.
void expand_experiment(ExperimentConfig& config, const Catalog& catalog);

}  // namespace blocklab
