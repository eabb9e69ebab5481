// Static shards (experiments/shard.h): parsing "i/n" and the split of cells (a partition, balanced, in expansion
// order, independent of anything but the keys).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.h"
#include "experiments/sha256.h"
#include "experiments/shard.h"

namespace blocklab {
namespace {

std::vector<std::string> keys_of(std::size_t count) {
  std::vector<std::string> keys;
  for (std::size_t i = 0; i < count; ++i) keys.push_back(sha256_hex("cell " + std::to_string(i)));
  return keys;
}

std::string error_of(const std::string& text) {
  try {
    parse_shard(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Shard, ParsesIndexSlashCount) {
  const ShardSpec shard = parse_shard("3/8");
  EXPECT_EQ(shard.index, 3u);
  EXPECT_EQ(shard.count, 8u);
  EXPECT_EQ(shard.text(), "3/8");
  EXPECT_EQ(shard.file_suffix(), ".shard-3-of-8");
  EXPECT_TRUE(parse_shard("0/1").whole());
}

TEST(Shard, RefusesMalformedOrOutOfRangeShardsNamingTheFlag) {
  for (const char* text : {"", "3", "/4", "1/", "a/2", "1/2/3", "-1/2", "1 /2", "1.0/2", "12345678901/2"}) {
    EXPECT_NE(error_of(text).find("--shard: expected i/n"), std::string::npos) << text << ": " << error_of(text);
  }
  EXPECT_NE(error_of("0/0").find("must be at least 1"), std::string::npos) << error_of("0/0");
  EXPECT_NE(error_of("4/4").find("shard index 4 is out of range for 4 shards (valid: 0 to 3)"), std::string::npos)
      << error_of("4/4");
}

TEST(Shard, ShardsPartitionTheCellsInExpansionOrderWithSizesWithinOne) {
  const std::vector<std::string> keys = keys_of(103);
  for (std::size_t n : {1u, 2u, 3u, 7u, 103u, 200u}) {
    std::multiset<std::size_t> seen;
    std::size_t smallest = keys.size(), largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::vector<std::size_t> mine = shard_cells(keys, {i, n});
      EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end())) << i << "/" << n;
      seen.insert(mine.begin(), mine.end());
      smallest = std::min(smallest, mine.size());
      largest = std::max(largest, mine.size());
    }
    EXPECT_EQ(seen.size(), keys.size()) << n;
    EXPECT_EQ(std::set<std::size_t>(seen.begin(), seen.end()).size(), keys.size()) << n << ": a cell in two shards";
    EXPECT_LE(largest - smallest, 1u) << n;
  }
}

TEST(Shard, SplitDependsOnTheKeysNotOnTheirPositionsInTheSweep) {
  // The same cells listed in another order land in the same shards: the split follows key order.
  const std::vector<std::string> keys = keys_of(40);
  std::vector<std::string> reversed(keys.rbegin(), keys.rend());
  for (std::size_t i = 0; i < 3; ++i) {
    std::set<std::string> a, b;
    for (std::size_t c : shard_cells(keys, {i, 3})) a.insert(keys[c]);
    for (std::size_t c : shard_cells(reversed, {i, 3})) b.insert(reversed[c]);
    EXPECT_EQ(a, b) << i;
  }
}

TEST(Shard, SplitIsNotTheSweepsStride) {
  // With 2 treatments per image and 2 shards, an index split would give one shard every first treatment; key order
  // gives each shard cells of both.
  const std::vector<std::string> keys = keys_of(64);
  const std::vector<std::size_t> first = shard_cells(keys, {0, 2});
  const auto even = std::count_if(first.begin(), first.end(), [](std::size_t c) { return c % 2 == 0; });
  EXPECT_GT(even, 0);
  EXPECT_LT(even, static_cast<long>(first.size()));
}

}  // namespace
}  // namespace blocklab
