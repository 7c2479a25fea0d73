#include "Registration/PointTransfer.h"

#include "Registration/WallVisibility.h"

#include "Core/Error.h"
#include "IO/MeshIO.h"
#include "Registration/EmbeddedProneMesh.h"
#include "Surface/MeanCurvature.h"
#include "Surface/VtkConversion.h"

#include <Eigen/Geometry>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkCellLocator.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

namespace colonmap::registration {

struct PointTransfer::Impl {
  TriangleMesh source, target;
  Eigen::VectorXi face;
  Eigen::MatrixXd bary, image;
  Eigen::MatrixXd sourceNormals, targetNormals;
  vtkNew<vtkPolyData> sourcePoly, targetPoly;
  vtkNew<vtkCellLocator> sourceLocator, targetLocator;
  Eigen::VectorXd segment, dilatation;
  std::unique_ptr<WallVisibility> sourceWall, targetWall;
};

namespace {

const DataArray& Need(const TriangleMesh& m, const std::string& name, int cols, const std::string& what) {
  const auto it = m.pointData.find(name);
  if (it == m.pointData.end() || it->second.values.cols() != cols || it->second.values.rows() != m.V.rows())
    throw Error(what + ": no point data " + name + " with " + std::to_string(cols) + " components");
  return it->second;
}

Eigen::Vector3d Bary(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& x) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, d = x - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), d1 = d.dot(e1), d2 = d.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(std::fabs(det) > 0)) return Eigen::Vector3d(1, 0, 0);
  const double l1 = (d22 * d1 - d12 * d2) / det, l2 = (d11 * d2 - d12 * d1) / det;
  Eigen::Vector3d l(1 - l1 - l2, l1, l2);
  l = l.cwiseMax(0.0);
  return l / l.sum();
}

}  // namespace

PointTransfer::PointTransfer(const TriangleMesh& source, const TriangleMesh& target, const std::string& prefix,
                             const std::string& sourceWhat)
    : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.source = source;
  I.target = target;
  if (source.F.rows() == 0 || target.F.rows() == 0) throw Error(sourceWhat + ": empty mesh");
  I.face = Need(source, prefix + "TriangleId", 1, sourceWhat).values.col(0).cast<int>();
  I.bary = Need(source, prefix + "Barycentric", 3, sourceWhat).values;
  if (I.face.size() > 0 && (I.face.minCoeff() < 0 || I.face.maxCoeff() >= target.F.rows()))
    throw Error(sourceWhat + ": " + prefix + "TriangleId out of range of the other scan's mesh (" +
                std::to_string(target.F.rows()) + " faces)");
  I.image.resize(source.V.rows(), 3);
  for (Eigen::Index i = 0; i < source.V.rows(); ++i) {
    const int f = I.face(i);
    I.image.row(i) = I.bary(i, 0) * target.V.row(target.F(f, 0)) + I.bary(i, 1) * target.V.row(target.F(f, 1)) +
                     I.bary(i, 2) * target.V.row(target.F(f, 2));
  }
  I.sourceNormals = surface::VertexNormals(source.V, source.F);
  I.targetNormals = surface::VertexNormals(target.V, target.F);
  I.sourceWall = std::make_unique<WallVisibility>(I.source);
  I.targetWall = std::make_unique<WallVisibility>(I.target);
  if (auto it = source.pointData.find("SegmentId"); it != source.pointData.end()) I.segment = it->second.values.col(0);
  if (auto it = source.cellData.find("Dilatation"); it != source.cellData.end()) I.dilatation = it->second.values.col(0);
  surface::ToPolyData(source, I.sourcePoly);
  surface::ToPolyData(target, I.targetPoly);
  I.sourceLocator->SetDataSet(I.sourcePoly);
  I.sourceLocator->BuildLocator();
  I.targetLocator->SetDataSet(I.targetPoly);
  I.targetLocator->BuildLocator();
}

PointTransfer::~PointTransfer() = default;

RegistrationMeshes ReadRegistration(const std::string& path, const std::string& pronePath) {
  namespace fs = std::filesystem;
  if (!fs::is_regular_file(path)) throw InputError("registration", path, fs::exists(path) ? "is not a file" : "does not exist");
  if (!pronePath.empty() && !fs::is_regular_file(pronePath))
    throw InputError("prone registration mesh", pronePath, fs::exists(pronePath) ? "is not a file" : "does not exist");
  RegistrationMeshes r;
  io::FieldArrays field;
  r.supine = io::ReadMesh(path, "registration", &field);
  // An explicit prone mesh wins; else the copy inside registration.vtp (bound to this very file,
  // so a stale sibling cannot be picked up); else, for registrations written before issue 23,
  // registration_prone.vtp beside it.
  if (!pronePath.empty()) {
    r.prone = io::ReadMesh(pronePath, "prone registration mesh");
    return r;
  }
  if (std::optional<TriangleMesh> embedded = EmbeddedProneMesh(field, path)) {
    r.prone = std::move(*embedded);
    return r;
  }
  const fs::path sibling = fs::path(path).parent_path() / "registration_prone.vtp";
  if (!fs::is_regular_file(sibling))
    throw InputError("registration", path,
                     "carries no prone mesh (written by an older ColonRegistration: run it again, or give --proneMesh) and "
                     "has no registration_prone.vtp beside it");
  r.prone = io::ReadMesh(sibling.string(), "prone registration mesh");
  return r;
}

void PointTransfer::NearestOnTarget(const Eigen::Vector3d& p, int* face, Eigen::Vector3d* bary) const {
  const Impl& I = *impl_;
  double y[3], d2 = 0;
  vtkIdType cell = -1;
  int sub = 0;
  vtkNew<vtkGenericCell> gc;
  I.targetLocator->FindClosestPoint(p.data(), y, gc, cell, sub, d2);
  const Eigen::Vector3i g = I.target.F.row(cell);
  *face = static_cast<int>(cell);
  *bary = Bary(I.target.V.row(g(0)), I.target.V.row(g(1)), I.target.V.row(g(2)), Eigen::Vector3d(y[0], y[1], y[2]));
}

double PointTransfer::Uncertainty(double edge, double offset, double dilatation) {
  const double K = std::isfinite(dilatation) ? std::max(1.0, dilatation) : 10.0;
  return std::sqrt(edge * edge + 0.25 * offset * offset) + 2.0 * (K - 1.0) * edge;
}

TransferredPoint PointTransfer::Transfer(const Eigen::Vector3d& p) const {
  const Impl& I = *impl_;
  TransferredPoint t;
  double x[3], d2 = 0;
  vtkIdType cell = -1;
  int sub = 0;
  vtkNew<vtkGenericCell> gc;
  I.sourceLocator->FindClosestPoint(p.data(), x, gc, cell, sub, d2);
  t.sourceFace = static_cast<int>(cell);
  t.sourceFoot = Eigen::Vector3d(x[0], x[1], x[2]);
  const Eigen::Vector3i f = I.source.F.row(cell);
  const Eigen::Vector3d b = Bary(I.source.V.row(f(0)), I.source.V.row(f(1)), I.source.V.row(f(2)), t.sourceFoot);
  Eigen::Vector3d n = b(0) * I.sourceNormals.row(f(0)) + b(1) * I.sourceNormals.row(f(1)) + b(2) * I.sourceNormals.row(f(2));
  if (n.norm() > 0) n.normalize();
  t.offset = (p - t.sourceFoot).dot(n);
  const Eigen::Vector3d image = b(0) * I.image.row(f(0)) + b(1) * I.image.row(f(1)) + b(2) * I.image.row(f(2));
  // Snap to the target wall (the barycentric combination of three images is a chord point).
  double y[3];
  vtkIdType tcell = -1;
  I.targetLocator->FindClosestPoint(image.data(), y, gc, tcell, sub, d2);
  t.targetFoot = Eigen::Vector3d(y[0], y[1], y[2]);
  const Eigen::Vector3i g = I.target.F.row(tcell);
  const Eigen::Vector3d c = Bary(I.target.V.row(g(0)), I.target.V.row(g(1)), I.target.V.row(g(2)), t.targetFoot);
  Eigen::Vector3d m = c(0) * I.targetNormals.row(g(0)) + c(1) * I.targetNormals.row(g(1)) + c(2) * I.targetNormals.row(g(2));
  if (m.norm() > 0) m.normalize();
  t.position = t.targetFoot + t.offset * m;
  t.sourceBary = b;
  t.targetFace = static_cast<int>(tcell);
  t.targetBary = c;
  int nearest = 0;
  b.maxCoeff(&nearest);
  if (I.segment.size() > 0) t.segment = static_cast<int>(std::lround(I.segment(f(nearest))));
  if (I.dilatation.size() > 0) t.dilatation = I.dilatation(cell);
  const double edge = ((I.source.V.row(f(0)) - I.source.V.row(f(1))).norm() + (I.source.V.row(f(1)) - I.source.V.row(f(2))).norm() +
                       (I.source.V.row(f(2)) - I.source.V.row(f(0))).norm()) / 3.0;
  const double u90 = SourceValue("Uncertainty90", t), u50 = SourceValue("Uncertainty", t);
  if (std::isfinite(u90) && std::isfinite(u50)) {
    t.uncertaintyMm = std::sqrt(u90 * u90 + 0.25 * t.offset * t.offset);
    t.uncertaintyMedianMm = std::sqrt(u50 * u50 + 0.25 * t.offset * t.offset);
  } else {
    t.uncertaintyMm = t.uncertaintyMedianMm = Uncertainty(edge, t.offset, t.dilatation);
  }
  // Reliable (0/1 per vertex, ColonRegistration): as the nearest of the face's vertices.
  if (const double r = SourceValue("Reliable", t); std::isfinite(r)) t.reliable = r >= 0.5;
  // Virtual wall (a bridged collapse) in either scan: no true position there.
  t.sourceVirtual = I.sourceWall->VirtualAt(t.sourceFace, t.sourceBary) >= 0.5 ||
                    I.sourceWall->OffSeenWall(p, (p - t.sourceFoot).norm());
  t.targetVirtual = I.targetWall->VirtualAt(t.targetFace, t.targetBary) >= 0.5;
  if (t.targetVirtual) {
    const OpenPlace open = I.targetWall->NearestOpen(t.targetFace, t.targetBary);
    if (open.vertex >= 0) {
      t.position = I.target.V.row(open.vertex).transpose() + t.offset * I.targetNormals.row(open.vertex).transpose();
      t.openDistanceMm = open.alongColonMm;
    }
  }
  t.visible = !t.sourceVirtual && !t.targetVirtual;
  if (!t.visible) t.reliable = false;
  return t;
}

double PointTransfer::SourceValue(const std::string& name, const TransferredPoint& t) const {
  const Impl& I = *impl_;
  const auto it = I.source.pointData.find(name);
  if (it == I.source.pointData.end() || it->second.values.rows() != I.source.V.rows() || t.sourceFace < 0)
    return std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3i f = I.source.F.row(t.sourceFace);
  double v = 0;
  for (int k = 0; k < 3; ++k) v += t.sourceBary(k) * it->second.values(f(k), 0);
  return v;
}

}  // namespace colonmap::registration
