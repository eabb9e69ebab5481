// Static shards of an experiment's cells (the split is defined in experiments/shard.h).
#include "experiments/shard.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace blocklab {

namespace {

bool parse_count(const std::string& text, std::size_t& value) {
  if (text.empty() || text.size() > 9) return false;
  value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<std::size_t>(c - '0');
  }
  return true;
}

}  // namespace

std::string ShardSpec::text() const { return std::to_string(index) + "/" + std::to_string(count); }

std::string ShardSpec::file_suffix() const {
  return ".shard-" + std::to_string(index) + "-of-" + std::to_string(count);
}

ShardSpec parse_shard(const std::string& text, const std::string& flag) {
  const std::size_t slash = text.find('/');
  ShardSpec shard;
  if (slash == std::string::npos || !parse_count(text.substr(0, slash), shard.index) ||
      !parse_count(text.substr(slash + 1), shard.count)) {
    fail(flag, "expected i/n with whole numbers 0 <= i < n (e.g. 0/4), got '" + text + "'");
  }
  if (shard.count == 0) fail(flag, "the shard count in '" + text + "' must be at least 1");
  if (shard.index >= shard.count) {
    fail(flag, "shard index " + std::to_string(shard.index) + " is out of range for " + std::to_string(shard.count) +
                   " shards (valid: 0 to " + std::to_string(shard.count - 1) + ")");
  }
  return shard;
}

std::vector<std::size_t> shard_cells(const std::vector<std::string>& cell_keys, const ShardSpec& shard) {
  std::vector<std::size_t> order(cell_keys.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (shard.whole()) return order;
  // Ties cannot happen (two cells never share a key), but the index breaks them so the order is total anyway.
  std::sort(order.begin(), order.end(), [&cell_keys](std::size_t a, std::size_t b) {
    return cell_keys[a] != cell_keys[b] ? cell_keys[a] < cell_keys[b] : a < b;
  });
  std::vector<std::size_t> mine;
  for (std::size_t j = shard.index; j < order.size(); j += shard.count) mine.push_back(order[j]);
  std::sort(mine.begin(), mine.end());
  return mine;
}

}  // namespace blocklab
