// Every writer of the tree (EXR, Radiance .hdr, PFM, PNG, the .blk container, DDS) reports a failed write and leaves
// no partial file at the target (core/atomic_write.h). Failures are produced two ways: /dev/full (ENOSPC on every
// write) reached through a symbolic link, and RLIMIT_FSIZE (EFBIG once a file passes a few bytes).
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <functional>
#include <string>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"
#include "formats/common/container.h"
#include "formats/common/dds.h"
#include "formats/registry.h"
#include "test_image_io_common.h"

namespace blocklab {
namespace {

namespace fs = std::filesystem;
using test_io::TempDir;

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

EncodedTexture texture_of(const std::string& format_name) {
  const Format& format = find_format(format_name);
  return format.encode(test_io::synthetic_image(16, 12, 3, true, 5), resolve_format_options(format, {}),
                       CodecContext{1, 1});
}

// One writer per output kind, each given the path it writes to.
struct NamedWriter {
  std::string extension;
  std::function<void(const std::string&)> write;
};

std::vector<NamedWriter> all_writers() {
  const Image hdr = test_io::synthetic_image(40, 30, 4, false, 3);
  return {
      {".exr", [hdr](const std::string& path) { write_image(path, hdr); }},
      {".exr", [hdr](const std::string& path) { write_image(path, hdr, WriteOptions{ExrPixelType::float32, 8}); }},
      {".hdr", [hdr](const std::string& path) { write_image(path, hdr); }},
      {".pfm", [hdr](const std::string& path) { write_image(path, hdr); }},
      {".png", [hdr](const std::string& path) { write_image(path, hdr); }},
      {".blk", [](const std::string& path) { write_container(path, texture_of("rgbe")); }},
      {".dds", [](const std::string& path) { write_dds(path, texture_of("bc1")); }},
  };
}

// `ln -sf /dev/full out.exr`: the link names a device, which cannot be renamed over, so it is written in place and
// the write error surfaces (the image writers pick the file type by the link's extension).
TEST(AtomicWrite, EveryWriterReportsAFullDiskReachedThroughASymlink) {
  TempDir dir("atomic_full_link");
  for (const NamedWriter& writer : all_writers()) {
    const std::string link = dir.file("out" + writer.extension);
    fs::remove(link);
    fs::create_symlink("/dev/full", link);
    const std::string message = error_of([&] { writer.write(link); });
    EXPECT_NE(message.find(link + ": cannot write (No space left on device)"), std::string::npos)
        << writer.extension << ": " << message;
    EXPECT_TRUE(fs::is_symlink(link)) << "the link must not be replaced by a regular file";
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("")), fs::directory_iterator()), 6);  // the links only
}

TEST(AtomicWrite, SymlinkToARegularFileIsWrittenThroughAndKept) {
  TempDir dir("atomic_link");
  fs::create_directories(dir.file("real"));
  test_io::write_text(dir.file("real/target.txt"), "old");
  fs::create_symlink("real/target.txt", dir.file("link.txt"));
  write_file_atomically(dir.file("link.txt"), std::string("new content"));
  EXPECT_TRUE(fs::is_symlink(dir.file("link.txt")));
  const test_io::Bytes bytes = test_io::read_bytes(dir.file("real/target.txt"));
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "new content");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("real")), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, ReplacedFileKeepsItsPermissionBits) {
  TempDir dir("atomic_mode");
  const std::string path = dir.file("kept.txt");
  test_io::write_text(path, "old");
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  write_file_atomically(path, std::string("new"));
  EXPECT_EQ(fs::status(path).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

TEST(AtomicWrite, DirectoryTargetIsAnError) {
  TempDir dir("atomic_dir");
  fs::create_directories(dir.file("sub"));
  EXPECT_NE(error_of([&] { write_file_atomically(dir.file("sub"), std::string("x")); }).find("is a directory"),
            std::string::npos);
}

// With RLIMIT_FSIZE at 64 bytes every writer fails part-way (EFBIG): the old file must survive untouched and no
// temporary may be left beside it.
TEST(AtomicWrite, FailedWriteLeavesTheOldFileAndNoTemporary) {
  TempDir dir("atomic_efbig");
  std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the default kill
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  for (const NamedWriter& writer : all_writers()) {
    const std::string path = dir.file("target" + writer.extension);
    test_io::write_text(path, "previous content");
    rlimit small = saved;
    small.rlim_cur = 64;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    const std::string message = error_of([&] { writer.write(path); });
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
    EXPECT_NE(message.find(path + ": cannot write (File too large)"), std::string::npos)
        << writer.extension << ": " << message;
    const test_io::Bytes bytes = test_io::read_bytes(path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "previous content") << writer.extension;
    fs::remove(path);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("")), fs::directory_iterator()), 0)
        << writer.extension << " left a temporary file";
  }
}

TEST(AtomicWrite, FailedFirstWriteLeavesNoFileAtAll) {
  TempDir dir("atomic_new");
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 64;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string message = error_of([&] { write_image(dir.file("new.exr"), test_io::synthetic_image(40, 30, 3, false)); });
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
  EXPECT_NE(message.find("cannot write"), std::string::npos) << message;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("")), fs::directory_iterator()), 0);
}

}  // namespace
}  // namespace blocklab
