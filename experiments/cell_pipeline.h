// One cell of an experiment: source image (already through the input policy) -> encode -> decode -> the requested
// metrics (and nothing else) -> optional artifacts -> one JSON record. Failures become records with status "error".
#pragma once

#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/input_policy.h"
#include "experiments/cell_key.h"
#include "experiments/config.h"
#include "experiments/run_folder.h"

namespace blocklab {

// A source image as the codec sees it, read once and shared by every cell of that image.
struct SourceImage {
  std::optional<Image> image;    // empty when reading or the input policy failed
  InputReport report;
  std::string error;             // the failure message when `image` is empty
  std::optional<std::array<int, 4>> crop;   // x, y, width, height of the crop taken (config.crop)
};

// Reads `absolute_path` and applies `policy`; a blocklab::Error is kept in `error`, not thrown.
// `crop` (config.crop): applied after reading, before the input policy; a rectangle at (x, y) that does not fit the
// image is this image's error (every cell of it fails with the message), a centred one is clipped to the image.
SourceImage load_source_image(const std::string& absolute_path, const std::string& relative_path, InputPolicy policy,
                              const ImageCrop& crop = ImageCrop{});

struct CellJob {
  const ExperimentConfig* config = nullptr;
  const Treatment* treatment = nullptr;
  ImageIdentity image;
  std::string key;
  int threads_used = 1;          // resolved thread count (recorded; CodecContext gets it)
  std::string git_sha;
  std::string host;              // the machine computing the cell (recorded)
  int rank = -1;                 // its MPI rank, -1 outside MPI (recorded as null)
};

// The record fields known without running the cell (identity, options, bpp, provenance).
nlohmann::json cell_record_skeleton(const CellJob& job);

// Runs the cell and returns its full record (status "ok" or "error"). Never throws for a cell failure.
nlohmann::json compute_cell(const CellJob& job, const SourceImage& source, const RunFolder& folder);

}  // namespace blocklab
