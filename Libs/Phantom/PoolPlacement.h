#pragma once
// Where tagged fluid pools go along a colon, the rule both phantoms share (the tube,
// ScanGeometry.cxx; the real colon, RealColon/RealColonPhantom.cxx): at the lowest places of
// the lumen floor, each filled to a seeded fraction of the local diameter, apart by 150 mm or
// more along the colon.
#include "Phantom/Random.h"

#include <functional>
#include <vector>

namespace colonmap::phantom {

struct PoolPlace {
  int deepest = 0;     // sample of the lowest floor point
  int lo = 0, hi = 0;  // samples whose floor lies below the level (a contiguous range)
  double level = 0.0;  // height of the air-fluid level
};

// floorHeight: the lowest height of the wall at samples every stepMm along the colon (larger is
// higher). diameter(i): the lumen diameter at sample i. wanted: how many pools at most; rng:
// one level fraction (0.2..0.4 of the diameter) is drawn per pool tried. Candidates: samples
// at least 20 from either end that are the lowest within 30 samples, lowest first.
std::vector<PoolPlace> PlacePools(const std::vector<double>& floorHeight, double stepMm,
                                  const std::function<double(int)>& diameter, int wanted, Rng& rng);

}  // namespace colonmap::phantom
