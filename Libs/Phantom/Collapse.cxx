#include "Collapse.h"

#include "Random.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace colonmap {
namespace phantom {

std::vector<CollapsedStretch> DrawCollapses(const ColonAnatomy& a, int count, std::uint32_t seed) {
  if (count < 0 || count > 4) throw std::invalid_argument("collapses: expected 0..4");
  constexpr double kEndClearance = 60.0, kSpacing = 60.0;
  constexpr double kWeights[5] = {0.05, 0.25, 0.30, 0.35, 0.05};  // A, T, D, S, R
  Rng rng(seed, 108);
  std::vector<CollapsedStretch> out;
  for (int i = 0; i < count; ++i) {
    // Rejection sampling: a draw that does not fit (too near an end or another stretch, or a
    // segment too short) is drawn again; 200 attempts are far more than any seed needs.
    for (int attempt = 0; attempt < 200; ++attempt) {
      double pick = rng.Uniform(), acc = 0.0;
      int seg = 4;
      for (int k = 0; k < 5; ++k)
        if (pick < (acc += kWeights[k])) {
          seg = k;
          break;
        }
      const double lo = seg == 0 ? 0.0 : a.flexureS[seg - 1], hi = seg == 4 ? a.length : a.flexureS[seg];
      const double length = rng.Uniform(20.0, 80.0), mid = rng.Uniform(lo, hi);
      const double scan = rng.Uniform();
      CollapsedStretch c;
      c.s0 = mid - 0.5 * length;
      c.s1 = mid + 0.5 * length;
      c.segment = seg;
      c.supine = scan < 0.4 || scan >= 0.8;
      c.prone = scan >= 0.4;
      if (c.s0 < kEndClearance || c.s1 > a.length - kEndClearance) continue;
      const bool clear = std::all_of(out.begin(), out.end(), [&](const CollapsedStretch& o) {
        return c.s1 + kSpacing < o.s0 || o.s1 + kSpacing < c.s0;
      });
      if (!clear) continue;
      out.push_back(c);
      break;
    }
  }
  std::sort(out.begin(), out.end(), [](const CollapsedStretch& x, const CollapsedStretch& y) { return x.s0 < y.s0; });
  return out;
}

const CollapsedStretch* CollapsedAt(const std::vector<CollapsedStretch>& collapses, double s, Posture posture) {
  for (const CollapsedStretch& c : collapses)
    if (s >= c.s0 && s <= c.s1 && (posture == Posture::Supine ? c.supine : c.prone)) return &c;
  return nullptr;
}

std::string CollapseNote(const std::vector<CollapsedStretch>& collapses, double s, Posture posture) {
  if (collapses.empty()) return "";
  return CollapsedAt(collapses, s, posture) ? " collapsed=true" : " collapsed=false";
}

}  // namespace phantom
}  // namespace colonmap
