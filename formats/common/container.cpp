// blocklab's own ".blk" container (layout in formats/common/container.h):
//   "BLKLAB\r\n" | u32 version | u32 header length | UTF-8 JSON header | block_count * block_bytes bytes
// The writer checks the texture before writing and stores it with write_file_atomically (core/atomic_write.h), so a
// reader never sees half a file under the final name. The reader validates every field in file order and throws
// Error("<path>: <reason>") at the first problem; it reads the block payload only after the header has said how
// big it must be, so a corrupt header cannot make it allocate more than the file holds.
#include "formats/common/container.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_write.h"
#include "core/blocks.h"
#include "core/error.h"
#include "formats/registry.h"

namespace blocklab {

namespace {

constexpr std::array<char, 8> kMagic = {'B', 'L', 'K', 'L', 'A', 'B', '\r', '\n'};
constexpr std::size_t kPrologueBytes = 8 + 4 + 4;   // magic, version, header length
const std::set<std::string> kHeaderKeys = {"format",      "options",     "width",    "height",
                                           "channels",    "block_bytes", "block_count", "side_data"};
// Optional: the encoding format's decoder revision (Format::decoder_revision()). Written by every save; files written
// before it existed lack it and are read as before.
constexpr const char* kRevisionKey = "format_revision";

void append_u32_le(std::string& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<char>((value >> shift) & 0xFFu));
}

std::uint32_t read_u32_le(const unsigned char* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24);
}

std::string system_reason() { return std::strerror(errno); }

std::string join(const std::set<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

// Parses the header, rejecting duplicate keys at any depth (nlohmann keeps the last one silently, which would let
// two tools read two different headers from one file).
nlohmann::json parse_header_json(const std::string& path, const std::string& text) {
  std::vector<std::set<std::string>> open_objects;
  std::string duplicate_key;
  const nlohmann::json::parser_callback_t reject_duplicates =
      [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        if (event == nlohmann::json::parse_event_t::object_start) {
          open_objects.emplace_back();
        } else if (event == nlohmann::json::parse_event_t::object_end) {
          if (!open_objects.empty()) open_objects.pop_back();
        } else if (event == nlohmann::json::parse_event_t::key && !open_objects.empty()) {
          const std::string key = parsed.get<std::string>();
          if (!open_objects.back().insert(key).second && duplicate_key.empty()) duplicate_key = key;
        }
        return true;
      };
  nlohmann::json header;
  try {
    header = nlohmann::json::parse(text, reject_duplicates);
  } catch (const nlohmann::json::exception& error) {
    fail(path, std::string("malformed JSON header: ") + error.what());
  }
  if (!duplicate_key.empty()) fail(path, "header: duplicate key '" + duplicate_key + "'");
  return header;
}

long long header_integer(const std::string& path, const nlohmann::json& header, const std::string& key,
                         long long min_value, long long max_value) {
  const nlohmann::json& value = header.at(key);
  if (!value.is_number_integer()) fail(path, "header: '" + key + "' must be an integer, got " + value.dump());
  // Unsigned JSON integers above the signed range are out of range for every field.
  const bool too_big = value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(max_value);
  const long long number = too_big ? max_value : value.get<long long>();
  if (too_big || number < min_value || number > max_value)
    fail(path, "header: '" + key + "' is " + value.dump() + ", outside [" + std::to_string(min_value) + ", " +
                   std::to_string(max_value) + "]");
  return number;
}

}  // namespace

void write_container(const std::string& path, const EncodedTexture& texture) {
  const Format* format = nullptr;
  try {
    format = &find_format(texture.format);
  } catch (const Error& error) {
    fail(path, error.what());
  }
  validate_encoded_texture(*format, texture, path);

  // ordered_json keeps the keys in the documented order, so headers read naturally with any tool.
  nlohmann::ordered_json header;
  header["format"] = texture.format;
  header[kRevisionKey] = format->decoder_revision();
  header["options"] = nlohmann::ordered_json::object();
  for (const auto& option : texture.options) header["options"][option.first] = option.second;
  header["width"] = texture.width;
  header["height"] = texture.height;
  header["channels"] = texture.channels;
  header["block_bytes"] = texture.block_bytes;
  header["block_count"] = format->stored_block_count(texture);   // validated above
  header["side_data"] = nlohmann::ordered_json::object();
  for (const auto& entry : texture.side_data) header["side_data"][entry.first] = entry.second;
  std::string header_text;
  try {
    header_text = header.dump();   // doubles are written in a form that reads back to the same bits
  } catch (const nlohmann::json::exception& error) {
    fail(path, std::string("cannot write header (option and side-data names must be UTF-8): ") + error.what());
  }

  std::string prologue(kMagic.begin(), kMagic.end());
  append_u32_le(prologue, kContainerVersion);
  append_u32_le(prologue, static_cast<std::uint32_t>(header_text.size()));

  std::string file_bytes = prologue + header_text;
  file_bytes.append(reinterpret_cast<const char*>(texture.blocks.data()), texture.blocks.size());
  write_file_atomically(path, file_bytes);
}

EncodedTexture read_container(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open: " + system_reason());
  in.seekg(0, std::ios::end);
  const std::streamoff file_size_signed = in.tellg();
  if (file_size_signed < 0) fail(path, "cannot determine the file size");
  const auto file_size = static_cast<std::uint64_t>(file_size_signed);
  in.seekg(0, std::ios::beg);

  // --- prologue: magic, version, header length ---
  unsigned char prologue[kPrologueBytes] = {};
  const std::size_t prologue_read = static_cast<std::size_t>(std::min<std::uint64_t>(file_size, kPrologueBytes));
  in.read(reinterpret_cast<char*>(prologue), static_cast<std::streamsize>(prologue_read));
  if (!in) fail(path, "read failed: " + system_reason());
  const std::size_t magic_bytes_present = std::min<std::size_t>(prologue_read, kMagic.size());
  if (std::memcmp(prologue, kMagic.data(), magic_bytes_present) != 0)
    fail(path, "not a blocklab container (bad magic; expected \"BLKLAB\\r\\n\")");
  // A file that is a strict prefix of a valid prologue is truncated rather than of another type.
  if (file_size < kPrologueBytes)
    fail(path, "truncated: " + std::to_string(file_size) + " bytes, shorter than the " +
                   std::to_string(kPrologueBytes) + "-byte prologue (magic, version, header length)");
  const std::uint32_t version = read_u32_le(prologue + 8);
  if (version != kContainerVersion)
    fail(path, "unsupported container version " + std::to_string(version) + " (this build reads version " +
                   std::to_string(kContainerVersion) + ")");
  const std::uint32_t header_length = read_u32_le(prologue + 12);
  const std::uint64_t after_prologue = file_size - kPrologueBytes;
  if (header_length > after_prologue)
    fail(path, "header length " + std::to_string(header_length) + " runs past the end of the file (" +
                   std::to_string(after_prologue) + " bytes follow the prologue)");

  // --- JSON header ---
  std::string header_text(header_length, '\0');
  in.read(header_text.data(), static_cast<std::streamsize>(header_length));
  if (!in) fail(path, "read failed: " + system_reason());
  const nlohmann::json header = parse_header_json(path, header_text);
  if (!header.is_object()) fail(path, "header must be a JSON object, got " + std::string(header.type_name()));
  for (const std::string& key : kHeaderKeys)
    if (!header.contains(key)) fail(path, "header is missing key '" + key + "'");
  for (const auto& item : header.items())
    if (kHeaderKeys.count(item.key()) == 0 && item.key() != kRevisionKey)
      fail(path, "header has unknown key '" + item.key() + "'; valid keys: " + join(kHeaderKeys) + ", " + kRevisionKey);

  EncodedTexture texture;
  const nlohmann::json& format_name = header.at("format");
  if (!format_name.is_string()) fail(path, "header: 'format' must be a string, got " + format_name.dump());
  const Format* format = nullptr;
  try {
    format = &find_format(format_name.get<std::string>());
  } catch (const Error& error) {
    fail(path, error.what());
  }
  texture.format = format->name();
  if (header.contains(kRevisionKey)) {
    const nlohmann::json& revision = header.at(kRevisionKey);
    if (!revision.is_number_integer())
      fail(path, std::string("header: '") + kRevisionKey + "' must be an integer, got " + revision.dump());
    // Blocks of another revision may decode differently (a layout or decoding rule changed): refuse, never guess.
    if (revision.get<long long>() != format->decoder_revision())
      fail(path, "encoded with " + texture.format + " revision " + revision.dump() + ", this build decodes revision " +
                     std::to_string(format->decoder_revision()) +
                     " (its blocks may decode differently); re-encode the source image");
  }

  const nlohmann::json& options = header.at("options");
  if (!options.is_object()) fail(path, "header: 'options' must be an object, got " + options.dump());
  FormatOptions given;
  for (const auto& option : options.items()) {
    if (!option.value().is_string())
      fail(path, "header: option '" + option.key() + "' must be a string, got " + option.value().dump());
    given[option.key()] = option.value().get<std::string>();
  }
  try {
    texture.options = resolve_format_options(*format, given);
  } catch (const Error& error) {
    fail(path, error.what());
  }

  texture.width = static_cast<int>(header_integer(path, header, "width", 1, kMaxTextureDimension));
  texture.height = static_cast<int>(header_integer(path, header, "height", 1, kMaxTextureDimension));
  texture.channels = static_cast<int>(header_integer(path, header, "channels", 1, 4));
  if (texture.channels == 2) fail(path, "header: 'channels' must be 1, 3 or 4, got 2");

  int expected_block_bytes = 0;
  try {
    expected_block_bytes = format->block_bytes(texture.options);
  } catch (const Error& error) {
    fail(path, error.what());
  }
  texture.block_bytes = static_cast<int>(header_integer(path, header, "block_bytes", 1, 1 << 20));
  if (texture.block_bytes != expected_block_bytes)
    fail(path, "header: block_bytes is " + std::to_string(texture.block_bytes) + " but format '" +
                   format->name() + "' with these options uses " + std::to_string(expected_block_bytes));
  const long long block_count = header_integer(path, header, "block_count", 0, 1LL << 40);

  const nlohmann::json& side_data = header.at("side_data");
  if (!side_data.is_object()) fail(path, "header: 'side_data' must be an object, got " + side_data.dump());
  for (const auto& entry : side_data.items()) {
    if (!entry.value().is_array())
      fail(path, "header: side data '" + entry.key() + "' must be an array of numbers");
    std::vector<double>& values = texture.side_data[entry.key()];
    for (const nlohmann::json& value : entry.value()) {
      if (!value.is_number()) fail(path, "header: side data '" + entry.key() + "' holds a non-number " + value.dump());
      const double number = value.get<double>();
      // JSON has no Inf/NaN literal, but an out-of-range literal such as 1e999 parses to Inf.
      if (!std::isfinite(number))
        fail(path, "header: side data '" + entry.key() + "'[" + std::to_string(values.size()) + "] is not finite");
      values.push_back(number);
    }
  }

  // The blocks the format stores for this header (the 4x4 grid of width x height unless the format keeps them on
  // another grid described by its side data, Format::stored_block_count).
  std::size_t stored_blocks = 0;
  try {
    stored_blocks = format->stored_block_count(texture);
  } catch (const Error& error) {
    fail(path, error.what());
  }
  if (static_cast<std::uint64_t>(block_count) != stored_blocks)
    fail(path, "header: block_count is " + std::to_string(block_count) + " but a " + std::to_string(texture.width) +
                   "x" + std::to_string(texture.height) + " texture has " + std::to_string(stored_blocks) + " blocks");

  // --- block payload: exactly block_count * block_bytes bytes, nothing after it ---
  const std::uint64_t expected_payload = stored_blocks * static_cast<std::uint64_t>(texture.block_bytes);
  const std::uint64_t payload = after_prologue - header_length;
  if (payload < expected_payload)
    fail(path, "block data truncated: expected " + std::to_string(expected_payload) + " bytes, found " +
                   std::to_string(payload));
  if (payload > expected_payload)
    fail(path, std::to_string(payload - expected_payload) + " trailing bytes after the " +
                   std::to_string(expected_payload) + " bytes of block data");
  texture.blocks.resize(static_cast<std::size_t>(expected_payload));
  in.read(reinterpret_cast<char*>(texture.blocks.data()), static_cast<std::streamsize>(expected_payload));
  if (!in) fail(path, "read failed: " + system_reason());

  validate_encoded_texture(*format, texture, path);   // the same checks every decoder runs
  return texture;
}

}  // namespace blocklab
