#pragma once
// Simple points for the (26,6) connectivity pair (foreground 26-connected, background
// 6-connected): a voxel is simple when adding it to (or removing it from) the foreground
// changes no topology — no component, cavity or handle appears or disappears. The test is
// local (Bertrand & Malandain 1994): with X the foreground in the 3x3x3 neighbourhood of x,
//   T26 = number of 26-components of X in N26*(x) = 1, and
//   T6  = number of 6-components of the background in N18*(x) that are 6-adjacent to x = 1.
#include <cstdint>

namespace colonmap::segmentation {

// Bit n of a neighbourhood is the voxel at offset (di, dj, dk) in -1..1 with
// n = (di + 1) + 3 (dj + 1) + 9 (dk + 1); bit 13 is the centre and is ignored.
constexpr int NeighbourBit(int di, int dj, int dk) { return (di + 1) + 3 * (dj + 1) + 9 * (dk + 1); }

// Number of 26-connected components of the foreground in N26*(x).
int ForegroundComponents26(std::uint32_t neighbourhood);
// Number of 6-connected components of the background in N18*(x) that are 6-adjacent to x.
int BackgroundComponents6(std::uint32_t neighbourhood);
// T26 == 1 and T6 == 1.
bool IsSimple26(std::uint32_t neighbourhood);

}  // namespace colonmap::segmentation
