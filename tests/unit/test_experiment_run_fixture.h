// Shared fixture for the runner tests: a temp folder with tiny PFM images, a config writer, and helpers to read the
// run folder back. Uses the fake formats and metrics of test_experiment_fakes.h.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "experiments/runner.h"
#include "test_experiment_fakes.h"

namespace blocklab::testing {

namespace fs = std::filesystem;

class ExperimentRunFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::path(::testing::TempDir()) /
            ("blocklab_run_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "data");
  }
  void TearDown() override { fs::remove_all(root_); }

  // A width x height image whose values are multiples of 1/8 (so fake_quant with step 0.125 is lossless).
  void write_test_image(const std::string& relative, int width, int height, int salt) const {
    Image image(width, height, 3);
    image.metadata.is_hdr = true;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = static_cast<float>((x * 3 + y * 5 + c + salt) % 17) / 8.0f;
      }
    }
    fs::create_directories((root_ / "data" / relative).parent_path());
    write_image((root_ / "data" / relative).string(), image);
  }

  std::string write_config(const std::string& name, const std::string& body) const {
    const fs::path path = root_ / (name + ".yaml");
    std::ofstream(path) << body;
    return path.string();
  }

  RunOptions options_for(const std::string& config_path, const std::string& run = "run") const {
    RunOptions options;
    options.config_path = config_path;
    options.out_dir = (root_ / run).string();
    options.data_root = (root_ / "data").string();
    options.threads = 1;
    return options;
  }

  RunSummary run(const RunOptions& options) const { return run_experiment(options, fake_catalog()); }

  static std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  static std::vector<nlohmann::json> read_jsonl(const fs::path& path) {
    std::vector<nlohmann::json> records;
    std::istringstream in(read_file(path));
    for (std::string line; std::getline(in, line);) records.push_back(nlohmann::json::parse(line));
    return records;
  }

  // Keys of the planned cells, in order, from resolved.json.
  static std::vector<std::string> planned_keys(const fs::path& run_dir) {
    std::vector<std::string> keys;
    const nlohmann::json resolved = nlohmann::json::parse(read_file(run_dir / "resolved.json"));
    for (const auto& cell : resolved["cells"]) {
      keys.push_back(cell["key"]);
    }
    return keys;
  }

  static std::vector<fs::path> cell_files(const fs::path& run_dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(run_dir / "cells")) {
      if (entry.is_regular_file()) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
  }

  fs::path root_;
};

}  // namespace blocklab::testing
