// `blocklab train munkberg-dct`: the training step of the munkberg format's fixed-rate DCT mode (Munkberg et al.
// 2008, section 6.2; formats/munkberg/dct_training.h). Reads every HDR image below <data root>/hdr except the
// held-out ones (default: the three images of the paper's tables, so Tables 2-3 and Fig. 4 are measured on images
// the tables were not trained on), in path order, and writes the tables with their provenance (relative path,
// SHA-256 and block count of each image; no dates or machine paths, so a re-run on the same images writes the same
// bytes). The format embeds formats/munkberg/dct_tables.yaml at build time.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "experiments/sha256.h"
#include "formats/munkberg/dct_training.h"

namespace blocklab::cli {

namespace {

const std::vector<std::string> kDefaultHeldOut = {"hdr/Desk.exr", "hdr/dani_cathedral_oBBC.hdr", "hdr/memorial.hdr"};

bool is_hdr_file(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace

int run_train(const TrainArgs& args) {
  if (args.what != "munkberg-dct") fail("train", "unknown training '" + args.what + "'; valid: munkberg-dct");
  std::string root = args.data_root;
  if (root.empty()) {
    const char* env = std::getenv("BLOCKLAB_DATA_ROOT");
    if (env == nullptr || *env == '\0') fail("train", "no data root: pass --data-root or set BLOCKLAB_DATA_ROOT");
    root = env;
  }
  const std::filesystem::path folder = std::filesystem::path(root) / "hdr";
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) fail(folder.string(), "not a folder (check --data-root)");
  const std::vector<std::string> held_out = args.held_out == "default" ? kDefaultHeldOut : split_commas(args.held_out);
  std::vector<std::string> files;   // relative to the root, '/' separated
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && is_hdr_file(entry.path()))
      files.push_back(std::filesystem::relative(entry.path(), root).generic_string());
  std::sort(files.begin(), files.end());
  for (const std::string& name : held_out)
    if (std::find(files.begin(), files.end(), name) == files.end())
      fail("train", "held-out image '" + name + "' is not an HDR image below " + folder.string());

  munkberg::DctTrainingStatistics statistics;
  munkberg::DctTrainingProvenance provenance;
  provenance.generator = "blocklab train munkberg-dct --data-root DATA" +
                         (args.held_out == "default" ? std::string() : " --hold-out " + args.held_out);
  provenance.held_out = held_out;
  for (const std::string& name : files) {
    if (std::find(held_out.begin(), held_out.end(), name) != held_out.end()) continue;
    const std::string path = (std::filesystem::path(root) / name).string();
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);   // finite, non-negative (the encoder's input)
    const long long blocks = munkberg::accumulate_dct_statistics(image, &statistics);
    provenance.images.push_back(name + " sha256=" + sha256_file_hex(path) + " blocks=" + std::to_string(blocks));
    if (!args.quiet) std::cerr << "train: " << name << ": " << blocks << " blocks\n";
  }
  const munkberg::DctTables tables = munkberg::design_dct_tables(statistics, provenance);
  const std::string yaml = munkberg::dct_tables_to_yaml(tables);
  munkberg::parse_dct_tables(yaml, args.output);   // what we write must load
  write_file_atomically(args.output, yaml);   // a full disk leaves no partial table file
  if (!args.quiet) {
    std::cerr << "train: " << statistics.blocks << " blocks from " << provenance.images.size() << " images -> "
              << args.output << "\n";
    for (int c = 0; c < munkberg::kDctChannelCount; ++c) {
      std::cerr << "  " << munkberg::kDctChannelNames[static_cast<std::size_t>(c)] << " bits:";
      for (const int b : tables.channel[static_cast<std::size_t>(c)].bits) std::cerr << ' ' << b;
      std::cerr << "\n";
    }
  }
  return 0;
}

}  // namespace blocklab::cli
