// The explicit table of formats (DESIGN.md: no self-registering statics). To add a format, declare its accessor
// (`const Format& <name>_format();`) in formats/<name>/<name>_format.h and add one line to the table below; the
// registry unit test checks that names are unique and every format's options resolve with their defaults.
#include "formats/registry.h"

#include "core/error.h"
#include "formats/banterle/banterle_format.h"
#include "formats/bc1/bc1_format.h"
#include "formats/bc3/bc3_format.h"
#include "formats/bc4/bc4_format.h"
#include "formats/bc7/bc7_format.h"
#include "formats/fp16/fp16_format.h"
#include "formats/mavridis/mavridis_format.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/rgbe/rgbe_format.h"
#include "formats/wang/wang_format.h"

namespace blocklab {

const std::vector<const Format*>& all_formats() {
  // Built on first use (thread-safe function-local static), in the order `blocklab list` shows them.
  static const std::vector<const Format*> table = {
      &rgbe_format(),
      &fp16_format(),
      &bc1_format(),
      &bc3_format(),
      &bc4_format(),
      &bc7_format(),
      &banterle_format(),
      &munkberg_format(),
      &wang_format(),
      &mavridis_format(),
  };
  return table;
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

}  // namespace blocklab
