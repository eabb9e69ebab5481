// Lattice polish of one BC7 subset's quantised endpoints: coordinate descent on the stored codes.
//
// Rounding least-squares endpoints to the lattice (bc7_endpoint_rounding.h) is optimal only for the indices it
// assumed; after the indices are re-assigned, a neighbouring lattice point can be better. Each pass tries every
// stored code of every weighted lane one step up and one step down (the P-bits fixed), re-assigns the indices on
// the exactly decoded palette and keeps a step when the error drops; passes repeat until one improves nothing or
// `max_passes` is reached. This is the endpoint-perturbation step of the classic BC6H/BC7 encoders (Microsoft
// DirectXTex BC6HBC7.cpp "PerturbOne" / "OptimizeOne", after Donovan's reference encoder), written from that
// description, here with unit steps and the real decoder's palette as the score.
#pragma once

#include <cstdint>

#include "formats/bc7/bc7_quantise.h"

namespace blocklab {
namespace bc7 {

// Improves `endpoints` and `indices` (member order) of `count` texels in place; `error` is their current weighted
// squared error on entry and the new one on return. Never makes the error larger.
void polish_endpoints(const float (*texels)[4], int count, int index_bits, const EndpointLattice& lattice,
                      const float weights[4], int max_passes, QuantisedEndpoints& endpoints, std::uint8_t* indices,
                      float& error);

}  // namespace bc7
}  // namespace blocklab
