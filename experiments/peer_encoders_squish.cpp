// The libsquish peer (experiments/peer_encoders.h): squish::CompressImage in-process on one core, BC1 (kDxt1, alpha
// forced to 255: squish's DXT1 would turn texels with alpha < 128 into transparent black, and blocklab's bc1 ignores
// alpha) and BC3 (kDxt5); fast = kColourRangeFit, medium = kColourClusterFit, thorough = kColourIterativeClusterFit.
// The blocks are decoded by blocklab's reference decoder (bit-replicated endpoints, exact-fraction interpolants) so
// metrics compare encoders; squish's own integer decoder (squish::DecompressImage) is returned as own_decoded.
// Without libsquish (BLOCKLAB_HAVE_SQUISH undefined) the peer reports itself unavailable.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/error.h"
#include "experiments/peer_encoders.h"
#include "formats/registry.h"

#ifdef BLOCKLAB_HAVE_SQUISH
#include <squish.h>
#endif

namespace blocklab {

bool squish_linked() {
#ifdef BLOCKLAB_HAVE_SQUISH
  return true;
#else
  return false;
#endif
}

PeerEncoder squish_peer(const std::string& format, const std::string& preset) {
  if (format != "bc1" && format != "bc3") fail("squish peer", "format '" + format + "'; valid: bc1, bc3");
  PeerEncoder peer;
  peer.tool = "squish";
  peer.target = format;
  peer.preset = preset;
  if (preset == "fast") peer.level = "range fit";
  else if (preset == "medium") peer.level = "cluster fit";
  else if (preset == "thorough") peer.level = "iterative cluster fit";
  else fail("squish peer", "preset '" + preset + "'; valid: fast, medium, thorough");
  peer.bits_per_pixel = format == "bc1" ? 4.0 : 8.0;
#ifdef BLOCKLAB_HAVE_SQUISH
  const int fit = preset == "fast" ? squish::kColourRangeFit
                  : preset == "medium" ? squish::kColourClusterFit : squish::kColourIterativeClusterFit;
  const int flags = (format == "bc1" ? squish::kDxt1 : squish::kDxt5) | fit;
  peer.run = [format, flags](const Image& source, const std::filesystem::path&) {
    std::vector<std::uint8_t> rgba(source.texel_count() * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i)
      rgba[i] = static_cast<std::uint8_t>(std::lround(std::clamp(source.pixels[i], 0.0f, 1.0f) * 255.0f));
    std::vector<std::uint8_t> input = rgba;
    if (format == "bc1")
      for (std::size_t i = 3; i < input.size(); i += 4) input[i] = 255;
    std::vector<std::uint8_t> blocks(
        static_cast<std::size_t>(squish::GetStorageRequirements(source.width, source.height, flags)));
    PeerRun run;
    double start = process_cpu_seconds();
    squish::CompressImage(input.data(), source.width, source.height, blocks.data(), flags);
    run.encode_seconds = process_cpu_seconds() - start;

    std::vector<std::uint8_t> own(rgba.size());
    squish::DecompressImage(own.data(), source.width, source.height, blocks.data(), flags);
    Image own_image(source.width, source.height, source.channels);
    for (std::size_t i = 0; i < own.size(); ++i) own_image.pixels[i] = own[i] / 255.0f;
    run.own_decoded = std::move(own_image);

    const Format& blocklab_format = find_format(format);
    EncodedTexture texture;
    texture.format = format;
    texture.options = resolve_format_options(blocklab_format, {});
    texture.width = source.width;
    texture.height = source.height;
    texture.channels = source.channels;
    texture.block_bytes = blocklab_format.block_bytes(texture.options);
    texture.blocks = std::move(blocks);
    start = process_cpu_seconds();
    run.decoded = blocklab_format.decode(texture, CodecContext{1, 1});
    run.decode_seconds = process_cpu_seconds() - start;
    return run;
  };
#else
  peer.run = [](const Image&, const std::filesystem::path&) -> PeerRun {
    fail("squish peer", "blocklab was built without libsquish (scripts/install-deps.sh installs libsquish-dev)");
  };
#endif
  return peer;
}

}  // namespace blocklab
