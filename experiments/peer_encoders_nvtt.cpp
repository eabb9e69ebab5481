// The NVIDIA Texture Tools 2.0 peer (experiments/peer_encoders.h): `nvcompress [-fast] -bc1|-bc3 -nomips -nocuda`
// on the reference as an 8-bit PNG, as an external process (single-threaded on the CPU path). Encode time is
// nvcompress's own "time taken" report, which excludes its process start and PNG loading; the DDS it writes is
// decoded by blocklab's reference decoder (timed in process CPU time). NVTT 2.0 has two quality levels: -fast
// (preset fast) and its default (preset medium).
#include <cstdlib>

#include "core/error.h"
#include "core/image_io.h"
#include "experiments/peer_encoders.h"
#include "formats/common/dds.h"
#include "formats/registry.h"

namespace blocklab {

PeerEncoder nvtt_peer(const std::string& format, const std::string& preset) {
  if (format != "bc1" && format != "bc3") fail("nvtt peer", "format '" + format + "'; valid: bc1, bc3");
  if (preset != "fast" && preset != "medium") fail("nvtt peer", "preset '" + preset + "'; valid: fast, medium");
  PeerEncoder peer;
  peer.tool = "nvtt";
  peer.target = format;
  peer.preset = preset;
  peer.level = preset == "fast" ? "-fast" : "default quality";
  peer.bits_per_pixel = format == "bc1" ? 4.0 : 8.0;
  peer.run = [format, fast = preset == "fast"](const Image& source, const std::filesystem::path& scratch) {
    const std::string in = (scratch / "nvtt_in.png").string(), out = (scratch / "nvtt_out.dds").string();
    write_image(in, source);
    const std::string report = peer_command_output(std::string("nvcompress ") + (fast ? "-fast " : "") + "-" +
                                                   format + " -nomips -nocuda '" + in + "' '" + out + "'");
    const std::size_t at = report.find("time taken:");
    if (at == std::string::npos) fail("nvtt peer", "nvcompress printed no 'time taken:' line: " + report);
    PeerRun run;
    run.encode_seconds = std::atof(report.c_str() + at + 11);
    const EncodedTexture texture = read_dds(out);
    const double start = process_cpu_seconds();
    run.decoded = find_format(format).decode(texture, CodecContext{1, 1});
    run.decode_seconds = process_cpu_seconds() - start;
    run.decoded.channels = source.channels;
    return run;
  };
  return peer;
}

}  // namespace blocklab
