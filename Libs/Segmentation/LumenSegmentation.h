#pragma once
// Colon lumen segmentation of a CT colonography scan (DESIGN 2.1, issue 4).
//
//   1. Air: voxels with HU below the threshold (cleansed fluid is air already).
//   2. 26-connected components of the air (LabelComponents.h). Components touching a side face of the image
//      (the faces of the two index axes that run across the body, whatever the file's axis
//      order) are the air around the body and are dropped; so are components touching the
//      superior face (the lung bases at the top of an abdominal scan; the colon lies below the
//      diaphragm).
//   3. The remaining components, largest first, are judged by volume and shape: too small
//      (small-bowel gas, isolated pockets), too thick (the radius of the largest inscribed ball
//      exceeds what a distended colon has: lungs), or not elongated (a compact pocket: the
//      length of a tube of that radius and volume is short compared with its diameter). The
//      largest component that passes is the colon.
//   3a. Pieces (issue 21): a collapsed stretch splits the colon into several components. The
//      other colon-like components, and smaller ones down to minPieceVolumeMl and
//      minPieceElongation, are joined to the colon where their ends continue it (PieceOrder.h:
//      gap and bend at the ends); the rest are dropped.
//   4. Topology: cavities of each piece (enclosed non-air pockets, e.g. noise or a fold pinched
//      off) are filled, then its lumen is regrown from its deepest voxel by topology-preserving
//      growth in order of decreasing depth (TopologyPreservingGrowth.h), which cuts every
//      handle at its thinnest place. Each piece is a topological ball.
// The label map holds the largest piece as 1 (what every later stage reads today) and the other
// pieces as 2, 3, ... in their order from the caecum; `pieces` gives the whole order. With
// bridgePieces the pieces and the virtual lumen between them are grown as one ball, label 1.
// When no component qualifies, SegmentColonLumen throws NoColonFound saying what was found.
#include "Core/Cancel.h"
#include "Core/Error.h"
#include "Core/Volume.h"
#include "Segmentation/PieceBridge.h"
#include "Segmentation/PieceOrder.h"
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
  double minPieceVolumeMl = 20.0;   // a further piece of a collapsed colon holds at least this
  double minPieceElongation = 1.0;  // and is at least as long as it is wide
  PieceOrderOptions pieceOrder;     // which pieces join and how (PieceOrder.h)
  // Join the pieces by virtual lumen through the collapsed stretches (PieceBridge.h): label 1
  // is then the whole colon, and `bridges` marks the voxels that are not real lumen.
  bool bridgePieces = false;
};

enum class Decision { Colon, OutsideBody, AtSuperiorBorder, TooSmall, TooThick, NotElongated, NotLargest, Piece };

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
  double lengthMm = -1.0;  // pieces of the colon when there are several: geodesic length through the lumen
  int labelValue = 0;      // pieces of the colon: value in the label map (the colon 1)
};

// A piece of the colon in its order from the caecum.
struct ColonPiece {
  std::size_t component = 0;  // index in LumenSegmentation::components
  int labelValue = 1;
  PieceShape shape;           // ends[caecalEnd] faces the caecum (not measured for a colon in one piece)
  int caecalEnd = 0;
  double gapAfterMm = 0.0;    // to the next piece (0 for the last)
};

struct LumenSegmentation {
  Volume<unsigned char> label;          // the input's geometry; the colon 1, further pieces 2.., else 0
  std::vector<AirComponent> components; // every air component, largest first
  std::size_t colon = 0;                // index of the colon (the largest piece) in components
  std::vector<ColonPiece> pieces;       // the colon's pieces from the caecum (one without collapse)
  double lumenVolumeMl = 0.0;           // of label 1 (the colon)
  double piecesVolumeMl = 0.0;          // of all pieces
  std::vector<Bridge> bridges;          // bridgePieces: one per gap, in order from the caecum
  Volume<unsigned char> bridgeLabel;    // bridgePieces: 1 where the lumen is virtual (empty without)
  std::size_t cavityVoxelsFilled = 0;   // enclosed pockets filled before the growth (the colon)
  std::size_t handleVoxelsRemoved = 0;  // voxels the growth left out (they would close handles; the colon)
  GrowthStatistics growth;              // of the colon
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
