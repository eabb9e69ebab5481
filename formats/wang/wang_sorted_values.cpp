// Radix sort of a texture's values for the `wang` zone splits (formats/wang/wang_sorted_values.h).
#include "formats/wang/wang_sorted_values.h"

#include <array>
#include <cstdint>
#include <cstring>

namespace blocklab {
namespace wang {

namespace {

constexpr int kDigitBits = 11;
constexpr int kDigits = (64 + kDigitBits - 1) / kDigitBits;   // 6 passes
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;

// Unsigned key whose order is the numeric order of the double.
std::uint64_t order_key(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

double from_key(std::uint64_t key) {
  const std::uint64_t bits = (key >> 63) != 0 ? key & ~(std::uint64_t{1} << 63) : ~key;
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

std::vector<double> sorted_values(const std::vector<double>& values) {
  const std::size_t n = values.size();
  std::vector<std::uint64_t> keys(n), scratch(n);
  std::vector<std::array<std::size_t, kBuckets>> counts(kDigits);
  for (auto& count : counts) count.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    keys[i] = order_key(values[i]);
    for (int digit = 0; digit < kDigits; ++digit) ++counts[digit][(keys[i] >> (digit * kDigitBits)) & (kBuckets - 1)];
  }
  for (int digit = 0; digit < kDigits; ++digit) {
    auto& count = counts[digit];
    // A digit every key shares moves nothing.
    if (count[(keys.empty() ? 0 : keys[0] >> (digit * kDigitBits)) & (kBuckets - 1)] == n) continue;
    std::size_t offset = 0;
    for (std::size_t& c : count) {
      const std::size_t here = c;
      c = offset;
      offset += here;
    }
    for (std::size_t i = 0; i < n; ++i) scratch[count[(keys[i] >> (digit * kDigitBits)) & (kBuckets - 1)]++] = keys[i];
    keys.swap(scratch);
  }
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = from_key(keys[i]);
  return out;
}

}  // namespace wang
}  // namespace blocklab
