// Options declared once (core/options.h OptionTable): the spec list, is_valid and from_resolved of every solver come
// from one table, so a value is accepted by resolve_solver_options exactly when the typed struct calls it valid; and
// the README option tables are the generated text of `blocklab list --markdown`.
#include <gtest/gtest.h>

#include <cfloat>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/error.h"
#include "formats/registry.h"
#include "formats/option_markdown.h"
#include "solvers/anneal/anneal_solver.h"
#include "solvers/ceres_lm/ceres_lm_solver.h"
#include "solvers/coeff_search/coeff_search_solver.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/nlopt/nlopt_solver.h"
#include "solvers/procrustes/procrustes_solver.h"
#include "solvers/registry.h"

namespace blocklab {
namespace {

bool resolves(const Solver& solver, const SolverOptions& given) {
  try {
    resolve_solver_options(solver, given);
    return true;
  } catch (const Error&) {
    return false;
  }
}

// Each ranged numeric option at its bounds (accepted) and one step outside them (rejected): resolve_solver_options
// and the typed struct's is_valid must say the same.
template <typename TypedOptions>
void expect_spec_and_is_valid_agree(const Solver& solver) {
  const SolverOptions defaults = resolve_solver_options(solver, {});
  for (const OptionSpec& spec : solver.option_specs()) {
    if (!(spec.min_value < spec.max_value)) continue;
    std::vector<std::pair<std::string, bool>> cases;   // value text, inside the range
    if (spec.type == OptionType::integer) {
      const long long lo = static_cast<long long>(spec.min_value);
      cases.push_back({std::to_string(lo), true});
      if (lo > LLONG_MIN) cases.push_back({std::to_string(lo - 1), false});
      if (spec.max_value < 9.2e18) {
        const long long hi = static_cast<long long>(spec.max_value);
        cases.push_back({std::to_string(hi), true});
        cases.push_back({std::to_string(hi + 1), false});
      }
    } else if (spec.type == OptionType::real) {
      cases.push_back({canonical_real_text(spec.min_value), !spec.min_exclusive});
      // One small step outside (nextafter below 0 would be a subnormal, which the option parser rejects).
      const auto step = [](double v) { return v != 0.0 ? std::fabs(v) * 1e-12 : 1e-300; };
      cases.push_back({canonical_real_text(spec.min_value - step(spec.min_value)), false});
      if (spec.max_value < DBL_MAX) {
        cases.push_back({canonical_real_text(spec.max_value), true});
        cases.push_back({canonical_real_text(spec.max_value + step(spec.max_value)), false});
      }
    }
    for (const auto& [text, inside] : cases) {
      SolverOptions given = defaults;
      given[spec.name] = text;
      EXPECT_EQ(resolves(solver, given), inside) << solver.name() << " " << spec.name << "=" << text;
      std::string why;
      EXPECT_EQ(TypedOptions::from_resolved(given).is_valid(&why), inside)
          << solver.name() << " " << spec.name << "=" << text << ": " << why;
    }
  }
}

// Each of these failed before the tables: is_valid accepted values the spec rejected (anneal iterations above the spec's limit,
// ceres_lm tolerances above 1, coeff_search grid_points above 1e6, nlopt max_evaluations above 2e9, procrustes
// kmeans_iterations above 1000, lattice_polish radius above 2^20, ...), or the spec rejected values is_valid accepted
// (anneal step_size below 1e-300, ceres_lm initial_trust_region_radius above 1e300).
TEST(OptionTables, EverySolversSpecAndIsValidAcceptTheSameValues) {
  expect_spec_and_is_valid_agree<AnnealOptions>(anneal_solver());
  expect_spec_and_is_valid_agree<CeresLmOptions>(ceres_lm_solver());
  expect_spec_and_is_valid_agree<CoeffSearchOptions>(coeff_search_solver());
  expect_spec_and_is_valid_agree<ExhaustiveOptions>(exhaustive_solver());
  expect_spec_and_is_valid_agree<IntervalBbOptions>(interval_bb_solver());
  expect_spec_and_is_valid_agree<LatticePolishOptions>(lattice_polish_solver());
  expect_spec_and_is_valid_agree<NloptOptions>(nlopt_solver());
  expect_spec_and_is_valid_agree<ProcrustesOptions>(procrustes_solver());
}

TEST(OptionTables, SpecificDriftsAreClosed) {
  CoeffSearchOptions coeff;
  coeff.grid_points = 2000000;   // spec: 2..1e6; is_valid used to allow up to LLONG_MAX
  EXPECT_FALSE(coeff.is_valid(nullptr));
  ProcrustesOptions procrustes;
  procrustes.kmeans_iterations = 1001;   // spec: 0..1000; is_valid used to allow up to INT_MAX
  EXPECT_FALSE(procrustes.is_valid(nullptr));
  AnnealOptions anneal;
  anneal.step_size = 1e-310;   // (0, 1]: is_valid accepted it, the spec's 1e-300 minimum did not
  EXPECT_TRUE(anneal.is_valid(nullptr));
  EXPECT_TRUE(resolves(anneal_solver(), {{"step_size", "1e-305"}}));
}

TEST(OptionTables, AnIntegerRangeIsComparedExactlyBeyondTwoToThe53) {
  // max_points' limit is 2^53; 2^53 + 1 rounds to 2^53 as a double and used to pass the range check.
  EXPECT_TRUE(resolves(exhaustive_solver(), {{"max_points", "9007199254740992"}}));
  EXPECT_FALSE(resolves(exhaustive_solver(), {{"max_points", "9007199254740993"}}));
}

TEST(OptionTables, RulesOverSeveralOptionsAreCheckedByIsValid) {
  ProcrustesOptions options;
  options.max_clusters = 2;
  options.min_clusters = 3;
  std::string why;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_EQ(why, "min_clusters must be in [1, 2], got 3");
}

struct ToyOptions {
  int count = 3;
  double weight = 0.5;
  bool flag = true;
  std::string name = "a";
};

TEST(OptionTables, DefaultsComeFromTheStructAndParsingFillsIt) {
  const auto table = OptionTable<ToyOptions>()
                         .integer("count", &ToyOptions::count, 0, LLONG_MAX, "a count")
                         .real("weight", &ToyOptions::weight, 0.0, 1.0, "a weight", kLowerOpen)
                         .boolean("flag", &ToyOptions::flag, "a flag")
                         .choice("name", &ToyOptions::name, {"a", "b"}, "a name");
  const std::vector<OptionSpec> specs = table.specs();
  ASSERT_EQ(specs.size(), 4u);
  EXPECT_EQ(specs[0].default_value, "3");
  EXPECT_EQ(specs[0].max_value, static_cast<double>(INT_MAX));   // clamped to the member's type
  EXPECT_EQ(specs[1].default_value, "0.5");
  EXPECT_TRUE(specs[1].min_exclusive);
  EXPECT_EQ(specs[2].default_value, "true");
  const Options resolved =
      resolve_options("toy", specs, {{"count", "7"}, {"weight", "1"}, {"flag", "no"}, {"name", "b"}});
  const ToyOptions typed = table.from_resolved(resolved);
  EXPECT_EQ(typed.count, 7);
  EXPECT_EQ(typed.weight, 1.0);
  EXPECT_FALSE(typed.flag);
  EXPECT_EQ(typed.name, "b");
  EXPECT_EQ(table.to_options(typed), resolved);
  // A value that does not fit the int member is rejected, not narrowed.
  EXPECT_THROW(resolve_options("toy", specs, {{"count", "3000000000"}}), Error);
  EXPECT_THROW(resolve_options("toy", specs, {{"weight", "0"}}), Error);
}

// ---- README tables ---------------------------------------------------------------------------------------------

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every generated block (marker comments of generated_markdown_block) in the READMEs: id -> (file, text).
std::map<std::string, std::vector<std::pair<std::string, std::string>>> readme_blocks() {
  const std::filesystem::path root = std::filesystem::path(BLOCKLAB_TEST_SAMPLES).parent_path();
  std::vector<std::filesystem::path> files = {root / "README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(root / "formats"))
    if (std::filesystem::exists(entry.path() / "README.md")) files.push_back(entry.path() / "README.md");
  const std::string begin = "<!-- generated by blocklab list --markdown: ";
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> blocks;
  for (const auto& file : files) {
    const std::string text = read_text(file);
    for (std::size_t at = text.find(begin); at != std::string::npos; at = text.find(begin, at + 1)) {
      const std::size_t id_start = at + begin.size();
      const std::string id = text.substr(id_start, text.find(" -->", id_start) - id_start);
      const std::string end = "<!-- end generated: " + id + " -->\n";
      const std::size_t stop = text.find(end, at);
      const std::string block = stop == std::string::npos ? text.substr(at) : text.substr(at, stop + end.size() - at);
      blocks[id].push_back({file.string(), block});
    }
  }
  return blocks;
}

void expect_table(const std::map<std::string, std::vector<std::pair<std::string, std::string>>>& blocks,
                  const std::string& id, const std::string& body) {
  const auto found = blocks.find(id);
  ASSERT_NE(found, blocks.end()) << "no README holds the generated table '" << id
                                 << "' (blocklab list --markdown prints it)";
  ASSERT_EQ(found->second.size(), 1u) << "the table '" << id << "' is in more than one place";
  EXPECT_EQ(found->second[0].second, generated_markdown_block(id, body))
      << found->second[0].first << ": the table '" << id
      << "' differs from `blocklab list --markdown`; paste the generated block";
}

TEST(OptionTables, EveryReadmeOptionTableIsTheGeneratedText) {
  const auto blocks = readme_blocks();
  for (const Format* format : all_formats())
    expect_table(blocks, "format " + format->name(), format_options_markdown(*format));
  for (const Solver* solver : all_solvers())
    expect_table(blocks, "solver " + solver->name(), option_table_markdown(solver->option_specs()));
}

}  // namespace
}  // namespace blocklab
