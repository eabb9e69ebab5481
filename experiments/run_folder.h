// The run folder and its content-addressed cell store.
//
// Layout:  <run>/config.yaml      copy of the source config            (written before work starts)
//          <run>/resolved.json    expanded cells + data root            (written before work starts)
//          <run>/provenance.json  git SHA, build, libraries, machine    (written before work starts, completed after)
//          <run>/cells/<h[0:2]>/<h>.json   one record per cell, h = cell key (experiments/cell_key.h), with
//                                          record_sha256, the checksum of the rest of the record
//          <run>/results.jsonl, results.csv   derived from the cell files after the run, in cell-expansion order
//          <run>/decoded/, <run>/error_maps/  optional artifacts named by cell key
// Every file is written by write_file_atomically (core/atomic_write.h) to "<name>.tmp.<pid>" and renamed over the
// final name (rename is atomic on POSIX), so a killed run leaves either the old file, the new file, or a stray temp file that the next run deletes - never half a record.
// Writers sharing a folder: the ranks of one MPI job (rank 0 removes stray temporaries before any rank writes),
// or the jobs of a sharded run (experiments/shard.h), which remove only temporaries untouched for an hour, since
// another job may be writing the rest. Otherwise one process per run folder at a time.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/atomic_write.h"  // write_file_atomically: every run-folder file is written through it

namespace blocklab {

// The field of a cell file holding the checksum of the rest of the record.
constexpr const char* kRecordChecksumKey = "record_sha256";

class RunFolder {
 public:
  // Creates the folder and cells/ when missing.
  explicit RunFolder(const std::string& dir);

  const std::string& dir() const { return dir_; }
  std::string path(const std::string& relative) const;      // <run>/<relative>
  std::string cell_path(const std::string& key) const;      // <run>/cells/<h[0:2]>/<h>.json

  // The stored record of a cell (without its record_sha256), or nothing when the file is absent, unreadable, not
  // JSON, holds another key, has no record_sha256, or its content no longer hashes to it (all of which mean:
  // compute it again). The checksum catches hand edits and disk damage, not deliberate forgery.
  std::optional<nlohmann::json> read_cell(const std::string& key) const;
  // Stores `record` with record_sha256 = SHA-256 of record.dump() (compact, keys sorted) added.
  void write_cell(const std::string& key, const nlohmann::json& record) const;

  // The stored records of `keys` (read_cell of each, on up to `threads` threads), in the order of `keys`.
  std::vector<std::optional<nlohmann::json>> read_cells(const std::vector<std::string>& keys, int threads) const;

  // Deletes "*.tmp.<digits>" files left in the folder (and below it) by a killed run whose last change is at least
  // `untouched_for` old; returns how many.
  std::size_t remove_stray_temp_files(std::chrono::seconds untouched_for = std::chrono::seconds(0)) const;

  // Writes <run>/<relative> (atomically) unless it already holds exactly `content`: several jobs of one sharded
  // run write the same config.yaml and resolved.json.
  void write_file_unless_same(const std::string& relative, const std::string& content) const;

  // <run>/<subdir>/<file name>, creating <subdir>.
  std::string artifact_path(const std::string& subdir, const std::string& file_name) const;

 private:
  std::string dir_;
};

}  // namespace blocklab
