#include "Segmentation/SimplePoint.h"

#include <array>

namespace colonmap::segmentation {
namespace {

constexpr std::uint32_t kAll = (1u << 27) - 1;
constexpr std::uint32_t kCentre = 1u << 13;

struct Tables {
  std::array<std::uint32_t, 27> adjacent26{};  // 26-neighbours of each bit within the 3x3x3 block
  std::array<std::uint32_t, 27> adjacent6{};   // 6-neighbours of each bit within the block
  std::uint32_t n18 = 0;                       // N18*: face and edge neighbours of the centre
  std::uint32_t n6 = 0;                        // the six face neighbours of the centre
};

constexpr Tables MakeTables() {
  Tables t;
  for (int a = 0; a < 27; ++a) {
    const int ai = a % 3, aj = (a / 3) % 3, ak = a / 9;
    const int ci = ai - 1 < 0 ? 1 - ai : ai - 1, cj = aj - 1 < 0 ? 1 - aj : aj - 1, ck = ak - 1 < 0 ? 1 - ak : ak - 1;
    const int centreDistance = ci + cj + ck;  // L1 distance to the centre
    if (centreDistance == 1) t.n6 |= 1u << a;
    if (centreDistance == 1 || centreDistance == 2) t.n18 |= 1u << a;
    for (int b = 0; b < 27; ++b) {
      if (a == b) continue;
      const int bi = b % 3, bj = (b / 3) % 3, bk = b / 9;
      const int di = ai > bi ? ai - bi : bi - ai, dj = aj > bj ? aj - bj : bj - aj, dk = ak > bk ? ak - bk : bk - ak;
      if (di <= 1 && dj <= 1 && dk <= 1) t.adjacent26[a] |= 1u << b;
      if (di + dj + dk == 1) t.adjacent6[a] |= 1u << b;
    }
  }
  return t;
}

constexpr Tables kTables = MakeTables();

// The part of `set` connected to `start` (a subset of set) through `adjacency`.
std::uint32_t Grow(std::uint32_t start, std::uint32_t set, const std::array<std::uint32_t, 27>& adjacency) {
  std::uint32_t component = start, frontier = start;
  while (frontier) {
    std::uint32_t reached = 0;
    for (std::uint32_t f = frontier; f; f &= f - 1) reached |= adjacency[__builtin_ctz(f)];
    frontier = reached & set & ~component;
    component |= frontier;
  }
  return component;
}

// Components of `set` that contain a bit of `seeds`; stops counting at 2.
int CountComponents(std::uint32_t set, std::uint32_t seeds, const std::array<std::uint32_t, 27>& adjacency) {
  int count = 0;
  seeds &= set;
  while (seeds && count < 2) {
    const std::uint32_t component = Grow(seeds & (~seeds + 1), set, adjacency);
    seeds &= ~component;
    ++count;
  }
  return count;
}

}  // namespace

int ForegroundComponents26(std::uint32_t neighbourhood) {
  const std::uint32_t x = neighbourhood & kAll & ~kCentre;
  int count = 0;
  for (std::uint32_t rest = x; rest; ++count) rest &= ~Grow(rest & (~rest + 1), x, kTables.adjacent26);
  return count;
}

int BackgroundComponents6(std::uint32_t neighbourhood) {
  const std::uint32_t background = ~neighbourhood & kTables.n18;
  int count = 0;
  for (std::uint32_t seeds = background & kTables.n6; seeds; ++count)
    seeds &= ~Grow(seeds & (~seeds + 1), background, kTables.adjacent6);
  return count;
}

bool IsSimple26(std::uint32_t neighbourhood) {
  const std::uint32_t x = neighbourhood & kAll & ~kCentre;
  if (CountComponents(x, x, kTables.adjacent26) != 1) return false;
  const std::uint32_t background = ~neighbourhood & kTables.n18;
  return CountComponents(background, background & kTables.n6, kTables.adjacent6) == 1;
}

}  // namespace colonmap::segmentation
