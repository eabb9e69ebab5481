// Text of a double that reads back as the same double: "%.17g" (17 significant digits always round-trip through a
// correctly rounded parser such as strtod or yaml-cpp's; NaN and infinities print as nan / inf). For error messages
// that must show the exact offending value and for generated data files (a format's trained tables), whose
// bytes must not depend on anything but the value.
#pragma once

#include <string>

namespace blocklab {

std::string exact_number_text(double value);

}  // namespace blocklab
