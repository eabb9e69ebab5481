// The command line of the benchmarks (CLI11): the options several benchmarks share (--data, --images, --presets,
// --repeat, --csv, --set, --no-astcenc), each with one meaning and one check everywhere, and the parse that answers
// --help with the benchmark's usage line and its options, and an unknown flag, a missing value or a malformed one with
// a one-line error on stderr.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "formats/format.h"

namespace blocklab {
namespace bench {

class CommandLine {
 public:
  // `usage` is the flags part of the usage line (e.g. "[--data DIR] [--repeat N]"); --help prints
  // "usage: NAME USAGE", then `description`, then every option with its help and default.
  CommandLine(const std::string& name, const std::string& usage, const std::string& description);

  CLI::App& app() { return app_; }

  // --data DIR: the data root (images in DIR/hdr, DIR/ldr).
  CLI::Option* add_data(std::string& root, const std::string& help = "data root");
  // FLAG a,b,...: a comma-separated list; given, it replaces the default.
  CLI::Option* add_list(const std::string& flag, std::vector<std::string>& values, const std::string& help);
  // An integer option or positional `name` in [lo, hi] (shown as N with its default).
  CLI::Option* add_integer(const std::string& name, int& value, int lo, int hi, const std::string& help);
  // --repeat N: rounds, an integer in [1, 1000].
  CLI::Option* add_repeat(int& rounds, const std::string& help);
  // --csv FILE: where the table is also written as CSV.
  CLI::Option* add_csv(std::string& path, const std::string& help);
  // --set key=value (repeatable): a format option, set in `options` over what they hold.
  CLI::Option* add_settings(FormatOptions& options, const std::string& help);
  // --no-astcenc: clears `astcenc` (no astcenc rows).
  CLI::Option* add_no_astcenc(bool& astcenc);

  // Parses the command line: nothing when the benchmark should run, else the exit status (0 after --help, 2 after an
  // error, both printed).
  std::optional<int> parse(int argc, char** argv);

 private:
  CLI::App app_;
};

}  // namespace bench
}  // namespace blocklab
