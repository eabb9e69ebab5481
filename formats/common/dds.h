// DDS (DirectDraw Surface) files for block-compressed textures: one 2-D texture, top mip level only.
//
// Layout (microsoft/DirectXTex DDS.h; learn.microsoft.com "DDS_HEADER", "DDS_HEADER_DXT10"; ECOSYSTEM.md
// section 2): "DDS " magic, the 124-byte DDS_HEADER with its 32-byte DDS_PIXELFORMAT (flags DDPF_FOURCC), an
// optional 20-byte DDS_HEADER_DXT10, then the blocks in row-major order. All fields little-endian u32.
//
// Writer: header flags CAPS|HEIGHT|WIDTH|PIXELFORMAT|LINEARSIZE (0x81007), caps TEXTURE (0x1000), mipMapCount 0,
// pitchOrLinearSize = blocks_x * blocks_y * block_bytes, the TRUE width/height (the data is padded to whole
// blocks). bc1, bc3, bc4 use the legacy FourCC header ("DXT1", "DXT5", "ATI1", read by every viewer); bc7, bc6h and
// bc6h_sf use the DX10 header (FourCC "DX10", dxgiFormat 98 BC7_UNORM, 95 BC6H_UF16, 96 BC6H_SF16,
// resourceDimension 3 = TEXTURE2D, arraySize 1, miscFlags2 = alpha mode: 1 straight for 4-channel bc7 sources, 3
// opaque otherwise).
//
// Reader: accepts FourCC DXT1 -> bc1, DXT5 -> bc3, ATI1 / BC4U -> bc4, and DX10 with dxgiFormat 71 (BC1_UNORM) ->
// bc1, 77 (BC3_UNORM) -> bc3, 80 (BC4_UNORM) -> bc4, 98 (BC7_UNORM) -> bc7, 95 (BC6H_UF16) -> bc6h,
// 96 (BC6H_SF16) -> bc6h_sf. Every field is validated (magic, sizes,
// flags, dimensions 1..65536, depth/volume/cube/array rejected, pitchOrLinearSize when LINEARSIZE is set, data
// length); extra mip levels after level 0 are ignored. Any problem -> Error("<path>: <reason>"), never a crash.
// The returned texture has: format name, true width/height, channels (bc1 3, bc3 4, bc4 1, bc6h/bc6h_sf 3, bc7 4
// or 3 when the DX10 alpha mode says opaque), block_bytes, the level-0 blocks, and the format's default options when the format
// is registered (a DDS file records no encoder options), otherwise no options.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/format.h"

namespace blocklab {

void write_dds(const std::string& path, const EncodedTexture& texture);
EncodedTexture read_dds(const std::string& path);

// The same on memory buffers (`where` names the source in error messages).
std::vector<std::uint8_t> dds_bytes(const EncodedTexture& texture, const std::string& where);
EncodedTexture parse_dds(const std::vector<std::uint8_t>& bytes, const std::string& where);

}  // namespace blocklab
