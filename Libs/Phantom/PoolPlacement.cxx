#include "Phantom/PoolPlacement.h"

#include <algorithm>
#include <cmath>

namespace colonmap::phantom {

std::vector<PoolPlace> PlacePools(const std::vector<double>& floorH, double stepMm,
                                  const std::function<double(int)>& diameter, int wanted, Rng& rng) {
  const int n = static_cast<int>(floorH.size());
  const int window = 30, margin = 20;
  const int apart = static_cast<int>(std::lround(150.0 / stepMm));  // samples between two pools
  std::vector<int> candidates;
  for (int i = margin; i < n - margin; ++i) {
    bool isMin = true;
    for (int j = std::max(0, i - window); j <= std::min(n - 1, i + window) && isMin; ++j)
      if (floorH[j] < floorH[i] || (floorH[j] == floorH[i] && j < i)) isMin = false;
    if (isMin) candidates.push_back(i);
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](int x, int y) { return floorH[x] != floorH[y] ? floorH[x] < floorH[y] : x < y; });
  std::vector<PoolPlace> pools;
  for (int c : candidates) {
    if (static_cast<int>(pools.size()) >= wanted) break;
    PoolPlace p;
    p.deepest = c;
    p.level = floorH[c] + rng.Uniform(0.2, 0.4) * diameter(c);
    p.lo = p.hi = c;
    while (p.lo > 0 && floorH[p.lo - 1] < p.level) --p.lo;
    while (p.hi < n - 1 && floorH[p.hi + 1] < p.level) ++p.hi;
    bool clear = true;
    for (const PoolPlace& q : pools)
      if (p.lo - apart <= q.hi && p.hi + apart >= q.lo) clear = false;
    if (clear) pools.push_back(p);
  }
  return pools;
}

}  // namespace colonmap::phantom
