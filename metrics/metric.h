// The Metric interface and registry. A metric compares a reference image with a test image (same size) and
// returns one number plus the details needed to reproduce it (variant, stop range, zero rule, clamped count).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"

namespace blocklab {

using MetricOptions = std::map<std::string, std::string>;

struct MetricResult {
  double value = 0.0;
  std::map<std::string, std::string> details;   // e.g. {"variant": "fixed stops -10..10", "zero_rule": "..."}
};

class Metric {
 public:
  virtual ~Metric() = default;
  virtual std::string name() const = 0;           // registry name, also the JSON key of results
  virtual std::string description() const = 0;   // one line with the definition's source
  virtual std::string unit() const = 0;            // "dB", "log2 units", ...
  virtual bool higher_is_better() const = 0;
  virtual std::vector<std::string> option_names() const { return {}; }
  // Throws Error naming the metric and the option on an unknown option or a bad value, and on size mismatch.
  virtual MetricResult compute(const Image& reference, const Image& test, const MetricOptions& options) const = 0;
  // Per-pixel error (R = G = B = the pixel's contribution, in the metric's own units) for error maps.
  virtual Image error_map(const Image& reference, const Image& test, const MetricOptions& options) const = 0;
};

const std::vector<const Metric*>& all_metrics();
const Metric& find_metric(const std::string& name);   // throws Error listing valid names

}  // namespace blocklab
