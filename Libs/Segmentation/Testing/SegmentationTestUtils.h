#pragma once
// Helpers of the segmentation tests: voxel shapes and an independent component count.
#include "Core/Volume.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace colonmap::segmentation::testing {

inline Volume<unsigned char> Shape(std::size_t n0, std::size_t n1, std::size_t n2,
                                   const std::function<bool(double, double, double)>& inside) {
  Volume<unsigned char> v;
  v.size = {{n0, n1, n2}};
  v.Allocate(0);
  for (std::size_t k = 0; k < n2; ++k)
    for (std::size_t j = 0; j < n1; ++j)
      for (std::size_t i = 0; i < n0; ++i) v.At(i, j, k) = inside(double(i), double(j), double(k)) ? 1 : 0;
  return v;
}

inline std::size_t CountSet(const Volume<unsigned char>& v) {
  std::size_t n = 0;
  for (auto x : v.voxels) n += x != 0;
  return n;
}

// Components of the voxels equal to `value` (breadth-first search): 26-connectivity for the
// foreground (value 1), 6-connectivity for the background (value 0).
inline int Components(const Volume<unsigned char>& v, unsigned char value) {
  const long n0 = long(v.size[0]), n1 = long(v.size[1]), n2 = long(v.size[2]);
  std::vector<char> seen(v.NumberOfVoxels(), 0);
  int count = 0;
  std::vector<long> stack;
  for (long start = 0; start < long(v.NumberOfVoxels()); ++start) {
    if (seen[start] || (v.voxels[start] != 0) != (value != 0)) continue;
    ++count;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty()) {
      const long x = stack.back();
      stack.pop_back();
      const long i = x % n0, j = (x / n0) % n1, k = x / (n0 * n1);
      for (int dk = -1; dk <= 1; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int l1 = (di != 0) + (dj != 0) + (dk != 0);
            if (l1 == 0 || (value == 0 && l1 > 1)) continue;
            const long a = i + di, b = j + dj, c = k + dk;
            if (a < 0 || b < 0 || c < 0 || a >= n0 || b >= n1 || c >= n2) continue;
            const long y = a + n0 * (b + n1 * c);
            if (seen[y] || (v.voxels[y] != 0) != (value != 0)) continue;
            seen[y] = 1;
            stack.push_back(y);
          }
    }
  }
  return count;
}

}  // namespace colonmap::segmentation::testing
