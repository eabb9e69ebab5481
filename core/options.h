// Named string options with typed specs: the one option machinery formats, solvers and metrics share.
//
// Option values are strings (the same text on the command line, `--set key=value`, and in YAML). `resolve_options`
// validates each value against its OptionSpec and rewrites it in one canonical spelling, because a resolved map is
// what results record and what cache keys hash: "1.50" and "1.5", "yes" and "true", "+007" and "7" must give the
// same map. Canonical forms: integers in plain decimal; reals in the shortest decimal that round-trips the double
// (std::to_chars); booleans "true"/"false" (input true/false/yes/no/1/0, any case); choices exact (case matters);
// text verbatim; leading/trailing blanks dropped except for text.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace blocklab {

using Options = std::map<std::string, std::string>;

enum class OptionType { integer, real, boolean, text, choice };

struct OptionSpec {
  std::string name;
  OptionType type = OptionType::text;
  std::string default_value;
  std::vector<std::string> choices;   // for OptionType::choice
  std::string help;
  double min_value = 0.0, max_value = 0.0;   // for integer/real when min_value < max_value
};

std::string to_string(OptionType type);

// Fills defaults, validates every value against its spec and rejects unknown keys:
// "<owner>: unknown option 'x'; valid options: a, b". A key declared twice in `specs` is an Error too.
Options resolve_options(const std::string& owner, const std::vector<OptionSpec>& specs, const Options& given);

// Typed accessors on a resolved option map (throw Error naming the key on a missing or malformed value).
long long option_int(const Options& options, const std::string& key);
double option_real(const Options& options, const std::string& key);
bool option_bool(const Options& options, const std::string& key);
const std::string& option_text(const Options& options, const std::string& key);

// "a, b, c"
std::string join_names(const std::vector<std::string>& names);

}  // namespace blocklab
