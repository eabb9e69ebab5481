// Experiment configuration: the strict YAML schema, loaded and validated completely before any work starts.
//
// Schema (schema version 1):
// ```yaml
// schema: 1                       # required, must be 1
// name: quickstart                # required, [A-Za-z0-9_.-]+ (default run folder runs/<name>)
// description: "..."              # optional
// data_root: samples              # optional; relative paths are relative to the REPOSITORY root (BLOCKLAB_SOURCE_DIR);
//                                 # overridden by the env var BLOCKLAB_DATA_ROOT, which is overridden by RunOptions.data_root
// images:                         # required, non-empty list of paths or globs relative to the data root
//   - hdr/Desk.exr                #   (glob: * ? within one path component; sorted; a pattern matching nothing is an Error)
//   - "ldr/kodak/*.png"
// input_policy: clamp             # optional: error | clamp | zero (core/input_policy.h)
// seed: 1                         # optional integer, passed to formats as option `seed` unless the entry sets it
// metrics:                        # required: names, or maps {name: mpsnr, start: -4, stop: 4} (other keys = metric options;
//                                 #   `column: mpsnr_narrow` names the results column, so a metric may be listed twice)
//   - log2rgb
//   - mpsnr
// formats:                        # required: list of entries
//   - format: fp16                #   registry name
//   - format: rgbe
//     label: rgbe_default         #   optional display label
//     options: {seed: [1, 2]}     #   a LIST value is a sweep axis: the entry expands to the product of all list values
// ablations:                      # optional: named patches; every cell runs once as "baseline" and once per ablation
//   no_offset: {decode_offset: half}   # patch = option overrides, applied to entries whose format declares that option
// save_decoded: false             # optional: write decoded images (EXR for HDR sources, PNG for LDR) into the run folder
// error_maps: []                  # optional: metric names whose per-pixel error map is written (EXR) per cell
// mode_maps: false                # optional: write each cell's colour-coded block-mode map (PNG, formats/common/mode_map.h)
// crop: {width: 128, height: 128} # optional: every image is cropped to this rectangle before encoding, centred
//                                 #   (clipped to smaller images), or at {x: .., y: ..} when given (then it must fit);
//                                 #   for solver studies too slow for whole images. Recorded in every cell.
// ```
//
// Strictness decisions (yaml-cpp 0.7 accepts all of these silently; ECOSYSTEM.md section 3, DESIGN.md "Known traps"):
// - Unknown keys and duplicate keys are errors at "<file>:<line>:<col>", with the YAML path and the valid keys.
// - A missing required key is an error at the line of the map that should hold it.
// - An UNQUOTED YAML-1.1 boolean word (y Y yes Yes YES n N no No NO on On ON off Off OFF) is rejected everywhere a
//   scalar is read: write true/false, or quote it if the word is meant as text. Booleans accept only true/false.
// - An UNQUOTED number with a leading zero (042, -07, 0x1F, 0o17) is rejected everywhere (YAML 1.1 readers such as
//   PyYAML read 042 as octal 34): write 42, or quote it if it is meant as text ("042").
// - Integers (schema, seed) must be plain decimal, e.g. 7 or -3; 7.0 or 1e3 are rejected.
// - null / empty values (`key:` or `key: ~`) are rejected where a value is expected.
// - Sweep order: within one format entry the options are nested loops in the order they are written, the first
//   option outermost (slowest) and the last innermost, each axis in list order. A one-element list is a sweep of one
//   value (it still labels the variant). Entries then expand in file order.
// - Every name (format, option, metric, metric option, error map) is checked against the registries, the option
//   values through resolve_format_options and a dry metric evaluation, and every error lists the valid names.
// - Two format variants that resolve to the same format and options are an error (they would be the same cell).
// - Two format variants with the same display label (the entry's `label`, else its format name, plus "[k=v,...]"
//   for swept options) are an error: results name rows by label. Two entries of one format need labels.
// - An ablation key that no format in the config declares is an error (a typo would otherwise run nothing). An
//   ablation whose patch touches none of a variant's options adds no cell for that variant: it would only repeat
//   the baseline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/input_policy.h"
#include "formats/format.h"
#include "metrics/metric.h"

namespace blocklab {

// Which formats and metrics a config may name. `registries()` is the normal catalog (formats/registry.h,
// metrics/metric.h); tests pass their own to exercise validation without depending on real formats.
struct Catalog {
  std::vector<const Format*> formats;
  std::vector<const Metric*> metrics;
  static Catalog registries();
  const Format* find_format(const std::string& name) const;   // nullptr if absent
  const Metric* find_metric(const std::string& name) const;   // nullptr if absent
};

struct MetricRequest {
  std::string name;
  std::string label;             // `column:` as written ("" when absent): the results column, so one metric can be
                                 // listed twice with different options (e.g. two log2rgb zero rules)
  MetricOptions options;
  const Metric* metric = nullptr;
  // The results column: the label when given, otherwise the metric name.
  const std::string& column() const { return label.empty() ? name : label; }
};

// One option of a format entry as written: a scalar (one value) or a list (a sweep axis).
struct OptionAxis {
  std::string key;
  std::vector<std::string> values;
  bool swept = false;            // written as a list
};

struct FormatEntry {
  std::string format;
  std::string label;             // as written ("" when absent)
  std::vector<OptionAxis> options;
  std::string where;             // "<file>:<line>:<col>" of the entry, for messages
};

// A format entry with one value chosen on every sweep axis.
struct FormatVariant {
  std::size_t entry_index = 0;
  const Format* format = nullptr;
  std::string label;             // display label: entry label (or format name) + "[k=v,...]" for swept options
  FormatOptions given;           // options as written (+ the config seed when the format declares `seed`)
  FormatOptions resolved;        // resolve_format_options(format, given)
};

struct Ablation {
  std::string name;
  FormatOptions patch;
  std::string where;
};

constexpr const char* kBaselineAblation = "baseline";

// What runs on each image: a variant, either as baseline or with one ablation patch applied.
struct Treatment {
  std::size_t variant_index = 0;
  std::string ablation = kBaselineAblation;   // "baseline" or an ablation name
  FormatOptions applied_patch;   // the part of the ablation patch this variant's format declares (empty for baseline)
  FormatOptions resolved;        // options the codec gets
};

// `crop:` of a config (see the schema above).
struct ImageCrop {
  bool enabled = false;
  bool centred = true;           // false when x and y are given
  int x = 0, y = 0, width = 0, height = 0;
};

struct ExperimentConfig {
  std::string source_path;       // the YAML file
  std::string source_text;       // its bytes, copied into the run folder
  int schema = 1;
  std::string name, description;
  std::string data_root;         // as written ("" when absent)
  std::vector<std::string> images;   // patterns as written
  InputPolicy input_policy = InputPolicy::clamp;
  bool seed_given = false;
  std::int64_t seed = 1;
  std::vector<MetricRequest> metrics;
  std::vector<FormatEntry> formats;
  std::vector<Ablation> ablations;
  bool save_decoded = false;
  std::vector<std::string> error_maps;
  bool mode_maps = false;
  ImageCrop crop;

  // Expansion (sweep.h): variants in entry order, treatments variant-major with baseline first then ablations in
  // file order. Cells are images x treatments, image-major (experiments/runner.h).
  std::vector<FormatVariant> variants;
  std::vector<Treatment> treatments;

  std::vector<std::string> metric_names() const;   // the results columns (MetricRequest::column), in order
};

// Largest experiment (images x format variants x (baseline + ablations)) run without --max-cells: beyond it the
// plan alone takes hundreds of MB. The count is checked from the list lengths before anything is expanded.
constexpr std::uint64_t kDefaultMaxCells = 100000;

// Reads and validates a config file against the registries / the given catalog; throws Error on the first problem,
// including a sweep whose cells (counting each image pattern as one image) exceed `max_cells`.
ExperimentConfig load_experiment(const std::string& path);
ExperimentConfig load_experiment(const std::string& path, const Catalog& catalog,
                                 std::uint64_t max_cells = kDefaultMaxCells);
// Same, from text; `source_name` is used in messages.
ExperimentConfig parse_experiment(const std::string& yaml_text, const std::string& source_name, const Catalog& catalog,
                                  std::uint64_t max_cells = kDefaultMaxCells);

}  // namespace blocklab
