// YAML helpers shared by the munkberg format's data files (the template shape set, munkberg_shapes.h, and the DCT
// tables, dct_tables.h): error positions and strict number parsing, so both report bad input the same way.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

namespace blocklab::munkberg {

// "where:line:column" of a node (1-based), or just `where` for a node built in memory.
std::string yaml_mark_text(const std::string& where, const YAML::Node& node);

// The node as one finite double; Error "where:line:column: what: '...' is not a finite number" otherwise (no "1.5x",
// no "nan", no "inf"). Parsed in the classic locale, correctly rounded (a value written with 17 digits reads back
// to the same double).
double yaml_finite_number(const YAML::Node& node, const std::string& where, const std::string& what);

}  // namespace blocklab::munkberg
