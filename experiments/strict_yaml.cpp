// Strict schema checks on top of yaml-cpp 0.7 (see strict_yaml.h; pitfalls listed in ECOSYSTEM.md section 3).
#include "experiments/strict_yaml.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <stdexcept>

#include "core/error.h"
#include "core/options.h"

namespace blocklab {
namespace {

// yaml-cpp tags: "?" = plain (unquoted) scalar, "!" = quoted scalar, anything else = an explicit tag such as !!str.
bool is_plain(const YAML::Node& node) { return node.Tag() == "?"; }

}  // namespace

bool is_yaml11_boolean_word(const std::string& text) {
  static const char* const kWords[] = {"y", "Y", "yes", "Yes", "YES", "n", "N", "no", "No", "NO",
                                       "on", "On", "ON", "off", "Off", "OFF"};
  return std::find(std::begin(kWords), std::end(kWords), text) != std::end(kWords);
}

bool is_radix_looking_number(const std::string& text) {
  std::size_t i = (!text.empty() && (text[0] == '-' || text[0] == '+')) ? 1 : 0;
  if (text.size() < i + 2 || text[i] != '0') return false;
  const char next = text[i + 1];
  // 0x.., 0o.., 0b..: YAML 1.1 / 1.2 radix prefixes.
  if (next == 'x' || next == 'X' || next == 'o' || next == 'O' || next == 'b' || next == 'B') return true;
  // 0 followed only by digits (042): octal in YAML 1.1. "0.5" and "0e3" are ordinary decimals and pass.
  return std::all_of(text.begin() + static_cast<long>(i) + 1, text.end(),
                     [](char c) { return (c >= '0' && c <= '9') || c == '_'; });
}

bool is_identifier(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
  });
}

StrictYaml::StrictYaml(const std::string& text, std::string source_name) : source_(std::move(source_name)) {
  try {
    root_ = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    fail(where(e.mark), "YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    fail(where(e.mark), std::string("YAML error: ") + e.msg);
  }
}

std::string StrictYaml::where(const YAML::Mark& mark) const {
  // yaml-cpp marks are 0-based; a null mark (-1) has no position.
  if (mark.line < 0) return source_;
  return source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

std::string StrictYaml::where(const YAML::Node& node) const { return where(node.Mark()); }

void StrictYaml::fail_at(const YAML::Node& node, const std::string& why) const { fail(where(node), why); }

std::vector<std::string> StrictYaml::map_keys(const YAML::Node& node, const std::string& path) const {
  if (!node.IsMap()) fail_at(node, path + " must be a map (key: value)");
  std::vector<std::string> keys;
  std::map<std::string, YAML::Mark> first_seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key = it->first;   // a copy: the iterator's proxy is a temporary
    if (!key.IsScalar()) fail_at(key, "keys of " + path + " must be plain names");
    const std::string name = key.Scalar();
    // yaml-cpp keeps both entries of a duplicated key and returns the first on lookup: reject it here.
    const auto [previous, inserted] = first_seen.emplace(name, key.Mark());
    if (!inserted) {
      fail_at(key, "duplicate key '" + name + "' in " + path + " (first at line " +
                       std::to_string(previous->second.line + 1) + ")");
    }
    keys.push_back(name);
  }
  return keys;
}

void StrictYaml::check_map(const YAML::Node& node, const std::string& path, const std::vector<std::string>& allowed,
                           const std::vector<std::string>& required) const {
  const std::vector<std::string> keys = map_keys(node, path);
  auto key_node = node.begin();
  for (const std::string& name : keys) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      fail_at(key_node->first, "unknown key '" + name + "' in " + path + "; valid keys: " + join_names(allowed));
    }
    ++key_node;
  }
  for (const std::string& name : required) {
    if (std::find(keys.begin(), keys.end(), name) == keys.end()) {
      fail_at(node, "missing required key '" + name + "' in " + path);
    }
  }
}

YAML::Node StrictYaml::child(const YAML::Node& map, const std::string& key) {
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (it->first.Scalar() == key) return it->second;
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

std::string StrictYaml::scalar(const YAML::Node& node, const std::string& path) const {
  // `key:` and `key: ~` give a null node; a value is required wherever scalar() is called.
  if (!node.IsDefined() || node.IsNull()) fail_at(node, path + " has no value");
  if (!node.IsScalar()) fail_at(node, path + " must be a single value, not a " + (node.IsMap() ? "map" : "list"));
  const std::string text = node.Scalar();
  if (is_plain(node) && is_yaml11_boolean_word(text)) {
    fail_at(node, path + ": '" + text + "' is a YAML 1.1 boolean; write true/false, or quote it if it is text");
  }
  if (is_plain(node) && is_radix_looking_number(text)) {
    fail_at(node, path + ": '" + text + "' has a leading zero (YAML 1.1 reads it as octal/hex); write the "
                                        "decimal number, or quote it if it is text");
  }
  return text;
}

std::int64_t StrictYaml::integer(const YAML::Node& node, const std::string& path) const {
  const std::string text = scalar(node, path);
  const bool quoted = !is_plain(node);
  std::size_t i = (!text.empty() && text[0] == '-') ? 1 : 0;
  const bool digits_only = text.size() > i && std::all_of(text.begin() + static_cast<long>(i), text.end(),
                                                          [](char c) { return c >= '0' && c <= '9'; });
  if (quoted || !digits_only) fail_at(node, path + " must be an integer, got '" + text + "'");
  // 19 or more digits can overflow int64: report it instead of leaking std::out_of_range.
  try {
    return std::stoll(text, nullptr, 10);
  } catch (const std::out_of_range&) {
    fail_at(node, path + ": integer '" + text + "' is out of range");
  }
}

bool StrictYaml::boolean(const YAML::Node& node, const std::string& path) const {
  const std::string text = scalar(node, path);
  if (is_plain(node) && text == "true") return true;
  if (is_plain(node) && text == "false") return false;
  fail_at(node, path + " must be true or false, got '" + text + "'");
}

std::string StrictYaml::identifier(const YAML::Node& node, const std::string& path) const {
  const std::string text = scalar(node, path);
  if (!is_identifier(text)) {
    fail_at(node, path + ": '" + text + "' is not a valid name (letters, digits, '_', '.', '-')");
  }
  return text;
}

const YAML::Node& StrictYaml::sequence(const YAML::Node& node, const std::string& path) const {
  if (!node.IsSequence()) fail_at(node, path + " must be a list");
  return node;
}

}  // namespace blocklab
