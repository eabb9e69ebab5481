// Range checks of the fields a packer writes (munkberg_block.cpp, ext_s3tc_block.cpp, two_plane_block.cpp), with an
// error that names the field. The name is built only when a check fails: the encoders pack every trial block, and
// building "base[2]"-style names for every field of every block cost ~8k instructions per packed block (callgrind,
// 2026-11-26), about 4 % of the fast encode.
#pragma once

#include <string>

#include "core/error.h"

namespace blocklab::munkberg {

// Throws Error("munkberg: <field_name()>: <value> is outside lo..hi") unless lo <= value <= hi.
template <typename FieldName>
void check_field_range(long long value, long long lo, long long hi, const FieldName& field_name) {
  if (value >= lo && value <= hi) return;
  fail("munkberg", field_name() + ": " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." +
                       std::to_string(hi));
}

}  // namespace blocklab::munkberg
