// YAML helpers of the munkberg data files (formats/munkberg/yaml_numbers.h).
#include "formats/munkberg/yaml_numbers.h"

#include <cmath>
#include <locale>
#include <sstream>

#include "core/error.h"

namespace blocklab::munkberg {

std::string yaml_mark_text(const std::string& where, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  // yaml-cpp marks are 0-based; -1 means "no position" (a node built in memory).
  if (mark.line < 0) return where;
  return where + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

double yaml_finite_number(const YAML::Node& node, const std::string& where, const std::string& what) {
  if (!node.IsScalar()) fail(yaml_mark_text(where, node), what + ": expected a number");
  const std::string text = node.Scalar();
  std::istringstream stream(text);
  stream.imbue(std::locale::classic());
  double value = 0.0;
  stream >> value;
  // The whole scalar must be one finite number (no "1.5x", no "nan", no "inf").
  if (stream.fail() || !stream.eof() || !std::isfinite(value))
    fail(yaml_mark_text(where, node), what + ": '" + text + "' is not a finite number");
  return value;
}

}  // namespace blocklab::munkberg
