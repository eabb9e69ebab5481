// Named string options with typed specs: the one option machinery formats, solvers and metrics share.
//
// Option values are strings (the same text on the command line, `--set key=value`, and in YAML). `resolve_options`
// validates each value against its OptionSpec and rewrites it in one canonical spelling, because a resolved map is
// what results record and what cache keys hash: "1.50" and "1.5", "yes" and "true", "+007" and "7" must give the
// same map. Canonical forms: integers in plain decimal; reals in the shortest decimal that round-trips the double
// (std::to_chars); booleans "true"/"false" (input true/false/yes/no/1/0, any case); choices exact (case matters);
// text verbatim; leading/trailing blanks dropped except for text.
#pragma once

#include <cfloat>
#include <climits>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
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
  bool min_exclusive = false;                 // real: the range is (min_value, max_value]
};

// A finite real in its canonical option spelling (shortest round-trip decimal, "-0" -> "0").
std::string canonical_real_text(double value);

// The allowed values of `spec` as text: "[1, 64]", ">= 0", "(0, 1]", "finite and > 0", "a | b | c", "" (any).
std::string option_range_text(const OptionSpec& spec);

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

// ---- One declaration per option: OptionTable --------------------------------------------------------------------
// A typed options struct declares each of its options once, in one table: name, member, range or choices and help;
// the default is the struct's own member initialiser. From that one table come the OptionSpec list (what
// resolve_options, `blocklab list` and the README tables use), is_valid (the same ranges, for structs filled in code)
// and from_resolved (a resolved map into the struct), so the three can no longer disagree:
//
//   const OptionTable<AnnealOptions>& anneal_table() {
//     static const auto table = OptionTable<AnnealOptions>()
//         .integer("iterations", &AnnealOptions::iterations, 1, LLONG_MAX, "moves per run")
//         .real("step_size", &AnnealOptions::step_size, 0.0, 1.0, "initial move size", kLowerOpen);
//     return table;
//   }
//
// Integer ranges are also clamped to the member's type, so a value that does not fit the member is rejected when
// the map is resolved instead of being narrowed. A real range with hi = DBL_MAX means "finite, no upper limit".
// Rules that tie several options together (min <= max) are added with rule() and checked by is_valid.
constexpr bool kLowerOpen = true;
// Throws Error("<name>: must be one of a, b, got 'x'") (a value map that was not resolved).
[[noreturn]] void fail_unknown_choice(const char* name, const std::string& value,
                                      const std::vector<std::string>& choices);
// Largest integer range end that every JSON reader keeps exact (2^53): the upper limit of counts with no natural one.
constexpr long long kMaxExactInteger = 1LL << 53;

// Choice pairs (name, value) of enum values whose names come from `to_string(value)`.
template <typename Enum, std::size_t N>
std::vector<std::pair<std::string, Enum>> named_choices(const Enum (&values)[N]) {
  std::vector<std::pair<std::string, Enum>> choices;
  for (Enum value : values) choices.emplace_back(to_string(value), value);
  return choices;
}

template <typename Struct>
class OptionTable {
 public:
  template <typename Integer>
  OptionTable&& integer(const char* name, Integer Struct::*member, long long lo, long long hi, const char* help) && {
    static_assert(std::is_integral<Integer>::value && !std::is_same<Integer, bool>::value, "integer member");
    const long long type_max = static_cast<long long>(std::numeric_limits<Integer>::max());
    const long long type_min = static_cast<long long>(std::numeric_limits<Integer>::lowest());
    hi = hi < type_max ? hi : type_max;
    lo = lo > type_min ? lo : type_min;
    Entry entry;
    entry.spec = integer_option(name, 0, static_cast<double>(lo), static_cast<double>(hi), help);
    entry.default_text = [member](const Struct& s) { return std::to_string(static_cast<long long>(s.*member)); };
    entry.check = [name, member, lo, hi](const Struct& s, std::string* why) {
      return check_integer_option(name, static_cast<long long>(s.*member), lo, hi, why);
    };
    entry.read = [name, member](const Options& o, Struct& s) {
      s.*member = static_cast<Integer>(option_int(o, name));
    };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  OptionTable&& real(const char* name, double Struct::*member, double lo, double hi, const char* help,
                     bool lower_open = false) && {
    Entry entry;
    entry.spec = real_option(name, 0.0, lo, hi, help);
    entry.spec.min_exclusive = lower_open;
    entry.default_text = [member](const Struct& s) { return canonical_real_text(s.*member); };
    entry.check = [name, member, lo, hi, lower_open](const Struct& s, std::string* why) {
      return check_real_option(name, s.*member, lo, hi, why, lower_open);
    };
    entry.read = [name, member](const Options& o, Struct& s) { s.*member = option_real(o, name); };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  OptionTable&& boolean(const char* name, bool Struct::*member, const char* help) && {
    Entry entry;
    entry.spec = bool_option(name, false, help);
    entry.default_text = [member](const Struct& s) { return std::string(s.*member ? "true" : "false"); };
    entry.check = [](const Struct&, std::string*) { return true; };
    entry.read = [name, member](const Options& o, Struct& s) { s.*member = option_bool(o, name); };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  OptionTable&& text(const char* name, std::string Struct::*member, const char* help) && {
    Entry entry;
    entry.spec = text_option(name, "", help);
    entry.default_text = [member](const Struct& s) { return s.*member; };
    entry.check = [](const Struct&, std::string*) { return true; };
    entry.read = [name, member](const Options& o, Struct& s) { s.*member = option_text(o, name); };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  // A choice held as its name.
  OptionTable&& choice(const char* name, std::string Struct::*member, std::vector<std::string> choices,
                       const char* help) && {
    Entry entry;
    entry.spec = choice_option(name, "", choices, help);
    entry.default_text = [member](const Struct& s) { return s.*member; };
    entry.check = [name, member, choices](const Struct& s, std::string* why) {
      return check_choice_option(name, s.*member, choices, why);
    };
    entry.read = [name, member](const Options& o, Struct& s) { s.*member = option_text(o, name); };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  // A choice held as an enum (or any comparable value): each choice's name and value.
  template <typename Value>
  OptionTable&& choice(const char* name, Value Struct::*member, std::vector<std::pair<std::string, Value>> choices,
                       const char* help) && {
    std::vector<std::string> names;
    for (const auto& choice : choices) names.push_back(choice.first);
    Entry entry;
    entry.spec = choice_option(name, "", names, help);
    entry.default_text = [member, choices](const Struct& s) {
      for (const auto& choice : choices)
        if (choice.second == s.*member) return choice.first;
      return std::string("?");
    };
    entry.check = [name, member, choices, names](const Struct& s, std::string* why) {
      for (const auto& choice : choices)
        if (choice.second == s.*member) return true;
      return reject_option(why, std::string(name) + " must be one of " + join_names(names));
    };
    entry.read = [name, member, choices, names](const Options& o, Struct& s) {
      const std::string& text = option_text(o, name);
      for (const auto& choice : choices)
        if (choice.first == text) {
          s.*member = choice.second;
          return;
        }
      fail_unknown_choice(name, text, names);
    };
    entries_.push_back(std::move(entry));
    return std::move(*this);
  }

  // A rule over several options, checked by is_valid after the per-option ranges.
  OptionTable&& rule(std::function<bool(const Struct&, std::string*)> check) && {
    rules_.push_back(std::move(check));
    return std::move(*this);
  }

  // The OptionSpec list in declaration order, defaults taken from `defaults`.
  std::vector<OptionSpec> specs(const Struct& defaults = Struct{}) const {
    std::vector<OptionSpec> out;
    for (const Entry& entry : entries_) {
      out.push_back(entry.spec);
      out.back().default_value = entry.default_text(defaults);
    }
    return out;
  }
  // Every declared range and rule; the first failing one names its option in *why.
  bool is_valid(const Struct& options, std::string* why) const {
    for (const Entry& entry : entries_)
      if (!entry.check(options, why)) return false;
    for (const auto& check : rules_)
      if (!check(options, why)) return false;
    return true;
  }
  // A resolved option map (every declared key present) into the struct; members outside the table keep `start`'s.
  Struct from_resolved(const Options& resolved, Struct start = Struct{}) const {
    for (const Entry& entry : entries_) entry.read(resolved, start);
    return start;
  }
  // The struct as an option map in canonical spelling (the inverse of from_resolved).
  Options to_options(const Struct& options) const {
    Options out;
    for (const Entry& entry : entries_) out[entry.spec.name] = entry.default_text(options);
    return out;
  }

 private:
  struct Entry {
    OptionSpec spec;
    std::function<std::string(const Struct&)> default_text;
    std::function<bool(const Struct&, std::string*)> check;
    std::function<void(const Options&, Struct&)> read;
  };
  std::vector<Entry> entries_;
  std::vector<std::function<bool(const Struct&, std::string*)>> rules_;
};

}  // namespace blocklab
