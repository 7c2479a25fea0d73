#pragma once
// Which lumen pieces make one colon, and in which order from the caecum (issue 21): a colon
// with collapsed stretches is several air components, and the order of their ends along the
// colon decides what every later stage pairs with what.
//
// Two pieces join where the colon runs out of one end and into the other: the cost of a link
// is the gap between the two ends plus a bend cost for each end's direction against the gap
// (the way the lumen leaves piece i must point at piece j's end, and piece j's lumen must
// continue the same way); an end facing away from the other by more than maxBendRad is never
// joined. A piece close by but facing sideways (a sigmoid loop crossing the
// descending colon) costs far more than a farther one straight ahead. The chain is the one of
// least total cost minus a reward per piece (the cost a link may have at most): every piece
// that can be joined is joined, each by its cheapest place. All orders and orientations of up
// to kMaxPieces pieces are tried (exact, no greedy choice). The caecal end of the chain is the
// one with the smaller LPS x (the caecum lies on the right), as for one piece in
// Landmarks/ColonLandmarks.h.
#include "Segmentation/PieceShape.h"

#include <vector>

namespace colonmap::segmentation {

struct PieceOrderOptions {
  double maxGapMm = 120.0;          // ends farther apart are never joined
  double bendCostMmPerRad = 20.0;   // mm of gap one radian of bend at an end costs (a collapsed sigmoid turns by 180 degrees in 80 mm)
  double maxLinkCostMm = 160.0;     // a link may cost at most this (gap + bends)
  double maxBendRad = 2.1;          // no end turns by more than 120 degrees towards the other
};

constexpr int kMaxPieces = 7;

// Cost (mm) of the colon running out of `from` and into `to`; +inf when not allowed.
double LinkCost(const PieceEnd& from, const PieceEnd& to, const PieceOrderOptions& options);

struct PieceChain {
  std::vector<int> pieces;       // indices into the input, from the caecum
  std::vector<int> caecalEnd;    // per chain piece: which of its ends (0, 1) faces the caecum
  std::vector<double> gapMm;     // per link (pieces.size() - 1): distance between the joined ends
  std::vector<double> linkCost;  // per link
};

// pieces: at most kMaxPieces (the caller keeps the largest); required: the index of a piece
// the chain must hold (the largest colon-like component). Pieces that cannot be joined are
// left out of the chain.
PieceChain OrderPieces(const std::vector<PieceShape>& pieces, int required, const PieceOrderOptions& options);

}  // namespace colonmap::segmentation
