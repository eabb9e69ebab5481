// Input checks and option parsing shared by every metric. Every failure throws blocklab::Error whose message starts
// with the metric's name (and the option's name), e.g. "mpsnr: option 'start': expected an integer, got 'x'".
#pragma once

#include <string>
#include <vector>

#include "metrics/metric.h"

namespace blocklab {

// Throws "<metric>: size mismatch WxH vs WxH" (reference first) and "<metric>: empty image (0x0)".
void check_same_size(const std::string& metric, const Image& reference, const Image& test);

// Throws "<metric>: unknown option 'k' (valid options: a, b)" for any key not in `valid_names`.
void check_option_names(const std::string& metric, const MetricOptions& options,
                        const std::vector<std::string>& valid_names);

// check_same_size + check_option_names, the first thing every compute() / error_map() does.
void validate_metric_inputs(const Metric& metric, const Image& reference, const Image& test,
                            const MetricOptions& options);

// Typed option lookups: the value when the option is present, otherwise `fallback`. The whole string must parse.
int option_int(const std::string& metric, const MetricOptions& options, const std::string& key, int fallback);
double option_double(const std::string& metric, const MetricOptions& options, const std::string& key, double fallback);
// Accepts true/false, 1/0, yes/no, on/off (case-sensitive lower case).
bool option_bool(const std::string& metric, const MetricOptions& options, const std::string& key, bool fallback);

// Shortest decimal text that reads back to exactly `value` ("inf", "-inf", "nan" for the non-finite ones).
std::string format_number(double value);

}  // namespace blocklab
