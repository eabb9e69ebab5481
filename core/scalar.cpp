// Text form of blocklab::Tribool (core/scalar.h).
#include "core/scalar.h"

namespace blocklab {

const char* to_string(Tribool value) {
  switch (value) {
    case Tribool::no: return "no";
    case Tribool::yes: return "yes";
    case Tribool::maybe: return "maybe";
  }
  return "maybe";   // unreachable for valid enumerators; an invalid value carries no information
}

}  // namespace blocklab
