// ColonSurface: lumen label map (+ CT) -> closed colon surface with mean curvature (issue 4).
// Thin: arguments, reading, Libs/Surface, writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MeshIO.h"
#include "Surface/SurfaceReconstruction.h"
#include "Surface/VirtualWall.h"

#include <optional>

namespace {

using namespace colonmap;

void Run(cli::ModuleContext& ctx) {
  surface::SurfaceOptions options;
  options.targetFaces = ctx.args.GetInt("targetFaces");
  options.labelValue = static_cast<double>(ctx.args.GetInt("labelValue"));
  options.isoValueHU = ctx.args.GetDouble("isoValue");
  const std::string labelPath = ctx.args.GetString("inputLabel");
  const std::string ctPath = ctx.args.GetString("referenceCT");
  const std::string outPath = ctx.args.GetString("outputSurface");
  const std::string virtualPath = ctx.args.GetString("virtualLabel");
  if (labelPath.empty()) throw Error("input label map: no file given");
  if (outPath.empty()) throw Error("output surface: no file given");
  ctx.progress.Plan({{"Reading", 2}, {"Surface", 10}, {"Writing", 1}});

  ctx.progress.StartStage("Reading", "label map and reference CT");
  // A report after each file, and between the pieces of a volume taken from the shelf: each is a
  // poll of Cancel too (ColonSupineProne's promise: 0.5 s).
  SubProgress labelStep(ctx.progress, 0.0, 0.4), ctStep(ctx.progress, 0.4, 0.8), virtualStep(ctx.progress, 0.8, 1.0);
  // The lumen's mask straight from the kept label map, else from the file read as float (any
  // integer label type, exact up to 2^24).
  const double labelValue = options.labelValue;
  const Volume<unsigned char> label = [&] {
    if (ctx.shelf)
      if (auto kept = ctx.shelf->TakeMapped<unsigned char>(
              labelPath, [labelValue](auto v) { return surface::IsLabel(v, labelValue); }, &labelStep))
        return std::move(*kept);
    return surface::LumenMask(io::ReadImage<float>(labelPath, "input label map", ctx.ReaderNotes()), labelValue, &labelStep);
  }();
  ctx.progress.Report(0.4);
  std::shared_ptr<const Volume<short>> ct;  // read only: shared with the pipeline's other readers
  if (!ctPath.empty()) ct = io::ReadImageShared<short>(ctx.shelf, ctPath, "reference CT", ctx.ReaderNotes(), &ctStep);
  ctx.progress.Report(0.8);
  std::optional<Volume<unsigned char>> virtualLumen;
  if (!virtualPath.empty()) {
    virtualLumen = io::ReadImageKept<unsigned char>(ctx.shelf, virtualPath, "virtual lumen label map", ctx.ReaderNotes(),
                                                    &virtualStep);
    if (virtualLumen->size != label.size || (virtualLumen->origin - label.origin).norm() > 1e-3 ||
        (virtualLumen->spacing - label.spacing).norm() > 1e-6)
      throw InputError("virtual lumen label map", virtualPath, "not on the grid of the input label map");
  }
  ctx.progress.EndStage();

  ctx.progress.StartStage("Surface", ct ? "iso-surface of the CT near the label boundary" : "surface of the label");
  surface::SurfaceResult result;
  try {
    result = surface::ReconstructSurfaceFromMask(label, ct.get(), options, ctx.progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    // Name the input file in the message.
    const std::string what = e.what();
    if (what.rfind("reference CT", 0) == 0) throw InputError("reference CT", ctPath, what.substr(what.find(':') + 2));
    throw InputError("input label map", labelPath, what.substr(what.find(':') + 2));
  }
  ctx.progress.EndStage();

  std::size_t virtualVertices = 0;
  if (virtualLumen) {
    // Wall of the virtual lumen through collapsed stretches: carried to the registration.
    const Eigen::VectorXd marks = surface::VirtualVertices(result.mesh.V, *virtualLumen);
    virtualVertices = static_cast<std::size_t>(marks.sum());
    // Only where there is virtual wall: a colon without collapse gives the same file as before.
    if (virtualVertices > 0) result.mesh.pointData["Virtual"] = DataArray{marks, true};
  }

  ctx.progress.StartStage("Writing", "surface file");
  io::WriteMesh(result.mesh, ctx.outputs.Stage(outPath, "output surface"), "output surface");
  ctx.progress.EndStage();

  const surface::TopologyReport& t = result.topology;
  ctx.SetReturn("faces", std::to_string(t.faces));
  ctx.SetReturn("eulerCharacteristic", std::to_string(t.euler));
  ctx.SetReturn("droppedComponents", std::to_string(result.droppedComponents.size()));
  ctx.SetReturn("handlesCut", std::to_string(result.changes.handles));
  ctx.SetReturn("voxelsChanged", std::to_string(result.voxelsChanged));
  ctx.SetReturn("topology", "closed-genus-0");  // ReconstructSurface fails on anything else

  ctx.progress.Note("ColonSurface: " + std::to_string(result.lumenVoxels) + " lumen voxels, " +
                    (result.usedCT ? "CT iso-value " + cli::FormatNumber(options.isoValueHU) + " HU" : "label only") +
                    ", contour " + std::to_string(result.contourFaces) + " faces; " + t.Summary());
  for (const std::string& n : result.notes) ctx.progress.Note("ColonSurface: " + n);
  if (virtualLumen)
    ctx.progress.Note("ColonSurface: " + std::to_string(virtualVertices) + " of " + std::to_string(result.mesh.V.rows()) +
                      " vertices on virtual wall (point array Virtual)");
  ctx.SetReturn("virtualVertices", std::to_string(virtualVertices));
  std::string times;
  for (const auto& [step, seconds] : result.stepSeconds)
    times += (times.empty() ? "" : ", ") + step + " " + cli::FormatFixed(seconds, 2) + " s";
  ctx.progress.Note("ColonSurface: steps: " + times);
}

}  // namespace

COLONMAP_MODULE_BODY(ColonSurface, Run)
