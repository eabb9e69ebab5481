// The metric registry: an explicit table, in the order `blocklab list` and results show them.
#include <string>

#include "core/error.h"
#include "metrics/builtin_metrics.h"
#include "metrics/metric.h"

namespace blocklab {

const std::vector<const Metric*>& all_metrics() {
  static const std::vector<const Metric*> table = {
      &log2rgb_metric(),     // SPECS.md 1a
      &mpsnr_metric(),       // SPECS.md 1b, fixed stops
      &mpsnr_auto_metric(),  // SPECS.md 1b, HDR_Toolbox automatic stops
      &psnr_metric(),        // SPECS.md 1d
      &psnr_luma_metric(),   // SPECS.md 1d
      &pu21_psnr_metric(),   // SPECS.md 1c
  };
  return table;
}

const Metric& find_metric(const std::string& name) {
  std::string valid;
  for (const Metric* metric : all_metrics()) {
    if (metric->name() == name) return *metric;
    valid += (valid.empty() ? "" : ", ") + metric->name();
  }
  throw Error("unknown metric '" + name + "'; valid metrics: " + valid);
}

}  // namespace blocklab
