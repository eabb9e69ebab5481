// Hostile-input robustness of EVERY registered format (formats/registry.h all_formats(); no format is named here,
// so a format added to the registry is fuzzed without editing this file).
//
// Promise under test (DESIGN.md, "bad input gets a clear Error"): corrupt or truncated packed files give a
// blocklab::Error, never a crash, a hang, a sanitizer report or another exception type. For each format, its
// default options and each of its presets (an option named `preset` with choices, read from the OptionSpec), a
// deterministic 10x7 RGBA image (alpha varies; 3 x 2 blocks, the last column and row of blocks partial), and the
// same image as RGB with the default options, is encoded and written as a .blk container (formats/common/container.h) and, when the DDS writer accepts the format (the
// CLI's rule: cli/command_codec.cpp calls write_dds, which refuses formats it cannot store), as DDS
// (formats/common/dds.h). Each file then goes through the in-process decode path (read_container / parse_dds +
// Format::decode):
//   (a) every proper truncation: must be an Error;
//   (b) seeded random byte flips, insertions and deletions over the whole file: Error or a well-formed image;
//   (c) every block replaced by random bytes under the valid header: Error or a well-formed image (values may be
//       non-finite for formats whose bits can encode Inf/NaN; the count is printed, not failed);
//   (d) side data: each key removed, each value set to extremes (huge, tiny, negative, zero, integer limits), each
//       value list emptied and lengthened: Error or a well-formed image.
// Any other exception fails the test naming the format, the options, the file kind, the case and the seed.
// Counts are scaled per format so the whole test stays at a few seconds of Release CPU.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/common/container.h"
#include "formats/common/dds.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

using Bytes = std::vector<std::uint8_t>;

// Budgets per format, shared by its option variants and file kinds.
constexpr int kMutationsPerFormat = 3000;
constexpr int kRandomBlockCasesPerFormat = 400;

enum class FileKind { container, dds };
const char* kind_name(FileKind kind) { return kind == FileKind::container ? "blk" : "dds"; }

// Deterministic synthetic HDR-capable image with values in [0, 1] (valid input for every format), varying alpha.
Image synthetic_rgba(int width, int height) {
  Image image(width, height, 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* texel = image.texel(x, y);
      texel[0] = 0.5f + 0.5f * std::sin(0.7f * static_cast<float>(x) + 0.3f * static_cast<float>(y));
      texel[1] = static_cast<float>(x + 1) / static_cast<float>(width + 1);
      texel[2] = static_cast<float>((x * 7 + y * 13) % 17) / 16.0f;
      texel[3] = static_cast<float>(y + 1) / static_cast<float>(height);
    }
  return image;
}

// The default options, then every other choice of an option named "preset" (read from the spec, not assumed).
std::vector<FormatOptions> option_variants(const Format& format) {
  std::vector<FormatOptions> variants = {resolve_format_options(format, {})};
  for (const OptionSpec& spec : format.option_specs()) {
    if (spec.name != "preset" || spec.type != OptionType::choice) continue;
    for (const std::string& choice : spec.choices)
      if (choice != spec.default_value) variants.push_back(resolve_format_options(format, {{"preset", choice}}));
  }
  return variants;
}

std::string describe(const FormatOptions& options) {
  const auto preset = options.find("preset");
  return preset == options.end() ? "defaults" : "preset=" + preset->second;
}

Bytes read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_file_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::uint64_t name_hash(const std::string& text) {   // FNV-1a: stable per-format seeds
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

struct Counts {
  std::size_t accepted = 0, rejected = 0, non_finite = 0;
};

class RegisteredFormatFuzz : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    // Every case goes through a file (read_container reads paths): a memory file system keeps that cheap.
    std::error_code error;
    const fs::path base = fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    directory_ = base /
                 ("blocklab_test_registered_formats_fuzz_" + std::to_string(::getpid()) + "_" + GetParam());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  Bytes container_bytes(const EncodedTexture& texture) const {
    const std::string path = (directory_ / "original.blk").string();
    write_container(path, texture);
    return read_file_bytes(path);
  }

  // Reads `bytes` as a packed file of `kind` and decodes it. True when a well-formed image came out, false on
  // blocklab::Error; any other exception fails the test with `label` (format, options, kind, case, seed).
  bool decodes(FileKind kind, const Bytes& bytes, const std::string& label, Counts& counts) const {
    try {
      EncodedTexture texture;
      if (kind == FileKind::container) {
        const std::string path = (directory_ / "case.blk").string();
        write_file_bytes(path, bytes);
        texture = read_container(path);
      } else {
        texture = parse_dds(bytes, "case.dds");
      }
      const Image image = find_format(texture.format).decode(texture, CodecContext{1, 1});
      EXPECT_EQ(image.width, texture.width) << label;
      EXPECT_EQ(image.height, texture.height) << label;
      EXPECT_EQ(image.pixels.size(), image.texel_count() * 4) << label;
      EXPECT_TRUE(image.channels == 1 || image.channels == 3 || image.channels == 4) << label;
      for (float value : image.pixels)
        if (!std::isfinite(value)) {
          ++counts.non_finite;
          break;
        }
      ++counts.accepted;
      return true;
    } catch (const Error&) {
      ++counts.rejected;
      return false;
    } catch (const std::exception& other) {
      ADD_FAILURE() << label << ": exception other than blocklab::Error: " << other.what();
      ++counts.rejected;
      return false;
    }
  }

  fs::path directory_;
};

TEST_P(RegisteredFormatFuzz, HostileFilesGiveAnErrorOrAWellFormedImage) {
  const Format& format = find_format(GetParam());
  const Image rgba = synthetic_rgba(10, 7);
  Image rgb = rgba;   // the same values without alpha: formats (and DDS headers) that branch on channels
  rgb.channels = 3;
  for (std::size_t i = 3; i < rgb.pixels.size(); i += 4) rgb.pixels[i] = 1.0f;

  struct Subject {
    std::string variant;
    FileKind kind;
    Bytes bytes;
    EncodedTexture texture;
  };
  std::vector<Subject> subjects;
  auto add_subjects = [&](const Image& image, const FormatOptions& options, const std::string& variant) {
    const CodecContext context{1, static_cast<std::uint64_t>(option_int(options, "seed"))};
    const EncodedTexture texture = format.encode(image, options, context);
    subjects.push_back({variant, FileKind::container, container_bytes(texture), texture});
    try {
      subjects.push_back({variant, FileKind::dds, dds_bytes(texture, "dds"), texture});
    } catch (const Error&) {
      // The DDS writer does not store this format (the CLI reports the same Error): .blk only.
    }
  };
  const std::vector<FormatOptions> variants = option_variants(format);
  for (const FormatOptions& options : variants) add_subjects(rgba, options, "rgba " + describe(options));
  add_subjects(rgb, variants.front(), "rgb " + describe(variants.front()));

  const int mutations = kMutationsPerFormat / static_cast<int>(subjects.size());
  const int random_block_cases = kRandomBlockCasesPerFormat / static_cast<int>(subjects.size());
  Counts truncation, mutation, random_blocks, side_data;
  std::size_t side_data_keys = 0;
  for (const Subject& subject : subjects) {
    const std::string where = format.name() + " " + subject.variant + " " + kind_name(subject.kind);
    const std::uint64_t base_seed = name_hash(where);
    Counts original;
    ASSERT_TRUE(decodes(subject.kind, subject.bytes, where + " original file", original));

    // (a) Every proper prefix.
    for (std::size_t length = 0; length < subject.bytes.size(); ++length) {
      const Bytes prefix(subject.bytes.begin(), subject.bytes.begin() + static_cast<std::ptrdiff_t>(length));
      EXPECT_FALSE(decodes(subject.kind, prefix, where + " truncated to " + std::to_string(length), truncation))
          << where << ": a file cut to " << length << " of " << subject.bytes.size() << " bytes was accepted";
    }

    // (b) Random flips / insertions / deletions anywhere; one generator per case so each seed replays alone.
    for (int iteration = 0; iteration < mutations; ++iteration) {
      const std::uint64_t seed = base_seed + static_cast<std::uint64_t>(iteration);
      std::mt19937_64 random(seed);
      Bytes bytes = subject.bytes;
      const int edits = 1 + static_cast<int>(random() % 4);
      for (int e = 0; e < edits && !bytes.empty(); ++e) {
        const std::size_t position = random() % bytes.size();
        switch (random() % 4) {
          case 0:
          case 1:
            bytes[position] = static_cast<std::uint8_t>(bytes[position] ^ (1 + random() % 255));
            break;
          case 2:
            bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(position), 1 + random() % 8,
                         static_cast<std::uint8_t>(random()));
            break;
          default:
            bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(position),
                        bytes.begin() + static_cast<std::ptrdiff_t>(std::min(bytes.size(), position + 1 + random() % 8)));
        }
      }
      decodes(subject.kind, bytes, where + " mutation seed " + std::to_string(seed), mutation);
    }

    // (c) Every block replaced by random bytes; the blocks are the last bytes of both file kinds.
    const std::size_t block_start = subject.bytes.size() - subject.texture.blocks.size();
    for (int iteration = 0; iteration < random_block_cases; ++iteration) {
      const std::uint64_t seed = base_seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(iteration + 1));
      std::mt19937_64 random(seed);
      Bytes bytes = subject.bytes;
      for (std::size_t i = block_start; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(random());
      decodes(subject.kind, bytes, where + " random blocks seed " + std::to_string(seed), random_blocks);
    }

    // (d) Side-data mutations (the container stores side data; DDS stores none).
    if (subject.kind != FileKind::container) continue;
    const std::vector<double> extremes = {0.0,     -0.0,     1.0,     -1.0,     1e-300, -1e-300, 1e300, -1e300,
                                          1e18,    -1e18,    2147483648.0, -2147483649.0, 65536.0, 0.5,
                                          std::numeric_limits<double>::max(),
                                          std::numeric_limits<double>::lowest(),
                                          std::numeric_limits<double>::denorm_min()};
    for (const auto& [key, values] : subject.texture.side_data) {
      ++side_data_keys;
      std::vector<EncodedTexture> cases;
      EncodedTexture removed = subject.texture;
      removed.side_data.erase(key);
      cases.push_back(removed);
      EncodedTexture emptied = subject.texture;
      emptied.side_data[key].clear();
      cases.push_back(emptied);
      EncodedTexture lengthened = subject.texture;
      lengthened.side_data[key].push_back(1e300);
      cases.push_back(lengthened);
      for (std::size_t index = 0; index < values.size(); ++index)
        for (double extreme : extremes) {
          EncodedTexture changed = subject.texture;
          changed.side_data[key][index] = extreme;
          cases.push_back(changed);
        }
      for (std::size_t c = 0; c < cases.size(); ++c) {
        Bytes bytes;
        try {
          bytes = container_bytes(cases[c]);   // the writer validates too: refusing here is an Error as well
        } catch (const Error&) {
          ++side_data.rejected;
          continue;
        }
        decodes(FileKind::container, bytes, where + " side data '" + key + "' case " + std::to_string(c), side_data);
      }
    }
  }

  std::printf("[fuzz] %-10s files %zu | truncations %zu | mutations %zu (accepted %zu) | random blocks %zu "
              "(accepted %zu, non-finite %zu) | side data keys %zu cases %zu (accepted %zu)\n",
              format.name().c_str(), subjects.size(), truncation.accepted + truncation.rejected,
              mutation.accepted + mutation.rejected, mutation.accepted,
              random_blocks.accepted + random_blocks.rejected, random_blocks.accepted, random_blocks.non_finite,
              side_data_keys, side_data.accepted + side_data.rejected, side_data.accepted);
}

std::vector<std::string> registered_format_names() {
  std::vector<std::string> names;
  for (const Format* format : all_formats()) names.push_back(format->name());
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RegisteredFormatFuzz, ::testing::ValuesIn(registered_format_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string test_name = info.param;   // gtest names allow only [A-Za-z0-9_]
                           for (char& c : test_name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return test_name;
                         });

}  // namespace
}  // namespace blocklab
