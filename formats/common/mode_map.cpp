// Mode-usage shares and colour-coded mode maps of any block format (formats/common/mode_map.h).
#include "formats/common/mode_map.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kWhere = "mode map";

// Okabe & Ito 2008, sRGB 8-bit values / 255 (orange E69F00, sky blue 56B4E9, bluish green 009E73, yellow F0E442,
// blue 0072B2, vermillion D55E00, reddish purple CC79A7, grey 999999).
constexpr std::array<ModeColour, 8> kOkabeIto = {{
    {230 / 255.0f, 159 / 255.0f, 0 / 255.0f},
    {86 / 255.0f, 180 / 255.0f, 233 / 255.0f},
    {0 / 255.0f, 158 / 255.0f, 115 / 255.0f},
    {240 / 255.0f, 228 / 255.0f, 66 / 255.0f},
    {0 / 255.0f, 114 / 255.0f, 178 / 255.0f},
    {213 / 255.0f, 94 / 255.0f, 0 / 255.0f},
    {204 / 255.0f, 121 / 255.0f, 167 / 255.0f},
    {153 / 255.0f, 153 / 255.0f, 153 / 255.0f},
}};
constexpr std::array<const char*, 8> kOkabeItoNames = {"orange", "sky blue",   "bluish green",   "yellow",
                                                       "blue",   "vermillion", "reddish purple", "grey"};

std::size_t block_count(const EncodedTexture& texture) {
  return static_cast<std::size_t>((texture.width + 3) / 4) * static_cast<std::size_t>((texture.height + 3) / 4);
}

// The recorded modes, checked against the texture's block count and the format's mode list.
const std::vector<std::uint8_t>& checked_modes(const EncodedTexture& texture, const std::vector<std::string>& names) {
  if (texture.block_modes.empty())
    fail(kWhere, "the '" + texture.format + "' texture records no block modes (only a fresh encode does)");
  if (texture.block_modes.size() != block_count(texture))
    fail(kWhere, "block_modes holds " + std::to_string(texture.block_modes.size()) + " entries for " +
                     std::to_string(block_count(texture)) + " blocks");
  for (const std::uint8_t m : texture.block_modes)
    if (m >= names.size())
      fail(kWhere, "mode index " + std::to_string(m) + " but format '" + texture.format + "' has " +
                       std::to_string(names.size()) + " modes");
  return texture.block_modes;
}

}  // namespace

ModeColour mode_colour(std::size_t mode) {
  if (mode >= 2 * kOkabeIto.size()) fail(kWhere, "no colour for mode index " + std::to_string(mode) + " (at most 16)");
  ModeColour colour = kOkabeIto[mode % kOkabeIto.size()];
  if (mode >= kOkabeIto.size())
    for (float& c : colour) c *= 0.5f;   // the second round of the palette, at half brightness
  return colour;
}

std::vector<double> mode_shares(const EncodedTexture& texture, const std::vector<std::string>& mode_names) {
  const std::vector<std::uint8_t>& modes = checked_modes(texture, mode_names);
  std::vector<double> shares(mode_names.size(), 0.0);
  for (const std::uint8_t m : modes) shares[m] += 1.0;
  for (double& s : shares) s /= static_cast<double>(modes.size());   // modes is non-empty (checked)
  return shares;
}

std::string mode_shares_text(const std::vector<double>& shares, const std::vector<std::string>& mode_names) {
  std::string text;
  for (std::size_t m = 0; m < shares.size() && m < mode_names.size(); ++m) {
    char value[32];
    std::snprintf(value, sizeof value, "%.4f", shares[m]);
    text += (m ? ";" : "") + mode_names[m] + "=" + value;
  }
  return text;
}

Image mode_map_image(const EncodedTexture& texture, const std::vector<std::string>& mode_names,
                     const Image* underlay) {
  const std::vector<std::uint8_t>& modes = checked_modes(texture, mode_names);
  if (underlay != nullptr && (underlay->width != texture.width || underlay->height != texture.height))
    fail(kWhere, "underlay is " + std::to_string(underlay->width) + "x" + std::to_string(underlay->height) +
                     ", texture " + std::to_string(texture.width) + "x" + std::to_string(texture.height));
  Image out(texture.width, texture.height, 3);
  const std::size_t across = static_cast<std::size_t>((texture.width + 3) / 4);
  for (int y = 0; y < texture.height; ++y)
    for (int x = 0; x < texture.width; ++x) {
      const std::size_t block = static_cast<std::size_t>(y / 4) * across + static_cast<std::size_t>(x / 4);
      const ModeColour colour = mode_colour(modes[block]);
      float shade = 1.0f;
      if (underlay != nullptr) {
        const float* t = underlay->texel(x, y);
        const int channels = underlay->channels;
        const double lum = channels >= 3 ? 0.299 * t[0] + 0.587 * t[1] + 0.114 * t[2] : t[0];
        // Reinhard tone map, then gamma 1/2.2; negative or NaN luminance (only without the input policy) counts as 0.
        const double mapped = lum > 0.0 ? std::pow(lum / (1.0 + lum), 1.0 / 2.2) : 0.0;
        shade = static_cast<float>(0.35 + 0.65 * mapped);
      }
      float* o = out.texel(x, y);
      for (int c = 0; c < 3; ++c) o[c] = colour[static_cast<std::size_t>(c)] * shade;
    }
  return out;
}

std::string mode_map_legend(const std::vector<double>& shares, const std::vector<std::string>& mode_names) {
  std::string legend;
  for (std::size_t m = 0; m < mode_names.size(); ++m) {
    const ModeColour c = mode_colour(m);
    char line[160];
    std::snprintf(line, sizeof line, "%s: %s%s (%.3f, %.3f, %.3f), %.2f%%\n", mode_names[m].c_str(),
                  m >= kOkabeIto.size() ? "dark " : "", kOkabeItoNames[m % kOkabeIto.size()], c[0], c[1], c[2],
                  m < shares.size() ? 100.0 * shares[m] : 0.0);
    legend += line;
  }
  return legend;
}

}  // namespace blocklab
