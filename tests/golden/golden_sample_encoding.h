// One golden case of a registered format on a bundled sample: read, input policy clamp, encode at 2 threads with seed
// 1, decode, and the FNV-1a 64 hashes (golden_hash.h) of the packed blocks and of the decoded floats.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"
#include "golden_hash.h"

namespace blocklab::golden {

struct SampleHashes {
  std::uint64_t blocks = 0;
  std::uint64_t decoded = 0;
};

inline SampleHashes hash_sample_encoding(const std::string& format_name, const std::string& image_path,
                                         const std::map<std::string, std::string>& options) {
  const Format& format = find_format(format_name);
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + image_path;
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  const EncodedTexture texture = format.encode(image, resolve_format_options(format, options), CodecContext{2, 1});
  const Image decoded = format.decode(texture, CodecContext{2, 1});
  return {fnv1a64(texture.blocks.data(), texture.blocks.size()), hash_floats(decoded.pixels)};
}

}  // namespace blocklab::golden
