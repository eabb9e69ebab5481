// Cell keys (see cell_key.h for what is hashed and why). Lessons from ECOSYSTEM.md section 3: the key includes the
// code version and the corpus digest, so stale cells are never served after a format change or an edited image.
#include "experiments/cell_key.h"

#include "experiments/sha256.h"

namespace blocklab {

std::uint64_t effective_seed(const ExperimentConfig& config, const Treatment& treatment) {
  const auto seed = treatment.resolved.find("seed");
  if (seed != treatment.resolved.end()) return static_cast<std::uint64_t>(option_int(treatment.resolved, "seed"));
  return static_cast<std::uint64_t>(config.seed);
}

nlohmann::json crop_json(const ImageCrop& crop) {
  nlohmann::json doc = {{"width", crop.width}, {"height", crop.height}};
  if (crop.centred) doc["centred"] = true;
  else doc.update({{"x", crop.x}, {"y", crop.y}});
  return doc;
}

nlohmann::json cell_key_document(const ExperimentConfig& config, const ImageIdentity& image, const Treatment& treatment) {
  const FormatVariant& variant = config.variants.at(treatment.variant_index);
  nlohmann::json metrics = nlohmann::json::object();
  for (const MetricRequest& m : config.metrics) {
    // Unlabelled metrics hash as before (name -> options), so adding `column:` support changed no existing key.
    if (m.label.empty()) metrics[m.name] = m.options;
    else metrics[m.label] = {{"metric", m.name}, {"options", m.options}};
  }
  nlohmann::json doc;
  doc["results_schema"] = kResultsSchemaVersion;
  doc["blocklab_version"] = BLOCKLAB_VERSION;
  doc["image"] = {{"path", image.relative_path}, {"sha256", image.sha256}};
  doc["format"] = {{"name", variant.format->name()},
                   {"revision", variant.format->revision()},
                   {"options", treatment.resolved}};
  doc["seed"] = effective_seed(config, treatment);
  doc["metrics"] = metrics;
  doc["input_policy"] = to_string(config.input_policy);
  doc["ablation"] = {{"name", treatment.ablation}, {"patch", treatment.applied_patch}};
  doc["artifacts"] = {{"save_decoded", config.save_decoded}, {"error_maps", config.error_maps}};
  // Only when asked for, so configs without mode maps keep the keys they had before the option existed.
  if (config.mode_maps) doc["artifacts"]["mode_maps"] = true;
  // Likewise the crop: only present when the config crops.
  if (config.crop.enabled) doc["crop"] = crop_json(config.crop);
  return doc;
}

std::string cell_key(const nlohmann::json& key_document) { return sha256_hex(key_document.dump()); }

}  // namespace blocklab
