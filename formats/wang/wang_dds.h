// The `wang` texture as the paper's two DXT5 textures (Wang et al. 2007 section 3.3): bytes 0-15 of every block form
// tex0, bytes 16-31 tex1, each a standard BC3 texture of the same size, written as two DDS files (FourCC "DXT5",
// formats/common/dds.h) that any DXT5 viewer or GPU loads. The shader constants are not in the DDS files (they are in
// the .blk side data, wang_side_data.h); joining two bc3 textures back needs them.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "formats/format.h"

namespace blocklab {
namespace wang {

// The two bc3 textures (format "bc3", default bc3 options, the wang texture's size; channels 4).
std::array<EncodedTexture, 2> split_into_dxt5_textures(const EncodedTexture& texture);
// The inverse: a wang texture with `options` (resolved wang options) and `side_data` from two bc3 textures of equal
// size. Throws Error("<who>: ...") when they are not bc3 or differ in size.
EncodedTexture join_dxt5_textures(const EncodedTexture& tex0, const EncodedTexture& tex1, const FormatOptions& options,
                                  const std::map<std::string, std::vector<double>>& side_data, const std::string& who);

// split_into_dxt5_textures + write_dds for both.
void write_dxt5_pair(const std::string& tex0_path, const std::string& tex1_path, const EncodedTexture& texture);

}  // namespace wang
}  // namespace blocklab
