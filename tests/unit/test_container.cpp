// The ".blk" container (formats/common/container.h): round trip, and one rejection test per validated field,
// each checking that the message names the file and the reason.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "formats/common/container.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

class Container : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("blocklab_test_container_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string path(const std::string& name) const { return (directory_ / name).string(); }

  // A small real texture: rgbe, 9x5 (3x2 blocks), with side data.
  static EncodedTexture sample_texture() {
    const Format& format = find_format("rgbe");
    Image image(9, 5, 4);
    for (std::size_t i = 0; i < image.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) image.pixels[4 * i + c] = 0.01f * static_cast<float>(i * 7 + c * 13);
    EncodedTexture texture = format.encode(image, resolve_format_options(format, {{"decode_offset", "half"}}),
                                           CodecContext{1, 1});
    texture.side_data["scale"] = {1.5, -2e-300, 0.1};
    texture.side_data["empty"] = {};
    return texture;
  }

  static nlohmann::json sample_header() {
    return {{"format", "rgbe"},
            {"options", {{"decode_offset", "none"}, {"seed", "1"}}},
            {"width", 9},
            {"height", 5},
            {"channels", 3},
            {"block_bytes", 64},
            {"block_count", 6},
            {"side_data", nlohmann::json::object()}};
  }

  // Writes magic + version + header length + header text + payload bytes.
  void write_raw(const std::string& file, const std::string& header_text, std::size_t payload_bytes = 6 * 64,
                 std::uint32_t version = 1, std::string magic = std::string("BLKLAB\r\n", 8),
                 std::int64_t header_length = -1) const {
    std::string bytes = magic;
    const auto append_u32 = [&](std::uint32_t value) {
      for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((value >> shift) & 0xFF));
    };
    append_u32(version);
    append_u32(static_cast<std::uint32_t>(header_length >= 0 ? header_length
                                                             : static_cast<std::int64_t>(header_text.size())));
    bytes += header_text;
    bytes.append(payload_bytes, '\x11');
    std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }

  // Reads `file` expecting an Error that starts with the path and contains `reason`.
  static void expect_rejected(const std::string& file, const std::string& reason) {
    try {
      read_container(file);
      ADD_FAILURE() << "accepted; expected: " << reason;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(reason), std::string::npos) << "message: " << message << "\nexpected: " << reason;
    }
  }

  void expect_header_rejected(const nlohmann::json& header, const std::string& reason,
                              std::size_t payload_bytes = 6 * 64) const {
    const std::string file = path("case.blk");
    write_raw(file, header.dump(), payload_bytes);
    expect_rejected(file, reason);
  }

  fs::path directory_;
};

TEST_F(Container, RoundTripsEveryStoredField) {
  const EncodedTexture texture = sample_texture();
  write_container(path("sample.blk"), texture);
  const EncodedTexture read = read_container(path("sample.blk"));
  EXPECT_EQ(read.format, texture.format);
  EXPECT_EQ(read.options, texture.options);
  EXPECT_EQ(read.width, 9);
  EXPECT_EQ(read.height, 5);
  EXPECT_EQ(read.channels, 4);
  EXPECT_EQ(read.block_bytes, 64);
  EXPECT_EQ(read.blocks, texture.blocks);
  EXPECT_EQ(read.side_data, texture.side_data);   // doubles come back bit for bit
  EXPECT_TRUE(read.block_modes.empty());          // not stored
  EXPECT_EQ(std::distance(fs::directory_iterator(path("")), fs::directory_iterator()), 1);   // no temporary left
  // The decoded images agree too.
  const Format& format = find_format("rgbe");
  const Image a = format.decode(texture, CodecContext{1, 1});
  const Image b = format.decode(read, CodecContext{1, 1});
  EXPECT_EQ(a.pixels, b.pixels);
}

TEST_F(Container, FileStartsWithMagicVersionAndReadableJsonHeader) {
  write_container(path("sample.blk"), sample_texture());
  std::ifstream in(path("sample.blk"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 16u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("BLKLAB\r\n", 8));
  EXPECT_EQ(bytes.substr(8, 4), std::string("\x01\x00\x00\x00", 4));
  const std::uint32_t length = static_cast<unsigned char>(bytes[12]) | (static_cast<unsigned char>(bytes[13]) << 8) |
                               (static_cast<unsigned char>(bytes[14]) << 16) |
                               (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[15])) << 24);
  const nlohmann::json header = nlohmann::json::parse(bytes.substr(16, length));
  EXPECT_EQ(header.at("format"), "rgbe");
  EXPECT_EQ(header.at("block_count"), 6);
  EXPECT_EQ(header.at("options").at("decode_offset"), "half");
  EXPECT_EQ(bytes.size(), 16u + length + 6u * 64u);
}

TEST_F(Container, AcceptsAHandWrittenHeaderAndResolvesItsOptions) {
  nlohmann::json header = sample_header();
  header["options"] = {{"decode_offset", " half "}};   // seed and preset missing, value not canonical: resolved on read
  write_raw(path("hand.blk"), header.dump());
  const EncodedTexture texture = read_container(path("hand.blk"));
  EXPECT_EQ(texture.options, (FormatOptions{{"decode_offset", "half"}, {"preset", "medium"}, {"seed", "1"}}));
  EXPECT_EQ(texture.blocks, std::vector<std::uint8_t>(6 * 64, 0x11));
}

TEST_F(Container, RejectsAMissingFile) { expect_rejected(path("absent.blk"), "cannot open"); }

TEST_F(Container, RejectsBadMagic) {
  write_raw(path("magic.blk"), sample_header().dump(), 384, 1, std::string("BLKLAB\n\n", 8));
  expect_rejected(path("magic.blk"), "not a blocklab container (bad magic");
  std::ofstream(path("png.blk"), std::ios::binary) << "\x89PNG\r\n\x1a\n and more";
  expect_rejected(path("png.blk"), "bad magic");
}

TEST_F(Container, RejectsTruncatedPrologue) {
  std::ofstream(path("empty.blk"), std::ios::binary).flush();
  expect_rejected(path("empty.blk"), "truncated: 0 bytes");
  std::ofstream(path("short.blk"), std::ios::binary) << std::string("BLKLAB\r\n\x01\x00", 10);
  expect_rejected(path("short.blk"), "truncated: 10 bytes");
}

TEST_F(Container, RejectsAnotherVersion) {
  write_raw(path("v2.blk"), sample_header().dump(), 384, 2);
  expect_rejected(path("v2.blk"), "unsupported container version 2 (this build reads version 1)");
}

TEST_F(Container, RejectsHeaderLengthBeyondTheFile) {
  const std::string text = sample_header().dump();
  write_raw(path("long.blk"), text, 0, 1, std::string("BLKLAB\r\n", 8), static_cast<std::int64_t>(text.size()) + 1);
  expect_rejected(path("long.blk"), "header length " + std::to_string(text.size() + 1) + " runs past the end");
  write_raw(path("huge.blk"), text, 384, 1, std::string("BLKLAB\r\n", 8), 0xFFFFFFFFll);
  expect_rejected(path("huge.blk"), "header length 4294967295 runs past the end");
}

TEST_F(Container, RejectsMalformedJson) {
  write_raw(path("json.blk"), "{\"format\": \"rgbe\",");
  expect_rejected(path("json.blk"), "malformed JSON header");
  write_raw(path("utf8.blk"), "{\"format\": \"rg\xff\"}");
  expect_rejected(path("utf8.blk"), "malformed JSON header");
  write_raw(path("array.blk"), "[1, 2]");
  expect_rejected(path("array.blk"), "header must be a JSON object");
}

TEST_F(Container, RejectsDuplicateKeys) {
  std::string text = sample_header().dump();
  text.insert(1, "\"width\":9,");
  write_raw(path("dup.blk"), text);
  expect_rejected(path("dup.blk"), "duplicate key 'width'");
  std::string nested = sample_header().dump();
  nested.replace(nested.find("\"decode_offset\""), 0, "\"seed\":\"2\",");
  write_raw(path("dup_option.blk"), nested);
  expect_rejected(path("dup_option.blk"), "duplicate key 'seed'");
}

TEST_F(Container, RejectsMissingAndExtraKeys) {
  for (const char* key : {"format", "options", "width", "height", "channels", "block_bytes", "block_count",
                          "side_data"}) {
    nlohmann::json header = sample_header();
    header.erase(key);
    expect_header_rejected(header, std::string("header is missing key '") + key + "'");
  }
  nlohmann::json header = sample_header();
  header["mip_levels"] = 1;
  expect_header_rejected(header, "header has unknown key 'mip_levels'; valid keys: ");
}

TEST_F(Container, RecordsTheFormatRevisionAndRefusesAnotherOne) {
  const std::string file = path("revision.blk");
  write_container(file, sample_texture());
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string expected = "\"format_revision\":" + std::to_string(find_format("rgbe").decoder_revision());
  EXPECT_NE(bytes.find(expected), std::string::npos) << "the writer records Format::decoder_revision()";
  // A header without the field (files written before it existed) is read; the current decoder revision is read; any
  // other is refused, naming both revisions.
  nlohmann::json header = sample_header();
  write_raw(path("old.blk"), header.dump());
  EXPECT_NO_THROW(read_container(path("old.blk")));
  header["format_revision"] = find_format("rgbe").decoder_revision();
  write_raw(path("same.blk"), header.dump());
  EXPECT_NO_THROW(read_container(path("same.blk")));
  header["format_revision"] = find_format("rgbe").decoder_revision() + 1;
  const int decoder_revision = find_format("rgbe").decoder_revision();
  expect_header_rejected(header, "encoded with rgbe revision " + std::to_string(decoder_revision + 1) +
                                     ", this build decodes revision " + std::to_string(decoder_revision));
  header["format_revision"] = "2";
  expect_header_rejected(header, "'format_revision' must be an integer");
}

TEST_F(Container, RejectsUnknownFormatListingTheValidOnes) {
  nlohmann::json header = sample_header();
  header["format"] = "bc9";
  expect_header_rejected(header, "unknown format 'bc9'; valid formats: ");
  header["format"] = 7;
  expect_header_rejected(header, "'format' must be a string");
}

TEST_F(Container, RejectsOptionsThatDoNotResolve) {
  nlohmann::json header = sample_header();
  header["options"]["decode_offset"] = "quarter";
  expect_header_rejected(header, "rgbe: option 'decode_offset' must be one of none, half, got 'quarter'");
  header = sample_header();
  header["options"]["quality"] = "high";
  expect_header_rejected(header, "rgbe: unknown option 'quality'; valid options: decode_offset, preset, seed");
  header = sample_header();
  header["options"]["seed"] = 1;
  expect_header_rejected(header, "option 'seed' must be a string");
  header = sample_header();
  header["options"] = {"seed", "1"};
  expect_header_rejected(header, "'options' must be an object");
}

TEST_F(Container, RejectsSizesOutsideOneTo65536AndNonIntegers) {
  for (const char* key : {"width", "height"}) {
    for (const nlohmann::json& bad : {nlohmann::json(0), nlohmann::json(-4), nlohmann::json(65537),
                                      nlohmann::json(std::numeric_limits<std::uint64_t>::max())}) {
      nlohmann::json header = sample_header();
      header[key] = bad;
      expect_header_rejected(header, "header: '" + std::string(key) + "' is " + bad.dump() + ", outside [1, 65536]");
    }
    for (const nlohmann::json& bad : {nlohmann::json(9.0), nlohmann::json("9"), nlohmann::json(nullptr)}) {
      nlohmann::json header = sample_header();
      header[key] = bad;
      expect_header_rejected(header, "header: '" + std::string(key) + "' must be an integer");
    }
  }
}

TEST_F(Container, RejectsChannelCountsOtherThanOneThreeFour) {
  for (int channels : {0, 2, 5}) {
    nlohmann::json header = sample_header();
    header["channels"] = channels;
    expect_header_rejected(header, "'channels'");
  }
}

TEST_F(Container, RejectsBlockBytesDifferentFromTheFormats) {
  nlohmann::json header = sample_header();
  header["block_bytes"] = 96;
  expect_header_rejected(header, "block_bytes is 96 but format 'rgbe' with these options uses 64", 6 * 96);
}

TEST_F(Container, RejectsBlockCountMismatch) {
  nlohmann::json header = sample_header();
  header["block_count"] = 5;
  expect_header_rejected(header, "block_count is 5 but a 9x5 texture has 6 blocks", 5 * 64);
}

TEST_F(Container, RejectsPayloadSizeMismatchAndTrailingBytes) {
  expect_header_rejected(sample_header(), "block data truncated: expected 384 bytes, found 383", 383);
  expect_header_rejected(sample_header(), "block data truncated: expected 384 bytes, found 0", 0);
  expect_header_rejected(sample_header(), "1 trailing bytes after the 384 bytes of block data", 385);
}

TEST_F(Container, RejectsMalformedOrNonFiniteSideData) {
  nlohmann::json header = sample_header();
  header["side_data"] = {{"scale", 1.0}};
  expect_header_rejected(header, "side data 'scale' must be an array of numbers");
  header["side_data"] = {{"scale", {1.0, "2"}}};
  expect_header_rejected(header, "side data 'scale' holds a non-number \"2\"");
  header["side_data"] = nlohmann::json::array();
  expect_header_rejected(header, "'side_data' must be an object");
  // JSON has no Inf/NaN literal; an overflowing literal is rejected by the parser (nlohmann reports a number
  // overflow), so non-finite side data cannot enter through a file. The writer refuses it (see below).
  std::string text = sample_header().dump();
  text.replace(text.find("\"side_data\":{}"), 14, "\"side_data\":{\"scale\":[1.0,1e999]}");
  write_raw(path("inf.blk"), text);
  expect_rejected(path("inf.blk"), "malformed JSON header");
  text = sample_header().dump();
  text.replace(text.find("\"side_data\":{}"), 14, "\"side_data\":{\"scale\":[1.0,NaN]}");
  write_raw(path("nan.blk"), text);
  expect_rejected(path("nan.blk"), "malformed JSON header");
}

TEST_F(Container, WriterRejectsInconsistentTexturesAndUnwritablePaths) {
  EncodedTexture texture = sample_texture();
  texture.blocks.pop_back();
  EXPECT_THROW(write_container(path("bad.blk"), texture), Error);
  EXPECT_FALSE(fs::exists(path("bad.blk")));
  texture = sample_texture();
  texture.side_data["scale"][0] = std::numeric_limits<double>::quiet_NaN();
  try {
    write_container(path("nan.blk"), texture);
    ADD_FAILURE() << "wrote NaN side data";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("nan.blk: side data 'scale'[0] is not finite"), std::string::npos)
        << error.what();
  }
  texture = sample_texture();
  texture.format = "bc9";
  EXPECT_THROW(write_container(path("bc9.blk"), texture), Error);
  try {
    write_container(path("no/such/dir/x.blk"), sample_texture());
    FAIL() << "wrote into a missing directory";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("x.blk: cannot create file (No such file or directory)"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace blocklab
