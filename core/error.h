// blocklab error type. Library code never prints and never exits: it throws blocklab::Error with a message that
// names the file / key / line and the reason, and the CLI turns it into one line on stderr and a non-zero exit.
#pragma once

#include <stdexcept>
#include <string>

namespace blocklab {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error("<where>: <why>"). `where` is a file path, "file:line", a YAML key path or an option name.
[[noreturn]] inline void fail(const std::string& where, const std::string& why) {
  throw Error(where.empty() ? why : where + ": " + why);
}

}  // namespace blocklab
