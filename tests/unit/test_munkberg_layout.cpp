// `munkberg` layout and template shapes (formats/munkberg/munkberg_layout.h, munkberg_shapes.h): each mode's named
// field widths sum to exactly 128 bits and the fields tile the block without gaps or overlaps; the bundled YAML shape
// set equals the compiled-in default bit for bit; shape-set YAML errors name the file, line and key; the side-data
// form of a shape set round-trips exactly and malformed side data is rejected.
#include <gtest/gtest.h>

#include <vector>

#include "core/error.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_shapes.h"

namespace blocklab::munkberg {
namespace {

struct Field {
  int position;
  int width;
};

// Every field of a shape mode, in layout order, from the named constants.
std::vector<Field> fields_of(Mode mode) {
  std::vector<Field> fields;
  fields.push_back({0, selector_bits(mode)});
  fields.push_back({shape_index_position(mode), kShapeIndexBits});
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    fields.push_back({base_coordinate_position(mode) + c * kBaseCoordinateBits, kBaseCoordinateBits});
  for (int e = 0; e < kLumEndpointCount; ++e)
    fields.push_back({lum_endpoint_position(mode) + e * kLumEndpointBits, kLumEndpointBits});
  int position = lum_index_position(mode);
  for (int i = 0; i < kTexels; ++i) {
    fields.push_back({position, lum_index_stored_bits(mode, i)});
    position += lum_index_stored_bits(mode, i);
  }
  for (int g = 0; g < chroma_groups(mode); ++g)
    fields.push_back({chroma_index_position(mode) + g * kChromaIndexBits, kChromaIndexBits});
  return fields;
}

TEST(MunkbergLayout, EachShapeModesFieldWidthsSumTo128) {
  for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
    int sum = 0;
    for (const Field& f : fields_of(mode)) sum += f.width;
    EXPECT_EQ(sum, 128) << "mode " << static_cast<int>(mode);
  }
  EXPECT_EQ(kShape2TotalBits, 128);
  EXPECT_EQ(kShape1TotalBits, 128);
}

TEST(MunkbergLayout, FieldsTileTheBlockWithoutGapsOrOverlaps) {
  for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
    int next = 0;
    for (const Field& f : fields_of(mode)) {
      EXPECT_EQ(f.position, next) << "mode " << static_cast<int>(mode);
      next = f.position + f.width;
    }
    EXPECT_EQ(next, kBlockBits);
  }
}

TEST(MunkbergLayout, LuminanceSplitIsThePapers80And64Bits) {
  // Section 5: 16 x 4 + 2 x 8 = 80 (shape II) and 16 x 3 + 16 = 64 (shape I; 63 stored thanks to the anchor).
  EXPECT_EQ(kShape2LuminanceBits, 16 * 4 + 2 * 8);
  EXPECT_EQ(kShape1LuminanceBits, 16 * 3 + 16);
  EXPECT_EQ(kShape1StoredLuminanceBits, 63);
  EXPECT_EQ(selector_bits(Mode::shape_ii), 1);   // the 2006 layout keeps its 127 payload bits
  // Shape I: one chroma index per texel (no subsampling); shape II: horizontal pairs.
  for (int i = 0; i < kTexels; ++i) {
    EXPECT_EQ(chroma_group_of_texel(Mode::shape_i, i), i);
    EXPECT_EQ(chroma_group_of_texel(Mode::shape_ii, i), i / 2);
  }
}

TEST(MunkbergShapes, BundledYamlEqualsTheCompiledInDefault) {
  const ShapeSet loaded = load_shape_set(default_shape_set_path());
  EXPECT_TRUE(loaded == default_shape_set());
  for (int s = 0; s < kShapeCount; ++s) {
    EXPECT_EQ(loaded.names[static_cast<std::size_t>(s)], default_shape_set().names[static_cast<std::size_t>(s)]);
    // Landmarks 0 and 1 are the stored base colours.
    const ShapeTemplate& shape = loaded.shapes[static_cast<std::size_t>(s)];
    EXPECT_EQ(shape.along(0), 0.0);
    EXPECT_EQ(shape.across(0), 0.0);
    EXPECT_EQ(shape.along(1), 1.0);
    EXPECT_EQ(shape.across(1), 0.0);
  }
}

TEST(MunkbergShapes, LandmarksInAnyFrameGiveTheSameTemplate) {
  // The square given rotated by 90 degrees, scaled by 2 and translated is still the square.
  const std::string yaml =
      "shapes:\n"
      "  - {name: a, landmarks: [[5, 5], [5, 7], [3, 7], [3, 5]]}\n"
      "  - {name: b, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: c, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: d, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: e, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: f, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: g, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n"
      "  - {name: h, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n";
  const ShapeSet set = parse_shape_set(yaml, "inline.yaml");
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    EXPECT_DOUBLE_EQ(set.shapes[0].along(k), default_shape_set().shapes[1].along(k));
    EXPECT_DOUBLE_EQ(set.shapes[0].across(k), default_shape_set().shapes[1].across(k));
  }
}

void expect_error_containing(const std::string& yaml, const std::string& needle) {
  try {
    parse_shape_set(yaml, "bad.yaml");
    ADD_FAILURE() << "no error for:\n" << yaml;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(MunkbergShapes, MalformedYamlIsRejectedNamingTheProblem) {
  std::string seven = "shapes:\n";
  for (int s = 0; s < 7; ++s) seven += "  - {name: s" + std::to_string(s) + ", landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n";
  expect_error_containing(seven, "exactly 8 shapes");
  expect_error_containing(seven + "  - {name: s7, landmarks: [[0, 0], [1, 0], [1, 1]]}\n", "shapes[7].landmarks");
  expect_error_containing(seven + "  - {name: s7, landmarks: [[0, 0], [0, 0], [1, 1], [0, 1]]}\n", "coincide");
  expect_error_containing(seven + "  - {name: s7, landmarks: [[0, 0], [1, x], [1, 1], [0, 1]]}\n", "not a finite number");
  expect_error_containing(seven + "  - {name: s0, landmarks: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n", "used twice");
  expect_error_containing(seven + "  - {name: s7, landmark: [[0, 0], [1, 0], [1, 1], [0, 1]]}\n", "unknown key 'landmark'");
  expect_error_containing("shape: []\n", "unknown key 'shape'");
  expect_error_containing(seven + "  - {name: s7, landmarks: [[0, 0], [1, x], [1, 1], [0, 1]]}\n", "bad.yaml:9:");
  EXPECT_THROW(load_shape_set("/nonexistent/shapes.yaml"), Error);
}

TEST(MunkbergShapes, SideDataRoundTripsExactlyAndRejectsMalformedValues) {
  const std::vector<double> values = shape_set_to_side_data(default_shape_set());
  ASSERT_EQ(values.size(), static_cast<std::size_t>(kShapeSideDataValues));
  EXPECT_TRUE(shape_set_from_side_data(values) == default_shape_set());
  EXPECT_TRUE(shape_set_of({}) == default_shape_set());
  EXPECT_TRUE(shape_set_of({{kShapeSideDataKey, values}}) == default_shape_set());
  EXPECT_THROW(shape_set_from_side_data(std::vector<double>(values.begin(), values.end() - 1)), Error);
  std::vector<double> bad = values;
  bad[1] = 0.5;   // along[1] of shape 0 must be 1 (landmark 1 is base colour B1)
  EXPECT_THROW(shape_set_from_side_data(bad), Error);
}

}  // namespace
}  // namespace blocklab::munkberg
