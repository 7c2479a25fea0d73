#include "Segmentation/LumenSegmentation.h"

#include "Segmentation/ItkSegmentationFilters.h"
#include "Segmentation/LabelComponents.h"

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <locale>
#include <numeric>
#include <sstream>

namespace colonmap::segmentation {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Fixed(double value, int decimals) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << value;
  return s.str();
}
// Volumes read best with the decimals their size needs.
std::string Ml(double ml) { return Fixed(ml, ml < 10.0 ? 1 : 0) + " ml"; }

// One component's padded bounding box as its own grid, for the per-component filters (cavities,
// ITK's distance map).
struct Crop {
  std::array<std::size_t, 3> first{{0, 0, 0}};  // image index of crop voxel (1, 1, 1)
  Volume<unsigned char> mask;                   // the component (1), padded by one zero voxel
  detail::Grid Grid() const {
    detail::Grid g;
    for (int d = 0; d < 3; ++d) {
      g.size[d] = mask.size[d];
      g.spacing[d] = mask.spacing[d];
    }
    return g;
  }
};

Crop CropComponent(const Volume<short>& ct, const detail::ComponentRuns& air, std::uint32_t label,
                   const AirComponent& c, ProgressSink& progress) {
  Crop crop;
  crop.first = c.boxMin;
  for (int d = 0; d < 3; ++d) crop.mask.size[d] = c.boxMax[d] - c.boxMin[d] + 3;
  crop.mask.spacing = ct.spacing;
  crop.mask.direction = ct.direction;
  crop.mask.origin = ct.IndexToPhysical(Eigen::Vector3d(double(c.boxMin[0]) - 1, double(c.boxMin[1]) - 1,
                                                        double(c.boxMin[2]) - 1));
  crop.mask.Allocate(0);
  for (std::size_t k = c.boxMin[2]; k <= c.boxMax[2]; ++k) {
    for (std::size_t j = c.boxMin[1]; j <= c.boxMax[1]; ++j) {
      const std::size_t row = j + ct.size[1] * k;
      unsigned char* out = &crop.mask.At(1, j - c.boxMin[1] + 1, k - c.boxMin[2] + 1);  // voxel i = boxMin[0]
      for (std::size_t r = air.rowStart[row]; r < air.rowStart[row + 1]; ++r)
        if (air.runs[r].label == label)
          std::fill(out + (air.runs[r].first - c.boxMin[0]), out + (air.runs[r].last - c.boxMin[0] + 1), 1);
    }
    progress.Report(double(k - c.boxMin[2] + 1) / double(c.boxMax[2] - c.boxMin[2] + 1));
  }
  return crop;
}

// A component kept for the piece analysis: its padded crop (cavities filled) and depth.
struct Candidate {
  std::size_t component = 0;
  Crop crop;
  std::vector<float> depth;
  std::size_t filled = 0;
  Volume<unsigned char> ball;  // the topological ball grown in the crop (handles cut)
  GrowthStatistics growth;
};

// Grows the candidate's ball from its deepest voxel, deepest first (step 4); its depth is used up.
void GrowBall(Candidate& c, ProgressSink& progress) {
  Volume<float> priority;
  priority.size = c.crop.mask.size;
  priority.voxels = std::move(c.depth);
  const std::size_t seed = static_cast<std::size_t>(
      std::max_element(priority.voxels.begin(), priority.voxels.end()) - priority.voxels.begin());
  c.ball = GrowTopologicalBall(c.crop.mask, priority, seed, progress, &c.growth);
}

// The pieces (in order from the caecum) and the virtual lumen between consecutive ones as one
// domain on the box of them all; result.bridges and result.bridgeLabel are filled. The bridge
// radius is half the narrower of the two pieces' inscribed radii, at least two voxels (a
// thinner tube would not survive the surface stage) and at most 12 mm.
Candidate BridgePieces(const Volume<short>& ct, const std::vector<Candidate*>& pieces, LumenSegmentation& result,
                       ProgressSink& progress) {
  const double maxSpacing = ct.spacing.maxCoeff();
  std::vector<Bridge> bridges;
  for (std::size_t k = 0; k + 1 < result.pieces.size(); ++k) {
    const ColonPiece& a = result.pieces[k];
    const ColonPiece& b = result.pieces[k + 1];
    const double ra = result.components[a.component].maxRadiusMm, rb = result.components[b.component].maxRadiusMm;
    const double radius = std::clamp(0.9 * std::min(ra, rb), 2.0 * maxSpacing, 25.0);
    bridges.push_back(MakeBridge(a.shape.ends[static_cast<std::size_t>(1 - a.caecalEnd)],
                                 b.shape.ends[static_cast<std::size_t>(b.caecalEnd)], radius));
  }
  // The box: every piece's crop and every bridge sample's ball, inside the image.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const Candidate* c : pieces)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], double(c->crop.first[d]));
      hi[d] = std::max(hi[d], double(c->crop.first[d] + c->crop.mask.size[d] - 3));
    }
  for (const Bridge& b : bridges)
    for (const Eigen::Vector3d& p : b.curve) {
      const Eigen::Vector3d idx = ct.PhysicalToIndex(p);
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(b.radiusMm).cwiseQuotient(ct.spacing) + Eigen::Vector3d::Ones();
      lo = lo.cwiseMin(idx - r);
      hi = hi.cwiseMax(idx + r);
    }
  Candidate out;
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::clamp(std::floor(lo[d]), 0.0, double(ct.size[d] - 1));
    hi[d] = std::clamp(std::ceil(hi[d]), 0.0, double(ct.size[d] - 1));
    out.crop.first[d] = static_cast<std::size_t>(lo[d]);
    out.crop.mask.size[d] = static_cast<std::size_t>(hi[d] - lo[d]) + 3;
  }
  out.crop.mask.spacing = ct.spacing;
  out.crop.mask.direction = ct.direction;
  out.crop.mask.origin = ct.IndexToPhysical(lo - Eigen::Vector3d::Ones());
  out.crop.mask.Allocate(0);
  for (const Candidate* c : pieces) {
    const Volume<unsigned char>& m = c->ball;
    for (std::size_t z = 1; z + 1 < m.size[2]; ++z)
      for (std::size_t y = 1; y + 1 < m.size[1]; ++y)
        for (std::size_t x = 1; x + 1 < m.size[0]; ++x)
          if (m.At(x, y, z))
            out.crop.mask.At(c->crop.first[0] - out.crop.first[0] + x, c->crop.first[1] - out.crop.first[1] + y,
                             c->crop.first[2] - out.crop.first[2] + z) = 1;
  }
  // Bridge voxels: drawn as 2 into the zeros of the pieces' mask (kept apart), then the virtual mask.
  Volume<unsigned char> virtualMask = out.crop.mask;
  for (const Bridge& b : bridges) DrawBridge(b, virtualMask, 2);
  for (unsigned char& v : virtualMask.voxels) v = v == 2;
  // The crop's border stays zero (the growth needs it).
  for (std::size_t z = 0; z < virtualMask.size[2]; ++z)
    for (std::size_t y = 0; y < virtualMask.size[1]; ++y)
      for (std::size_t x = 0; x < virtualMask.size[0]; ++x) {
        const bool border = x == 0 || y == 0 || z == 0 || x + 1 == virtualMask.size[0] || y + 1 == virtualMask.size[1] ||
                            z + 1 == virtualMask.size[2];
        unsigned char& v = virtualMask.At(x, y, z);
        if (border) v = 0;
        if (v) out.crop.mask.At(x, y, z) = 1;
      }
  SubProgress fillStep(progress, 0.0, 0.5), depthStep(progress, 0.5, 1.0);
  detail::FillCavities6(out.crop.Grid(), out.crop.mask.voxels, fillStep);
  detail::InsideDistance(out.crop.Grid(), out.crop.mask.voxels.data(), out.depth, depthStep);
  result.bridgeLabel = ct.Like<unsigned char>(0);
  for (std::size_t z = 1; z + 1 < virtualMask.size[2]; ++z)
    for (std::size_t y = 1; y + 1 < virtualMask.size[1]; ++y)
      for (std::size_t x = 1; x + 1 < virtualMask.size[0]; ++x)
        if (virtualMask.At(x, y, z))
          result.bridgeLabel.At(out.crop.first[0] + x - 1, out.crop.first[1] + y - 1, out.crop.first[2] + z - 1) = 1;
  result.bridges = std::move(bridges);
  return out;
}

void CheckOptions(const SegmentationOptions& o) {
  if (!std::isfinite(o.airThresholdHU) || o.airThresholdHU <= -1024.0 || o.airThresholdHU >= 0.0)
    throw Error("air threshold " + Fixed(o.airThresholdHU, 1) + " HU: expected a value between -1024 and 0");
  if (!(o.minColonVolumeMl > 0.0) || !std::isfinite(o.minColonVolumeMl))
    throw Error("minimum colon volume: expected a positive number of ml");
  if (!(o.maxColonRadiusMm > 0.0) || !std::isfinite(o.maxColonRadiusMm))
    throw Error("maximum colon radius: expected a positive number of mm");
  if (!(o.minElongation >= 0.0) || !std::isfinite(o.minElongation))
    throw Error("minimum elongation: expected a number >= 0");
}

}  // namespace

const char* DecisionName(Decision d) {
  switch (d) {
    case Decision::Colon: return "colon";
    case Decision::OutsideBody: return "outside body";
    case Decision::AtSuperiorBorder: return "at superior border";
    case Decision::TooSmall: return "too small";
    case Decision::TooThick: return "too thick";
    case Decision::NotElongated: return "not elongated";
    case Decision::NotLargest: return "not the largest";
    case Decision::Piece: return "colon piece";
  }
  return "?";
}

std::size_t LumenSegmentation::Dropped(Decision d) const {
  return static_cast<std::size_t>(
      std::count_if(components.begin(), components.end(), [d](const AirComponent& c) { return c.decision == d; }));
}

LumenSegmentation SegmentColonLumen(const Volume<short>& ct, const SegmentationOptions& options,
                                    ProgressSink& progress) {
  CheckOptions(options);
  const std::size_t n0 = ct.size[0], n1 = ct.size[1], n2 = ct.size[2];
  const std::size_t count = ct.NumberOfVoxels();
  if (count == 0 || ct.voxels.size() != count) throw Error("empty CT");
  const double voxelMl = std::abs(ct.direction.determinant()) * ct.spacing.prod() / 1000.0;
  const double minSpacing = ct.spacing.minCoeff();

  LumenSegmentation result;
  auto clock = std::chrono::steady_clock::now();
  const auto lap = [&](const char* step) {
    const auto now = std::chrono::steady_clock::now();
    result.stepSeconds.emplace_back(step, std::chrono::duration<double>(now - clock).count());
    clock = now;
  };

  // 1-2. Air (cleansed fluid is air already) and its components, kept as runs along i.
  detail::Grid grid;
  for (int d = 0; d < 3; ++d) {
    grid.size[d] = ct.size[d];
    grid.spacing[d] = ct.spacing[d];
  }
  detail::ComponentRuns air;
  {
    SubProgress step(progress, 0.0, 0.35);
    const short threshold = static_cast<short>(std::ceil(options.airThresholdHU));  // HU < t <=> HU < ceil(t) for integers
    air = detail::LabelComponentRunsBelow26(grid, ct.voxels.data(), threshold, step);
  }
  const std::uint32_t labelCount = air.count;
  lap("threshold and components");
  std::vector<AirComponent> byLabel(labelCount + 1);
  // The index axis closest to the body's long (LPS z, superior) axis; the other two run across.
  int longAxis = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(ct.direction(2, d)) > std::abs(ct.direction(2, longAxis))) longAxis = d;
  const std::size_t superiorIndex = ct.direction(2, longAxis) > 0 ? ct.size[longAxis] - 1 : 0;
  std::vector<bool> touchesSide(labelCount + 1, false), touchesTop(labelCount + 1, false);
  // Sums of voxel indices: integers, exact in a double whatever the order of the sums.
  std::vector<Eigen::Vector3d> indexSum(labelCount + 1, Eigen::Vector3d::Zero());
  for (auto& c : byLabel) {
    c.boxMin = {{n0, n1, n2}};
    c.boxMax = {{0, 0, 0}};
  }
  {
    SubProgress step(progress, 0.35, 0.45);
    for (std::size_t k = 0; k < n2; ++k) {
      for (std::size_t j = 0; j < n1; ++j) {
        const std::size_t row = j + n1 * k;
        const std::size_t at[3] = {0, j, k};
        bool rowSide = false, rowTop = false;  // the row lies on a side face / the superior face
        for (int d = 1; d < 3; ++d) {
          const bool border = at[d] == 0 || at[d] + 1 == ct.size[d];
          if (d == longAxis)
            rowTop = at[d] == superiorIndex;
          else
            rowSide = rowSide || border;
        }
        for (std::size_t r = air.rowStart[row]; r < air.rowStart[row + 1]; ++r) {
          const detail::ComponentRuns::Run& run = air.runs[r];
          const std::size_t l = run.label, first = run.first, last = run.last, length = last - first + 1;
          if (rowTop || (longAxis == 0 && first <= superiorIndex && superiorIndex <= last)) touchesTop[l] = true;
          AirComponent& c = byLabel[l];
          c.voxels += length;
          c.boxMin = {{std::min(c.boxMin[0], first), std::min(c.boxMin[1], j), std::min(c.boxMin[2], k)}};
          c.boxMax = {{std::max(c.boxMax[0], last), std::max(c.boxMax[1], j), std::max(c.boxMax[2], k)}};
          indexSum[l] += Eigen::Vector3d(double((first + last) * length / 2), double(j * length), double(k * length));
          if (rowSide || (longAxis != 0 && (first == 0 || last + 1 == n0))) touchesSide[l] = true;
        }
      }
      if (k % 8 == 7) step.Report(double(k + 1) / double(n2));
    }
  }
  // Largest first; ties (equal volume) by label, which follows raster order: deterministic.
  std::vector<std::uint32_t> order(labelCount);
  std::iota(order.begin(), order.end(), 1u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return byLabel[a].voxels > byLabel[b].voxels; });

  lap("component statistics");

  // 3. Decisions, largest first; shape measured on the component's own padded box.
  result.components.reserve(labelCount);
  bool found = false;
  // The colon and the smaller candidates for further pieces keep their crops for 3a and 4.
  std::vector<Candidate> candidates;  // the colon first
  const AirComponent* largestInside = nullptr;
  const double measuredFrom = std::min(options.minColonVolumeMl, options.minPieceVolumeMl);
  // The shape analysis shares its part of the progress by component size (monotone progress).
  double analysed = 0.0, toAnalyse = 0.0;
  for (std::uint32_t l : order)
    if (!touchesSide[l] && !touchesTop[l] && double(byLabel[l].voxels) * voxelMl >= measuredFrom)
      toAnalyse += double(byLabel[l].voxels);
  for (std::uint32_t l : order) {
    AirComponent c = byLabel[l];
    c.volumeMl = double(c.voxels) * voxelMl;
    c.centroid = ct.IndexToPhysical(indexSum[l] / double(c.voxels));
    const bool small = c.volumeMl < options.minColonVolumeMl;
    const std::string smallReason =
        "below " + Ml(options.minColonVolumeMl) + " (small-bowel gas or an isolated pocket)";
    if (touchesSide[l]) {
      c.decision = Decision::OutsideBody;
      c.reason = "touches a side of the image (air outside the body)";
    } else if (touchesTop[l]) {
      c.decision = Decision::AtSuperiorBorder;
      c.reason = "touches the superior face of the image (lung base)";
    } else if (c.volumeMl < measuredFrom) {
      c.decision = Decision::TooSmall;
      c.reason = smallReason;
    } else {
      // Fill the cavities first: the depth (and the growth below) then sees the whole lumen.
      SubProgress step(progress, 0.45 + 0.17 * analysed / toAnalyse,
                        0.45 + 0.17 * (analysed + double(c.voxels)) / toAnalyse);
      analysed += double(c.voxels);
      SubProgress cropStep(step, 0.0, 0.1), fillStep(step, 0.1, 0.5), depthStep(step, 0.5, 1.0);
      Crop crop = CropComponent(ct, air, l, c, cropStep);
      const std::size_t before = std::count(crop.mask.voxels.begin(), crop.mask.voxels.end(), 1);
      detail::FillCavities6(crop.Grid(), crop.mask.voxels, fillStep);
      const std::size_t filled = std::count(crop.mask.voxels.begin(), crop.mask.voxels.end(), 1) - before;
      std::vector<float> depth;
      detail::InsideDistance(crop.Grid(), crop.mask.voxels.data(), depth, depthStep);
      // Voxel centres of the boundary layer have depth 0 and lie about half a voxel inside.
      c.maxRadiusMm = double(*std::max_element(depth.begin(), depth.end())) + 0.5 * minSpacing;
      c.elongation = c.volumeMl * 1000.0 / (kPi * c.maxRadiusMm * c.maxRadiusMm) / (2.0 * c.maxRadiusMm);
      const bool thick = c.maxRadiusMm > options.maxColonRadiusMm;
      // A piece candidate: not lung-like, and at least a short tube (joined or not in 3a).
      const bool candidate = !thick && c.volumeMl >= options.minPieceVolumeMl && c.elongation >= options.minPieceElongation;
      if (small) {
        c.decision = Decision::TooSmall;
        c.reason = smallReason;
      } else if (thick) {
        c.decision = Decision::TooThick;
        c.reason = "inscribed radius " + Fixed(c.maxRadiusMm, 0) + " mm > " + Fixed(options.maxColonRadiusMm, 0) +
                   " mm (lung-like)";
      } else if (c.elongation < options.minElongation) {
        c.decision = Decision::NotElongated;
        c.reason = "elongation " + Fixed(c.elongation, 1) + " < " + Fixed(options.minElongation, 1) +
                   " (a compact pocket, not a tube)";
      } else if (found) {
        c.decision = Decision::NotLargest;
        c.reason = "colon-like but smaller than the colon, and its ends do not continue the colon";
      } else {
        c.decision = Decision::Colon;
        c.reason = "largest thin, elongated air component inside the body";
        found = true;
        result.colon = result.components.size();
        result.cavityVoxelsFilled = filled;
        candidates.insert(candidates.begin(), Candidate{result.colon, std::move(crop), std::move(depth), filled, {}, {}});
      }
      // The largest candidates only: more pieces than kMaxPieces are not a collapsed colon.
      if (c.decision != Decision::Colon && candidate && candidates.size() + (found ? 0 : 1) < std::size_t(kMaxPieces))
        candidates.push_back(Candidate{result.components.size(), std::move(crop), std::move(depth), filled, {}, {}});
    }
    result.components.push_back(std::move(c));
  }
  for (const AirComponent& c : result.components)
    if (c.decision != Decision::OutsideBody && c.decision != Decision::AtSuperiorBorder) {
      largestInside = &c;
      break;
    }

  if (!found) {
    std::string what;
    if (!largestInside) {
      what = "no air inside the body below its top (" + std::to_string(result.components.size()) +
             " air components, all touching the sides or the superior face of the image)";
    } else if (largestInside->decision == Decision::TooSmall) {
      what = "the largest air component inside the body is " + Ml(largestInside->volumeMl) + " (a colon needs >= " +
             Ml(options.minColonVolumeMl) + ")";
      const std::size_t top = std::count_if(result.components.begin(), result.components.end(), [](const AirComponent& c) {
        return c.decision == Decision::AtSuperiorBorder && c.volumeMl >= 1.0;
      });
      if (top) what += "; " + std::to_string(top) + " larger than 1 ml at the superior face of the image were taken for lung";
    } else {
      std::size_t big = 0;
      for (const AirComponent& c : result.components) big += c.decision == Decision::TooThick || c.decision == Decision::NotElongated;
      what = std::to_string(big) + " air component" + (big == 1 ? "" : "s") + " inside the body of >= " +
             Ml(options.minColonVolumeMl) + ", none colon-like: the largest, " + Ml(largestInside->volumeMl) +
             ", has " + largestInside->reason;
    }
    throw NoColonFound("no distended colon found: " + what);
  }
  air = detail::ComponentRuns();
  lap("shape analysis, cavity filling, depth");

  // 4 (first part). Topology: each candidate's ball, so that the piece ends below are not taken
  // through a handle (two loops touching) but along the colon.
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    SubProgress step(progress, 0.62 + 0.3 * double(k) / double(candidates.size()),
                     0.62 + 0.3 * double(k + 1) / double(candidates.size()));
    GrowBall(candidates[k], step);
  }
  lap("topology-preserving growth");

  // 3a. Pieces: which candidates continue the colon, in their order from the caecum. Without
  // further candidates the colon is the one piece (nothing to order: its ends are not measured).
  std::vector<PieceShape> shapes(candidates.size());
  PieceChain chain;
  if (candidates.size() > 1) {
    for (std::size_t k = 0; k < candidates.size(); ++k) shapes[k] = MeasurePieceShape(candidates[k].ball);
    chain = OrderPieces(shapes, 0, options.pieceOrder);
  } else {
    chain.pieces = {0};
    chain.caecalEnd = {0};
  }
  {
    int nextLabel = 2;
    for (std::size_t k = 0; k < chain.pieces.size(); ++k) {
      const std::size_t cand = static_cast<std::size_t>(chain.pieces[k]);
      AirComponent& c = result.components[candidates[cand].component];
      ColonPiece piece;
      piece.component = candidates[cand].component;
      piece.labelValue = cand == 0 ? 1 : nextLabel++;
      piece.shape = shapes[cand];
      piece.caecalEnd = chain.caecalEnd[k];
      piece.gapAfterMm = k < chain.gapMm.size() ? chain.gapMm[k] : 0.0;
      c.lengthMm = candidates.size() > 1 ? shapes[cand].lengthMm : -1.0;
      c.labelValue = piece.labelValue;
      if (cand != 0) {
        c.decision = Decision::Piece;
        c.reason = "a further piece of the colon (piece " + std::to_string(k + 1) + " of " +
                   std::to_string(chain.pieces.size()) + " from the caecum; a collapsed stretch between)";
      }
      result.pieces.push_back(piece);
    }
  }
  lap("pieces");

  // 4 (second part). The label map: each piece's ball, or the bridged colon grown as one ball.
  result.label = ct.Like<unsigned char>(0);
  std::vector<Candidate*> grown;
  for (std::size_t k = 0; k < result.pieces.size(); ++k) grown.push_back(&candidates[static_cast<std::size_t>(chain.pieces[k])]);
  Candidate bridged;
  if (options.bridgePieces && result.pieces.size() > 1) {
    SubProgress step(progress, 0.92, 0.99);
    SubProgress prepare(step, 0.0, 0.4), grow(step, 0.4, 1.0);
    bridged = BridgePieces(ct, grown, result, prepare);
    GrowBall(bridged, grow);
    grown = {&bridged};
  }
  for (std::size_t k = 0; k < grown.size(); ++k) {
    const Candidate& c = *grown[k];
    const bool colon = grown.size() == 1 || static_cast<std::size_t>(chain.pieces[k]) == 0;
    const unsigned char value = grown.size() == 1 ? 1 : static_cast<unsigned char>(result.pieces[k].labelValue);
    const auto& first = c.crop.first;
    for (std::size_t z = 1; z + 1 < c.ball.size[2]; ++z)
      for (std::size_t y = 1; y + 1 < c.ball.size[1]; ++y) {
        const unsigned char* row = &c.ball.At(1, y, z);
        unsigned char* out = &result.label.At(first[0], first[1] + y - 1, first[2] + z - 1);
        for (std::size_t x = 0; x + 2 < c.ball.size[0]; ++x)
          if (row[x]) out[x] = value;
      }
    result.piecesVolumeMl += double(c.growth.grownVoxels) * voxelMl;
    if (colon) {
      result.growth = c.growth;
      result.handleVoxelsRemoved = c.growth.refusedVoxels;
      result.lumenVolumeMl = double(c.growth.grownVoxels) * voxelMl;
    }
  }
  if (!result.bridgeLabel.voxels.empty()) {
    // Virtual voxels the growth left out are not lumen at all; the real ones are not virtual.
    for (std::size_t v = 0; v < result.label.voxels.size(); ++v)
      result.bridgeLabel.voxels[v] = result.bridgeLabel.voxels[v] && result.label.voxels[v];
    std::size_t virtualVoxels = std::count(result.bridgeLabel.voxels.begin(), result.bridgeLabel.voxels.end(), 1);
    result.piecesVolumeMl = result.lumenVolumeMl - double(virtualVoxels) * voxelMl;
  }
  lap("label map");
  progress.Report(1.0);
  return result;
}

}  // namespace colonmap::segmentation
