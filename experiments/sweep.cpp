// Sweep expansion (Hydra-style "multi-run" grid: every list-valued option is an axis of a cartesian product;
// ECOSYSTEM.md section 3) and ablation patches applied on top of each variant.
#include "experiments/sweep.h"

#include <algorithm>
#include <map>
#include <set>

#include "core/error.h"

namespace blocklab {
namespace {

bool declares_option(const Format& format, const std::string& key) {
  for (const OptionSpec& spec : all_option_specs(format)) {   // own options + common ones (seed)
    if (spec.name == key) return true;
  }
  return false;
}

std::string describe_options(const FormatOptions& options) {
  std::string out;
  for (const auto& [key, value] : options) out += (out.empty() ? "" : ",") + key + "=" + value;
  return out;
}

// Runs resolve_format_options and puts `where` and `context` in front of its message.
FormatOptions resolve_or_explain(const Format& format, const FormatOptions& given, const std::string& where,
                                 const std::string& context) {
  try {
    return resolve_format_options(format, given);
  } catch (const Error& e) {
    fail(where, context + ": " + e.what());
  }
}

std::uint64_t saturating_multiply(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > UINT64_MAX / a) return UINT64_MAX;
  return a * b;
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return b > UINT64_MAX - a ? UINT64_MAX : a + b; }

std::string count_text(std::uint64_t n) { return n == UINT64_MAX ? "more than 18446744073709551614" : std::to_string(n); }

}  // namespace

SweepSize sweep_size(const ExperimentConfig& config, const Catalog& catalog) {
  SweepSize size;
  for (std::size_t e = 0; e < config.formats.size(); ++e) {
    const FormatEntry& entry = config.formats[e];
    const Format* format = catalog.find_format(entry.format);
    std::uint64_t count = 1;
    std::string factors;
    for (const OptionAxis& axis : entry.options) {
      if (!axis.swept) continue;
      count = saturating_multiply(count, axis.values.size());
      factors += (factors.empty() ? "" : " x ") + axis.key + " (" + std::to_string(axis.values.size()) + ")";
    }
    // An ablation adds a cell only for formats that declare one of its keys (expand_experiment).
    std::uint64_t ablations = 0;
    for (const Ablation& ablation : config.ablations) {
      const bool applies = format != nullptr && std::any_of(ablation.patch.begin(), ablation.patch.end(),
                                                            [&](const auto& kv) { return declares_option(*format, kv.first); });
      if (applies) ++ablations;
    }
    if (ablations > 0) {
      count = saturating_multiply(count, 1 + ablations);
      factors += (factors.empty() ? "" : " x ") + std::string("(baseline + ") + std::to_string(ablations) +
                 (ablations == 1 ? " ablation)" : " ablations)");
    }
    size.treatments = saturating_add(size.treatments, count);
    size.account += (size.account.empty() ? "" : "; ") + std::string("formats[") + std::to_string(e) + "] " +
                    (entry.label.empty() ? entry.format : entry.label) + ": " +
                    (factors.empty() ? "" : factors + " = ") + count_text(count);
  }
  return size;
}

void check_cell_limit(const ExperimentConfig& config, const SweepSize& size, std::uint64_t images,
                      const std::string& images_text, std::uint64_t max_cells) {
  const std::uint64_t cells = saturating_multiply(size.treatments, images);
  if (cells <= max_cells) return;
  fail(config.source_path, "the experiment expands to " + count_text(cells) + " cells, above the limit of " +
                               std::to_string(max_cells) + " (raise it with --max-cells N): " + size.account +
                               "; total " + count_text(size.treatments) + " treatments x " + images_text);
}

std::size_t variant_count(const FormatEntry& entry) {
  std::size_t count = 1;
  for (const OptionAxis& axis : entry.options) count *= axis.values.size();
  return count;
}

std::vector<FormatVariant> expand_format_entry(const FormatEntry& entry, std::size_t entry_index,
                                               const Format& format, bool seed_given, std::int64_t seed) {
  const std::size_t count = variant_count(entry);
  std::vector<FormatVariant> variants;
  variants.reserve(count);
  const bool entry_sets_seed = std::any_of(entry.options.begin(), entry.options.end(),
                                           [](const OptionAxis& axis) { return axis.key == "seed"; });
  // Mixed-radix counter over the axes: the LAST axis varies fastest, so the first option is the outermost loop.
  std::vector<std::size_t> digit(entry.options.size(), 0);
  for (std::size_t v = 0; v < count; ++v) {
    FormatVariant variant;
    variant.entry_index = entry_index;
    variant.format = &format;
    std::string swept;
    for (std::size_t a = 0; a < entry.options.size(); ++a) {
      const OptionAxis& axis = entry.options[a];
      const std::string& value = axis.values[digit[a]];
      variant.given[axis.key] = value;
      if (axis.swept) swept += (swept.empty() ? "" : ",") + axis.key + "=" + value;
    }
    // The experiment seed reaches formats that declare a `seed` option, unless the entry sets its own.
    if (seed_given && !entry_sets_seed && declares_option(format, "seed")) variant.given["seed"] = std::to_string(seed);
    variant.label = (entry.label.empty() ? entry.format : entry.label) + (swept.empty() ? "" : "[" + swept + "]");
    variant.resolved = resolve_or_explain(format, variant.given, entry.where,
                                          "formats[" + std::to_string(entry_index) + "] (" + variant.label + ")");
    variants.push_back(std::move(variant));
    for (std::size_t a = entry.options.size(); a-- > 0;) {   // increment, last axis first
      if (++digit[a] < entry.options[a].values.size()) break;
      digit[a] = 0;
    }
  }
  return variants;
}

void expand_experiment(ExperimentConfig& config, const Catalog& catalog) {
  config.variants.clear();
  config.treatments.clear();
  for (std::size_t e = 0; e < config.formats.size(); ++e) {
    const FormatEntry& entry = config.formats[e];
    const Format* format = catalog.find_format(entry.format);
    if (format == nullptr) fail(entry.where, "unknown format '" + entry.format + "'");   // checked by the loader
    for (FormatVariant& variant : expand_format_entry(entry, e, *format, config.seed_given, config.seed)) {
      config.variants.push_back(std::move(variant));
    }
  }

  // Two variants with the same format and resolved options would be one cell under two labels.
  std::map<std::pair<std::string, FormatOptions>, std::size_t> seen;
  for (std::size_t v = 0; v < config.variants.size(); ++v) {
    const FormatVariant& variant = config.variants[v];
    const auto [it, inserted] = seen.emplace(std::make_pair(variant.format->name(), variant.resolved), v);
    if (!inserted) {
      const FormatVariant& first = config.variants[it->second];
      fail(config.formats[variant.entry_index].where,
           "formats[" + std::to_string(variant.entry_index) + "] (" + variant.label + ") repeats formats[" +
               std::to_string(first.entry_index) + "] (" + first.label + "): both are " + variant.format->name() +
               " {" + describe_options(variant.resolved) + "}");
    }
  }

  // Labels name the rows of every result (table, CSV, plots): two variants under one label would be ambiguous.
  std::map<std::string, std::size_t> labelled;
  for (std::size_t v = 0; v < config.variants.size(); ++v) {
    const FormatVariant& variant = config.variants[v];
    const auto [it, inserted] = labelled.emplace(variant.label, v);
    if (!inserted) {
      const FormatVariant& first = config.variants[it->second];
      fail(config.formats[variant.entry_index].where,
           "formats[" + std::to_string(variant.entry_index) + "] has the label '" + variant.label +
               "', already used by formats[" + std::to_string(first.entry_index) +
               "]: results would be ambiguous; give each entry its own label");
    }
  }

  // Every ablation key must be declared by at least one format of this config (a typo would otherwise do nothing).
  for (const Ablation& ablation : config.ablations) {
    for (const auto& [key, value] : ablation.patch) {
      const bool declared = std::any_of(config.variants.begin(), config.variants.end(),
                                        [&](const FormatVariant& v) { return declares_option(*v.format, key); });
      if (!declared) {
        std::set<std::string> names;
        for (const FormatVariant& v : config.variants) names.insert(v.format->name());
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        fail(ablation.where, "ablations." + ablation.name + ": option '" + key +
                                 "' is not declared by any format of this config (" + list + ")");
      }
    }
  }

  for (std::size_t v = 0; v < config.variants.size(); ++v) {
    const FormatVariant& variant = config.variants[v];
    Treatment baseline;
    baseline.variant_index = v;
    baseline.resolved = variant.resolved;
    config.treatments.push_back(baseline);
    for (const Ablation& ablation : config.ablations) {
      Treatment treatment;
      treatment.variant_index = v;
      treatment.ablation = ablation.name;
      FormatOptions given = variant.given;
      for (const auto& [key, value] : ablation.patch) {
        if (!declares_option(*variant.format, key)) continue;   // the patch only touches options the format has
        treatment.applied_patch[key] = value;
        given[key] = value;
      }
      // Nothing of the patch applies to this format: the cell would repeat the baseline, so there is none.
      if (treatment.applied_patch.empty()) continue;
      treatment.resolved = resolve_or_explain(*variant.format, given, ablation.where,
                                              "ablations." + ablation.name + " on " + variant.label);
      config.treatments.push_back(std::move(treatment));
    }
  }
}

}  // namespace blocklab
