#pragma once
// Reading real colons packaged by the Edinburgh Gut Cell Atlas (GCA) in its model format, in
// ../shared/data, for the tests and the real-colon phantom: EdinGCA_3D_00020 (an inflated CTC
// colon with haustra; credit "Edinburgh Gut Cell Atlas, EdinGCA_3D_00020") and the HuBMAP
// Visible Human male and female colons HuBMAPVHM_3D_00070 and HuBMAPVHF_3D_00080 (credit
// "HuBMAP, via the Edinburgh Gut Cell Atlas"), all CC BY 4.0.
//
// Format (shared/README.md and the upstream READMEs): one model JSON (<model>_<v>_<sv>.json)
// naming the surfaces, the voxel size and the landmarks; Paths/large_intestine_path.jsn, the
// midline from the anus (index 0) up; SegmentedSurfaces/large-intestine-<piece>.vtk, surface
// pieces cut at landmarks, in voxel units (times voxel_size for mm: 0.808594 x 0.808594 x 0.7
// for GCA 00020, 1 for the HuBMAP models), each with a per-vertex map to midline indices.
// Landmarks are indices into the midline (GCA 00020: DSJ 1367, SF 2441, HF 3666, ICVc 4139,
// AO, ...). The axes of all three are LPS-like (checked on the midline: the splenic flexure
// has larger x than the hepatic flexure, so +x is patient left; the anus is at the smallest z
// and the flexures at the largest, so +z is superior; the rectum lies at larger y than the
// transverse colon, so +y is posterior); the origin is not that of any scanner frame.
//
//   GcaModel g = ReadGcaModel(dir);              // midline (mm), arc, landmark indices, pieces
//   TriangleMesh piece = ReadGcaSurface(g, "A-DSJ");   // one segmented surface, mm
//   GcaWeld w = WeldGcaColon(g);                 // one closed colon, mm (see below)
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"

#include <Eigen/Core>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace colonmap::analysis {

struct GcaModel {
  std::string directory;           // the model folder
  std::string modelFile;           // its model JSON
  std::string name;                // the model's name, e.g. "Edinburgh GCA Inflated-Gut CT Atlas"
  std::string serial;              // e.g. "00020"
  Eigen::Vector3d voxelSize{1, 1, 1};  // mm per voxel unit
  Eigen::MatrixXd midline;         // large-intestine path, anus -> appendix tip, mm
  Eigen::VectorXd midlineArc;      // its cumulative arc length, mm
  std::map<std::string, int> landmark;  // abbreviated name -> index into midline (large-intestine path only)
  std::map<std::string, std::string> surfaceMap;  // surface file name -> per-vertex midline map file
  // The pieces of the colon lumen from the anus to the caecal pole, ordered along the midline:
  // the large-intestine surfaces that have a midline map, except those past the appendix
  // orifice (the appendix) and those whose midline range lies inside the others' (overlapping
  // flexure regions of the HuBMAP models). GCA 00020: A-DSJ ... HF+-ICVc, ICVc-AO.
  std::vector<std::string> colonPieces;
  // Arc length (mm from the anus) of a landmark; Error if the model has no such landmark.
  double Arc(const std::string& name) const;
};

// directory: a GCA model folder (one model JSON, Paths/, SegmentedSurfaces/). Error (one line
// naming the file) when a file is missing or malformed, or the folder holds no such model.
GcaModel ReadGcaModel(const std::string& directory);
// Whether `directory` looks like a GCA model folder (a model JSON with a large-intestine path).
bool IsGcaModelFolder(const std::string& directory);

// SegmentedSurfaces/large-intestine-<piece>.vtk scaled to mm, e.g. piece "A-DSJ", "HF+-ICVc".
TriangleMesh ReadGcaSurface(const GcaModel& model, const std::string& piece);

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
  TriangleMesh colon;  // closed, one component, manifold, consistently oriented, mm (handles possible)
  std::vector<GcaWeldStep> steps;
  int capVertices = 0;        // fan-centre vertices added (one per capped hole; the last ones in colon.V)
  std::vector<int> capLoopSizes;  // boundary loop lengths (edges) that were capped
  long duplicateFaces = 0, degenerateFaces = 0, nonManifoldFaces = 0, droppedFaces = 0;
  long outerShellFaces = 0;   // faces of outer shells left out (thick-walled models: the lumen is the inner one)
  int splitVertices = 0;
};

// Welds model.colonPieces into one closed colon (see the .cxx for each step and why):
// pieces appended, coincident points merged (surface::MergeCoincidentPoints, absolute tolerance
// toleranceMm: the pieces were cut from one surface, so their boundary points coincide; in
// the HuBMAP models to within 0.02 mm, in GCA 00020 exactly),
// degenerate and duplicate faces removed, faces on non-manifold edges removed, non-manifold
// vertices split, components under a quarter of the largest dropped, orientation made
// consistent, every remaining boundary loop (anal opening, appendix orifice, holes left by the
// removed faces) capped by a fan around a new vertex at the loop's centroid, and of nested
// closed shells (the HuBMAP models' inner and outer wall) the one enclosing the least volume,
// the lumen, kept.
// The result is closed, manifold and oriented, but NOT genus 0: the atlas surfaces have
// handles (measured: A-DSJ genus 3, SF+-HF- genus 3; welded colon genus 6), which no choice
// of faces or caps removes; see GenusZeroGcaColon.
GcaWeld WeldGcaColon(const GcaModel& model, double toleranceMm = 0.05);

// A closed surface voxelised (surface::FillInsideMask: parity along rays, so handles and
// self-touching walls do not matter) on a spacingMm grid over its bounding box plus 4 voxels:
// 1 inside, 0 outside.
Volume<unsigned char> VoxeliseSurface(const TriangleMesh& closedSurface, double spacingMm);

// The same made a topological ball, well-composed (segmentation::SimplifyLumenTopology: the
// largest component, cavities filled, handles cut at their thinnest places), so that any field
// with the ball's sign at the voxel centres contours to a closed manifold genus-0 surface.
struct LumenBall {
  Volume<unsigned char> ball;           // on a crop of the voxel grid, geometry set; 1 inside
  double lumenMl = 0.0;
  long handles = 0;                     // handles of the voxelised lumen
  std::size_t handleVoxelsRemoved = 0;  // voxels the topology-preserving growth left out
  std::size_t cavityVoxelsFilled = 0;
  long wellComposedVoxels = 0;          // voxels added or removed (simple points) to make it well-composed
};
// progress (optional) gets the topology step's reports (and its Cancelled).
LumenBall GenusZeroBall(const TriangleMesh& closedSurface, double spacingMm, ProgressSink* progress = nullptr);

struct GcaGenusZero {
  TriangleMesh colon;  // closed genus-0 surface, normals into the lumen, point data MeanCurvature, mm
  double lumenMl = 0.0;
  std::size_t handleVoxelsRemoved = 0;  // voxels the topology-preserving growth left out
  std::size_t cavityVoxelsFilled = 0;
  long wellComposedVoxels = 0;  // voxels added or removed (simple points) to make the ball well-composed
  long handles = 0;             // handles of the voxelised weld
  // Distance (mm) from each vertex of `colon` to the welded surface, and from each vertex of
  // the welded surface to `colon` (large where a handle was cut).
  double toWeldMean = 0.0, toWeldP99 = 0.0, toWeldMax = 0.0;
  double fromWeldMean = 0.0, fromWeldP99 = 0.0, fromWeldMax = 0.0;
  double seconds = 0.0;
  std::vector<std::string> notes;  // ReconstructSurface's notes: what its topology step changed
};

// The welded colon made genus 0 the way our surface stage makes any lumen mask genus 0: the
// closed welded surface voxelised on a spacingMm grid (VoxeliseSurface) and given to
// surface::ReconstructSurface as a label map (its topology step keeps one component, fills
// cavities and cuts each handle at its thinnest place; contour of the label smoothed with its
// sign kept, manifold decimation to about targetFaces). Error if any step fails.
GcaGenusZero GenusZeroGcaColon(const GcaWeld& weld, double spacingMm = 2.0, long targetFaces = 200000);

}  // namespace colonmap::analysis
