// Peer encoders: the reference codecs blocklab's formats are measured against, run side by side on the same
// reference image (the source after the input policy) and decoded so the same metrics read them.
//   * astcenc (Debian package astcenc, ARM's reference ASTC encoder) as an external process:
//     `astcenc -ch|-cl IN OUT BLOCK -fast|-medium|-thorough -j 1` (HDR `-ch` on a float32 EXR, LDR `-cl` on a PNG),
//     decoded by `astcenc -dh|-dl`; encode and decode time = user + system CPU time of the child (getrusage).
//   * libsquish 1.15 (squish::CompressImage; range fit, cluster fit, iterative cluster fit) for BC1 (kDxt1, alpha
//     forced to 255: blocklab's bc1 ignores alpha) and BC3 (kDxt5), in-process, timed in process CPU time; the
//     blocks are decoded by blocklab's reference bc1/bc3 decoder (so metrics compare encoders, not decoders), and
//     squish's own integer decoder is returned beside it. Built only where libsquish is found.
//   * NVIDIA Texture Tools 2.0 `nvcompress [-fast] -bc1|-bc3 -nomips -nocuda IN.png OUT.dds` as an external process;
//     encode time = its own "time taken" report (excludes process start and PNG loading), decoded by blocklab.
// Names: "<tool>-<target>-<preset>", e.g. astcenc-4x4-medium, squish-bc1-thorough, nvtt-bc3-fast; the preset maps
// fast/medium/thorough onto the tool's levels (squish: range / cluster / iterative cluster fit; NVTT 2.0 has only
// -fast and its default, so nvtt has fast and medium).
// Used by `blocklab bench formats` (experiments/format_bench.h), benchmarks/bench_munkberg.cpp and bench_s3tc.cpp.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace blocklab {

struct PeerRun {
  Image decoded;                     // what the metrics read (astcenc's own decoder; blocklab's for BC1/BC3 blocks)
  std::optional<Image> own_decoded;  // squish: squish::DecompressImage's output
  double encode_seconds = 0.0;       // one core
  double decode_seconds = 0.0;
};

struct PeerEncoder {
  std::string tool;      // "astcenc", "squish", "nvtt"
  std::string target;    // "4x4", "6x6", "8x8", "bc1", "bc3"
  std::string preset;    // "fast", "medium", "thorough"
  std::string level;     // the tool's own name of the preset: "-medium", "cluster fit", "-fast"
  bool hdr = false;      // encodes HDR sources (astcenc -ch); otherwise LDR code values in [0, 1]
  double bits_per_pixel = 0.0;
  // Encodes `source` (reference image after the input policy) on one core; scratch files go under `scratch`.
  std::function<PeerRun(const Image& source, const std::filesystem::path& scratch)> run;

  std::string format_name() const { return tool + "-" + target; }         // astcenc-4x4
  std::string name() const { return format_name() + "-" + preset; }      // astcenc-4x4-medium
};

// True when the tool can run here (astcenc / nvcompress on PATH; squish linked in).
bool peer_tool_available(const std::string& tool);

// astcenc at `block` ("4x4", "6x6", "8x8", any size astcenc accepts) and `preset` (fast, medium, thorough).
PeerEncoder astcenc_peer(const std::string& block, const std::string& preset, bool hdr);
// libsquish for `format` (bc1, bc3) at `preset` (fast = range fit, medium = cluster fit, thorough = iterative).
PeerEncoder squish_peer(const std::string& format, const std::string& preset);
// NVTT 2.0 nvcompress for `format` (bc1, bc3) at `preset` (fast = -fast, medium = default quality).
PeerEncoder nvtt_peer(const std::string& format, const std::string& preset);

// Every peer of one image kind whose tool is available, restricted to `presets`: HDR astcenc -ch at 4x4, 6x6,
// 8x8; LDR astcenc -cl at 4x4, 6x6, 8x8, squish and nvtt for BC1 and BC3.
std::vector<PeerEncoder> available_peers(bool hdr, const std::vector<std::string>& presets);

// Shared by the peers: CPU seconds of this process and of its waited-for children; running a shell command
// (throws Error naming it on a non-zero exit) and capturing its output.
double process_cpu_seconds();
double children_cpu_seconds();
void run_peer_command(const std::string& command);
std::string peer_command_output(const std::string& command);

}  // namespace blocklab
