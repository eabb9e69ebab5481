// Input checks and option parsing shared by every metric (see validation.h).
#include "metrics/validation.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace blocklab {

namespace {

std::string size_text(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

std::string option_where(const std::string& metric, const std::string& key) {
  return metric + ": option '" + key + "'";
}

}  // namespace

void check_same_size(const std::string& metric, const Image& reference, const Image& test) {
  if (reference.width != test.width || reference.height != test.height)
    fail(metric, "size mismatch " + size_text(reference) + " vs " + size_text(test));
  // A metric over zero pixels would divide by zero; refuse it instead of returning NaN.
  if (reference.width <= 0 || reference.height <= 0) fail(metric, "empty image (" + size_text(reference) + ")");
  if (reference.pixels.size() < reference.texel_count() * 4 || test.pixels.size() < test.texel_count() * 4)
    fail(metric, "image pixel storage is smaller than width x height x 4 floats");
}

void check_option_names(const std::string& metric, const MetricOptions& options,
                        const std::vector<std::string>& valid_names) {
  for (const auto& [key, value] : options) {
    bool known = false;
    for (const std::string& name : valid_names) known |= (name == key);
    if (known) continue;
    std::string valid;
    for (const std::string& name : valid_names) valid += (valid.empty() ? "" : ", ") + name;
    fail(metric, "unknown option '" + key + "' (" +
                     (valid.empty() ? std::string("this metric takes no options") : "valid options: " + valid) + ")");
  }
}

void validate_metric_inputs(const Metric& metric, const Image& reference, const Image& test,
                            const MetricOptions& options) {
  check_option_names(metric.name(), options, metric.option_names());
  check_same_size(metric.name(), reference, test);
}

int option_int(const std::string& metric, const MetricOptions& options, const std::string& key, int fallback) {
  const auto it = options.find(key);
  if (it == options.end()) return fallback;
  const std::string& text = it->second;
  int value = 0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (!text.empty() && *begin == '+') ++begin;   // from_chars rejects a leading '+', users write "+10"
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (text.empty() || ec != std::errc() || ptr != end)
    fail(option_where(metric, key), "expected an integer, got '" + text + "'");
  return value;
}

double option_double(const std::string& metric, const MetricOptions& options, const std::string& key,
                     double fallback) {
  const auto it = options.find(key);
  if (it == options.end()) return fallback;
  const std::string& text = it->second;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    fail(option_where(metric, key), "expected a finite number, got '" + text + "'");
  return value;
}

bool option_bool(const std::string& metric, const MetricOptions& options, const std::string& key, bool fallback) {
  const auto it = options.find(key);
  if (it == options.end()) return fallback;
  const std::string& text = it->second;
  if (text == "true" || text == "1" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "0" || text == "no" || text == "off") return false;
  fail(option_where(metric, key), "expected true or false, got '" + text + "'");
}

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, ptr);
}

}  // namespace blocklab
