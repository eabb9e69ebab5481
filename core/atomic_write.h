// Whole-file writes that never leave a partial file at the target path. Every writer of the tree (images,
// .blk containers, DDS, run-folder records) goes through here.
//
// Contract (POSIX rename(2) is atomic within one file system):
//   - the bytes go to "<target>.tmp.<pid>" in the target's own folder, are checked by every write(2) and by
//     close(2), and only then is the temporary renamed over the target: a reader, or a process killed at any
//     point, sees the old file or the complete new one, never half of one. On any failure the temporary is
//     removed and Error("<path>: cannot write (<reason>)") is thrown; the target is untouched.
//   - a symbolic link at the target is written THROUGH: the link stays, and the file it names is replaced (the
//     temporary lives beside that file, so the rename stays within one file system). A dangling link is replaced
//     by the new file.
//   - a target that exists and is not a regular file (a character device such as /dev/full or /dev/null, a FIFO)
//     cannot be renamed over: it is opened and written in place, and every write error is still reported.
//   - a replaced regular file keeps its permission bits.
//   - no fsync: the guarantee covers a killed process, not a power cut.
// The temporary's name ends in ".tmp.<digits>", the pattern RunFolder::remove_stray_temp_files deletes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace blocklab {

void write_file_atomically(const std::string& path, const void* data, std::size_t size);

inline void write_file_atomically(const std::string& path, const std::string& content) {
  write_file_atomically(path, content.data(), content.size());
}
inline void write_file_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file_atomically(path, bytes.data(), bytes.size());
}

}  // namespace blocklab
