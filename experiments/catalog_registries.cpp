// The default catalog: the explicit format and metric registries. Kept in its own file so that code using a custom
// Catalog (the experiment tests) does not link every format and metric.
#include "experiments/config.h"
#include "experiments/runner.h"
#include "formats/registry.h"

namespace blocklab {

Catalog Catalog::registries() { return Catalog{all_formats(), all_metrics()}; }

ExperimentConfig load_experiment(const std::string& path) { return load_experiment(path, Catalog::registries()); }

RunSummary run_experiment(const RunOptions& options) { return run_experiment(options, Catalog::registries()); }

}  // namespace blocklab
