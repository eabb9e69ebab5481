// The template shape set of the `munkberg` format (Munkberg et al. 2008, section 7.1 and Figure 5: "a scaled and
// rotated template shape chosen out of the set of pre-defined shapes ... The transform parameters ... are implicitly
// encoded by storing the location of two base colors").
//
// Figure 5's coordinates are not in the paper text; blocklab's default set of kShapeCount = 8 shapes is listed in
// formats/munkberg/shapes.yaml (and compiled in, identical: a test checks it) with the rationale in the README.
// Each shape has four landmarks; landmarks 0 and 1 are the stored base colours
// (formats/munkberg/shape_fit/shape_fit_problem.h frame).
//
// A set can be loaded from YAML (format option `shapes`), and it travels with the encoded texture as side data
// (key kShapeSideDataKey: for each shape, along[0..3] then across[0..3]), so the decoder of a file never depends on
// a file path and the bytes decode the same everywhere.
//
// YAML schema (strict: unknown keys, a wrong count or a non-number are Errors naming file:line:column):
//   shapes:                       # exactly 8 entries, in shape-index order
//     - name: line                # [A-Za-z0-9_]+
//       landmarks: [[0, 0], [1, 0], [0.333333333333333333, 0], [0.666666666666666667, 0]]
// Landmarks are in any frame; ShapeTemplate::from_landmarks maps landmark 0 to B0 and landmark 1 to B1.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/munkberg/munkberg_layout.h"

namespace blocklab::munkberg {

constexpr const char* kShapeSideDataKey = "munkberg_shapes";
constexpr int kShapeSideDataValues = kShapeCount * 2 * kShapeLandmarkCount;   // 64

struct ShapeSet {
  std::array<std::string, kShapeCount> names;
  std::array<ShapeTemplate, kShapeCount> shapes;

  // Equal coefficients (names are labels and do not travel in side data).
  bool operator==(const ShapeSet& other) const;
};

// The compiled-in default set (the content of formats/munkberg/shapes.yaml).
const ShapeSet& default_shape_set();
// Path of the bundled YAML copy of the default set (BLOCKLAB_SOURCE_DIR/formats/munkberg/shapes.yaml).
std::string default_shape_set_path();

// Parses a shape-set YAML file / text. `where` names the source in messages. Throws Error on any schema violation.
ShapeSet load_shape_set(const std::string& path);
ShapeSet parse_shape_set(const std::string& yaml_text, const std::string& where);

// Side data round trip: 64 doubles (coefficients exactly as stored in the ShapeTemplates).
std::vector<double> shape_set_to_side_data(const ShapeSet& set);
// Throws Error("munkberg: side data 'munkberg_shapes': ...") on a wrong count or invalid coefficients.
ShapeSet shape_set_from_side_data(const std::vector<double>& values);

// The shape set of an encoded texture: from its side data when present, otherwise the default set.
ShapeSet shape_set_of(const std::map<std::string, std::vector<double>>& side_data);

}  // namespace blocklab::munkberg
