// The Format interface: a fixed-rate block codec that encodes an image to packed blocks and decodes them back.
//
// Options are string key/value pairs, the same keys on the command line (`--set key=value`) and in YAML
// (`options: {key: value}`). Each format declares its options (name, type, default, allowed values, help);
// `resolve_format_options` fills defaults, checks types and rejects unknown keys with the valid ones listed.
// A resolved option map is what results record and what cache keys hash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"

namespace blocklab {

using FormatOptions = std::map<std::string, std::string>;

enum class OptionType { integer, real, boolean, text, choice };

struct OptionSpec {
  std::string name;
  OptionType type = OptionType::text;
  std::string default_value;
  std::vector<std::string> choices;   // for OptionType::choice
  std::string help;
  double min_value = 0.0, max_value = 0.0;   // for integer/real when min_value < max_value
};

std::string to_string(OptionType type);

// Typed accessors on a resolved option map (throw Error naming the key on a missing or malformed value).
long long option_int(const FormatOptions& options, const std::string& key);
double option_real(const FormatOptions& options, const std::string& key);
bool option_bool(const FormatOptions& options, const std::string& key);
const std::string& option_text(const FormatOptions& options, const std::string& key);

// Everything `encode` produces and `decode` needs; also what the container file stores.
struct EncodedTexture {
  std::string format;                        // registry name
  FormatOptions options;                     // resolved options used to encode
  int width = 0, height = 0;                 // true image size (blocks cover it, padded to multiples of 4)
  int channels = 3;                          // channels of the source image (1, 3 or 4)
  int block_bytes = 0;                       // bytes per 4x4 block
  std::vector<std::uint8_t> blocks;          // block_count * block_bytes, blocks in row-major order
  // Per-texture side data (e.g. tone-mapping parameters, a global scale). Values must be finite.
  std::map<std::string, std::vector<double>> side_data;
  // Optional per-block mode index (into Format::modes()) for mode-usage maps; not stored in files, decoders
  // may recompute it.
  std::vector<std::uint8_t> block_modes;
};

struct CodecContext {
  int threads = 0;                 // 0 = all hardware threads
  std::uint64_t seed = 1;          // global seed; per-block seeds derive from (seed, block index)
};

class Format {
 public:
  virtual ~Format() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;     // one line, cites the paper / spec
  virtual std::vector<OptionSpec> option_specs() const = 0;
  virtual std::vector<std::string> modes() const = 0;   // block modes the format can emit
  virtual int block_bytes(const FormatOptions& options) const = 0;
  double bits_per_pixel(const FormatOptions& options) const { return block_bytes(options) * 8.0 / 16.0; }
  // Bumped whenever the bytes this format writes for the same input and options change (part of cache keys).
  virtual int revision() const { return 1; }

  // `image` has already passed the input policy (finite, non-negative). `options` are resolved.
  virtual EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const = 0;
  // Throws Error when the texture is inconsistent (wrong sizes, bad side data).
  virtual Image decode(const EncodedTexture& texture, const CodecContext& context) const = 0;
};

// Fills defaults, validates every value against its spec, rejects unknown keys ("<format>: unknown option 'x';
// valid options: a, b").
FormatOptions resolve_format_options(const Format& format, const FormatOptions& given);

}  // namespace blocklab
