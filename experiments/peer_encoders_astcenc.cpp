// The astcenc peer (experiments/peer_encoders.h): ARM's reference ASTC encoder 4.x as an external process, one
// thread (-j 1). HDR: the reference as a float32 EXR, `astcenc -ch`, decoded by `astcenc -dh` (half EXR); LDR: the
// reference as an 8-bit PNG (exact for PNG sources), `astcenc -cl`, decoded by `astcenc -dl` (PNG). Times are the
// child's user + system CPU seconds, so they include astcenc's process start and image load (a few ms).
#include <cstdio>

#include "core/error.h"
#include "core/image_io.h"
#include "experiments/peer_encoders.h"

namespace blocklab {

PeerEncoder astcenc_peer(const std::string& block, const std::string& preset, bool hdr) {
  int width = 0, height = 0;
  if (std::sscanf(block.c_str(), "%dx%d", &width, &height) != 2 || width < 4 || height < 4)
    fail("astcenc peer", "block size '" + block + "' is not WxH (e.g. 4x4, 6x6, 8x8)");
  if (preset != "fast" && preset != "medium" && preset != "thorough")
    fail("astcenc peer", "preset '" + preset + "'; valid: fast, medium, thorough");
  PeerEncoder peer;
  peer.tool = "astcenc";
  peer.target = block;
  peer.preset = preset;
  peer.level = "-" + preset;
  peer.hdr = hdr;
  peer.bits_per_pixel = 128.0 / (width * height);
  peer.run = [block, level = peer.level, hdr](const Image& source, const std::filesystem::path& scratch) {
    const std::string in = (scratch / (hdr ? "astcenc_in.exr" : "astcenc_in.png")).string();
    const std::string packed = (scratch / "astcenc_out.astc").string();
    const std::string back = (scratch / (hdr ? "astcenc_back.exr" : "astcenc_back.png")).string();
    WriteOptions options;
    options.exr_pixel_type = ExrPixelType::float32;
    write_image(in, source, options);
    PeerRun run;
    double before = children_cpu_seconds();
    run_peer_command(std::string("astcenc ") + (hdr ? "-ch" : "-cl") + " '" + in + "' '" + packed + "' " + block +
                     " " + level + " -j 1");
    run.encode_seconds = children_cpu_seconds() - before;
    before = children_cpu_seconds();
    run_peer_command(std::string("astcenc ") + (hdr ? "-dh" : "-dl") + " '" + packed + "' '" + back + "' -j 1");
    run.decode_seconds = children_cpu_seconds() - before;
    run.decoded = read_image(back);
    run.decoded.channels = source.channels;
    return run;
  };
  return peer;
}

}  // namespace blocklab
