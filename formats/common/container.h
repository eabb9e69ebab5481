// blocklab's own container for packed blocks of any format (".blk").
//
// Layout (all integers little-endian):
//   magic      8 bytes  "BLKLAB\r\n" (the CR/LF pair catches text-mode transfers, as PNG's magic does)
//   version    u32      kContainerVersion
//   header     u32 length + UTF-8 JSON: {"format", "format_revision", "options", "width", "height", "channels",
//              "block_bytes", "block_count", "side_data"}   (JSON keeps the header readable with any tool)
//              "format_revision" (Format::decoder_revision() of the encoder) is optional on reading, for files written
//              before it existed; when present it must equal this build's decoder revision of the format, since
//              blocks of another one may decode differently (e.g. munkberg 3 -> 4 moved the two-plane layout). An
//              encoder-only change (Format::revision()) keeps older files readable.
//   blocks     block_count * block_bytes bytes
// The reader validates every field (magic, version, lengths, sizes > 0 and <= 65536, block_count equal to
// Format::stored_block_count (ceil(w/4)*ceil(h/4) unless the format stores another grid), block_bytes equal to what
// the format declares for the options, finite side data, no trailing bytes) and throws Error("<path>: <reason>").
#pragma once

#include <string>

#include "formats/format.h"

namespace blocklab {

constexpr unsigned kContainerVersion = 1;

void write_container(const std::string& path, const EncodedTexture& texture);
EncodedTexture read_container(const std::string& path);

}  // namespace blocklab
