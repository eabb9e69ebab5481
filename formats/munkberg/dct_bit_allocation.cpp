// Lagrangian bit allocation (formats/munkberg/dct_bit_allocation.h).
#include "formats/munkberg/dct_bit_allocation.h"

#include <algorithm>
#include <limits>
#include <string>

#include "core/error.h"

namespace blocklab::munkberg {

namespace {

// Every coefficient's argmin_b D_k(b) + lambda b (ties: fewer bits).
std::vector<int> allocation_at(const std::vector<std::vector<double>>& distortion, double lambda) {
  std::vector<int> bits(distortion.size(), 0);
  for (std::size_t k = 0; k < distortion.size(); ++k) {
    double best = distortion[k][0];
    for (std::size_t b = 1; b < distortion[k].size(); ++b) {
      const double cost = distortion[k][b] + lambda * static_cast<double>(b);
      if (cost < best) {
        best = cost;
        bits[k] = static_cast<int>(b);
      }
    }
  }
  return bits;
}

int total(const std::vector<int>& bits) {
  int sum = 0;
  for (const int b : bits) sum += b;
  return sum;
}

}  // namespace

std::vector<int> lagrangian_bit_allocation(const std::vector<std::vector<double>>& distortion, int budget) {
  int capacity = 0;
  double largest = 0.0;
  for (const std::vector<double>& d : distortion) {
    if (d.empty()) fail("munkberg dct", "bit allocation: a coefficient without a distortion curve");
    capacity += static_cast<int>(d.size()) - 1;
    for (const double v : d) largest = std::max(largest, v);
  }
  if (budget < 0 || budget > capacity)
    fail("munkberg dct", "bit allocation: budget " + std::to_string(budget) + " outside [0, " + std::to_string(capacity) + "]");
  // lambda = 0 spends every useful bit; lambda above the largest distortion spends none (one bit never saves more
  // than D_k(0) <= largest). Bisect for the smallest lambda whose rate fits the budget.
  double lo = 0.0, hi = 2.0 * largest + 1.0;
  std::vector<int> bits = allocation_at(distortion, hi);
  if (total(allocation_at(distortion, lo)) <= budget) {
    bits = allocation_at(distortion, lo);
  } else {
    for (int iteration = 0; iteration < 200; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;   // the interval is one ulp wide
      if (total(allocation_at(distortion, mid)) <= budget) {
        hi = mid;
      } else {
        lo = mid;
      }
    }
    bits = allocation_at(distortion, hi);
  }
  // Spend what is left: repeatedly the step (coefficient k, from bits[k] to bits[k] + s, s <= left) with the largest
  // decrease per bit (ties: smaller step, then lower k); a zero decrease still spends bits, so the sum is exact.
  int left = budget - total(bits);
  while (left > 0) {
    std::size_t best_k = distortion.size();
    int best_step = 0;
    double best_rate = -1.0;
    for (std::size_t k = 0; k < distortion.size(); ++k)
      for (int s = 1; s <= left && bits[k] + s < static_cast<int>(distortion[k].size()); ++s) {
        const double rate = (distortion[k][static_cast<std::size_t>(bits[k])] -
                             distortion[k][static_cast<std::size_t>(bits[k] + s)]) / static_cast<double>(s);
        if (rate > best_rate) {
          best_rate = rate;
          best_k = k;
          best_step = s;
        }
      }
    if (best_k == distortion.size()) fail("munkberg dct", "internal: bit allocation cannot reach the budget");
    bits[best_k] += best_step;
    left -= best_step;
  }
  return bits;
}

std::vector<int> exact_bit_allocation(const std::vector<std::vector<double>>& distortion, int budget) {
  const std::size_t count = distortion.size();
  // best[k][r]: the least total distortion of coefficients k.. with exactly r bits (infinity when impossible).
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> best(count + 1, std::vector<double>(static_cast<std::size_t>(budget) + 1, infinity));
  best[count][0] = 0.0;
  for (std::size_t k = count; k-- > 0;)
    for (int r = 0; r <= budget; ++r)
      for (std::size_t b = 0; b < distortion[k].size() && static_cast<int>(b) <= r; ++b) {
        const double rest = best[k + 1][static_cast<std::size_t>(r) - b];
        if (rest == infinity) continue;
        best[k][static_cast<std::size_t>(r)] = std::min(best[k][static_cast<std::size_t>(r)], distortion[k][b] + rest);
      }
  if (best[0][static_cast<std::size_t>(budget)] == infinity)
    fail("munkberg dct", "bit allocation: budget " + std::to_string(budget) + " cannot be spent exactly");
  std::vector<int> bits(count, 0);
  int left = budget;
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t b = 0; b < distortion[k].size() && static_cast<int>(b) <= left; ++b) {
      const double rest = best[k + 1][static_cast<std::size_t>(left) - b];
      // The first b whose completion attains the optimum (same sums as the table, so equality is exact).
      if (rest != infinity && distortion[k][b] + rest == best[k][static_cast<std::size_t>(left)]) {
        bits[k] = static_cast<int>(b);
        left -= static_cast<int>(b);
        break;
      }
    }
  return bits;
}

}  // namespace blocklab::munkberg
