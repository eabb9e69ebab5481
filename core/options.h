// Named string options with typed specs: the one option machinery formats, solvers and metrics share.
//
// Option values are strings (the same text on the command line, `--set key=value`, and in YAML). `resolve_options`
// validates each value against its OptionSpec and rewrites it in one canonical spelling, because a resolved map is
// what results record and what cache keys hash: "1.50" and "1.5", "yes" and "true", "+007" and "7" must give the
// same map. Canonical forms: integers in plain decimal; reals in the shortest decimal that round-trips the double
// (std::to_chars); booleans "true"/"false" (input true/false/yes/no/1/0, any case); choices exact (case matters);
// text verbatim; leading/trailing blanks dropped except for text.
#pragma once

#include <climits>
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

// ---- Spec builders: one call per entry of an option_specs() list ---------------------------------------------
// Defaults are given typed and written in their canonical spelling, so a default cannot drift from the value the
// typed options struct starts with. A range applies when min_value < max_value (OptionSpec's rule).
OptionSpec integer_option(std::string name, long long default_value, double min_value, double max_value,
                          std::string help);
OptionSpec real_option(std::string name, double default_value, double min_value, double max_value, std::string help);
OptionSpec bool_option(std::string name, bool default_value, std::string help);
OptionSpec choice_option(std::string name, std::string default_value, std::vector<std::string> choices,
                         std::string help);
OptionSpec text_option(std::string name, std::string default_value, std::string help);

// ---- Checks for typed options structs' `bool is_valid(std::string* why) const` --------------------------------
// Each returns true when the value is acceptable; otherwise false and, when `why` is not null, one reason naming
// the option ("radius must be >= 1, got 0", "step_size must be in (0, 1], got 2"). Chain them with && so the first
// failing check names its option; the reason text is only built on failure (is_valid runs once per solve).
// Integer range [lo, hi]; hi = LLONG_MAX means "no upper limit" (said as ">= lo").
bool check_integer_option(const char* name, long long value, long long lo, long long hi, std::string* why);
// Real range [lo, hi], or (lo, hi] with lower_open; NaN always fails, and so does an infinite value unless the
// bound itself is infinite. hi = DBL_MAX means "finite, no upper limit".
bool check_real_option(const char* name, double value, double lo, double hi, std::string* why,
                       bool lower_open = false);
// `value` is one of `choices` ("<name> must be one of a, b, got 'x'").
bool check_choice_option(const char* name, const std::string& value, const std::vector<std::string>& choices,
                         std::string* why);
// Any other rule: stores `reason` in *why (when not null) and returns false.
bool reject_option(std::string* why, const std::string& reason);

}  // namespace blocklab
