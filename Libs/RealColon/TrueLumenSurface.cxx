#include "RealColon/TrueLumenSurface.h"

#include "Analysis/GcaModel.h"
#include "Core/Error.h"
#include "Surface/MeshTopology.h"
#include "Surface/SelfIntersection.h"
#include "Surface/SignedVolume.h"
#include "Surface/VtkConversion.h"

#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/Geometry>
#include <algorithm>

namespace colonmap::realcolon {
namespace {

// Smoothing can push a few faces through others where the contour is tight (a cut handle, two
// walls a voxel apart). Their vertices and those around them go back to the contour's
// positions (the contour of a well-composed set is embedded), repeated while crossings remain.
long RestoreCrossings(TriangleMesh& mesh, const Eigen::MatrixXd& contour) {
  long restored = 0;
  std::vector<char> back(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (int round = 0; round < 10; ++round) {
    const std::vector<int> folded = surface::SelfIntersectingFaces(mesh.V, mesh.F);
    if (folded.empty()) break;
    std::vector<char> mark(static_cast<std::size_t>(mesh.V.rows()), 0);
    for (int f : folded)
      for (int c = 0; c < 3; ++c) mark[mesh.F(f, c)] = 1;
    // and their one-ring
    std::vector<char> ring = mark;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      if (mark[mesh.F(f, 0)] || mark[mesh.F(f, 1)] || mark[mesh.F(f, 2)])
        for (int c = 0; c < 3; ++c) ring[mesh.F(f, c)] = 1;
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
      if (ring[v] && !back[v]) {
        mesh.V.row(v) = contour.row(v);
        back[v] = 1;
        ++restored;
      }
  }
  return restored;
}

}  // namespace

TrueLumen MakeTrueLumen(const TriangleMesh& closedSurface, const TrueLumenOptions& options, ProgressSink& progress) {
  if (!(options.gridMm > 0.2 && options.gridMm < 10.0)) throw Error("true lumen: the grid must be within 0.2..10 mm");
  TrueLumen out;
  SubProgress segmenting(progress, 0.0, 0.6);
  analysis::LumenBall lumen = analysis::GenusZeroBall(closedSurface, options.gridMm, &segmenting);
  out.lumenMl = lumen.lumenMl;
  out.handleVoxelsRemoved = lumen.handleVoxelsRemoved;
  out.cavityVoxelsFilled = lumen.cavityVoxelsFilled;
  out.wellComposedVoxels = lumen.wellComposedVoxels;
  const Volume<unsigned char>& ball = lumen.ball;

  Volume<float> field = ball.Like<float>(0.0f);
  std::copy(ball.voxels.begin(), ball.voxels.end(), field.voxels.begin());
  vtkNew<vtkImageData> image;
  surface::ToImageData(field, image);
  vtkNew<vtkImageGaussianSmooth> gauss;
  gauss->SetInputData(image);
  gauss->SetDimensionality(3);
  gauss->SetStandardDeviations(0.7, 0.7, 0.7);
  gauss->SetRadiusFactors(3.0, 3.0, 3.0);
  gauss->Update();
  surface::FromImageData(gauss->GetOutput(), field);
  // The clamp keeps the ball's sign at every voxel centre (unclamped, the smoothing bridges the
  // one-voxel gaps where a handle was cut), with a margin: at 0.55 / 0.45 the contour passed
  // within 0.1 mm of many voxel centres and left clusters of needle faces a few microns apart
  // in flat walls, which the prone flow then made cross (GCA 00020, 1.5 mm, 3 of 8 seeds).
  constexpr float kInside = 0.65f, kOutside = 0.35f;
  for (std::size_t v = 0; v < field.voxels.size(); ++v)
    field.voxels[v] = ball.voxels[v] ? std::max(field.voxels[v], kInside) : std::min(field.voxels[v], kOutside);
  surface::ToImageData(field, image);
  progress.Report(0.7);

  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.5);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->InterpolateAttributesOff();
  contour->Update();
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputConnection(contour->GetOutputPort());
  smooth->SetNumberOfIterations(options.smoothingIterations);
  smooth->SetPassBand(options.passBand);
  smooth->NormalizeCoordinatesOn();
  smooth->FeatureEdgeSmoothingOff();
  smooth->BoundarySmoothingOff();
  smooth->NonManifoldSmoothingOn();
  smooth->Update();
  progress.Report(0.9);
  TriangleMesh mesh = surface::FromPolyData(smooth->GetOutput());
  out.restoredVertices = RestoreCrossings(mesh, surface::FromPolyData(contour->GetOutput()).V);
  // Drop unused points (flying edges leaves none, but the check below counts used ones only).
  surface::KeepFaces(mesh.V, mesh.F, std::vector<bool>(static_cast<std::size_t>(mesh.F.rows()), true), mesh.V, mesh.F);
  surface::GridToPhysical(field, mesh.V);
  const surface::TopologyReport t = surface::AnalyzeTopology(mesh.F);
  if (t.components > 1) {
    int count = 0;
    const std::vector<int> comp = surface::FaceComponents(mesh.F, &count);
    const std::vector<int> sizes = surface::ComponentSizes(comp, count);
    std::string list;
    for (int z : sizes) list += " " + std::to_string(z);
    throw Error("true lumen: the contour has components of" + list + " faces");
  }
  if (!t.IsClosedGenusZero())
    throw Error("true lumen: the contour of the genus-0 ball is not a closed genus-0 manifold: " + t.Summary());
  if (surface::SignedVolume(mesh.V, mesh.F) > 0) mesh.F.col(1).swap(mesh.F.col(2));  // outward -> into the lumen
  out.surface = std::move(mesh);
  return out;
}

}  // namespace colonmap::realcolon
