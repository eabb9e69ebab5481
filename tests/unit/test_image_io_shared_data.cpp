// read_image on the real third-party images of shared/data (MANIFEST.md): every file loads with the size the
// manifest gives, and its luminance statistics (Y min / median / max, computed the way the manifest says) match
// the manifest's three significant figures, which checks the decoded values and not only the size. Orientation
// is checked on images whose layout is documented (black bands, black last row/column). Skipped when the shared
// data folder is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"

namespace blocklab {
namespace {

const std::string kSharedData = BLOCKLAB_TEST_SHARED_DATA;

struct ManifestEntry {
  std::string relative_path;  // e.g. "hdr/Desk.exr"
  int width = 0;
  int height = 0;
  double y_min = 0, y_median = 0, y_max = 0;
};

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// Parses the statistics tables of MANIFEST.md: "| `hdr/X.exr` | WxH... | type | Ymin | Ymedian | Ymax | ...".
std::vector<ManifestEntry> read_manifest() {
  std::ifstream in(kSharedData + "/MANIFEST.md");
  std::vector<ManifestEntry> entries;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream row(line.substr(1));
    std::string cell;
    while (std::getline(row, cell, '|')) cells.push_back(trim(cell));
    if (cells.size() < 6) continue;
    ManifestEntry entry;
    entry.relative_path = cells[0].substr(1, cells[0].size() - 2);
    // Only the statistics tables have "WxH" in the second column (the source tables have a GitHub/Debian source).
    if (std::sscanf(cells[1].c_str(), "%dx%d", &entry.width, &entry.height) != 2) continue;
    entry.y_min = std::strtod(cells[3].c_str(), nullptr);
    entry.y_median = std::strtod(cells[4].c_str(), nullptr);
    entry.y_max = std::strtod(cells[5].c_str(), nullptr);
    entries.push_back(entry);
  }
  return entries;
}

// Luminance weights = Y row of the RGB -> XYZ matrix built from chromaticities (SMPTE RP 177 construction):
// primaries' XYZ columns (x/y, 1, z/y) scaled so that RGB = (1,1,1) maps to the white point with Y = 1.
std::array<double, 3> luminance_weights(const std::array<float, 8>& c) {
  double m[3][3];
  for (int i = 0; i < 3; ++i) {
    const double x = c[2 * i], y = c[2 * i + 1];
    m[0][i] = x / y;
    m[1][i] = 1.0;
    m[2][i] = (1.0 - x - y) / y;
  }
  const double white[3] = {c[6] / c[7], 1.0, (1.0 - c[6] - c[7]) / c[7]};
  auto det3 = [](double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det3(m);
  std::array<double, 3> scale{};
  for (int col = 0; col < 3; ++col) {  // Cramer's rule for m * scale = white
    double replaced[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) replaced[r][k] = k == col ? white[r] : m[r][k];
    scale[col] = det3(replaced) / d;
  }
  return scale;  // Y row is (1 * s0, 1 * s1, 1 * s2)
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

struct LuminanceStats {
  double min, median, max;
};

LuminanceStats luminance_stats(const Image& image) {
  std::array<double, 3> weights{0.2126, 0.7152, 0.0722};
  if (image.metadata.chromaticities) weights = luminance_weights(*image.metadata.chromaticities);
  std::vector<double> values;
  values.reserve(image.texel_count());
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const float* t = &image.pixels[4 * i];
    double y;
    if (image.channels == 1) {
      y = t[0];  // luminance-only files: the Y channel itself
    } else if (!image.metadata.is_hdr) {
      y = weights[0] * srgb_to_linear(t[0]) + weights[1] * srgb_to_linear(t[1]) + weights[2] * srgb_to_linear(t[2]);
    } else {
      y = weights[0] * t[0] + weights[1] * t[1] + weights[2] * t[2];
    }
    if (std::isfinite(y)) values.push_back(y);
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return {*std::min_element(values.begin(), values.end()), *middle, *std::max_element(values.begin(), values.end())};
}

// The manifest prints three significant figures: allow the rounding of the third digit.
void expect_three_figures(double expected, double actual, const std::string& what) {
  EXPECT_NEAR(actual, expected, 0.006 * std::fabs(expected) + 1e-9) << what;
}

class SharedData : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::is_directory(kSharedData + "/hdr") || !std::filesystem::is_directory(kSharedData + "/ldr")) {
      GTEST_SKIP() << "shared data folder not found at " << kSharedData;
    }
  }
  Image load(const std::string& relative) { return read_image(kSharedData + "/" + relative); }
};

TEST_F(SharedData, ManifestListsEveryImageInTheFolders) {
  const auto entries = read_manifest();
  std::map<std::string, bool> listed;
  for (const auto& entry : entries) listed[entry.relative_path] = true;
  EXPECT_EQ(entries.size(), 56u);  // 28 HDR + 28 LDR
  for (const auto& file : std::filesystem::recursive_directory_iterator(kSharedData)) {
    if (!file.is_regular_file() || file.path().filename() == "MANIFEST.md") continue;
    const std::string relative = std::filesystem::relative(file.path(), kSharedData).string();
    EXPECT_TRUE(listed.count(relative)) << relative << " is not in MANIFEST.md";
  }
}

TEST_F(SharedData, EveryImageLoadsWithTheManifestSizeAndLuminanceStatistics) {
  const auto entries = read_manifest();
  ASSERT_FALSE(entries.empty());
  for (const auto& entry : entries) {
    SCOPED_TRACE(entry.relative_path);
    Image image;
    ASSERT_NO_THROW(image = load(entry.relative_path));
    EXPECT_EQ(image.width, entry.width);
    EXPECT_EQ(image.height, entry.height);
    ASSERT_EQ(image.pixels.size(), image.texel_count() * 4);
    EXPECT_EQ(image.metadata.source_path, kSharedData + "/" + entry.relative_path);
    const bool is_hdr_folder = entry.relative_path.rfind("hdr/", 0) == 0;
    EXPECT_EQ(image.metadata.is_hdr, is_hdr_folder);
    const LuminanceStats stats = luminance_stats(image);
    expect_three_figures(entry.y_min, stats.min, "Y min");
    expect_three_figures(entry.y_median, stats.median, "Y median");
    expect_three_figures(entry.y_max, stats.max, "Y max");
  }
}

TEST_F(SharedData, LuminanceOnlyGardenHasOneChannelCopiedToRgb) {
  const Image image = load("hdr/Garden.exr");
  EXPECT_EQ(image.channels, 1);
  EXPECT_EQ(image.width, 874);
  EXPECT_EQ(image.height, 493);
  EXPECT_EQ(image.metadata.pixel_type, "half");
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    ASSERT_EQ(image.pixels[4 * i], image.pixels[4 * i + 1]);
    ASSERT_EQ(image.pixels[4 * i], image.pixels[4 * i + 2]);
    ASSERT_EQ(image.pixels[4 * i + 3], 1.0f);
  }
}

TEST_F(SharedData, SubsampledLuminanceChromaMtTamNorthDecodesToColour) {
  const Image image = load("hdr/MtTamNorth.exr");
  EXPECT_EQ(image.width, 1198);
  EXPECT_EQ(image.height, 796);
  EXPECT_EQ(image.channels, 3);
  // Reconstructed chroma must give real colour, not grey: some texels have clearly different R and B.
  std::size_t coloured = 0;
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const float r = image.pixels[4 * i], b = image.pixels[4 * i + 2];
    if (std::fabs(r - b) > 0.1f * std::max(r, b)) ++coloured;
  }
  EXPECT_GT(coloured, image.texel_count() / 20);
}

TEST_F(SharedData, OffsetDataWindowIsTheImage) {
  const Image image = load("hdr/v2_LowResLeftView_composited.exr");
  EXPECT_EQ(image.width, 1022);
  EXPECT_EQ(image.height, 574);
  EXPECT_EQ(image.channels, 4);
}

TEST_F(SharedData, ChromaticitiesAttributeIsKept) {
  const Image carrots = load("hdr/Carrots.exr");
  ASSERT_TRUE(carrots.metadata.chromaticities.has_value());
  // ACES AP0: red (0.7347, 0.2653), green (0, 1), blue (0.0001, -0.077), white (0.32168, 0.33767).
  const std::array<float, 8> ap0{0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.077f, 0.32168f, 0.33767f};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR((*carrots.metadata.chromaticities)[i], ap0[i], 1e-4) << i;

  const Image tree = load("hdr/Tree.exr");
  ASSERT_TRUE(tree.metadata.chromaticities.has_value());
  EXPECT_NEAR((*tree.metadata.chromaticities)[0], 0.64f, 0.02f);  // close to (not equal to) Rec.709 red x

  EXPECT_FALSE(load("hdr/Desk.exr").metadata.chromaticities.has_value());
}

TEST_F(SharedData, PixelTypesAndChannelsFollowTheSource) {
  const Image desk = load("hdr/Desk.exr");
  EXPECT_EQ(desk.metadata.container, "exr");
  EXPECT_EQ(desk.metadata.pixel_type, "half");
  EXPECT_EQ(desk.channels, 4);
  EXPECT_EQ(load("hdr/blender_world_city.exr").metadata.pixel_type, "float");
  EXPECT_EQ(load("hdr/Cannon.exr").channels, 3);
  const Image grace = load("hdr/grace.hdr");
  EXPECT_EQ(grace.metadata.container, "hdr");
  EXPECT_EQ(grace.metadata.pixel_type, "rgbe");
  const Image base = load("ldr/textures/ldr-rgba-base.png");
  EXPECT_EQ(base.channels, 4);
  EXPECT_EQ(base.metadata.container, "png");
  EXPECT_EQ(base.metadata.pixel_type, "uint8");
  EXPECT_EQ(load("ldr/kodak/kodim24.png").channels, 3);
}

TEST_F(SharedData, NegativeValuesAreLoadedUnchanged) {
  const Image desk = load("hdr/Desk.exr");
  std::size_t negative_texels = 0;
  for (std::size_t i = 0; i < desk.texel_count(); ++i) {
    const float* t = &desk.pixels[4 * i];
    if (t[0] < 0 || t[1] < 0 || t[2] < 0) ++negative_texels;
  }
  EXPECT_EQ(negative_texels, 9354u);  // MANIFEST.md: "negative channel: 9354 px"
}

bool row_is_black(const Image& image, int y) {
  for (int x = 0; x < image.width; ++x)
    for (int c = 0; c < 3; ++c)
      if (image.texel(x, y)[c] != 0.0f) return false;
  return true;
}
bool column_is_black(const Image& image, int x) {
  for (int y = 0; y < image.height; ++y)
    for (int c = 0; c < 3; ++c)
      if (image.texel(x, y)[c] != 0.0f) return false;
  return true;
}

TEST_F(SharedData, KodakBlackLineIsTheLastRowOrColumn) {
  const Image landscape = load("ldr/kodak/kodim01.png");
  EXPECT_TRUE(row_is_black(landscape, landscape.height - 1));
  EXPECT_FALSE(row_is_black(landscape, 0));
  const Image portrait = load("ldr/kodak/kodim04.png");
  EXPECT_TRUE(column_is_black(portrait, portrait.width - 1));
  EXPECT_FALSE(column_is_black(portrait, 0));
}

TEST_F(SharedData, FlatRadianceScanlinesAreTopRowFirst) {
  const Image warwick = load("hdr/CS_Warwick.hdr");  // bottom rows are a black band
  EXPECT_EQ(warwick.metadata.pixel_type, "rgbe");
  EXPECT_FALSE(row_is_black(warwick, 0));
  // The band holds exact zeros and values at the RGBE floor (~8.5e-11); the very last row is below 1e-9.
  float bottom_max = 0.0f;
  for (int x = 0; x < warwick.width; ++x)
    for (int c = 0; c < 3; ++c) bottom_max = std::max(bottom_max, warwick.texel(x, warwick.height - 1)[c]);
  EXPECT_LT(bottom_max, 1e-9f);
}

TEST_F(SharedData, RadianceHeaderNeedNotStartWithTheProgramLine) {
  const Image memorial = load("hdr/memorial.hdr");  // starts with "VIEW=", "#?RADIANCE" is the second line
  EXPECT_EQ(memorial.width, 512);
  EXPECT_EQ(memorial.height, 768);
}

}  // namespace
}  // namespace blocklab
