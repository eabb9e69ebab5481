// Side data of the `banterle` format (formats/banterle/banterle_side_data.h).
#include "formats/banterle/banterle_side_data.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr double kMaxResidualMagnitude = 1e30;

std::string show(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

const std::vector<double>& require_key(const EncodedTexture& texture, const std::string& key, std::size_t count,
                                       const std::string& who) {
  const auto found = texture.side_data.find(key);
  if (found == texture.side_data.end()) fail(who, "side data '" + key + "' is missing");
  if (found->second.size() != count)
    fail(who, "side data '" + key + "' must hold " + std::to_string(count) + " value(s), got " +
                  std::to_string(found->second.size()));
  return found->second;
}

double require_positive(const EncodedTexture& texture, const std::string& key, const std::string& who) {
  const double value = require_key(texture, key, 1, who)[0];
  // NaN fails `> 0`; infinity fails isfinite.
  if (!(value > 0.0) || !std::isfinite(value))
    fail(who, "side data '" + key + "' must be finite and > 0, got " + show(value));
  return value;
}

}  // namespace

void store_banterle_side_data(const BanterleSideData& data, EncodedTexture& texture) {
  texture.side_data["alpha"] = {data.alpha};
  texture.side_data["l_white"] = {data.l_white};
  texture.side_data["mean"] = {data.mean};
  if (data.has_residual)
    texture.side_data["residual_range"] = {static_cast<double>(data.residual.lo), static_cast<double>(data.residual.hi)};
}

BanterleSideData read_banterle_side_data(const EncodedTexture& texture, bool with_residual, const std::string& who) {
  const std::vector<std::string> keys = with_residual
                                            ? std::vector<std::string>{"alpha", "l_white", "mean", "residual_range"}
                                            : std::vector<std::string>{"alpha", "l_white", "mean"};
  for (const auto& entry : texture.side_data) {
    bool known = false;
    for (const std::string& key : keys) known = known || key == entry.first;
    if (!known)
      fail(who, "unexpected side data '" + entry.first + "' for bpp " + (with_residual ? "8" : "4") +
                    "; expected: " + join_names(keys));
  }
  BanterleSideData data;
  data.alpha = require_positive(texture, "alpha", who);
  data.l_white = require_positive(texture, "l_white", who);
  data.mean = require_positive(texture, "mean", who);
  data.has_residual = with_residual;
  if (with_residual) {
    const std::vector<double>& range = require_key(texture, "residual_range", 2, who);
    for (double value : range)
      // NaN fails the comparison; the bound keeps lo + (hi - lo) * a finite in float.
      if (!(std::abs(value) <= kMaxResidualMagnitude))
        fail(who, "side data 'residual_range' value " + show(value) + " is not finite or exceeds 1e30 in magnitude");
    if (!(range[0] <= range[1]))
      fail(who, "side data 'residual_range' must have lo <= hi, got [" + show(range[0]) + ", " + show(range[1]) + "]");
    data.residual.lo = static_cast<float>(range[0]);
    data.residual.hi = static_cast<float>(range[1]);
  }
  return data;
}

}  // namespace blocklab
