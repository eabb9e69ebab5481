// `blocklab list [--json | --markdown]`: formats with their modes, options and presets (what each expands to),
// solvers with their options, metrics. --markdown prints the README option tables, each between the marker comments
// that tests/unit/test_option_tables.cpp compares with the READMEs.
#include <nlohmann/json.hpp>

#include <cstdio>

#include "cli/commands.h"
#include "formats/registry.h"
#include "formats/option_markdown.h"
#include "metrics/metric.h"
#include "solvers/registry.h"

namespace blocklab::cli {

namespace {

nlohmann::json option_json(const OptionSpec& spec) {
  nlohmann::json j = {{"name", spec.name}, {"type", to_string(spec.type)}, {"default", spec.default_value},
                      {"help", spec.help}};
  if (!spec.choices.empty()) j["choices"] = spec.choices;
  if (spec.min_value < spec.max_value) j["range"] = {spec.min_value, spec.max_value};
  if (spec.min_exclusive) j["range_excludes_min"] = true;
  return j;
}

int print_markdown() {
  for (const Format* format : all_formats())
    std::printf("%s\n", generated_markdown_block("format " + format->name(), format_options_markdown(*format)).c_str());
  for (const Solver* solver : all_solvers())
    std::printf("%s\n", generated_markdown_block("solver " + solver->name(),
                                                 option_table_markdown(solver->option_specs())).c_str());
  return 0;
}

}  // namespace

int run_list(const ListArgs& args) {
  if (args.markdown) return print_markdown();
  nlohmann::json formats = nlohmann::json::array();
  for (const Format* format : all_formats()) {
    const FormatOptions defaults = resolve_format_options(*format, {});
    nlohmann::json options = nlohmann::json::array();
    for (const OptionSpec& spec : all_option_specs(*format)) options.push_back(option_json(spec));
    nlohmann::json problems = nlohmann::json::array();
    for (const BlockProblem& problem : format->block_problems())
      problems.push_back({{"name", format->name() + "." + problem.name}, {"description", problem.description},
                          {"images", problem.image_kind == BlockImageKind::hdr ? "hdr" : "ldr"}});
    // Each preset with its own values and the full map it resolves to.
    nlohmann::json presets = nlohmann::json::array();
    for (const FormatPreset& preset : format->presets())
      presets.push_back({{"name", preset.name}, {"summary", preset.summary}, {"values", preset.values},
                         {"aliases", preset.aliases},
                         {"expanded", resolve_format_options(*format, {{"preset", preset.name}})}});
    formats.push_back({{"name", format->name()}, {"description", format->description()},
                       {"bits_per_pixel", format->bits_per_pixel(defaults)}, {"modes", format->modes()},
                       {"options", options}, {"presets", presets}, {"block_problems", problems}});
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
    for (const auto& p : f["presets"]) {
      std::string values;
      for (const auto& v : p["values"].items())
        values += (values.empty() ? "" : " ") + v.key() + "=" + v.value().get<std::string>();
      const std::string summary = p["summary"].get<std::string>();
      std::printf("      preset %s%s: %s%s\n", p["name"].get<std::string>().c_str(),
                  p["name"] == kDefaultPreset ? " (default)" : "", values.empty() ? "the defaults" : values.c_str(),
                  summary.empty() ? "" : ("  (" + summary + ")").c_str());
    }
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
