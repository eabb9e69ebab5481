// Side data of the `wang` format (formats/wang/wang_side_data.h).
#include "formats/wang/wang_side_data.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace blocklab {
namespace wang {

namespace {

constexpr double kMaxMagnitude = 1e30;
constexpr const char* kLuminanceZones = "luminance_zones";
constexpr const char* kLuminanceRange = "luminance_range";
constexpr const char* kResidualZones = "residual_zones";
constexpr const char* kLuminanceSplitError = "luminance_split_error";
constexpr const char* kResidualSplitError = "residual_split_error";

std::string show(const std::vector<double>& values) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (std::size_t k = 0; k < values.size(); ++k) out << (k ? ", " : "") << values[k];
  out << "]";
  return out.str();
}

// The values of `key`: present, `count` of them, finite, |v| <= 1e30 and (when `ordered`) non-decreasing.
const std::vector<double>& require(const EncodedTexture& texture, const std::string& key, std::size_t count,
                                   bool ordered, const std::string& who) {
  const auto found = texture.side_data.find(key);
  if (found == texture.side_data.end()) fail(who, "side data '" + key + "' is missing");
  const std::vector<double>& values = found->second;
  if (values.size() != count)
    fail(who, "side data '" + key + "' must hold " + std::to_string(count) + " values, got " + show(values));
  for (std::size_t k = 0; k < count; ++k) {
    // NaN fails the comparison.
    if (!(std::abs(values[k]) <= kMaxMagnitude))
      fail(who, "side data '" + key + "' " + show(values) + " has a value that is not finite or exceeds 1e30");
    if (ordered && k > 0 && !(values[k - 1] <= values[k]))
      fail(who, "side data '" + key + "' must be non-decreasing, got " + show(values));
  }
  return values;
}

std::vector<std::string> expected_keys(LuminanceSplit split, Residual residual) {
  std::vector<std::string> keys;
  keys.push_back(split == LuminanceSplit::two_zones ? kLuminanceZones : kLuminanceRange);
  if (split == LuminanceSplit::two_zones) keys.push_back(kLuminanceSplitError);
  if (residual != Residual::none) {
    keys.push_back(kResidualZones);
    keys.push_back(kResidualSplitError);
  }
  return keys;
}

}  // namespace

void store_side_data(const SideData& data, LuminanceSplit split, Residual residual, EncodedTexture& texture) {
  const Zones& z = data.zones;
  if (split == LuminanceSplit::two_zones) {
    texture.side_data[kLuminanceZones] = {z.tmin, z.t1, z.tmax};
    if (data.has_split_records)
      texture.side_data[kLuminanceSplitError] = {data.luminance_split_eq2, data.luminance_split_quantisation};
  } else {
    texture.side_data[kLuminanceRange] = {z.tmin, z.tmax};
  }
  if (residual != Residual::none) {
    texture.side_data[kResidualZones] = {z.smin, z.s1, z.s2, z.smax};
    if (data.has_split_records)
      texture.side_data[kResidualSplitError] = {data.residual_split_eq2, data.residual_split_quantisation};
  }
}

SideData read_side_data(const EncodedTexture& texture, LuminanceSplit split, Residual residual,
                        const std::string& who) {
  const std::vector<std::string> keys = expected_keys(split, residual);
  for (const auto& entry : texture.side_data) {
    bool known = false;
    for (const std::string& key : keys) known = known || key == entry.first;
    if (!known) fail(who, "unexpected side data '" + entry.first + "'; expected: " + join_names(keys));
  }
  SideData data;
  Zones& z = data.zones;
  if (split == LuminanceSplit::two_zones) {
    const std::vector<double>& zones = require(texture, kLuminanceZones, 3, true, who);
    z.tmin = zones[0];
    z.t1 = zones[1];
    z.tmax = zones[2];
    if (texture.side_data.count(kLuminanceSplitError)) {
      const std::vector<double>& record = require(texture, kLuminanceSplitError, 2, false, who);
      data.has_split_records = true;
      data.luminance_split_eq2 = record[0];
      data.luminance_split_quantisation = record[1];
    }
  } else {
    const std::vector<double>& range = require(texture, kLuminanceRange, 2, true, who);
    z.tmin = range[0];
    z.t1 = range[0];
    z.tmax = range[1];
  }
  if (residual != Residual::none) {
    const std::vector<double>& zones = require(texture, kResidualZones, 4, true, who);
    z.smin = zones[0];
    z.s1 = zones[1];
    z.s2 = zones[2];
    z.smax = zones[3];
    if (texture.side_data.count(kResidualSplitError)) {
      const std::vector<double>& record = require(texture, kResidualSplitError, 2, false, who);
      data.has_split_records = true;
      data.residual_split_eq2 = record[0];
      data.residual_split_quantisation = record[1];
    }
  }
  return data;
}

}  // namespace wang
}  // namespace blocklab
