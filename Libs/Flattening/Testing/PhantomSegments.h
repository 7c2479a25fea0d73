#pragma once
// Test inputs of the flattening stage cut from the phantom's TRUE wall, following the
// landmarks -> flattening file contract (/tmp/contract.md, DESIGN §2.0): per segment a
// topological cylinder (the faces whose three vertices have that SegmentId; the wall grid is
// rows along s, so each segment is a band of whole rows) with CenterlineArcLength = L -
// MaterialS (mm from the anal end), and the three taeniae as vertex paths along mesh edges,
// following the grid column nearest TaeniaTheta(k, s) row by row.
#include "Core/Polyline.h"
#include "Core/TriangleMesh.h"
#include "Phantom/Phantom.h"

#include <array>
#include <vector>

namespace colonmap::flattening::testing {

struct PhantomSegment {
  int id = 0;                         // SegmentId 0..4 = A..R
  TriangleMesh mesh;                  // SegmentId, CenterlineArcLength, MaterialS, MaterialTheta
  std::array<Eigen::VectorXi, 3> taenia;  // TL, TO, TM as vertex indices of mesh, cecal end first
};

// Phantom options of the test-data drivers' common arguments: <mesh step mm> <points around>
// <seed> (text, as on their command lines).
phantom::PhantomOptions TrueWallOptions(const char* meshStepMm, const char* pointsAround, const char* seed);

// The whole true wall with CenterlineArcLength added (the contract's colon_open.vtp).
TriangleMesh TrueWallWithArcLength(const phantom::ScanGeometry& scan, const phantom::PhantomOptions& o);
// The five segments of that wall.
std::vector<PhantomSegment> PhantomTruthSegments(const phantom::ScanGeometry& scan, const phantom::PhantomOptions& o);
// taeniae.vtp contents for the given segments (IsCut = 1 for TO).
PolylineSet TaeniaePolylines(const std::vector<PhantomSegment>& segments);

}  // namespace colonmap::flattening::testing
