// The explicit table of formats (no self-registering statics): formats/registry.cpp lists them all.
#pragma once

#include <string>
#include <vector>

#include "formats/format.h"

namespace blocklab {

const std::vector<const Format*>& all_formats();
// Throws Error("unknown format 'x'; valid formats: a, b, c").
const Format& find_format(const std::string& name);

}  // namespace blocklab
