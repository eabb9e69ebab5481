// One experiment cell: encode, decode, requested metrics, artifacts, record (see cell_pipeline.h).
#include "experiments/cell_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "core/error.h"
#include "core/image_io.h"
#include "experiments/results_writer.h"
#include "formats/common/mode_map.h"

namespace blocklab {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json input_report_json(const InputReport& report) {
  return {{"nan", report.nan_count},
          {"positive_inf", report.positive_inf_count},
          {"negative_inf", report.negative_inf_count},
          {"negative", report.negative_count},
          {"changed", report.changed_count()}};
}

// JSON numbers hold no infinity or NaN: those are the strings "inf", "-inf", "nan" (experiments/results_writer.h).
void store_metric(nlohmann::json& record, const std::string& name, const MetricResult& result) {
  record["metrics"][name] = metric_value_json(result.value);
  record["metric_details"][name] = result.details;
}

void mark_failed(nlohmann::json& record, const std::string& message) {
  record["status"] = "error";
  record["error"] = message;
}

}  // namespace

SourceImage load_source_image(const std::string& absolute_path, const std::string& relative_path, InputPolicy policy,
                              const ImageCrop& crop) {
  SourceImage source;
  try {
    Image image = read_image(absolute_path);
    if (crop.enabled) {
      int width = crop.width, height = crop.height, x = crop.x, y = crop.y;
      if (crop.centred) {
        width = std::min(width, image.width);   // an image smaller than the crop is kept whole in that direction
        height = std::min(height, image.height);
        x = (image.width - width) / 2;
        y = (image.height - height) / 2;
      } else if (x + width > image.width || y + height > image.height) {
        fail(relative_path, "crop " + std::to_string(crop.width) + "x" + std::to_string(crop.height) + " at (" +
                                std::to_string(x) + ", " + std::to_string(y) + ") does not fit the " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
      }
      image = crop_image(image, x, y, width, height);
      source.crop = {x, y, width, height};
    }
    source.report = apply_input_policy(image, policy, relative_path);
    source.image = std::move(image);
  } catch (const Error& e) {
    source.error = e.what();
  }
  return source;
}

nlohmann::json cell_record_skeleton(const CellJob& job) {
  const ExperimentConfig& config = *job.config;
  const Treatment& treatment = *job.treatment;
  const FormatVariant& variant = config.variants.at(treatment.variant_index);
  nlohmann::json record;
  record["key"] = job.key;
  record["results_schema"] = kResultsSchemaVersion;
  record["experiment"] = config.name;
  record["image"] = job.image.relative_path;
  record["image_sha256"] = job.image.sha256;
  record["width"] = nullptr;
  record["height"] = nullptr;
  record["channels"] = nullptr;
  record["format"] = variant.format->name();
  record["format_revision"] = variant.format->revision();
  record["label"] = variant.label;
  record["options"] = treatment.resolved;
  record["ablation"] = treatment.ablation;
  record["ablation_patch"] = treatment.applied_patch;
  record["bpp"] = nullptr;
  record["metrics"] = nlohmann::json::object();
  record["metric_details"] = nlohmann::json::object();
  record["encode_seconds"] = nullptr;
  record["decode_seconds"] = nullptr;
  record["threads"] = job.threads_used;
  record["seed"] = effective_seed(config, treatment);
  record["input_policy"] = to_string(config.input_policy);
  record["input_report"] = nullptr;
  record["mode_shares"] = nullptr;   // {mode: share of blocks} when the format records block modes
  record["status"] = "ok";
  record["blocklab_version"] = BLOCKLAB_VERSION;
  record["git_sha"] = job.git_sha;
  record["host"] = job.host;
  record["rank"] = job.rank >= 0 ? nlohmann::json(job.rank) : nlohmann::json();
  return record;
}

nlohmann::json compute_cell(const CellJob& job, const SourceImage& source, const RunFolder& folder) {
  const ExperimentConfig& config = *job.config;
  const Treatment& treatment = *job.treatment;
  const Format& format = *config.variants.at(treatment.variant_index).format;
  nlohmann::json record = cell_record_skeleton(job);
  // Every failure of this cell (including a bug surfacing as another std::exception) becomes an "error" record so
  // that the remaining cells still run; the run then exits non-zero.
  try {
    record["bpp"] = format.bits_per_pixel(treatment.resolved);
    if (!source.image) {
      mark_failed(record, source.error);
      return record;
    }
    const Image& reference = *source.image;
    record["width"] = reference.width;
    record["height"] = reference.height;
    record["channels"] = reference.channels;
    record["input_report"] = input_report_json(source.report);
    if (source.crop) record["crop"] = {{"x", (*source.crop)[0]}, {"y", (*source.crop)[1]}, {"width", (*source.crop)[2]},
                                       {"height", (*source.crop)[3]}};

    const CodecContext context{job.threads_used, effective_seed(config, treatment)};
    const auto encode_start = std::chrono::steady_clock::now();
    const EncodedTexture encoded = format.encode(reference, treatment.resolved, context);
    record["encode_seconds"] = seconds_since(encode_start);
    const auto decode_start = std::chrono::steady_clock::now();
    const Image decoded = format.decode(encoded, context);
    record["decode_seconds"] = seconds_since(decode_start);

    for (const MetricRequest& request : config.metrics) {
      store_metric(record, request.column(), request.metric->compute(reference, decoded, request.options));
    }
    if (!encoded.block_modes.empty()) {
      const std::vector<std::string> names = format.modes();
      const std::vector<double> shares = mode_shares(encoded, names);
      // A JSON object (keys sort alphabetically in nlohmann::json); readers look modes up by name.
      nlohmann::json object = nlohmann::json::object();
      for (std::size_t m = 0; m < names.size(); ++m) object[names[m]] = shares[m];
      record["mode_shares"] = object;
      if (config.mode_maps) {
        const std::string name = job.key + ".modes.png";
        write_image(folder.artifact_path("mode_maps", name), mode_map_image(encoded, names, &reference));
        record["artifacts"]["mode_map"] = "mode_maps/" + name;
      }
    }

    // Artifacts are named by cell key, so two cells never share a file and a re-run overwrites its own.
    if (config.save_decoded) {
      const bool hdr = reference.metadata.is_hdr;
      WriteOptions options;
      options.exr_pixel_type = ExrPixelType::float32;   // decoded values are written exactly, not re-quantised
      options.png_bits = reference.metadata.pixel_type == "uint16" ? 16 : 8;
      const std::string name = job.key + (hdr ? ".exr" : ".png");
      write_image(folder.artifact_path("decoded", name), decoded, options);
      record["artifacts"]["decoded"] = "decoded/" + name;
    }
    for (const std::string& metric_name : config.error_maps) {
      const MetricRequest* request = nullptr;
      for (const MetricRequest& m : config.metrics) {
        if (m.column() == metric_name) request = &m;
      }
      const Image map = request->metric->error_map(reference, decoded, request->options);
      const std::string name = job.key + "." + metric_name + ".exr";
      WriteOptions options;
      options.exr_pixel_type = ExrPixelType::float32;
      write_image(folder.artifact_path("error_maps", name), map, options);
      record["artifacts"]["error_maps"][metric_name] = "error_maps/" + name;
    }
  } catch (const Error& e) {
    mark_failed(record, e.what());
  } catch (const std::exception& e) {
    mark_failed(record, std::string("internal error: ") + e.what());
  }
  return record;
}

}  // namespace blocklab
