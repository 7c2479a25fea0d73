#pragma once
// Carrying points across a registration (ColonTransferPoints, DESIGN §2.0, §2.4): a point is
// projected to the nearest point of the source wall (closest point on the nearest triangle),
// that foot is sent across with the per-vertex map (barycentric combination of the images of the
// triangle's three vertices), snapped to the nearest point of the target wall, and the point's
// signed offset along the source normal is re-applied along the target normal (a polyp tip or a
// point in the lumen keeps its height above the wall). VTK only in the .cxx: vtkCellLocator,
// whose serial build breaks ties between equally close triangles the same way on every run (the
// threaded vtkStaticCellLocator does not, and a point on a shared edge then changes triangle).
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

#include <memory>
#include <string>

namespace colonmap::registration {

struct TransferredPoint {
  Eigen::Vector3d position;   // on the target (plus the re-applied normal offset)
  Eigen::Vector3d sourceFoot; // nearest source wall point
  Eigen::Vector3d targetFoot; // its image on the target wall
  double offset = 0.0;        // signed distance from the source wall along its normal (mm)
  int sourceFace = -1;
  Eigen::Vector3d sourceBary{1, 0, 0};  // of sourceFoot in sourceFace
  int targetFace = -1;
  Eigen::Vector3d targetBary{1, 0, 0};  // of targetFoot in targetFace
  int segment = -1;           // SegmentId of the foot's nearest vertex (-1 without the array)
  double dilatation = 1.0;    // K of the source face (1 without the array)
  double uncertaintyMm = 0.0; // 90% bound of the error (mm), see PointTransfer::Transfer
  double uncertaintyMedianMm = 0.0;  // the predicted median error (mm)
  bool reliable = true;       // false where the registration cannot be trusted (RegistrationReliability.h)
  // Collapsed stretches (WallVisibility.h): the source foot or its image lies on virtual wall.
  // A point on virtual target wall is moved to the nearest open wall along the colon
  // (openDistanceMm away along the colon); either way visible and reliable are false.
  bool visible = true;
  bool sourceVirtual = false, targetVirtual = false;
  double openDistanceMm = 0.0;
};

// registration.vtp (supine, with the Prone* arrays) and the prone mesh: `pronePath` when given,
// else the copy registration.vtp carries (EmbeddedProneMesh.h: one file is enough, as in Slicer,
// which hands over a renamed copy in its own folder), else registration_prone.vtp beside it
// (registrations written before that copy existed).
struct RegistrationMeshes {
  TriangleMesh supine, prone;
};
// Reads both; throws colonmap::Error naming the file that is missing, unreadable or inconsistent.
RegistrationMeshes ReadRegistration(const std::string& registrationPath, const std::string& pronePath = std::string());

class PointTransfer {
 public:
  // source: mesh with point data <prefix>TriangleId (int), <prefix>Barycentric (3) (e.g. prefix
  // "Prone" on registration.vtp); target: the mesh those triangle ids index. Optional source
  // arrays: SegmentId (point), Dilatation (cell). Throws colonmap::Error (naming `sourceWhat`)
  // when arrays are missing or ids out of range.
  PointTransfer(const TriangleMesh& source, const TriangleMesh& target, const std::string& prefix,
                const std::string& sourceWhat);
  ~PointTransfer();
  PointTransfer(const PointTransfer&) = delete;
  PointTransfer& operator=(const PointTransfer&) = delete;

  // uncertaintyMm: with the source arrays Uncertainty90 and Uncertainty (point data, mm, written
  // by ColonRegistration: RegistrationUncertainty.h) interpolated at the source foot, combined
  // with the re-attachment term: sqrt(U^2 + (0.5 |offset|)^2); without them the heuristic
  // Uncertainty() below (registrations written before those arrays existed).
  TransferredPoint Transfer(const Eigen::Vector3d& p) const;
  // A source point array (1 component) interpolated at a transferred point's source foot; NaN
  // when the array is missing.
  double SourceValue(const std::string& name, const TransferredPoint& t) const;
  // Nearest point of the target mesh: face and barycentric coordinates.
  void NearestOnTarget(const Eigen::Vector3d& p, int* face, Eigen::Vector3d* bary) const;

  // Uncertainty (mm) of a transferred point, from what the map itself shows (no truth):
  //   sqrt(h^2 + (0.5 |offset|)^2) + 2 (K - 1) h
  // h: mean edge length of the source face (the discretisation of the map), 0.5 |offset|: a
  // point off the wall is re-attached along a normal that may tilt between the scans, K: the
  // map's local dilatation (where the shape changed most between the scans the baseline map is
  // least reliable). A heuristic; its calibration against true errors is measured on the phantom.
  static double Uncertainty(double edge, double offset, double dilatation);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace colonmap::registration
