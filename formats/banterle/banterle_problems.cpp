// The `banterle` block problem: the tone-mapping parameter fit of Banterle et al. 2008 section 3.1 (eq. 3,
// tmo_fit_problem.h). The format fits it once per IMAGE; as a block problem it is drawn from ONE 4x4 HDR block: the
// luminance histogram of the block's 16 texels (Listing 1 weights), the Reinhard 2002 estimate of those
// luminances with the format's default geometric mean, and the fit box of tmo_fit.h around it. Continuous
// parameters (log2 alpha, log2 Lwhite, no lattice): solvers that need a lattice report themselves unavailable.
#include "formats/banterle/banterle_problems.h"

#include <cmath>
#include <memory>

#include "formats/banterle/reinhard_operator.h"
#include "formats/banterle/tmo_fit.h"
#include "formats/banterle/tmo_fit_problem.h"

namespace blocklab {

namespace {

std::unique_ptr<Problem> make_block_tmo_fit(const BlockTexels& block, std::uint64_t) {
  std::vector<double> luminances;
  for (int t = 0; t < kBlockTexels; ++t) luminances.push_back(static_cast<double>(banterle_luminance(block.rgba[t])));
  const ReinhardParameters estimate =
      clamp_to_fit_box(estimate_reinhard_parameters(luminances, TmoMean::geometric));
  auto histogram = std::make_shared<const LuminanceHistogram>(build_luminance_histogram(luminances));
  return std::make_unique<ErrorProblem<Eq3Error>>(
      make_problem(Eq3Error{std::move(histogram), std::log2(estimate.mean)}, tmo_fit_bounds(estimate)));
}

}  // namespace

std::vector<BlockProblem> banterle_block_problems() {
  BlockProblem tmo_fit{"tmo_fit",
                       "section 3.1 eq. 3: (log2 alpha, log2 Lwhite) of the Reinhard operator, mean squared log2 "
                       "error after 8-bit quantisation, on the luminances of one block",
                       BlockImageKind::hdr, make_block_tmo_fit};
  tmo_fit.min_checked_gradient_fraction = 0.2;   // the 8-bit quantiser makes eq. 3 a staircase
  // Over a box whose codes reach 255, the interval inverse of eq. 2 divides by an enclosure of
  // sqrt(discriminant) + (1 - L') that contains 0 (the dependency problem): [finite, +inf] enclosures.
  tmo_fit.bounded_enclosures = false;
  return {tmo_fit};
}

}  // namespace blocklab
