// `blocklab analyze CONFIG`: analyses that are not (image x format x metric) cells, as a registry beside the
// experiment runner (experiments/runner.h). The config is strict YAML (experiments/strict_yaml.h: unknown /
// duplicate keys, YAML 1.1 booleans, octal-looking numbers are errors at file:line:col). Schema 1, keys every
// analysis shares:
// ```yaml
// analysis: banterle_filtering     # required: the analysis kind, a name of all_analyses() (`blocklab analyze
//                                  # --help` lists them). Written FIRST by convention: tools (and
//                                  # tests/unit/test_experiment_registry_run.cpp) tell an analysis config from an
//                                  # experiment config by its first key (`schema`)
// schema: 1                        # required, must be 1
// name: banterle2008_filtering     # required, [A-Za-z0-9_.-]+; default output folder runs/<name>
// description: "..."               # optional
// data_root: samples               # optional, as in `blocklab run` (repository-relative; BLOCKLAB_DATA_ROOT and
//                                  # --data-root override it)
// images: [hdr/Desk.exr]           # required, paths or globs relative to the data root (as in `blocklab run`)
// input_policy: clamp              # optional: error | clamp | zero
// output: runs/filtering           # optional output folder (relative to the working directory); --out overrides
// ```
// Each analysis adds its own keys, parses them and writes its CSV / JSON into the output folder; its file's header
// documents them (experiments/analysis_<name>.cpp, one analysis per file). A plot script next to its paper config
// draws the figure.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/input_policy.h"
#include "experiments/strict_yaml.h"
#include "formats/format.h"

namespace blocklab {

// The keys every analysis shares, as parsed.
struct AnalysisConfig {
  std::string source_path, source_text;
  std::string name, description, kind, data_root, output;
  std::vector<std::string> images;   // patterns relative to the data root
  InputPolicy input_policy = InputPolicy::clamp;
};

// What a parsed analysis runs on: the shared config, the resolved data root and image list, the output folder
// (already created).
struct AnalysisRun {
  const AnalysisConfig& config;
  std::string data_root;
  std::vector<std::string> images;   // relative to data_root
  std::filesystem::path out;
};

using AnalysisRunner = std::function<void(const AnalysisRun& run)>;

// One analysis kind: its `analysis:` name, its own top-level keys, and a parser of those keys (called after the
// shared keys are checked, before any image is read) that returns the runner.
struct Analysis {
  std::string name;
  std::vector<std::string> keys;
  std::function<AnalysisRunner(const StrictYaml& yaml, const YAML::Node& root)> parse;
};

// The explicit table (experiments/analysis.cpp), one entry per experiments/analysis_<name>.cpp.
const std::vector<Analysis>& all_analyses();
// The names of all_analyses(), comma-separated: the kinds `blocklab analyze --help` lists and an unknown kind's error
// names.
std::string analysis_names();

// The entries of the table, each defined (its keys documented) in experiments/analysis_<name>.cpp.
// Banterle 2008 section 4.5: the filtering error of the tone-mapped representation.
Analysis banterle_filtering_analysis();
// Munkberg 2008 section 4: filtering in logYuv and the luminance normalisation trick.
Analysis munkberg_filtering_analysis();
// Munkberg 2008 section 7.3, Figure 8: the histogram of per-block luminance ranges.
Analysis munkberg_luminance_histogram_analysis();
// Munkberg 2008 section 6: an approximate mode choice (e.g. mode_predictor) against the full mode search.
Analysis munkberg_mode_predictor_analysis();
// Munkberg 2008 sections 5-7: where the format loses on saturated colours and dark texels.
Analysis munkberg_saturation_analysis();
// Wang 2007 section 4.4, Fig. 5: sampling between texels, source against decoded.
Analysis wang_filtering_analysis();
// Wang 2007 section 3.5: the 1D codec against plain BC3 in the format's own luminance error.
Analysis wang_codec_error_analysis();
// Mavridis 2012 section 3.2: the clamp fraction and gamma the coefficient search converges to.
Analysis mavridis_coefficient_search_analysis();
// Mavridis 2012 Tables 1 and 6: the error of one subband against three per texture, and after each stage.
Analysis mavridis_error_breakdown_analysis();

struct AnalyzeOptions {
  std::string out_dir;     // overrides the config's output (and runs/<name>)
  std::string data_root;   // overrides the config's data_root (see resolve_data_root)
};

// Parses `config_path` (every error before any work), resolves the data root and images, creates the output folder
// and runs the analysis. Throws Error naming the file (and line:column for config errors).
void run_analysis_config(const std::string& config_path, const AnalyzeOptions& options);

// ---- helpers the analyses share ----------------------------------------------------------------------------------
// A finite decimal number (the whole scalar; StrictYaml::scalar already rejects octal-looking and boolean words).
double analysis_number(const StrictYaml& yaml, const YAML::Node& node, const std::string& path);
// An integer scalar in [lo, hi].
int analysis_bounded_integer(const StrictYaml& yaml, const YAML::Node& node, const std::string& path, int lo, int hi);
// The optional top-level `variants` key: label -> options of `format` (`variants: {a: {}, b: {key: value}}`), each
// resolved by resolve_format_options; `defaults` when the key is absent. A bad option is an error at the key.
struct AnalysisVariant {
  std::string label;
  FormatOptions options;   // resolved
};
std::vector<AnalysisVariant> analysis_format_variants(const StrictYaml& yaml, const YAML::Node& root,
                                                    const Format& format,
                                                    const std::vector<std::pair<std::string, FormatOptions>>& defaults);
// "path[i]".
std::string indexed_path(const std::string& path, std::size_t i);
// The shortest of %.15g / %.16g / %.17g that reads back as the same double (0.3 stays "0.3").
std::string g17(double value);
// A CSV field, quoted (RFC 4180) when it holds a comma, a quote or a newline.
std::string csv_field(const std::string& text);
// The image data_root/relative after the config's input policy.
Image load_analysis_image(const AnalysisRun& run, const std::string& relative);
// analysis, name, blocklab_version, config, data_root, input_policy.
nlohmann::json analysis_base_record(const AnalysisRun& run);
// Writes the run folder: the config as given, each (file name, CSV text), analysis.json, and prints where they are
// and the command that plots them.
void write_analysis_folder(const AnalysisRun& run, const std::vector<std::pair<std::string, std::string>>& csv_files,
                           const nlohmann::json& record, const std::string& plot_script);

}  // namespace blocklab
