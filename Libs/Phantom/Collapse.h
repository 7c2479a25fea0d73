#pragma once
// Collapsed stretches of the phantom colon (issue 21): where the lumen of one scan (or both) is
// closed, as in clinical CT colonography, where a stretch is often collapsed or fluid-filled in
// one position and open in the other. Drawn from the seed on a stream of their own, so a
// phantom without collapses is unchanged and one with them has the same anatomy otherwise.
#include "ColonAnatomy.h"

#include <cstdint>
#include <string>
#include <vector>

namespace colonmap {
namespace phantom {

// `count` stretches of 20-80 mm, most likely in the sigmoid, then the descending and the
// transverse colon (weights 0.35, 0.30, 0.25; ascending and rectum 0.05 each), at least 60 mm
// from either end of the colon and 60 mm from each other; each collapsed in the supine scan
// (40%), the prone scan (40%) or both (20%). Sorted by s. Throws std::invalid_argument for a
// count outside 0..4.
std::vector<CollapsedStretch> DrawCollapses(const ColonAnatomy& anatomy, int count, std::uint32_t seed);

// The stretch closed in this posture that contains material s, or nullptr.
const CollapsedStretch* CollapsedAt(const std::vector<CollapsedStretch>& collapses, double s, Posture posture);

// The truth's note on a wall point at material s (both phantoms' markups): "" without
// collapses, else " collapsed=true" or " collapsed=false" for this posture.
std::string CollapseNote(const std::vector<CollapsedStretch>& collapses, double s, Posture posture);

}  // namespace phantom
}  // namespace colonmap
