// Test helper: every lattice point of a 4-D box of lattice index ranges (interval_bb's boxes), for the tests that
// check a box enclosure against the error at each point of the box.
#pragma once

#include <cstdint>

#include "core/problem.h"

namespace blocklab {

// Calls visit(x) for every x with x[p] = lattice.point(i_p), lo[p] <= i_p <= hi[p], in lexicographic index order.
template <typename Visit>
void for_each_lattice_point(const Lattice& lattice, const std::int64_t (&lo)[4], const std::int64_t (&hi)[4],
                            Visit visit) {
  double x[4];
  for (std::int64_t a = lo[0]; a <= hi[0]; ++a)
    for (std::int64_t b = lo[1]; b <= hi[1]; ++b)
      for (std::int64_t c = lo[2]; c <= hi[2]; ++c)
        for (std::int64_t d = lo[3]; d <= hi[3]; ++d) {
          x[0] = lattice.point(a);
          x[1] = lattice.point(b);
          x[2] = lattice.point(c);
          x[3] = lattice.point(d);
          visit(static_cast<const double*>(x));
        }
}

}  // namespace blocklab
