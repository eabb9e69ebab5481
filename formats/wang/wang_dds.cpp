// The `wang` texture as two DXT5 textures (formats/wang/wang_dds.h).
#include "formats/wang/wang_dds.h"

#include "core/error.h"
#include "core/blocks.h"
#include "formats/bc3/bc3_format.h"
#include "formats/common/dds.h"
#include "formats/common/s3tc_common.h"
#include "formats/wang/wang_block.h"

namespace blocklab {
namespace wang {

std::array<EncodedTexture, 2> split_into_dxt5_textures(const EncodedTexture& texture) {
  const BlockGrid grid(texture.width, texture.height);
  if (texture.format != "wang" || texture.block_bytes != kBlockBytes ||
      texture.blocks.size() != grid.block_count() * static_cast<std::size_t>(kBlockBytes))
    fail("wang", "split into DXT5 textures: not a consistent wang texture");
  std::array<EncodedTexture, 2> halves;
  for (int half = 0; half < 2; ++half) {
    EncodedTexture& out = halves[half];
    out.format = "bc3";
    out.options = resolve_format_options(bc3_format(), {});
    out.width = texture.width;
    out.height = texture.height;
    out.channels = 4;
    out.block_bytes = kBc3BlockBytes;
    out.blocks.resize(grid.block_count() * kBc3BlockBytes);
    for (std::size_t block = 0; block < grid.block_count(); ++block)
      for (int byte = 0; byte < kBc3BlockBytes; ++byte)
        out.blocks[block * kBc3BlockBytes + byte] = texture.blocks[block * kBlockBytes + half * kBc3BlockBytes + byte];
  }
  return halves;
}

EncodedTexture join_dxt5_textures(const EncodedTexture& tex0, const EncodedTexture& tex1, const FormatOptions& options,
                                  const std::map<std::string, std::vector<double>>& side_data, const std::string& who) {
  for (const EncodedTexture* half : {&tex0, &tex1})
    if (half->format != "bc3" || half->block_bytes != kBc3BlockBytes)
      fail(who, "both textures must be DXT5 (bc3), got '" + half->format + "'");
  if (tex0.width != tex1.width || tex0.height != tex1.height)
    fail(who, "the two DXT5 textures differ in size: " + std::to_string(tex0.width) + "x" +
                  std::to_string(tex0.height) + " and " + std::to_string(tex1.width) + "x" +
                  std::to_string(tex1.height));
  const BlockGrid grid(tex0.width, tex0.height);
  EncodedTexture texture;
  texture.format = "wang";
  texture.options = options;
  texture.width = tex0.width;
  texture.height = tex0.height;
  texture.channels = 3;
  texture.block_bytes = kBlockBytes;
  texture.side_data = side_data;
  texture.blocks.resize(grid.block_count() * kBlockBytes);
  for (std::size_t block = 0; block < grid.block_count(); ++block)
    for (int byte = 0; byte < kBc3BlockBytes; ++byte) {
      texture.blocks[block * kBlockBytes + byte] = tex0.blocks.at(block * kBc3BlockBytes + byte);
      texture.blocks[block * kBlockBytes + kBc3BlockBytes + byte] = tex1.blocks.at(block * kBc3BlockBytes + byte);
    }
  return texture;
}

void write_dxt5_pair(const std::string& tex0_path, const std::string& tex1_path, const EncodedTexture& texture) {
  const std::array<EncodedTexture, 2> halves = split_into_dxt5_textures(texture);
  write_dds(tex0_path, halves[0]);
  write_dds(tex1_path, halves[1]);
}

}  // namespace wang
}  // namespace blocklab
