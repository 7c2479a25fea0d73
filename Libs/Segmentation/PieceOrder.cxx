#include "Segmentation/PieceOrder.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::segmentation {
namespace {

double Angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Depth-first search over chains grown at their tail; `tailEnd` is the free end of the last piece.
struct Search {
  Search(const std::vector<PieceShape>& p, const PieceOrderOptions& o, int r) : pieces(p), options(o), required(r) {}
  const std::vector<PieceShape>& pieces;
  const PieceOrderOptions& options;
  int required;
  std::vector<std::vector<double>> cost;  // cost[2p + e][2q + f]: out of end e of p into end f of q
  std::vector<int> chain, entry;          // pieces and the end each is entered by
  std::vector<bool> used;
  double bestScore = std::numeric_limits<double>::infinity();
  std::vector<int> bestChain, bestEntry;

  void Visit(double score) {
    const bool hasRequired = std::find(chain.begin(), chain.end(), required) != chain.end();
    if (hasRequired && score < bestScore - 1e-9) {
      bestScore = score;
      bestChain = chain;
      bestEntry = entry;
    }
    const int tail = chain.back(), tailEnd = 1 - entry.back();
    for (int q = 0; q < static_cast<int>(pieces.size()); ++q) {
      if (used[static_cast<std::size_t>(q)]) continue;
      for (int f = 0; f < 2; ++f) {
        const double c = cost[static_cast<std::size_t>(2 * tail + tailEnd)][static_cast<std::size_t>(2 * q + f)];
        if (!std::isfinite(c)) continue;
        used[static_cast<std::size_t>(q)] = true;
        chain.push_back(q);
        entry.push_back(f);
        Visit(score + c - options.maxLinkCostMm);
        chain.pop_back();
        entry.pop_back();
        used[static_cast<std::size_t>(q)] = false;
      }
    }
  }
};

}  // namespace

double LinkCost(const PieceEnd& from, const PieceEnd& to, const PieceOrderOptions& o) {
  const Eigen::Vector3d g = to.point - from.point;
  const double gap = g.norm();
  if (!(gap <= o.maxGapMm)) return std::numeric_limits<double>::infinity();
  // The lumen leaves `from` along from.outward and enters `to` against to.outward. Across a
  // short gap its direction is noise: then only the two ends' directions are compared.
  double bend;
  if (gap < 5.0) {
    bend = Angle(from.outward, -to.outward);
    if (bend > o.maxBendRad) return std::numeric_limits<double>::infinity();
  } else {
    const double out = Angle(from.outward, g), in = Angle(-to.outward, g);
    if (out > o.maxBendRad || in > o.maxBendRad) return std::numeric_limits<double>::infinity();
    bend = out + in;
  }
  const double cost = gap + o.bendCostMmPerRad * bend;
  return cost <= o.maxLinkCostMm ? cost : std::numeric_limits<double>::infinity();
}

PieceChain OrderPieces(const std::vector<PieceShape>& pieces, int required, const PieceOrderOptions& options) {
  const int n = static_cast<int>(pieces.size());
  if (n == 0 || n > kMaxPieces) throw Error("piece order: expected 1.." + std::to_string(kMaxPieces) + " pieces");
  if (required < 0 || required >= n) throw Error("piece order: the required piece is not among the pieces");
  Search search{pieces, options, required};
  search.used.assign(static_cast<std::size_t>(n), false);
  search.cost.assign(static_cast<std::size_t>(2 * n), std::vector<double>(static_cast<std::size_t>(2 * n),
                                                                          std::numeric_limits<double>::infinity()));
  for (int p = 0; p < n; ++p)
    for (int e = 0; e < 2; ++e)
      for (int q = 0; q < n; ++q)
        for (int f = 0; f < 2; ++f)
          if (p != q)
            search.cost[static_cast<std::size_t>(2 * p + e)][static_cast<std::size_t>(2 * q + f)] =
                LinkCost(pieces[static_cast<std::size_t>(p)].ends[static_cast<std::size_t>(e)],
                         pieces[static_cast<std::size_t>(q)].ends[static_cast<std::size_t>(f)], options);
  for (int p = 0; p < n; ++p)
    for (int e = 0; e < 2; ++e) {
      search.used[static_cast<std::size_t>(p)] = true;
      search.chain = {p};
      search.entry = {e};
      search.Visit(0.0);
      search.used[static_cast<std::size_t>(p)] = false;
    }

  PieceChain out;
  out.pieces = search.bestChain;
  out.caecalEnd = search.bestEntry;
  // Orientation: the free end of the first piece against that of the last, by LPS x.
  const auto endOf = [&](std::size_t k, int e) -> const PieceEnd& {
    return pieces[static_cast<std::size_t>(out.pieces[k])].ends[static_cast<std::size_t>(e)];
  };
  const std::size_t last = out.pieces.size() - 1;
  const double firstX = endOf(0, out.caecalEnd[0]).point.x(), lastX = endOf(last, 1 - out.caecalEnd[last]).point.x();
  if (lastX < firstX) {
    std::reverse(out.pieces.begin(), out.pieces.end());
    std::reverse(out.caecalEnd.begin(), out.caecalEnd.end());
    for (int& e : out.caecalEnd) e = 1 - e;
  }
  for (std::size_t k = 0; k < last; ++k) {
    const PieceEnd& a = endOf(k, 1 - out.caecalEnd[k]);
    const PieceEnd& b = endOf(k + 1, out.caecalEnd[k + 1]);
    out.gapMm.push_back((b.point - a.point).norm());
    out.linkCost.push_back(LinkCost(a, b, options));
  }
  return out;
}

}  // namespace colonmap::segmentation
