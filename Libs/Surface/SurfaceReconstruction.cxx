#include "Surface/SurfaceReconstruction.h"

#include "Core/Error.h"
#include "Segmentation/LumenTopology.h"
#include "Surface/ManifoldDecimation.h"
#include "Surface/MeanCurvature.h"
#include "Surface/SignedVolume.h"
#include "Surface/VtkConversion.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>
#include <cstdlib>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
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

// vtkImageGaussianSmooth in slabs along k, so that the host can cancel between them (the
// filter's own progress comes from its first thread's piece only, and that ends at once). Each
// output voxel is the same sum as in one pass: the filter convolves along k first, reading the
// input's whole extent.
void GaussianSmooth(Volume<float>& volume, double sigmaVoxels, ProgressSink& progress, double from, double to) {
  vtkNew<vtkImageData> image;
  ToImageData(volume, image);
  vtkNew<vtkImageGaussianSmooth> smooth;
  smooth->SetInputData(image);
  smooth->SetDimensionality(3);
  smooth->SetStandardDeviations(sigmaVoxels, sigmaVoxels, sigmaVoxels);  // in voxels
  smooth->SetRadiusFactors(3.0, 3.0, 3.0);
  const int nx = int(volume.size[0]), ny = int(volume.size[1]), nz = int(volume.size[2]);
  const std::size_t sliceVoxels = volume.size[0] * volume.size[1];
  const int slab = std::max(1, int(kPollPiece / std::max<std::size_t>(1, sliceVoxels)));
  std::vector<float> smoothed;
  smoothed.reserve(volume.voxels.size());  // filled slab by slab: first touched between polls
  for (int k0 = 0; k0 < nz; k0 += slab) {
    const int k1 = std::min(nz, k0 + slab) - 1;
    progress.Report(from + (to - from) * double(k0) / double(nz));
    const int extent[6] = {0, nx - 1, 0, ny - 1, k0, k1};
    smooth->UpdateExtent(extent);
    auto* scalars = vtkFloatArray::SafeDownCast(smooth->GetOutput()->GetPointData()->GetScalars());
    if (!scalars || scalars->GetNumberOfValues() != vtkIdType(sliceVoxels) * (k1 - k0 + 1))
      throw Error("surface: the Gaussian smoothing gave no field");
    smoothed.insert(smoothed.end(), scalars->GetPointer(0), scalars->GetPointer(0) + scalars->GetNumberOfValues());
  }
  volume.voxels.swap(smoothed);
  progress.Report(to);
}

template <typename T>
bool SameGrid(const Volume<T>& a, const Volume<short>& b) {
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

// The lumen box of the mask (voxels equal to the label value), grown by `margin` voxels.
Volume<float> CropAround(const Volume<unsigned char>& label, long margin, std::array<long, 3>& first, long& count,
                         ProgressSink& progress) {
  const long n0 = long(label.size[0]), n1 = long(label.size[1]), n2 = long(label.size[2]);
  std::array<long, 3> lo{{std::numeric_limits<long>::max(), std::numeric_limits<long>::max(), std::numeric_limits<long>::max()}};
  std::array<long, 3> hi{{-1, -1, -1}};
  count = 0;
  SubProgress boxStep(progress, 0.0, 0.5), copyStep(progress, 0.5, 1.0);
  for (long k = 0; k < n2; ++k) {
    if (k % 8 == 0) boxStep.Report(double(k) / double(n2));
    for (long j = 0; j < n1; ++j) {
      const unsigned char* row = &label.voxels[label.Offset(0, std::size_t(j), std::size_t(k))];
      for (long i = 0; i < n0; ++i) {
        if (!row[i]) continue;
        ++count;
        lo[0] = std::min(lo[0], i), hi[0] = std::max(hi[0], i);
        lo[1] = std::min(lo[1], j), hi[1] = std::max(hi[1], j);
        lo[2] = std::min(lo[2], k), hi[2] = std::max(hi[2], k);
      }
    }
  }
  Volume<float> crop;
  if (count == 0) return crop;
  for (int d = 0; d < 3; ++d) {
    first[d] = lo[d] - margin;
    crop.size[d] = static_cast<std::size_t>(hi[d] + margin - first[d] + 1);
  }
  crop.spacing = label.spacing;
  crop.direction = label.direction;
  crop.origin = label.IndexToPhysical(Eigen::Vector3d(double(first[0]), double(first[1]), double(first[2])));
  crop.Allocate(0.0f);
  // Only the lumen's box holds lumen voxels; the margin around it stays 0.
  for (long k = lo[2]; k <= hi[2]; ++k) {
    if (k % 8 == 0) copyStep.Report(double(k - lo[2]) / double(hi[2] - lo[2] + 1));
    for (long j = lo[1]; j <= hi[1]; ++j) {
      const unsigned char* in = &label.voxels[label.Offset(0, std::size_t(j), std::size_t(k))];
      float* out = &crop.voxels[crop.Offset(std::size_t(lo[0] - first[0]), std::size_t(j - first[1]), std::size_t(k - first[2]))];
      for (long i = lo[0]; i <= hi[0]; ++i) out[i - lo[0]] = in[i] ? 1.0f : 0.0f;
    }
  }
  return crop;
}

class Timer {
 public:
  explicit Timer(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void Lap(const std::string& step) {
    const auto now = std::chrono::steady_clock::now();
    out_.emplace_back(step, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

SurfaceResult ReconstructSurface(const Volume<float>& label, const Volume<short>* ct,
                                 const SurfaceOptions& options, ProgressSink& progress) {
  return ReconstructSurfaceFromMask(LumenMask(label, options.labelValue), ct, options, progress);
}

SurfaceResult ReconstructSurfaceFromMask(const Volume<unsigned char>& label, const Volume<short>* ct,
                                         const SurfaceOptions& options, ProgressSink& progress) {
  if (ct && !SameGrid(label, *ct))
    throw Error("reference CT: its grid (size, spacing, origin or direction) differs from the label map's");
  if (options.targetFaces < 100) throw Error("target faces: must be at least 100");
  SurfaceResult result;
  result.usedCT = ct != nullptr;
  Timer timer(result.stepSeconds);

  // 1. The mask, on a crop around it, made one well-composed topological ball: the largest
  // component, cavities filled, handles (two lumen parts touching) cut at their thinnest places.
  const double sigma = ct ? options.bandVoxels / 2.326 : options.labelSigmaVoxels;  // Phi(-2.326) = 0.01
  const long margin = static_cast<long>(std::ceil(3.0 * sigma + options.bandVoxels)) + 3;
  std::array<long, 3> first{};
  SubProgress cropStep(progress, 0.0, 0.02);
  Volume<float> field = CropAround(label, margin, first, result.lumenVoxels, cropStep);
  if (result.lumenVoxels == 0) throw Error("label map: no voxel has the label value " + Str(options.labelValue));
  Volume<unsigned char> ball = field.Like<unsigned char>(0);
  {
    std::vector<unsigned char> before(ball.voxels.size());
    SubProgress toBall(progress, 0.02, 0.03), step(progress, 0.03, 0.24), compare(progress, 0.24, 0.245);
    ForPieces(ball.voxels.size(), kPollPiece, &toBall, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) before[v] = ball.voxels[v] = field.voxels[v] > 0.5f ? 1 : 0;
    });
    result.changes = segmentation::MakeLumenBall(ball, step);
    ForPieces(ball.voxels.size(), kPollPiece, &compare, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) result.voxelsChanged += ball.voxels[v] != before[v];
    });
  }
  for (std::size_t n : result.changes.dropped) result.droppedComponents.push_back(static_cast<long>(n));
  const segmentation::LumenTopology& t = result.changes;
  if (t.components > 1)
    result.notes.push_back("kept the largest of " + std::to_string(t.components) + " lumen components (" +
                           std::to_string(t.droppedVoxels) + " voxels in the others)");
  if (t.cavityVoxelsFilled) result.notes.push_back("filled " + std::to_string(t.cavityVoxelsFilled) + " cavity voxels");
  if (t.handles > 0)
    result.notes.push_back("cut " + std::to_string(t.handles) + " handle(s) at their thinnest places (" +
                           std::to_string(t.handleVoxelsRemoved) + " voxels left out)");
  if (t.rounds > 1)
    result.notes.push_back(std::to_string(t.forcedVoxels) + " voxels of a rough mask boundary changed although that changes the topology (" +
                           std::to_string(t.rounds) + " rounds of the topology step)");
  timer.Lap("topology");

  // 2. The field: the ball blurred (label only), or the CT in a band around the ball's boundary
  // (air deeper inside, wall farther out).
  {
    SubProgress step(progress, 0.245, 0.25);
    ForPieces(ball.voxels.size(), kPollPiece, &step, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) field.voxels[v] = ball.voxels[v];
    });
  }
  GaussianSmooth(field, sigma, progress, 0.25, 0.31);
  const float iso = ct ? static_cast<float>(options.isoValueHU) : 0.5f;
  if (ct) {
    const float air = static_cast<float>(options.airHU), wall = static_cast<float>(options.wallHU);
    const long nx = long(field.size[0]), ny = long(field.size[1]), nz = long(field.size[2]);
    for (long k = 0; k < nz; ++k) {
      if (k % 4 == 0) progress.Report(0.31 + 0.01 * double(k) / double(nz));
      const long z = first[2] + k;
      const bool zIn = z >= 0 && z < long(ct->size[2]);
      for (long j = 0; j < ny; ++j) {
        float* row = &field.voxels[field.Offset(0, std::size_t(j), std::size_t(k))];
        const long y = first[1] + j;
        const short* ctRow = zIn && y >= 0 && y < long(ct->size[1]) ? &ct->voxels[ct->Offset(0, std::size_t(y), std::size_t(z))] : nullptr;
        for (long i = 0; i < nx; ++i) {
          float& f = row[i];
          if (f >= 0.99f) {
            f = air;
          } else if (f <= 0.01f) {
            f = wall;
          } else {
            const long x = first[0] + i;
            f = ctRow && x >= 0 && x < long(ct->size[0]) ? std::clamp(static_cast<float>(ctRow[x]), air, wall) : wall;
          }
        }
      }
    }
  }
  const auto inside = [&](float f) { return ct ? f < iso : f > iso; };
  timer.Lap("field");

  vtkNew<vtkImageData> image;
  const auto contourOf = [&](double from, double to) {
    ToImageData(field, image);
    vtkNew<vtkFlyingEdges3D> contour;
    contour->SetInputData(image);
    contour->SetValue(0, iso);
    contour->ComputeNormalsOff();
    contour->ComputeGradientsOff();
    contour->ComputeScalarsOff();
    contour->InterpolateAttributesOff();
    RunFilter(contour, progress, from, to);
    ++result.contourPasses;
    return FromPolyData(contour->GetOutput());
  };

  // 3. Label only: the blurred ball's own iso-surface (its largest component) when that is one
  // closed genus-0 surface: the blur rounds the cuts and removes voxel-thin fingers and stray
  // voxels. Measured on the GCA colon (1.5 mm, 781 handles in the voxelised weld): it flattens
  // best (A segment |mu| 0.027; with the ball's sign forced on it, 0.033).
  TriangleMesh raw;
  if (!ct) {
    raw = contourOf(0.32, 0.42);
    int count = 0;
    const std::vector<int> component = FaceComponents(raw.F, &count);
    if (count > 1) {
      std::vector<bool> keep(component.size());
      for (std::size_t f = 0; f < component.size(); ++f) keep[f] = component[f] == 0;
      KeepFaces(raw.V, raw.F, keep, raw.V, raw.F);
      result.notes.push_back("kept the largest of " + std::to_string(count) + " pieces of the blurred lumen's surface");
    }
    const TopologyReport r = AnalyzeTopology(raw.F);
    if (!r.IsClosedGenusZero()) {
      result.notes.push_back("the blurred lumen's surface is not closed genus 0 (" + r.Summary() +
                             "): contoured again with the ball's inside and outside at the voxel centres");
      raw = TriangleMesh();
    }
    timer.Lap("contour");
  }

  // 4. Otherwise (always with a CT) the field's sign at every voxel centre made the ball's where
  // it differs (moved just past the iso-value: the field still places the surface between voxel
  // centres, the ball decides which side they are on), and the contour: on a well-composed sign
  // pattern a closed manifold with the ball's topology.
  if (raw.F.rows() == 0) {
    SubProgress step(progress, 0.42, 0.43);
    ForPieces(ball.voxels.size(), kPollPiece, &step, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) {
        float& f = field.voxels[v];
        if (ball.voxels[v] && !inside(f)) f = ct ? iso - 1.0f : iso + 0.001f;
        if (!ball.voxels[v] && inside(f)) f = ct ? iso + 1.0f : iso - 0.001f;
      }
    });
    raw = contourOf(0.43, 0.5);
    timer.Lap("contour with the ball's signs");
  }
  ball = Volume<unsigned char>();
  field.voxels = std::vector<float>();
  result.contourFaces = raw.F.rows();
  if (raw.F.rows() == 0) throw Error("label map: the lumen gives no surface (iso-value " + Str(iso) + ")");

  // 3. Decimation that keeps the surface a closed manifold of the same topology.
  DecimationOptions dec;
  dec.targetFaces = options.targetFaces;
  Decimation decimated;
  {
    SubProgress step(progress, 0.5, 0.8);
    decimated = DecimateManifold(raw.V, raw.F, dec, step);
  }
  raw = TriangleMesh();
  timer.Lap("decimation");

  // 4. Windowed-sinc smoothing (moves vertices only).
  TriangleMesh coarse;
  coarse.V = std::move(decimated.V);
  coarse.F = std::move(decimated.F);
  vtkNew<vtkPolyData> poly;
  ToPolyData(coarse, poly);
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputData(poly);
  smooth->SetNumberOfIterations(options.smoothingIterations);
  smooth->SetPassBand(options.smoothingPassBand);
  smooth->NormalizeCoordinatesOn();
  smooth->FeatureEdgeSmoothingOff();
  smooth->BoundarySmoothingOff();
  smooth->NonManifoldSmoothingOn();
  RunFilter(smooth, progress, 0.8, 0.9);
  TriangleMesh mesh = FromPolyData(smooth->GetOutput());
  if (mesh.F.rows() != coarse.F.rows()) throw Error("label map: smoothing changed the surface's faces");
  mesh.F = coarse.F;  // same faces, same order
  timer.Lap("smoothing");

  // 5. To LPS, normals into the lumen; curvature; checks.
  GridToPhysical(field, mesh.V);
  if (SignedVolume(mesh.V, mesh.F) > 0) mesh.F.col(1).swap(mesh.F.col(2));  // outward -> inward
  DataArray h;
  h.values = MeanCurvature(mesh.V, mesh.F);
  mesh.pointData["MeanCurvature"] = std::move(h);
  result.topology = AnalyzeTopology(mesh.F);
  if (!result.topology.IsClosedGenusZero())
    throw Error("label map: the surface could not be made a closed genus-0 surface (" + result.topology.Summary() + ")");
  result.mesh = std::move(mesh);
  timer.Lap("curvature and checks");
  progress.Report(1.0);
  return result;
}

}  // namespace colonmap::surface
