#pragma once
// Reading the real colon of the Edinburgh Gut Cell Atlas model EdinGCA_3D_00020 (CC BY 4.0;
// credit "Edinburgh Gut Cell Atlas, EdinGCA_3D_00020"), in ../shared/data/gca-00020, for the
// tests that check our methods on real data.
//
// GCA conventions (shared/README.md and the upstream READMEs): surfaces and the midline are in
// voxel units, times voxel_size (read from the model JSON, 0.808594 x 0.808594 x 0.7) for mm.
// The voxel axes are LPS-like (checked on the midline: the splenic flexure has larger x than
// the hepatic flexure, so +x is patient left; the anus is at the smallest z and the flexures
// at the largest, so +z is superior; the rectum lies at larger y than the transverse colon, so
// +y is posterior); the origin is not that of any scanner frame (irrelevant here: only
// directions matter). The midline runs from the anus (index 0) to the appendix tip;
// landmarks are indices into it (DSJ 1367, SF 2441, HF 3666, ICVc 4139, AO, ...).
//
//   GcaModel g = ReadGcaModel(dir);              // midline (mm), arc, landmark indices
//   TriangleMesh piece = ReadGcaSurface(g, "A-DSJ");   // one segmented surface, mm
//   GcaWeld w = WeldGcaColon(g);                 // one closed genus-0 colon, mm (see below)
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace colonmap::analysis {

struct GcaModel {
  std::string directory;           // the gca-00020 folder
  Eigen::Vector3d voxelSize{1, 1, 1};  // mm per voxel unit
  Eigen::MatrixXd midline;         // large-intestine path, anus -> appendix tip, mm
  Eigen::VectorXd midlineArc;      // its cumulative arc length, mm
  std::map<std::string, int> landmark;  // abbreviated name -> index into midline (large-intestine path only)
  std::map<std::string, std::string> surfaceMap;  // surface file name -> per-vertex midline map file
  // Arc length (mm from the anus) of a landmark; Error if the model has no such landmark.
  double Arc(const std::string& name) const;
};

// directory: the gca-00020 folder (EdinGCA_3D_00020_1_14.json, Paths/, SegmentedSurfaces/).
// Error (one line naming the file) when a file is missing or malformed.
GcaModel ReadGcaModel(const std::string& directory);

// SegmentedSurfaces/large-intestine-<piece>.vtk scaled to mm, e.g. piece "A-DSJ", "HF+-ICVc".
TriangleMesh ReadGcaSurface(const GcaModel& model, const std::string& piece);

// The pieces from the anus to the caecal pole: A-DSJ ... HF+-ICVc, ICVc-AO (the appendix AO-TA
// left out; the model has no small-intestine piece among the large-intestine surfaces).
const std::vector<std::string>& GcaColonPieces();

// Topology of the colon at one step of the welding, for reports.
struct GcaWeldStep {
  std::string step;
  long vertices = 0, faces = 0;
  int components = 0;
  long euler = 0;
  int boundaryLoops = 0;
  long nonManifoldEdges = 0, nonManifoldVertices = 0;
};

struct GcaWeld {
  TriangleMesh colon;  // closed, one component, genus 0, manifold, consistently oriented, mm
  std::vector<GcaWeldStep> steps;
  int capVertices = 0;        // fan-centre vertices added (one per capped hole; the last ones in colon.V)
  std::vector<int> capLoopSizes;  // boundary loop lengths (edges) that were capped
  long duplicateFaces = 0, degenerateFaces = 0, nonManifoldFaces = 0, droppedFaces = 0;
  int splitVertices = 0;
};

// Welds GcaColonPieces() into one closed genus-0 colon (see the .cxx for each step and why):
// pieces appended, coincident points merged (vtkStaticCleanPolyData, absolute tolerance
// toleranceMm: the pieces were cut from one surface, so their boundary points coincide),
// degenerate and duplicate faces removed, faces on non-manifold edges removed, non-manifold
// vertices split, the largest component kept, orientation made consistent, and every
// remaining boundary loop (anal opening, appendix orifice, holes left by the removed faces)
// capped by a fan around a new vertex at the loop's centroid.
// The result is closed, manifold and oriented, but NOT genus 0: the atlas surfaces have
// handles (measured: A-DSJ genus 3, SF+-HF- genus 3; welded colon genus 6), which no choice
// of faces or caps removes; see GenusZeroGcaColon.
GcaWeld WeldGcaColon(const GcaModel& model, double toleranceMm = 1e-3);

struct GcaGenusZero {
  TriangleMesh colon;  // closed genus-0 surface, normals into the lumen, point data MeanCurvature, mm
  double lumenMl = 0.0;
  std::size_t handleVoxelsRemoved = 0;  // voxels the topology-preserving growth left out
  std::size_t cavityVoxelsFilled = 0;
  long wellComposedVoxels = 0;  // voxels added or removed (simple points) to make the ball well-composed
  // Distance (mm) from each vertex of `colon` to the welded surface, and from each vertex of
  // the welded surface to `colon` (large where a handle was cut).
  double toWeldMean = 0.0, toWeldP99 = 0.0, toWeldMax = 0.0;
  double fromWeldMean = 0.0, fromWeldP99 = 0.0, fromWeldMax = 0.0;
  double seconds = 0.0;
  bool contouredCT = false;        // the CT-like field's surface was used (false: the label alone)
  std::vector<std::string> notes;  // ReconstructSurface's notes: what was retried and why
};

// The welded colon made genus 0 the way our pipeline makes a CT lumen genus 0: the closed
// welded surface is voxelised (vtkPolyDataToImageStencil, parity along rays, so handles and
// self-touching walls do not matter) on a spacingMm grid as a CT (lumen -1000 HU, wall 40 HU),
// segmented by segmentation::SegmentColonLumen (cavities filled, ball grown deepest first from
// the deepest voxel adding only simple points: each handle is cut at its thinnest place), made
// well-composed by simple-point changes (see the .cxx: marching cubes then cannot open handles
// at diagonal voxel contacts), and contoured by surface::ReconstructSurface on a CT-like field
// (the Gaussian-smoothed ball clamped so that its sign at every voxel centre is the ball's;
// decimated to about targetFaces, windowed-sinc smoothed), with ReconstructSurface's fallbacks
// (measured at 1.5 mm, 200K faces: the CT-like surface and its retry keep 6 non-manifold edges
// after decimation, and the label-only contour, the same ball smoothed without the clamp, is
// what is returned; contouredCT and notes say so). Error if any step fails or the result is not
// closed genus 0.
// Measured (2 mm grid, 200K faces): 4.4 s; vertices of the result within 0.25 mm (mean) of
// the weld; before the well-composed repair the contour had genus 3-29 depending on smoothing.
GcaGenusZero GenusZeroGcaColon(const GcaWeld& weld, double spacingMm = 2.0, long targetFaces = 200000);

}  // namespace colonmap::analysis
