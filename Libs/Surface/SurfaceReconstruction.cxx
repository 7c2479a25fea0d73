#include "Surface/SurfaceReconstruction.h"

#include "Core/Error.h"
#include "Surface/MeanCurvature.h"
#include "Surface/VtkConversion.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkQuadricDecimation.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>

namespace colonmap::surface {
namespace {

// Runs a VTK filter with its progress forwarded to `progress` (scaled to [from, to]) from the
// calling thread only. Cancellation is not thrown through VTK: the filter is asked to abort
// and Cancelled is thrown after Update() returns.
void RunFilter(vtkAlgorithm* filter, ProgressSink& progress, double from, double to) {
  struct State {
    ProgressSink* progress;
    double from, to;
    std::thread::id thread;
    bool cancelled = false;
  } state{&progress, from, to, std::this_thread::get_id()};
  vtkNew<vtkCallbackCommand> command;
  command->SetClientData(&state);
  command->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
    auto* s = static_cast<State*>(client);
    if (s->cancelled || std::this_thread::get_id() != s->thread) return;
    const double f = data ? *static_cast<double*>(data) : 0.0;
    try {
      s->progress->Report(s->from + (s->to - s->from) * std::clamp(f, 0.0, 1.0));
    } catch (const Cancelled&) {
      s->cancelled = true;
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  });
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, command);
  progress.Report(from);
  filter->Update();
  filter->RemoveObserver(tag);
  if (state.cancelled) throw Cancelled();
  progress.Report(to);
}

// Index box of the lumen voxels.
struct Box {
  std::array<long, 3> lo{{std::numeric_limits<long>::max(), std::numeric_limits<long>::max(),
                          std::numeric_limits<long>::max()}};
  std::array<long, 3> hi{{-1, -1, -1}};
  long count = 0;
};

Box LumenBox(const Volume<float>& label, double value, ProgressSink& progress, double from, double to) {
  Box box;
  const auto& n = label.size;
  for (std::size_t k = 0; k < n[2]; ++k) {
    if (k % 16 == 0) progress.Report(from + (to - from) * double(k) / double(n[2]));
    for (std::size_t j = 0; j < n[1]; ++j) {
      const float* row = &label.voxels[label.Offset(0, j, k)];
      for (std::size_t i = 0; i < n[0]; ++i) {
        if (std::fabs(row[i] - value) >= 0.5) continue;
        ++box.count;
        const long idx[3] = {long(i), long(j), long(k)};
        for (int a = 0; a < 3; ++a) {
          box.lo[a] = std::min(box.lo[a], idx[a]);
          box.hi[a] = std::max(box.hi[a], idx[a]);
        }
      }
    }
  }
  return box;
}

// The crop grid: the lumen box grown by `margin` voxels (may reach outside the image).
template <typename T>
Volume<float> CropGrid(const Volume<T>& image, const Box& box, long margin, std::array<long, 3>& first) {
  Volume<float> crop;
  for (int a = 0; a < 3; ++a) {
    first[a] = box.lo[a] - margin;
    crop.size[a] = static_cast<std::size_t>(box.hi[a] + margin - first[a] + 1);
  }
  crop.spacing = image.spacing;
  crop.direction = image.direction;
  crop.origin = image.IndexToPhysical(Eigen::Vector3d(double(first[0]), double(first[1]), double(first[2])));
  crop.Allocate(0.0f);
  return crop;
}

// Copies f(value) of `image` into the crop; voxels outside the image get `outside`.
template <typename T, typename Fn>
void FillCrop(const Volume<T>& image, const std::array<long, 3>& first, float outside, Fn f, Volume<float>& crop) {
  for (std::size_t k = 0; k < crop.size[2]; ++k)
    for (std::size_t j = 0; j < crop.size[1]; ++j)
      for (std::size_t i = 0; i < crop.size[0]; ++i) {
        const long x = first[0] + long(i), y = first[1] + long(j), z = first[2] + long(k);
        const bool inside = x >= 0 && y >= 0 && z >= 0 && x < long(image.size[0]) && y < long(image.size[1]) &&
                            z < long(image.size[2]);
        crop.At(i, j, k) = inside ? f(image.At(std::size_t(x), std::size_t(y), std::size_t(z))) : outside;
      }
}

void GaussianSmooth(Volume<float>& volume, double sigmaVoxels, ProgressSink& progress, double from, double to) {
  vtkNew<vtkImageData> image;
  ToImageData(volume, image);
  vtkNew<vtkImageGaussianSmooth> smooth;
  smooth->SetInputData(image);
  smooth->SetDimensionality(3);
  smooth->SetStandardDeviations(sigmaVoxels, sigmaVoxels, sigmaVoxels);  // in voxels
  smooth->SetRadiusFactors(3.0, 3.0, 3.0);
  RunFilter(smooth, progress, from, to);
  FromImageData(smooth->GetOutput(), volume);
}

double SignedVolume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double v = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

// Quadric decimation can leave a triangle (or a small flap of them) hanging on an edge of the
// closed surface: that edge then has three faces, and the flap has edges with one face only.
// Removes the faces that have both a one-face edge and a more-than-two-face edge until none is
// left (the contour of a volume is closed, so every one-face edge is such a defect); returns
// whether any face was removed.
bool RemoveFins(TriangleMesh& mesh) {
  bool removed = false;
  while (true) {
    std::vector<int> boundaryEdges(static_cast<std::size_t>(mesh.F.rows()), 0);
    std::vector<int> nonManifoldEdges(boundaryEdges.size(), 0);
    for (const MeshEdge& e : MeshEdges(mesh.F)) {
      if (e.faces.size() == 1) ++boundaryEdges[e.faces[0]];
      if (e.faces.size() > 2)
        for (int f : e.faces) ++nonManifoldEdges[f];
    }
    std::vector<bool> keep(boundaryEdges.size());
    bool any = false;
    for (std::size_t f = 0; f < keep.size(); ++f) {
      keep[f] = !(boundaryEdges[f] > 0 && nonManifoldEdges[f] > 0);
      any = any || !keep[f];
    }
    if (!any) return removed;
    KeepFaces(mesh.V, mesh.F, keep, mesh.V, mesh.F);
    removed = true;
  }
}

bool SameGrid(const Volume<float>& a, const Volume<short>& b) {
  const double tol = 1e-4 * a.spacing.minCoeff();
  return a.size == b.size && (a.spacing - b.spacing).cwiseAbs().maxCoeff() < 1e-6 * a.spacing.maxCoeff() &&
         (a.origin - b.origin).cwiseAbs().maxCoeff() < tol &&
         (a.direction - b.direction).cwiseAbs().maxCoeff() < 1e-6;
}

std::string Str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}


// Progress that never goes back (retries restart their fractions).
class Monotonic : public ProgressSink {
 public:
  explicit Monotonic(ProgressSink& parent) : parent_(parent) {}
  void Report(double f) override {
    last_ = std::max(last_, f);
    parent_.Report(last_);
  }

 private:
  ProgressSink& parent_;
  double last_ = 0.0;
};

// labelTopology (CT path): voxel centres take the label's inside/outside where the CT disagrees.
SurfaceResult Attempt(const Volume<float>& label, const Volume<short>* ct, const SurfaceOptions& options,
                      ProgressSink& progress, bool labelTopology = false) {
  SurfaceResult result;
  result.usedCT = ct != nullptr;

  // 1. Lumen mask and crop.
  const Box box = LumenBox(label, options.labelValue, progress, 0.0, 0.05);
  result.lumenVoxels = box.count;
  if (box.count == 0)
    throw Error("label map: no voxel has the label value " + Str(options.labelValue));
  const double sigmaBand = options.bandVoxels / 2.326;  // Phi(-2.326) = 0.01
  const double sigma = ct ? sigmaBand : options.labelSigmaVoxels;
  const long margin = static_cast<long>(std::ceil(3.0 * sigma + options.bandVoxels)) + 2;
  std::array<long, 3> first{};
  Volume<float> field = CropGrid(label, box, margin, first);
  const float value = static_cast<float>(options.labelValue);
  FillCrop(label, first, 0.0f, [value](float v) { return std::fabs(v - value) < 0.5f ? 1.0f : 0.0f; }, field);
  progress.Report(0.08);
  const std::vector<float> mask = ct && labelTopology ? field.voxels : std::vector<float>();

  // 2. The field to contour and its iso-value.
  GaussianSmooth(field, sigma, progress, 0.08, 0.2);
  double iso = 0.5;
  if (ct) {
    // Band of the label boundary: smoothed mask strictly between 0.01 and 0.99.
    const float air = static_cast<float>(options.airHU), wall = static_cast<float>(options.wallHU);
    Volume<float> hu = field;
    FillCrop(*ct, first, wall, [](short v) { return static_cast<float>(v); }, hu);
    const float isoF = static_cast<float>(options.isoValueHU);
    for (std::size_t n = 0; n < field.voxels.size(); ++n) {
      const float b = field.voxels[n];
      field.voxels[n] = b >= 0.99f ? air : b <= 0.01f ? wall : std::clamp(hu.voxels[n], air, wall);
      // The label decides inside and outside at the voxel centres, the CT only where the
      // surface passes between them: a voxel the label left out (a handle it cut) stays wall.
      if (!mask.empty()) {
        if (mask[n] > 0.5f && field.voxels[n] >= isoF) field.voxels[n] = isoF - 1.0f;
        if (mask[n] < 0.5f && field.voxels[n] < isoF) field.voxels[n] = isoF + 1.0f;
      }
    }
    iso = options.isoValueHU;
    progress.Report(0.25);
  }

  vtkNew<vtkImageData> image;
  ToImageData(field, image);
  field.voxels = std::vector<float>();  // the copy in `image` is the one used now
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, iso);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->InterpolateAttributesOff();
  RunFilter(contour, progress, 0.25, 0.45);
  TriangleMesh raw = FromPolyData(contour->GetOutput());
  result.contourFaces = raw.F.rows();
  if (raw.F.rows() == 0) throw Error("label map: the lumen gives no surface (iso-value " + Str(iso) + ")");

  // 3. Largest component.
  int count = 0;
  const std::vector<int> component = FaceComponents(raw.F, &count);
  const std::vector<int> sizes = ComponentSizes(component, count);
  for (int c = 1; c < count; ++c) result.droppedComponents.push_back(sizes[c]);
  std::vector<bool> keep(component.size());
  for (std::size_t f = 0; f < component.size(); ++f) keep[f] = component[f] == 0;
  KeepFaces(raw.V, raw.F, keep, raw.V, raw.F);
  progress.Report(0.5);

  // 4. Decimation, then smoothing (on the smaller mesh: faster, and the quadric error keeps the
  // sub-voxel positions of the iso-surface).
  vtkNew<vtkPolyData> poly;
  ToPolyData(raw, poly);
  raw = TriangleMesh();
  vtkSmartPointer<vtkPolyData> current = poly.GetPointer();
  vtkNew<vtkQuadricDecimation> decimate;
  if (current->GetNumberOfPolys() > options.targetFaces) {
    decimate->SetInputData(current);
    decimate->SetTargetReduction(1.0 - double(options.targetFaces) / double(current->GetNumberOfPolys()));
    decimate->VolumePreservationOn();
    RunFilter(decimate, progress, 0.5, 0.8);
    current = decimate->GetOutput();
  }
  {
    TriangleMesh decimated = FromPolyData(current);
    // Removing fins, and the contour or the decimation themselves (measured: one vertex in 8 of
    // 20 clinical phantom scans, which then fell back to the label-only surface, 3x the distance
    // to the true wall), can leave two sheets touching at one vertex: split it. The checks below
    // still catch a split that changes the topology.
    const bool finsRemoved = RemoveFins(decimated);
    const int pinches = SplitNonManifoldVertices(decimated.V, decimated.F);
    if (finsRemoved || pinches > 0) {
      vtkNew<vtkPolyData> repaired;
      ToPolyData(decimated, repaired);
      current = repaired.GetPointer();
    }
  }
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputData(current);
  smooth->SetNumberOfIterations(options.smoothingIterations);
  smooth->SetPassBand(options.smoothingPassBand);
  smooth->NormalizeCoordinatesOn();
  smooth->FeatureEdgeSmoothingOff();
  smooth->BoundarySmoothingOff();
  smooth->NonManifoldSmoothingOn();
  RunFilter(smooth, progress, 0.8, 0.9);
  TriangleMesh mesh = FromPolyData(smooth->GetOutput());
  KeepFaces(mesh.V, mesh.F, std::vector<bool>(static_cast<std::size_t>(mesh.F.rows()), true), mesh.V, mesh.F);

  // 5. Orientation: consistent (repaired by vtkPolyDataNormals if needed), then into the lumen.
  if (InconsistentlyOrientedEdges(mesh.F) > 0) {
    vtkNew<vtkPolyData> p;
    ToPolyData(mesh, p);
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(p);
    normals->ConsistencyOn();
    normals->SplittingOff();
    normals->ComputePointNormalsOff();
    normals->ComputeCellNormalsOff();
    RunFilter(normals, progress, 0.9, 0.92);
    mesh = FromPolyData(normals->GetOutput());
  }
  GridToPhysical(field, mesh.V);
  if (SignedVolume(mesh.V, mesh.F) > 0) mesh.F.col(1).swap(mesh.F.col(2));  // outward -> inward
  progress.Report(0.93);

  // 6. Curvature and checks.
  DataArray h;
  h.values = MeanCurvature(mesh.V, mesh.F);
  mesh.pointData["MeanCurvature"] = std::move(h);
  result.topology = AnalyzeTopology(mesh.F);
  const TopologyReport& t = result.topology;
  if (t.nonManifoldEdges) result.problems.push_back(std::to_string(t.nonManifoldEdges) + " non-manifold edge(s)");
  if (t.nonManifoldVertices)
    result.problems.push_back(std::to_string(t.nonManifoldVertices) + " non-manifold vertex(es)");
  if (t.inconsistentEdges)
    result.problems.push_back(std::to_string(t.inconsistentEdges) + " inconsistently oriented edge(s)");
  if (t.boundaryLoops) result.problems.push_back("not closed: " + std::to_string(t.boundaryLoops) + " boundary loop(s)");
  if (t.euler != 2 && !t.boundaryLoops)
    result.problems.push_back("Euler characteristic " + std::to_string(t.euler) + " instead of 2 (" +
                              (t.Genus() > 0 ? std::to_string(t.Genus()) + " handle(s)" : "not genus 0") + ")");
  result.mesh = std::move(mesh);
  return result;
}

}  // namespace

SurfaceResult ReconstructSurface(const Volume<float>& label, const Volume<short>* ct,
                                 const SurfaceOptions& options, ProgressSink& progress) {
  if (ct && !SameGrid(label, *ct))
    throw Error("reference CT: its grid (size, spacing, origin or direction) differs from the label map's");
  if (options.targetFaces < 100) throw Error("target faces: must be at least 100");
  Monotonic monotonic(progress);
  SurfaceResult result = Attempt(label, ct, options, monotonic);
  if (ct && !result.problems.empty()) {
    // Partial volume between two lumen parts closer than the band can bridge them (a handle the
    // label does not have): retry with the label deciding inside and outside at the voxel
    // centres (measured: fixes the handles of 6 of 20 clinical phantom scans, which had fallen
    // back to the label alone at 3x the distance to the true wall), then from the label alone.
    const std::string first = "CT band " + Str(options.bandVoxels) + " voxels: ";
    SurfaceResult retry = Attempt(label, ct, options, monotonic, true);
    retry.notes.push_back(first + result.problems.front() + "; retried with the label's inside and outside at the voxel centres");
    if (!retry.problems.empty()) {
      SurfaceResult labelOnly = Attempt(label, nullptr, options, monotonic);
      labelOnly.notes = retry.notes;
      labelOnly.notes.push_back("CT band with the label's voxel centres: " + retry.problems.front() +
                                "; used the label map alone");
      retry = std::move(labelOnly);
    }
    result = std::move(retry);
  }
  progress.Report(1.0);
  return result;
}

}  // namespace colonmap::surface
