// The template shape set of the `munkberg` format: the compiled-in default, the YAML loader and the side-data round
// trip (formats/munkberg/munkberg_shapes.h; Munkberg et al. 2008, section 7.1, Figure 5).
#include "formats/munkberg/munkberg_shapes.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "formats/munkberg/yaml_numbers.h"

namespace blocklab::munkberg {

namespace {

using Landmarks = std::array<Point2, kShapeLandmarkCount>;

// sqrt(3) / 2 and sqrt(3) / 6 to double precision (the equilateral triangle's apex and centroid heights).
constexpr double kHalfSqrt3 = 0.8660254037844386;
constexpr double kSixthSqrt3 = 0.28867513459481287;

// The default set, in the base frame B0 = (0, 0), B1 = (1, 0). Keep in sync with shapes.yaml (a test compares them).
const std::array<std::pair<const char*, Landmarks>, kShapeCount>& default_landmarks() {
  static const std::array<std::pair<const char*, Landmarks>, kShapeCount> table = {{
      {"line", {{{0, 0}, {1, 0}, {1.0 / 3.0, 0}, {2.0 / 3.0, 0}}}},
      {"square", {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}},
      {"rectangle", {{{0, 0}, {1, 0}, {1, 0.5}, {0, 0.5}}}},
      {"triangle_centroid", {{{0, 0}, {1, 0}, {0.5, kHalfSqrt3}, {0.5, kSixthSqrt3}}}},
      {"triangle_midpoint", {{{0, 0}, {1, 0}, {0.5, 0.5}, {0.5, 0}}}},
      {"rhombus", {{{0, 0}, {1, 0}, {0.5, 0.25}, {0.5, -0.25}}}},
      {"kite", {{{0, 0}, {1, 0}, {0.25, 0.4}, {0.25, -0.4}}}},
      {"trapezoid", {{{0, 0}, {1, 0}, {0.75, 0.5}, {0.25, 0.5}}}},
  }};
  return table;
}

bool valid_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

}  // namespace

// Names are labels only: two sets are equal when their coefficients are (what the decoder uses).
bool ShapeSet::operator==(const ShapeSet& other) const {
  for (int s = 0; s < kShapeCount; ++s) {
    const std::size_t ss = static_cast<std::size_t>(s);
    for (int k = 0; k < kShapeLandmarkCount; ++k)
      if (shapes[ss].along(k) != other.shapes[ss].along(k) || shapes[ss].across(k) != other.shapes[ss].across(k))
        return false;
  }
  return true;
}

const ShapeSet& default_shape_set() {
  static const ShapeSet set = [] {
    ShapeSet out;
    for (int s = 0; s < kShapeCount; ++s) {
      const std::size_t ss = static_cast<std::size_t>(s);
      out.names[ss] = default_landmarks()[ss].first;
      out.shapes[ss] = ShapeTemplate::from_landmarks(default_landmarks()[ss].second);
    }
    return out;
  }();
  return set;
}

std::string default_shape_set_path() { return std::string(BLOCKLAB_SOURCE_DIR) + "/formats/munkberg/shapes.yaml"; }

ShapeSet parse_shape_set(const std::string& yaml_text, const std::string& where) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    fail(where, std::string("invalid YAML: ") + e.what());
  }
  if (!root.IsMap()) fail(where, "expected a map with the key 'shapes'");
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    if (key != "shapes") fail(yaml_mark_text(where, entry.first), "unknown key '" + key + "'; valid keys: shapes");
  }
  const YAML::Node list = root["shapes"];
  if (!list || !list.IsSequence()) fail(yaml_mark_text(where, root), "'shapes' must be a list");
  if (list.size() != static_cast<std::size_t>(kShapeCount))
    fail(yaml_mark_text(where, list), "'shapes' must list exactly " + std::to_string(kShapeCount) + " shapes (the " +
                                     std::to_string(kShapeIndexBits) + "-bit shape index), got " +
                                     std::to_string(list.size()));
  ShapeSet set;
  for (std::size_t s = 0; s < list.size(); ++s) {
    const YAML::Node shape = list[s];
    const std::string shape_where = "shapes[" + std::to_string(s) + "]";
    if (!shape.IsMap()) fail(yaml_mark_text(where, shape), shape_where + ": expected a map with 'name' and 'landmarks'");
    for (const auto& entry : shape) {
      const std::string key = entry.first.Scalar();
      if (key != "name" && key != "landmarks")
        fail(yaml_mark_text(where, entry.first), shape_where + ": unknown key '" + key + "'; valid keys: landmarks, name");
    }
    const YAML::Node name = shape["name"];
    if (!name || !name.IsScalar() || !valid_name(name.Scalar()))
      fail(yaml_mark_text(where, shape), shape_where + ".name: required, [A-Za-z0-9_]+");
    for (std::size_t t = 0; t < s; ++t)
      if (set.names[t] == name.Scalar())
        fail(yaml_mark_text(where, name), shape_where + ".name: '" + name.Scalar() + "' is used twice");
    const YAML::Node landmarks = shape["landmarks"];
    if (!landmarks || !landmarks.IsSequence() || landmarks.size() != static_cast<std::size_t>(kShapeLandmarkCount))
      fail(yaml_mark_text(where, shape), shape_where + ".landmarks: required, a list of " +
                                        std::to_string(kShapeLandmarkCount) + " [x, y] pairs");
    Landmarks points{};
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
      const YAML::Node pair = landmarks[k];
      const std::string what = shape_where + ".landmarks[" + std::to_string(k) + "]";
      if (!pair.IsSequence() || pair.size() != 2) fail(yaml_mark_text(where, pair), what + ": expected [x, y]");
      points[k] = {yaml_finite_number(pair[0], where, what), yaml_finite_number(pair[1], where, what)};
    }
    set.names[s] = name.Scalar();
    try {
      set.shapes[s] = ShapeTemplate::from_landmarks(points);
    } catch (const Error& e) {
      fail(yaml_mark_text(where, landmarks), shape_where + ": " + e.what());
    }
  }
  return set;
}

ShapeSet load_shape_set(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, "cannot open the shape set file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_shape_set(text.str(), path);
}

std::vector<double> shape_set_to_side_data(const ShapeSet& set) {
  std::vector<double> values;
  values.reserve(kShapeSideDataValues);
  for (const ShapeTemplate& shape : set.shapes) {
    for (int k = 0; k < kShapeLandmarkCount; ++k) values.push_back(shape.along(k));
    for (int k = 0; k < kShapeLandmarkCount; ++k) values.push_back(shape.across(k));
  }
  return values;
}

ShapeSet shape_set_from_side_data(const std::vector<double>& values) {
  const std::string where = std::string("munkberg: side data '") + kShapeSideDataKey + "'";
  if (values.size() != static_cast<std::size_t>(kShapeSideDataValues))
    fail(where, "expected " + std::to_string(kShapeSideDataValues) + " values, got " + std::to_string(values.size()));
  ShapeSet set;
  for (int s = 0; s < kShapeCount; ++s) {
    std::array<double, kShapeLandmarkCount> along{}, across{};
    for (int k = 0; k < kShapeLandmarkCount; ++k) {
      along[static_cast<std::size_t>(k)] = values[static_cast<std::size_t>(s * 8 + k)];
      across[static_cast<std::size_t>(k)] = values[static_cast<std::size_t>(s * 8 + 4 + k)];
    }
    const std::size_t ss = static_cast<std::size_t>(s);
    set.names[ss] = "shape" + std::to_string(s);
    try {
      set.shapes[ss] = ShapeTemplate::from_coefficients(along, across);
    } catch (const Error& e) {
      fail(where, "shape " + std::to_string(s) + ": " + e.what());
    }
  }
  return set;
}

ShapeSet shape_set_of(const std::map<std::string, std::vector<double>>& side_data) {
  const auto found = side_data.find(kShapeSideDataKey);
  if (found == side_data.end()) return default_shape_set();
  return shape_set_from_side_data(found->second);
}

}  // namespace blocklab::munkberg
