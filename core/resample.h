// Image resampling to another size, format-agnostic: every channel of the RGBA storage is filtered alike, on the
// values as stored (code values for LDR images, linear radiance for HDR ones; no gamma conversion).
//
// Geometry (both filters): texel centres are aligned, so destination texel x samples the source at
//     u = (x + 0.5) * source_width / width - 0.5
// (the same for rows), the convention of GPU texture sampling and of the common image libraries; corners of the two
// images coincide.
//
// Edges: clamp. A tap or neighbour outside the source reads the nearest edge texel (the source is extended by
// replicating its border), the GPU's clamp-to-edge addressing.
//
// Channels: the result has the source's `channels`; for sources without alpha (1 or 3 channels) the stored alpha
// stays exactly 1. Values are not clamped (Lanczos lobes overshoot at edges; clamping is the caller's business).
#pragma once

#include <string>

#include "core/error.h"
#include "core/image.h"

namespace blocklab {

// Largest destination side (the largest texture side of formats/format.h).
constexpr int kMaxResizeDimension = 65536;

// Lanczos resampling (core/resample_lanczos.cpp): separable, kernel L(t) = sinc(t) sinc(t / a) for |t| < a, else 0,
// with a = `lobes` (1..8; Lanczos-3 by default). When shrinking by the factor f = width / source_width < 1 the kernel
// is stretched by 1 / f (its support becomes a / f source texels on each side: 12 taps per axis for a = 3 at
// f = 1/2), the usual antialiasing form; when enlarging it is used as is (2a taps). The weights of each destination
// texel are normalised to sum to 1, so a constant image stays constant; a linear ramp stays linear away from the
// edges exactly where the taps sit symmetrically about the sample (shrinking by 1/2) and to a few hundredths of a
// texel step elsewhere (the sampled kernel's first moment is not exactly zero). Throws Error when a size is below 1,
// lobes is outside 1..8 or the source holds fewer floats than width * height * 4.
Image lanczos_resize(const Image& source, int width, int height, int lobes = 3);

// Bilinear resampling (core/resample_bilinear.cpp): each destination texel interpolates the 2x2 source texels around
// u, v (clamped to [0, source size - 1]) with weights (1 - tu, tu) x (1 - tv, tv); a linear ramp stays linear away
// from the edges. Meant for enlarging (it does not low-pass when shrinking). Errors as lanczos_resize.
Image bilinear_resize(const Image& source, int width, int height);

// The argument checks both filters share: Error("<who>: ...") naming the bad size.
inline void check_resize_arguments(const Image& source, int width, int height, const std::string& who) {
  if (source.width < 1 || source.height < 1 || source.pixels.size() != source.texel_count() * 4)
    fail(who, "the source image is " + std::to_string(source.width) + "x" + std::to_string(source.height) + " with " +
                  std::to_string(source.pixels.size()) + " floats (needs sizes >= 1 and 4 floats per texel)");
  if (width < 1 || height < 1 || width > kMaxResizeDimension || height > kMaxResizeDimension)
    fail(who, "cannot resize to " + std::to_string(width) + "x" + std::to_string(height) + " (each side must be in [1, " +
                  std::to_string(kMaxResizeDimension) + "])");
}

}  // namespace blocklab
