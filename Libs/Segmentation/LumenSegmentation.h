#pragma once
// Colon lumen segmentation of a CT colonography scan (DESIGN 2.1, issue 4).
//
//   1. Air: voxels with HU below the threshold (cleansed fluid is air already).
//   2. 26-connected components of the air (ITK). Components touching a side face of the image
//      (the faces of the two index axes that run across the body, whatever the file's axis
//      order) are the air around the body and are dropped; so are components touching the
//      superior face (the lung bases at the top of an abdominal scan; the colon lies below the
//      diaphragm).
//   3. The remaining components, largest first, are judged by volume and shape: too small
//      (small-bowel gas, isolated pockets), too thick (the radius of the largest inscribed ball
//      exceeds what a distended colon has: lungs), or not elongated (a compact pocket: the
//      length of a tube of that radius and volume is short compared with its diameter). The
//      largest component that passes is the colon; any further one is dropped ("not the
//      largest"), since the lumen must be one component.
//   4. Topology: cavities of the colon component (enclosed non-air pockets, e.g. noise or a
//      fold pinched off) are filled, then the lumen is regrown from its deepest voxel by
//      topology-preserving growth in order of decreasing depth (TopologyPreservingGrowth.h),
//      which cuts every handle at its thinnest place. The result is a topological ball.
// When no component qualifies, SegmentColonLumen throws NoColonFound saying what was found.
#include "Core/Cancel.h"
#include "Core/Error.h"
#include "Core/Volume.h"
#include "Segmentation/TopologyPreservingGrowth.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::segmentation {

struct SegmentationOptions {
  double airThresholdHU = -480.0;   // air when HU < this; -480 is half-way between air and wall
  double minColonVolumeMl = 150.0;  // a distended colon holds a litre or more of gas
  double maxColonRadiusMm = 40.0;   // radius of the largest inscribed ball; lungs are thicker
  double minElongation = 4.0;       // (volume / (pi r^2)) / (2 r): tube length over diameter
};

enum class Decision { Colon, OutsideBody, AtSuperiorBorder, TooSmall, TooThick, NotElongated, NotLargest };

// One air component and what was decided about it. Shape figures are measured only for
// components inside the body of at least minColonVolumeMl (otherwise maxRadiusMm and
// elongation are negative).
struct AirComponent {
  std::size_t voxels = 0;
  double volumeMl = 0.0;
  std::array<std::size_t, 3> boxMin{{0, 0, 0}}, boxMax{{0, 0, 0}};  // index bounding box, inclusive
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();               // LPS mm
  double maxRadiusMm = -1.0;
  double elongation = -1.0;
  Decision decision = Decision::TooSmall;
  std::string reason;  // one phrase, e.g. "touches the image border (air outside the body)"
};

struct LumenSegmentation {
  Volume<unsigned char> label;          // the input's geometry; lumen 1, else 0
  std::vector<AirComponent> components; // every air component, largest first
  std::size_t colon = 0;                // index of the colon in components
  double lumenVolumeMl = 0.0;           // of `label`
  std::size_t cavityVoxelsFilled = 0;   // enclosed pockets filled before the growth
  std::size_t handleVoxelsRemoved = 0;  // voxels the growth left out (they would close handles)
  GrowthStatistics growth;
  std::vector<std::pair<std::string, double>> stepSeconds;  // wall time per step, for the report
  std::size_t Dropped(Decision d) const;  // number of components with this decision
};

// Thrown when the scan holds no component that qualifies as a distended colon; the message is
// one line saying what was found, e.g. "no distended colon found: the largest air component
// inside the body is 12 ml (a colon needs >= 150 ml)".
struct NoColonFound : Error {
  using Error::Error;
};

// ct in HU, any geometry. Throws NoColonFound, colonmap::Error for bad options, Cancelled from
// progress (reported at least every few tens of milliseconds of work).
LumenSegmentation SegmentColonLumen(const Volume<short>& ct, const SegmentationOptions& options,
                                    ProgressSink& progress);

const char* DecisionName(Decision d);  // "colon", "outside body", "too small", ...

}  // namespace colonmap::segmentation
