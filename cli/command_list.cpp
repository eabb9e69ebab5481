// `blocklab list [--json]`: formats with their modes and options, solvers, metrics.
#include <nlohmann/json.hpp>

#include <cstdio>

#include "cli/commands.h"
#include "formats/registry.h"
#include "metrics/metric.h"
#include "solvers/registry.h"

namespace blocklab::cli {

namespace {

nlohmann::json option_json(const OptionSpec& spec) {
  nlohmann::json j = {{"name", spec.name}, {"type", to_string(spec.type)}, {"default", spec.default_value},
                      {"help", spec.help}};
  if (!spec.choices.empty()) j["choices"] = spec.choices;
  if (spec.min_value < spec.max_value) j["range"] = {spec.min_value, spec.max_value};
  return j;
}

}  // namespace

int run_list(const ListArgs& args) {
  nlohmann::json formats = nlohmann::json::array();
  for (const Format* format : all_formats()) {
    const FormatOptions defaults = resolve_format_options(*format, {});
    nlohmann::json options = nlohmann::json::array();
    for (const OptionSpec& spec : all_option_specs(*format)) options.push_back(option_json(spec));
    nlohmann::json problems = nlohmann::json::array();
    for (const BlockProblem& problem : format->block_problems())
      problems.push_back({{"name", format->name() + "." + problem.name}, {"description", problem.description},
                          {"images", problem.image_kind == BlockImageKind::hdr ? "hdr" : "ldr"}});
    formats.push_back({{"name", format->name()}, {"description", format->description()},
                       {"bits_per_pixel", format->bits_per_pixel(defaults)}, {"modes", format->modes()},
                       {"options", options}, {"block_problems", problems}});
  }
  nlohmann::json solvers = nlohmann::json::array();
  for (const Solver* solver : all_solvers()) {
    nlohmann::json options = nlohmann::json::array();
    for (const OptionSpec& spec : solver->option_specs()) options.push_back(option_json(spec));
    solvers.push_back({{"name", solver->name()}, {"description", solver->description()}, {"options", options}});
  }
  nlohmann::json metrics = nlohmann::json::array();
  for (const Metric* metric : all_metrics()) {
    metrics.push_back({{"name", metric->name()}, {"description", metric->description()}, {"unit", metric->unit()},
                       {"higher_is_better", metric->higher_is_better()}, {"options", metric->option_names()}});
  }

  if (args.json) {
    const nlohmann::json all = {{"formats", formats}, {"solvers", solvers}, {"metrics", metrics}};
    std::printf("%s\n", all.dump(2).c_str());
    return 0;
  }
  std::printf("formats:\n");
  for (const auto& f : formats) {
    std::printf("  %-12s %5.4g bpp  %s\n", f["name"].get<std::string>().c_str(), f["bits_per_pixel"].get<double>(),
                f["description"].get<std::string>().c_str());
    std::string modes;
    for (const auto& m : f["modes"]) modes += (modes.empty() ? "" : ", ") + m.get<std::string>();
    std::printf("      modes: %s\n", modes.c_str());
    for (const auto& p : f["block_problems"])
      std::printf("      block problem %s (%s)  %s\n", p["name"].get<std::string>().c_str(),
                  p["images"].get<std::string>().c_str(), p["description"].get<std::string>().c_str());
    for (const auto& o : f["options"])
      std::printf("      --set %s=<%s> (default %s)  %s\n", o["name"].get<std::string>().c_str(),
                  o["type"].get<std::string>().c_str(), o["default"].get<std::string>().c_str(),
                  o["help"].get<std::string>().c_str());
  }
  std::printf("solvers:\n");
  for (const auto& s : solvers)
    std::printf("  %-12s %s\n", s["name"].get<std::string>().c_str(), s["description"].get<std::string>().c_str());
  std::printf("metrics:\n");
  for (const auto& m : metrics)
    std::printf("  %-12s [%s] %s\n", m["name"].get<std::string>().c_str(), m["unit"].get<std::string>().c_str(),
                m["description"].get<std::string>().c_str());
  return 0;
}

}  // namespace blocklab::cli
