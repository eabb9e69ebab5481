// Chroma subsampling of `mavridis` (Mavridis & Papaioannou 2012, section 3.5: "the two chrominance channels are
// downsampled by a factor of two or four"; the paper names no filter): a box average over factor x factor texels
// (edge replication beyond the plane) on encode, bilinear upsampling at texel centres on decode; and the YCoCg-R
// planes of an image (the format's default colour transform, core/color_spaces.h) for the analyses.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/color_spaces.h"
#include "core/image.h"

#include "formats/mavridis/mavridis_plane_codec.h"

namespace blocklab {
namespace mavridis {

// Box average over factor x factor texels (edge replication beyond the plane).
inline Plane subsample(const Plane& plane, int factor) {
  Plane out;
  out.width = (plane.width + factor - 1) / factor;
  out.height = (plane.height + factor - 1) / factor;
  out.values.resize(static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      double sum = 0.0;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i)
          sum += plane.at(std::min(x * factor + i, plane.width - 1), std::min(y * factor + j, plane.height - 1));
      out.values[static_cast<std::size_t>(y) * out.width + x] = sum / (factor * factor);
    }
  return out;
}

// Bilinear upsampling to width x height: sample k sits at the centre of its factor x factor footprint.
inline double upsampled(const Plane& plane, int factor, int x, int y) {
  const double fx = (x + 0.5) / factor - 0.5, fy = (y + 0.5) / factor - 0.5;
  const double cx = std::clamp(fx, 0.0, double(plane.width - 1)), cy = std::clamp(fy, 0.0, double(plane.height - 1));
  const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
  const int x1 = std::min(x0 + 1, plane.width - 1), y1 = std::min(y0 + 1, plane.height - 1);
  const double tx = cx - x0, ty = cy - y0;
  return (1 - ty) * ((1 - tx) * plane.at(x0, y0) + tx * plane.at(x1, y0)) +
         ty * ((1 - tx) * plane.at(x0, y1) + tx * plane.at(x1, y1));
}

// Y, Co, Cg of YCoCg-R (integer lifting) of the image's RGB rounded to 8-bit code values.
inline std::array<Plane, 3> ycocg_r_planes(const Image& image) {
  std::array<Plane, 3> planes;
  for (Plane& p : planes) p = Plane::zeros(image.width, image.height);
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    int c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = static_cast<int>(std::lround(std::clamp(static_cast<double>(image.pixels[i * 4 + k]), 0.0, 1.0) * 255.0));
    const YCoCgR v = rgb_to_ycocg_r(c[0], c[1], c[2]);
    planes[0].values[i] = v.y;
    planes[1].values[i] = v.co;
    planes[2].values[i] = v.cg;
  }
  return planes;
}

}  // namespace mavridis
}  // namespace blocklab
