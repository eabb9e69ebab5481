// The Format interface: a fixed-rate block codec that encodes an image to packed blocks and decodes them back.
//
// Options are string key/value pairs, the same keys on the command line (`--set key=value`) and in YAML
// (`options: {key: value}`). Each format declares its options (name, type, default, allowed values, help);
// `resolve_format_options` fills defaults, checks types and rejects unknown keys with the valid ones listed.
// A resolved option map is what results record and what cache keys hash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "core/image.h"
#include "core/options.h"

namespace blocklab {

class Problem;   // core/problem.h

// One block mode a format can emit: its row in the format's mode table (Format::mode_table()).
struct ModeSpec {
  std::string name;          // the mode maps' legend entry; its position is the block_modes index
  std::string description;   // one line
};

// The samples a block problem is drawn from: LDR (PNG code values in [0, 1], <data root>/ldr) or HDR (linear
// radiance, <data root>/hdr).
enum class BlockImageKind { ldr, hdr };

// A search a format hands a solver, as a Problem drawn from one real 4x4 block: the contract test, the interval
// soundness stress test and `blocklab bench solvers` iterate every registered format's table
// (formats/registry.h registered_block_problems), so declaring a problem here is all its coverage needs.
struct BlockProblem {
  std::string name;          // unique within the format; "<format>.<name>" names it across formats
  std::string description;   // one line: what the parameters and the error are, citing the paper / spec
  BlockImageKind image_kind = BlockImageKind::ldr;
  // The Problem of `block` (texels as read, after the input policy). `seed` draws whatever the format's search
  // would choose per block (a template, a mode, a partition): the same (block, seed) gives the same Problem.
  std::function<std::unique_ptr<Problem>(const BlockTexels& block, std::uint64_t seed)> make;
  // The error is a staircase (a quantiser inside it): the contract's finite-difference gradient check then finds
  // fewer points where its two step sizes agree, and asks only this share of them (problem_contract.h).
  double min_checked_gradient_fraction = 0.5;
  // The interval error is finite on every box (the soundness test requires it). False when the natural extension
  // can be unbounded above on wide boxes; its lower bound, the one a branch-and-bound prunes with, stays required.
  bool bounded_enclosures = true;
};

using FormatOptions = Options;   // core/options.h: OptionSpec, OptionType, option_int/real/bool/text

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

// A named option set of a format (the astcenc model: fast | medium | thorough, and paper where the paper's own search
// differs). `--set preset=NAME` fills every option the preset lists that was not given explicitly; the expanded map is
// what an encode records, so a result names the values really used. `medium` is every format's default.
struct FormatPreset {
  std::string name;
  std::string summary;                 // one line: what the preset trades
  FormatOptions values;                // option -> value; options it does not list keep their defaults
  std::vector<std::string> aliases;    // other names accepted for it (resolved to `name`)
};
constexpr const char* kDefaultPreset = "medium";

// One standard GPU texture of a packed texture: a BCn texture a game engine or an image viewer loads as is.
struct GpuTexture {
  std::string suffix;       // "" for a format that is one texture; else the file-name part before ".dds" ("tex0")
  EncodedTexture texture;   // a format formats/common/dds.h writes (bc1, bc3, bc4, bc7)
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
  // The block modes the format can emit, in block_modes index order.
  virtual std::vector<ModeSpec> mode_table() const = 0;
  // The names of mode_table(), in the same order.
  std::vector<std::string> modes() const {
    std::vector<std::string> names;
    for (const ModeSpec& mode : mode_table()) names.push_back(mode.name);
    return names;
  }
  // The block problems of the format's searches (default: none).
  virtual std::vector<BlockProblem> block_problems() const { return {}; }
  // fast, medium (the default), thorough [, paper]. Default: identical_presets (a format without search effort).
  virtual std::vector<FormatPreset> presets() const;
  virtual int block_bytes(const FormatOptions& options) const = 0;
  // The rate results report. Default: block_bytes per 16 texels. A format whose blocks cover another grid than the
  // texture's (stored_block_count) overrides it with its nominal rate.
  virtual double bits_per_pixel(const FormatOptions& options) const { return block_bytes(options) * 8.0 / 16.0; }
  // How many blocks of block_bytes `texture.blocks` holds. Default: the 4x4 blocks covering width x height. A format
  // that stores its blocks on another grid (downscaled: the blocks of a reduced image whose size is side data)
  // overrides it and throws Error naming the side-data key when that size is missing or inconsistent.
  virtual std::size_t stored_block_count(const EncodedTexture& texture) const;
  // Bumped whenever the bytes this format writes for the same input and options change, encoder changes included
  // (part of the experiment cache keys, so results of an older encoder are recomputed).
  virtual int revision() const { return 1; }
  // Bumped whenever the MEANING of the bytes changes (a bit layout or a decoding rule): recorded in .blk headers,
  // whose reader refuses blocks of another decoder revision (formats/common/container.h). An encoder-only change
  // bumps revision() and keeps this number (override it with the old value), so files written before stay
  // readable. Default: revision(), right for every bump so far (each changed a layout or decoding rule).
  virtual int decoder_revision() const { return revision(); }

  // `image` has already passed the input policy (finite, non-negative). `options` are resolved.
  virtual EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const = 0;
  // Throws Error when the texture is inconsistent (wrong sizes, bad side data).
  virtual Image decode(const EncodedTexture& texture, const CodecContext& context) const = 0;
  // The packed texture as standard GPU textures, what `blocklab encode IN OUT.dds` writes (one DDS file each): the
  // texture itself for the BCn formats, the paper's textures for a format built from them (wang: two DXT5). Shader
  // constants and other side data stay in the .blk. Default: none (the format has no DDS form).
  virtual std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const {
    (void)texture;
    return {};
  }
  // Whether gpu_textures() returns textures (true exactly for the formats that override it), asked before encoding
  // so that `encode OUT.dds` refuses a format without a DDS form at once. tests/unit/test_format_registry.cpp checks
  // the two agree for every registered format.
  virtual bool has_gpu_textures() const { return false; }
};

// Fills defaults, validates every value against its spec, rejects unknown keys ("<format>: unknown option 'x';
// valid options: a, b").
//
// The preset (option `preset`, default kDefaultPreset) is expanded first: each option it lists that `given` does not
// set explicitly takes the preset's value. Then:
// Accepted keys are the format's own option_specs() followed by common_option_specs() (appended here, so every
// format accepts the same common keys; a format must not declare a common key itself). Values are normalised so
// that equal settings give equal maps (the map is hashed for result caching): integers in plain decimal ("+007" ->
// "7"), reals in the shortest round-trip form ("1.50" -> "1.5", "-0" -> "0"), booleans as "true"/"false" (input
// true/false/yes/no/1/0, any case); leading/trailing blanks are dropped except for text options.
FormatOptions resolve_format_options(const Format& format, const FormatOptions& given);

// fast, medium and thorough with no values: for deterministic formats, whose bytes no search effort changes.
std::vector<FormatPreset> identical_presets();
// fast, medium and thorough that each set one option (e.g. the S3TC codecs' `search`: fast, default, exhaustive).
std::vector<FormatPreset> one_option_presets(const std::string& option, const std::string& fast,
                                             const std::string& medium, const std::string& thorough);

// The options every format accepts: `seed` (integer, default 1; deterministic formats accept and record it) and
// `preset` (choice of format.presets(), default medium).
std::vector<OptionSpec> common_option_specs(const Format& format);
// The format's option table and a table of its presets with what each expands to (Markdown, for the READMEs).
std::string format_options_markdown(const Format& format);
// format.option_specs() followed by common_option_specs(): every key resolve_format_options accepts.
std::vector<OptionSpec> all_option_specs(const Format& format);

// Largest width/height of a texture (containers and decoders reject anything bigger).
constexpr int kMaxTextureDimension = 65536;

// Throws Error("<where>: <reason>") unless `texture` is self-consistent for `format`: texture.format names it,
// 1 <= width, height <= kMaxTextureDimension, channels is 1, 3 or 4, block_bytes equals
// format.block_bytes(texture.options), every side-data value is finite, blocks holds exactly
// format.stored_block_count(texture) blocks (ceil(w/4)*ceil(h/4) unless the format says otherwise), and block_modes is
// empty or one per stored block with indices into format.modes(). Decoders call it first; the
// container writer and reader too.
void validate_encoded_texture(const Format& format, const EncodedTexture& texture, const std::string& where);

// Throws Error("<where>: <reason>") unless `image` can be encoded: 1 <= width, height <= kMaxTextureDimension,
// channels is 1, 3 or 4 and pixels holds width * height * 4 floats. (Values are the input policy's business.)
void validate_encoder_input(const Image& image, const std::string& where);

}  // namespace blocklab
