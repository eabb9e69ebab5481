// Option resolution and typed accessors (core/options.h).
#include "core/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <system_error>
#include <utility>

#include "core/error.h"
#include "core/number_text.h"

namespace blocklab {

namespace {

std::string trim_blanks(const std::string& text) {
  const auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  std::size_t begin = 0, end = text.size();
  while (begin < end && is_blank(text[begin])) ++begin;
  while (end > begin && is_blank(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

std::string lower_ascii(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Strict decimal integer: optional sign, then digits only ("1.0", "1e3", "0x10" and "" are rejected).
bool parse_integer(const std::string& raw, long long& value) {
  const std::string text = trim_blanks(raw);
  std::size_t start = 0;
  bool negative = false;
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
    negative = text[0] == '-';
    start = 1;
  }
  if (start == text.size()) return false;
  for (std::size_t i = start; i < text.size(); ++i)
    if (text[i] < '0' || text[i] > '9') return false;
  // Parse the digits including the sign so that LLONG_MIN is accepted; from_chars reports overflow as an error.
  const std::string signed_digits = (negative ? "-" : "") + text.substr(start);
  const char* first = signed_digits.data();
  const char* last = first + signed_digits.size();
  const auto result = std::from_chars(first, last, value);
  return result.ec == std::errc() && result.ptr == last;
}

// Finite decimal real ("1.5", ".5", "1e-3", "+2"); "inf", "nan" and hexadecimal forms are rejected.
bool parse_real(const std::string& raw, double& value) {
  std::string text = trim_blanks(raw);
  // from_chars does not accept a leading '+' (unlike strtod); allow it once, but not "+-1".
  if (!text.empty() && text[0] == '+') {
    text.erase(0, 1);
    if (!text.empty() && text[0] == '-') return false;
  }
  if (text.empty()) return false;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto result = std::from_chars(first, last, value, std::chars_format::general);
  if (result.ec != std::errc() || result.ptr != last) return false;
  return std::isfinite(value);   // from_chars accepts "inf" and "nan": options are always finite
}

bool parse_boolean(const std::string& raw, bool& value) {
  const std::string text = lower_ascii(trim_blanks(raw));
  if (text == "true" || text == "yes" || text == "1") { value = true; return true; }
  if (text == "false" || text == "no" || text == "0") { value = false; return true; }
  return false;
}

}  // namespace

std::string canonical_real_text(double value) {
  if (value == 0.0) value = 0.0;   // -0 and +0 are the same setting: spell both "0"
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);   // shortest round-trip form
  return std::string(buffer, result.ptr);
}

namespace {

std::string canonical_real(double value) { return canonical_real_text(value); }

bool has_range(const OptionSpec& spec) { return spec.min_value < spec.max_value; }

// An integer bound as text; bounds at or beyond the long long range are spelled as the range's end.
std::string integer_bound_text(double bound) {
  if (bound >= 9.2e18) return std::to_string(LLONG_MAX);
  if (bound <= -9.2e18) return std::to_string(LLONG_MIN);
  return std::to_string(static_cast<long long>(bound));
}

// A range bound as the integer range it allows: the largest integer <= bound (upper) or smallest >= bound (lower),
// bounds beyond the long long range at its ends.
long long integer_bound(double bound, bool upper) {
  if (bound >= 9.2e18) return LLONG_MAX;
  if (bound <= -9.2e18) return LLONG_MIN;
  return static_cast<long long>(upper ? std::floor(bound) : std::ceil(bound));
}

std::string range_text(const OptionSpec& spec) {
  if (spec.type == OptionType::integer)
    return "[" + integer_bound_text(spec.min_value) + ", " + integer_bound_text(spec.max_value) + "]";
  return (spec.min_exclusive ? "(" : "[") + canonical_real(spec.min_value) + ", " + canonical_real(spec.max_value) +
         "]";
}

bool below_minimum(const OptionSpec& spec, double value) {
  return spec.min_exclusive ? !(value > spec.min_value) : value < spec.min_value;
}

// Validates `value` against `spec` and returns its canonical spelling; throws Error("<where>: ...").
std::string normalise_value(const std::string& where, const OptionSpec& spec, const std::string& value) {
  const std::string quoted = "'" + value + "'";
  switch (spec.type) {
    case OptionType::integer: {
      long long parsed = 0;
      if (!parse_integer(value, parsed))
        fail(where, "option '" + spec.name + "' expects an integer, got " + quoted);
      // Compared as integers (a double comparison would accept 2^53 + 1 under a bound of 2^53).
      if (has_range(spec) && (parsed < integer_bound(spec.min_value, false) ||
                              parsed > integer_bound(spec.max_value, true)))
        fail(where, "option '" + spec.name + "' must be an integer in " + range_text(spec) + ", got " + quoted);
      return std::to_string(parsed);
    }
    case OptionType::real: {
      double parsed = 0.0;
      if (!parse_real(value, parsed))
        fail(where, "option '" + spec.name + "' expects a finite real number, got " + quoted);
      if (has_range(spec) && (below_minimum(spec, parsed) || parsed > spec.max_value))
        fail(where, "option '" + spec.name + "' must be a real in " + range_text(spec) + ", got " + quoted);
      return canonical_real(parsed);
    }
    case OptionType::boolean: {
      bool parsed = false;
      if (!parse_boolean(value, parsed))
        fail(where, "option '" + spec.name + "' expects a boolean (true/false/yes/no/1/0), got " + quoted);
      return parsed ? "true" : "false";
    }
    case OptionType::choice: {
      const std::string text = trim_blanks(value);
      // Choices are case-sensitive: they are names, and names are compared exactly everywhere in blocklab.
      if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
        fail(where, "option '" + spec.name + "' must be one of " + join_names(spec.choices) + ", got " + quoted);
      return text;
    }
    case OptionType::text:
      return value;   // free text is recorded verbatim
  }
  fail(where, "option '" + spec.name + "' has an unknown option type");
}

const std::string& find_value(const Options& options, const std::string& key) {
  const auto found = options.find(key);
  if (found == options.end()) fail(key, "option is missing from the resolved option map");
  return found->second;
}

}  // namespace

std::string join_names(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

std::string option_range_text(const OptionSpec& spec) {
  switch (spec.type) {
    case OptionType::choice: {
      std::string text;
      for (const std::string& choice : spec.choices) text += (text.empty() ? "" : " | ") + choice;
      return text;
    }
    case OptionType::boolean: return "true | false";
    case OptionType::text: return "";
    case OptionType::integer:
      if (!has_range(spec)) return "";
      if (spec.max_value >= 9.2e18) return ">= " + integer_bound_text(spec.min_value);
      return range_text(spec);
    case OptionType::real:
      if (!has_range(spec)) return "";
      if (spec.max_value == std::numeric_limits<double>::max())
        return std::string(spec.min_exclusive ? "finite and > " : "finite and >= ") + canonical_real(spec.min_value);
      return range_text(spec);
  }
  return "";
}

std::string to_string(OptionType type) {
  switch (type) {
    case OptionType::integer: return "integer";
    case OptionType::real: return "real";
    case OptionType::boolean: return "boolean";
    case OptionType::text: return "text";
    case OptionType::choice: return "choice";
  }
  fail("OptionType", "unknown value " + std::to_string(static_cast<int>(type)));
}

Options resolve_options(const std::string& owner, const std::vector<OptionSpec>& specs, const Options& given) {
  const std::string& where = owner;

  std::set<std::string> declared;
  std::vector<std::string> valid_names;
  for (const OptionSpec& spec : specs) {
    // The same key declared twice (e.g. a format declaring a common key) is a programming error; say so
    // instead of letting one declaration silently win.
    if (!declared.insert(spec.name).second) fail(where, "option '" + spec.name + "' is declared twice");
    valid_names.push_back(spec.name);
  }
  std::sort(valid_names.begin(), valid_names.end());

  for (const auto& entry : given)
    if (declared.count(entry.first) == 0)
      fail(where, "unknown option '" + entry.first + "'; valid options: " + join_names(valid_names));

  Options resolved;
  for (const OptionSpec& spec : specs) {
    const auto found = given.find(spec.name);
    if (found != given.end()) {
      resolved[spec.name] = normalise_value(where, spec, found->second);
    } else {
      // Defaults go through the same normalisation, so a sloppy default still hashes like the explicit value.
      resolved[spec.name] = normalise_value(where + " (default)", spec, spec.default_value);
    }
  }
  return resolved;
}

long long option_int(const Options& options, const std::string& key) {
  const std::string& text = find_value(options, key);
  long long value = 0;
  if (!parse_integer(text, value)) fail(key, "expected an integer, got '" + text + "'");
  return value;
}

double option_real(const Options& options, const std::string& key) {
  const std::string& text = find_value(options, key);
  double value = 0.0;
  if (!parse_real(text, value)) fail(key, "expected a finite real number, got '" + text + "'");
  return value;
}

bool option_bool(const Options& options, const std::string& key) {
  const std::string& text = find_value(options, key);
  bool value = false;
  if (!parse_boolean(text, value)) fail(key, "expected a boolean (true/false), got '" + text + "'");
  return value;
}

const std::string& option_text(const Options& options, const std::string& key) {
  return find_value(options, key);
}

// ---- spec builders ---------------------------------------------------------------------------------------------

namespace {

OptionSpec make_spec(std::string name, OptionType type, std::string default_value, std::string help) {
  OptionSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  spec.default_value = std::move(default_value);
  spec.help = std::move(help);
  return spec;
}

}  // namespace

OptionSpec integer_option(std::string name, long long default_value, double min_value, double max_value,
                          std::string help) {
  OptionSpec spec = make_spec(std::move(name), OptionType::integer, std::to_string(default_value), std::move(help));
  spec.min_value = min_value;
  spec.max_value = max_value;
  return spec;
}

OptionSpec real_option(std::string name, double default_value, double min_value, double max_value, std::string help) {
  OptionSpec spec = make_spec(std::move(name), OptionType::real, canonical_real(default_value), std::move(help));
  spec.min_value = min_value;
  spec.max_value = max_value;
  return spec;
}

OptionSpec bool_option(std::string name, bool default_value, std::string help) {
  return make_spec(std::move(name), OptionType::boolean, default_value ? "true" : "false", std::move(help));
}

OptionSpec choice_option(std::string name, std::string default_value, std::vector<std::string> choices,
                         std::string help) {
  OptionSpec spec = make_spec(std::move(name), OptionType::choice, std::move(default_value), std::move(help));
  spec.choices = std::move(choices);
  return spec;
}

OptionSpec text_option(std::string name, std::string default_value, std::string help) {
  return make_spec(std::move(name), OptionType::text, std::move(default_value), std::move(help));
}

// ---- is_valid checks -------------------------------------------------------------------------------------------

bool reject_option(std::string* why, const std::string& reason) {
  if (why != nullptr) *why = reason;
  return false;
}

bool check_integer_option(const char* name, long long value, long long lo, long long hi, std::string* why) {
  if (value >= lo && value <= hi) return true;
  const std::string range = hi == LLONG_MAX ? ">= " + std::to_string(lo)
                                            : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return reject_option(why, std::string(name) + " must be " + range + ", got " + std::to_string(value));
}

bool check_real_option(const char* name, double value, double lo, double hi, std::string* why, bool lower_open) {
  // Written so that NaN fails every comparison; an infinite value only passes an infinite bound.
  const bool above = lower_open ? value > lo : value >= lo;
  if (above && value <= hi) return true;
  std::string range;
  if (hi == std::numeric_limits<double>::max())   // "no upper limit" (finite values only)
    range = (lower_open ? "finite and > " : "finite and >= ") + canonical_real(lo);
  else
    range = std::string("in ") + (lower_open ? "(" : "[") + canonical_real(lo) + ", " + canonical_real(hi) + "]";
  // canonical_real is for finite values; spell the offending value with %g so NaN and inf read as such.
  return reject_option(why, std::string(name) + " must be " + range + ", got " + exact_number_text(value));
}

void fail_unknown_choice(const char* name, const std::string& value, const std::vector<std::string>& choices) {
  fail(name, "must be one of " + join_names(choices) + ", got '" + value + "'");
}

bool check_choice_option(const char* name, const std::string& value, const std::vector<std::string>& choices,
                         std::string* why) {
  if (std::find(choices.begin(), choices.end(), value) != choices.end()) return true;
  return reject_option(why, std::string(name) + " must be one of " + join_names(choices) + ", got '" + value + "'");
}

}  // namespace blocklab
