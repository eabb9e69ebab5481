// Container reader robustness (MISSION.md section 6): seeded random flips concentrated on the prologue and JSON
// header of a real .blk file of every registered format, and headers of printable junk, must give either a
// blocklab::Error or a texture that decodes (or is rejected by its decoder with an Error) -- never a crash, a hang
// or another exception type. Every truncation and whole-file flips, insertions and deletions of every format and
// preset, in .blk and DDS, are in test_registered_formats_fuzz.cpp. Run under BLOCKLAB_SANITIZE=ON to also catch
// memory errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "formats/common/container.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;

class ContainerFuzz : public ::testing::Test {
 protected:
  void SetUp() override {
    // Every case goes through a file (read_container reads paths): a memory file system keeps that cheap.
    std::error_code error;
    const fs::path base = fs::is_directory("/dev/shm", error) ? fs::path("/dev/shm") : fs::temp_directory_path();
    directory_ = base /
                 ("blocklab_test_container_fuzz_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  // Bytes of a real container written by write_container.
  std::string real_container(const std::string& format_name) const {
    const Format& format = find_format(format_name);
    Image image(7, 6);
    for (std::size_t i = 0; i < image.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) image.pixels[4 * i + c] = 0.37f * static_cast<float>(i + 1) * static_cast<float>(c + 1);
    EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{1, 1});
    const std::string file = (directory_ / (format_name + ".blk")).string();
    write_container(file, texture);
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }

  enum class Outcome { rejected, accepted };

  // Writes `bytes`, reads and decodes them; fails the test on anything but Error or a consistent decoded image.
  Outcome read_and_decode(const std::string& bytes) const {
    const std::string file = (directory_ / "case.blk").string();
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    try {
      const EncodedTexture texture = read_container(file);
      const Image image = find_format(texture.format).decode(texture, CodecContext{1, 1});
      EXPECT_EQ(image.width, texture.width);
      EXPECT_EQ(image.height, texture.height);
      for (float value : image.pixels) EXPECT_TRUE(std::isfinite(value));
      return Outcome::accepted;
    } catch (const Error& error) {
      last_error_ = error.what();
      return Outcome::rejected;
    } catch (const std::exception& other) {
      ADD_FAILURE() << "non-blocklab exception: " << other.what();
      return Outcome::rejected;
    }
  }

  fs::path directory_;
  mutable std::string last_error_;   // message of the latest Error, for failure reports
};

// Header-focused flips for every registered format (the whole-file truncations, flips, insertions and deletions of
// each format and preset are in test_registered_formats_fuzz.cpp).
TEST_F(ContainerFuzz, RandomHeaderFlipsGiveAnErrorOrAValidTexture) {
  for (const Format* format : all_formats()) {
    const std::string format_name = format->name();
    const std::string original = real_container(format_name);
    ASSERT_EQ(read_and_decode(original), Outcome::accepted) << format_name << ": " << last_error_;
    const std::size_t header_end = 16 + (static_cast<unsigned char>(original[12]) |
                                         (static_cast<unsigned char>(original[13]) << 8));
    std::mt19937_64 random(20240601);   // fixed seed: the same cases on every run
    std::size_t accepted = 0, rejected = 0;
    for (int iteration = 0; iteration < 600; ++iteration) {
      std::string bytes = original;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int f = 0; f < flips; ++f) {
        // Three flips in four land in the prologue + header, where the reader has the most to check.
        const std::size_t position =
            (random() % 4 != 0) ? random() % header_end : header_end + random() % (bytes.size() - header_end);
        bytes[position] = static_cast<char>(bytes[position] ^ static_cast<char>(1 + random() % 255));
      }
      (read_and_decode(bytes) == Outcome::accepted ? accepted : rejected) += 1;
    }
    // Header flips mostly break the file; some flips (in the payload or in a JSON string's case) keep it valid.
    EXPECT_GT(accepted, 0u) << format_name;
    EXPECT_GT(rejected, 0u) << format_name;
  }
}

TEST_F(ContainerFuzz, RandomHeadersOfPrintableJunkAreRejected) {
  std::mt19937_64 random(99);
  const std::string alphabet = "{}[]\":,0123456789.eE-+ abcdefghijklmnopqrstuvwxyz_\\";
  for (int iteration = 0; iteration < 1000; ++iteration) {
    std::string header(random() % 120, ' ');
    for (char& c : header) c = alphabet[random() % alphabet.size()];
    std::string bytes("BLKLAB\r\n\x01\x00\x00\x00", 12);
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((header.size() >> shift) & 0xFF));
    bytes += header;
    EXPECT_EQ(read_and_decode(bytes), Outcome::rejected) << header;
  }
}

}  // namespace
}  // namespace blocklab
