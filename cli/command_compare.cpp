// `blocklab compare REF TEST [--metrics a,b] [--json]`. With --json a non-finite metric value is the string "inf",
// "-inf" or "nan", as in results.jsonl (experiments/results_writer.h).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "experiments/results_writer.h"   // metric_value_json: "inf" / "-inf" / "nan" for non-finite values
#include "metrics/metric.h"

namespace blocklab::cli {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

int run_compare(const CompareArgs& args) {
  std::vector<const Metric*> metrics;
  if (args.metrics.empty()) {
    metrics = all_metrics();
  } else {
    for (const std::string& name : split_commas(args.metrics)) metrics.push_back(&find_metric(name));
  }
  std::map<std::string, MetricOptions> options;
  for (const std::string& s : args.settings) {
    auto [key, value] = split_setting(s, "--set");
    const auto dot = key.find('.');
    if (dot == std::string::npos) fail("--set", "metric options are written metric.key=value, got '" + s + "'");
    const std::string metric = key.substr(0, dot);
    bool selected = false;
    for (const Metric* m : metrics) selected |= m->name() == metric;
    if (!selected) fail("--set", "metric '" + metric + "' is not among the metrics being computed");
    options[metric][key.substr(dot + 1)] = value;
  }
  // Either side may be a packed texture (DDS, .blk): it is decoded with its format first.
  const Image reference = read_image_or_decode(args.reference, args.threads);
  const Image test = read_image_or_decode(args.test, args.threads);

  nlohmann::json json = nlohmann::json::object();
  for (const Metric* metric : metrics) {
    const MetricOptions& metric_options = options[metric->name()];
    const MetricResult result = metric->compute(reference, test, metric_options);
    if (!args.error_map_dir.empty()) {
      write_image(args.error_map_dir + "/" + metric->name() + ".exr",
                  metric->error_map(reference, test, metric_options), WriteOptions{ExrPixelType::float32, 8});
    }
    if (args.json) {
      if (args.details) {
        json[metric->name()] = {{"value", metric_value_json(result.value)}, {"unit", metric->unit()},
                                {"details", result.details}};
      } else {
        json[metric->name()] = metric_value_json(result.value);
      }
    } else {
      std::string details;
      for (const auto& [k, v] : result.details) details += (details.empty() ? "" : ", ") + k + "=" + v;
      std::printf("%-12s %14.6f %-10s %s\n", metric->name().c_str(), result.value, metric->unit().c_str(),
                  details.c_str());
    }
  }
  if (args.json) std::printf("%s\n", json.dump(2).c_str());
  return 0;
}

}  // namespace blocklab::cli
