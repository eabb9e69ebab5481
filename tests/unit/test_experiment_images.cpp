// Image lists (experiments/image_set.h): glob matching inside one path component, sorted matches in config order,
// errors for patterns that match nothing, missing files and duplicates, and the data-root precedence.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "experiments/image_set.h"
#include "test_experiment_fakes.h"

namespace blocklab {
namespace {
namespace fs = std::filesystem;

class ExperimentImages : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("experiment_images_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    for (const char* file : {"hdr/b.exr", "hdr/a.exr", "hdr/c.hdr", "hdr/.hidden.exr", "hdr/sub/d.exr",
                             "ldr/kodak/kodim01.png", "ldr/kodak/kodim02.png", "ldr/x[1].png"}) {
      fs::create_directories((root_ / file).parent_path());
      std::ofstream(root_ / file) << "x";
    }
    unsetenv("BLOCKLAB_DATA_ROOT");
  }
  void TearDown() override {
    fs::remove_all(root_);
    unsetenv("BLOCKLAB_DATA_ROOT");
  }

  ExperimentConfig config_with_images(const std::vector<std::string>& images) const {
    ExperimentConfig config;
    config.source_path = "images.yaml";
    config.images = images;
    return config;
  }
  std::vector<std::string> resolve(const std::vector<std::string>& images) const {
    return resolve_images(config_with_images(images), root_.string());
  }
  std::string error_of(const std::vector<std::string>& images) const {
    try {
      resolve(images);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an error";
    return "";
  }

  fs::path root_;
};

TEST(ExperimentGlob, StarAndQuestionMarkMatchWithinOneComponent) {
  EXPECT_TRUE(glob_component_matches("*.png", "a.png"));
  EXPECT_TRUE(glob_component_matches("*.png", ".png"));
  EXPECT_FALSE(glob_component_matches("*.png", "a.pngx"));
  EXPECT_TRUE(glob_component_matches("kodim0?.png", "kodim07.png"));
  EXPECT_FALSE(glob_component_matches("kodim0?.png", "kodim7.png"));
  EXPECT_TRUE(glob_component_matches("a*b*c", "a_b_b_c"));
  EXPECT_FALSE(glob_component_matches("a*b*c", "a_c_b"));
  EXPECT_TRUE(glob_component_matches("*", "anything"));
  EXPECT_TRUE(glob_component_matches("**", ""));
  EXPECT_FALSE(glob_component_matches("?", ""));
  EXPECT_TRUE(glob_component_matches("x[1].png", "x[1].png"));   // brackets are literal
  EXPECT_FALSE(glob_component_matches("x[1].png", "x1.png"));
}

TEST_F(ExperimentImages, LiteralPathsAndGlobsKeepConfigOrderWithSortedMatches) {
  EXPECT_EQ(resolve({"hdr/c.hdr", "hdr/*.exr", "ldr/kodak/kodim0?.png"}),
            (std::vector<std::string>{"hdr/c.hdr", "hdr/a.exr", "hdr/b.exr", "ldr/kodak/kodim01.png",
                                      "ldr/kodak/kodim02.png"}));
}

TEST_F(ExperimentImages, StarDoesNotCrossDirectoriesOrMatchHiddenFilesOrFolders) {
  EXPECT_EQ(resolve({"hdr/*"}), (std::vector<std::string>{"hdr/a.exr", "hdr/b.exr", "hdr/c.hdr"}));
  EXPECT_EQ(resolve({"hdr/*/*.exr"}), (std::vector<std::string>{"hdr/sub/d.exr"}));
  EXPECT_EQ(resolve({"hdr/.*.exr"}), (std::vector<std::string>{"hdr/.hidden.exr"}));
  EXPECT_EQ(resolve({"*/kodak/kodim01.png"}), (std::vector<std::string>{"ldr/kodak/kodim01.png"}));
}

TEST_F(ExperimentImages, PathsAreNormalised) {
  EXPECT_EQ(resolve({"hdr/./a.exr", "ldr//kodak/kodim01.png"}),
            (std::vector<std::string>{"hdr/a.exr", "ldr/kodak/kodim01.png"}));
}

TEST_F(ExperimentImages, PatternMatchingNothingOrMissingFileIsAnErrorNamingIt) {
  const std::string glob = error_of({"hdr/a.exr", "hdr/*.pfm"});
  EXPECT_NE(glob.find("images.yaml: images[1]: pattern 'hdr/*.pfm' matches no file under data root"),
            std::string::npos) << glob;
  const std::string missing = error_of({"hdr/zzz.exr"});
  EXPECT_NE(missing.find("images[0]: 'hdr/zzz.exr' not found under data root " + root_.string()), std::string::npos)
      << missing;
  EXPECT_NE(error_of({"hdr"}).find("not found"), std::string::npos);   // a directory is not an image
}

TEST_F(ExperimentImages, PathsThatLeaveTheDataRootAreRefusedBeforeAnythingIsOpened) {
  // A file beside the data root, reachable with '..'.
  std::ofstream(root_.parent_path() / ("outside_" + std::to_string(::getpid()) + ".png")) << "secret";
  const std::string outside = "../outside_" + std::to_string(::getpid()) + ".png";
  const std::string message = error_of({outside});
  EXPECT_NE(message.find("images[0]: '" + outside + "' leads outside the data root " + root_.string()),
            std::string::npos) << message;
  EXPECT_NE(error_of({"hdr/../../etc/passwd"}).find("leads outside the data root"), std::string::npos);
  EXPECT_NE(error_of({"../*/*.png"}).find("leads outside the data root"), std::string::npos);
  EXPECT_NE(error_of({"hdr/a.exr", "ldr/../../x"}).find("images[1]"), std::string::npos);
  fs::remove(root_.parent_path() / ("outside_" + std::to_string(::getpid()) + ".png"));
  // '..' that stays inside the root is only a detour.
  EXPECT_EQ(resolve({"ldr/../hdr/a.exr"}), std::vector<std::string>{"hdr/a.exr"});
}

TEST_F(ExperimentImages, SymlinkInsideTheRootIsFollowedWhereverItPoints) {
  const fs::path target = root_.parent_path() / ("linked_" + std::to_string(::getpid()) + ".exr");
  std::ofstream(target) << "x";
  fs::create_symlink(target, root_ / "hdr" / "linked.exr");
  EXPECT_EQ(resolve({"hdr/linked.exr"}), std::vector<std::string>{"hdr/linked.exr"});
  fs::remove(target);
}

TEST_F(ExperimentImages, AnImageMatchedTwiceIsAnError) {
  const std::string message = error_of({"hdr/*.exr", "hdr/a.exr"});
  EXPECT_NE(message.find("images[1]: 'hdr/a.exr' is already listed by images[0]"), std::string::npos) << message;
}

TEST_F(ExperimentImages, DataRootPrecedenceIsOverrideThenEnvironmentThenConfig) {
  ExperimentConfig config = config_with_images({"hdr/a.exr"});
  // No data_root anywhere: the repository root.
  EXPECT_EQ(resolve_data_root(config, ""), fs::path(BLOCKLAB_SOURCE_DIR).lexically_normal().string());
  // Config data_root, relative to the repository root.
  config.data_root = "experiments";
  EXPECT_EQ(resolve_data_root(config, ""), (fs::path(BLOCKLAB_SOURCE_DIR) / "experiments").lexically_normal().string());
  // The environment beats the config.
  const fs::path env_root = root_ / "hdr";
  setenv("BLOCKLAB_DATA_ROOT", env_root.c_str(), 1);
  EXPECT_EQ(resolve_data_root(config, ""), env_root.string());
  // The explicit override beats both.
  EXPECT_EQ(resolve_data_root(config, (root_ / "ldr").string()), (root_ / "ldr").string());
  EXPECT_EQ(resolve_data_root(config, (root_ / "ldr/").string()), (root_ / "ldr").string());
}

TEST_F(ExperimentImages, DataRootThatIsNotADirectoryIsAnErrorSayingWhereItCameFrom) {
  ExperimentConfig config = config_with_images({"a"});
  try {
    resolve_data_root(config, (root_ / "nope").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("data root (from --data-root) is not a directory"), std::string::npos)
        << e.what();
  }
  config.data_root = "no/such/folder";
  try {
    resolve_data_root(config, "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("images.yaml: data_root"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace blocklab
