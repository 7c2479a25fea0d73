#pragma once
// Collapsed stretches of the phantom colon (issue 21): where the lumen of one scan (or both) is
// closed, as in clinical CT colonography, where a stretch is often collapsed or fluid-filled in
// one position and open in the other. Drawn from the seed on a stream of their own, so a
// phantom without collapses is unchanged and one with them has the same anatomy otherwise.
#include "ColonAnatomy.h"

#include <cstdint>
#include <vector>

namespace colonmap {
namespace phantom {

// `count` stretches of 20-80 mm, most likely in the sigmoid, then the descending and the
// transverse colon (weights 0.35, 0.30, 0.25; ascending and rectum 0.05 each), at least 60 mm
// from either end of the colon and 60 mm from each other; each collapsed in the supine scan
// (40%), the prone scan (40%) or both (20%). Sorted by s. Throws std::invalid_argument for a
// count outside 0..4.
std::vector<CollapsedStretch> DrawCollapses(const ColonAnatomy& anatomy, int count, std::uint32_t seed);

}  // namespace phantom
}  // namespace colonmap
