// The explicit table of formats (DESIGN.md: no self-registering statics). To add a format, declare its accessor
// (`const Format& <name>_format();`) in formats/<name>/<name>_format.h and add one line to the table below; the
// registry unit test checks that names are unique and every format's options resolve with their defaults.
#include "formats/registry.h"

#include "core/error.h"
#include "formats/banterle/banterle_format.h"
#include "formats/bc6h/bc6h_format.h"
#include "formats/bc1/bc1_format.h"
#include "formats/bc3/bc3_format.h"
#include "formats/bc4/bc4_format.h"
#include "formats/bc7/bc7_format.h"
#include "formats/compete/compete_format.h"
#include "formats/downscaled/downscaled_format.h"
#include "formats/fp16/fp16_format.h"
#include "formats/mavridis/mavridis_format.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/rgbe/rgbe_format.h"
#include "formats/wang/wang_format.h"

namespace blocklab {

namespace {

std::vector<const Format*>& format_table() {
  // Built on first use (thread-safe function-local static), in the order `blocklab list` shows them.
  static std::vector<const Format*> table = {
      &rgbe_format(),
      &fp16_format(),
      &bc1_format(),
      &bc3_format(),
      &bc4_format(),
      &bc7_format(),
      &bc6h_format(),
      &bc6h_sf_format(),
      &banterle_format(),
      &munkberg_format(),
      &compete_format(),
      &wang_format(),
      &mavridis_format(),
      &downscaled_format(),
  };
  return table;
}

}  // namespace

const std::vector<const Format*>& all_formats() { return format_table(); }

void register_format(const Format& format) {
  for (const Format* known : format_table())
    if (known->name() == format.name()) throw Error("register_format: format '" + format.name() + "' already exists");
  format_table().push_back(&format);
}

const Format& find_format(const std::string& name) {
  std::string valid;
  for (const Format* format : all_formats()) {
    if (format->name() == name) return *format;
    valid += (valid.empty() ? "" : ", ") + format->name();
  }
  // Never fall back silently on an unknown name: list the valid ones.
  throw Error("unknown format '" + name + "'; valid formats: " + valid);
}

std::vector<RegisteredBlockProblem> registered_block_problems() {
  std::vector<RegisteredBlockProblem> problems;
  for (const Format* format : all_formats())
    for (BlockProblem& problem : format->block_problems()) problems.push_back({format, std::move(problem)});
  return problems;
}

RegisteredBlockProblem find_block_problem(const std::string& full_name) {
  std::string valid;
  for (RegisteredBlockProblem& entry : registered_block_problems()) {
    if (entry.full_name() == full_name) return entry;
    valid += (valid.empty() ? "" : ", ") + entry.full_name();
  }
  throw Error("unknown block problem '" + full_name + "'; valid problems: " + valid);
}

}  // namespace blocklab
