// The explicit table of formats (no self-registering statics): formats/registry.cpp lists them all. A test binary
// may add a format of its own at run time (register_format) to show that table-driven coverage picks it up.
#pragma once

#include <string>
#include <vector>

#include "formats/format.h"

namespace blocklab {

const std::vector<const Format*>& all_formats();
// Throws Error("unknown format 'x'; valid formats: a, b, c").
const Format& find_format(const std::string& name);

// Appends `format` (which must outlive every later use of the registry) to all_formats(); throws Error when its
// name is taken. Not safe while another thread reads the registry: call it before any work starts (a test's setup).
void register_format(const Format& format);

// One block problem of a registered format (Format::block_problems()).
struct RegisteredBlockProblem {
  const Format* format = nullptr;
  BlockProblem problem;
  std::string full_name() const { return format->name() + "." + problem.name; }
};

// Every registered format's block problems, formats in registry order, each format's in its table's order.
std::vector<RegisteredBlockProblem> registered_block_problems();
// By "<format>.<problem>"; throws Error("unknown block problem 'x'; valid problems: a.b, ...").
RegisteredBlockProblem find_block_problem(const std::string& full_name);

}  // namespace blocklab
