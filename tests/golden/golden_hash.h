// Hashes of golden bytes shared by the golden tests: FNV-1a 64-bit (Fowler, Noll, Vo; offset basis
// 14695981039346656037, prime 1099511628211) of raw bytes, and of floats as their little-endian IEEE bit patterns
// (so the hash is the same on every machine and catches a change of a single bit).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace blocklab::golden {

inline std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

inline std::uint64_t hash_floats(const std::vector<float>& values) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(values.size() * 4);
  for (float value : values) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<std::uint8_t>(bits >> shift));   // LE
  }
  return fnv1a64(bytes.data(), bytes.size());
}

}  // namespace blocklab::golden
