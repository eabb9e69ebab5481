// Strict reading of a yaml-cpp node tree against a schema the caller declares.
//
// yaml-cpp 0.7 parses YAML 1.2-ish syntax but keeps duplicate keys, ignores misspelled ones and leaves the meaning
// of plain scalars to the reader (ECOSYSTEM.md section 3). These helpers reject unknown and duplicate keys, missing
// required keys, YAML-1.1 boolean words and octal-looking numbers in unquoted scalars, and report every problem as
// "<file>:<line>:<col>: <problem> in <yaml path>" (lines and columns 1-based).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace blocklab {

class StrictYaml {
 public:
  // Parses `text`; a syntax error throws Error("<source>:<line>:<col>: YAML syntax error: <reason>").
  StrictYaml(const std::string& text, std::string source_name);

  const YAML::Node& root() const { return root_; }
  const std::string& source_name() const { return source_; }

  // "<source>:<line>:<col>" of a node (1-based).
  std::string where(const YAML::Node& node) const;
  std::string where(const YAML::Mark& mark) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& why) const;

  // The node must be a map whose keys are unique plain scalars from `allowed`; every key in `required` must be
  // present. `path` names the map in messages ("the top level", "formats[1]").
  void check_map(const YAML::Node& node, const std::string& path, const std::vector<std::string>& allowed,
                 const std::vector<std::string>& required) const;
  // The node must be a map with unique scalar keys (any names); returns the keys in document order.
  std::vector<std::string> map_keys(const YAML::Node& node, const std::string& path) const;
  // Values of a checked map by key (the map has no duplicates once checked).
  static YAML::Node child(const YAML::Node& map, const std::string& key);

  // Scalars. `path` is the YAML path of the value ("seed", "formats[0].options.seed").
  std::string scalar(const YAML::Node& node, const std::string& path) const;   // any non-null, non-surprising scalar
  std::int64_t integer(const YAML::Node& node, const std::string& path) const;   // plain decimal only
  bool boolean(const YAML::Node& node, const std::string& path) const;           // true / false only
  std::string identifier(const YAML::Node& node, const std::string& path) const; // [A-Za-z0-9_.-]+
  const YAML::Node& sequence(const YAML::Node& node, const std::string& path) const;  // must be a list

 private:
  std::string source_;
  YAML::Node root_;
};

// True for the YAML-1.1 boolean words (y, yes, on, off, n, no in their three spellings).
bool is_yaml11_boolean_word(const std::string& text);
// True for unquoted numbers a YAML 1.1 reader would take as octal / hex / binary (042, -07, 0x1F, 0o17, 0b1).
bool is_radix_looking_number(const std::string& text);
// True for [A-Za-z0-9_.-]+.
bool is_identifier(const std::string& text);

}  // namespace blocklab
