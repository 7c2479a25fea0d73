// ColonLandmarks: closed colon surface -> centreline, flexures, opened colon, five segment
// cylinders, taeniae (issue 5, DESIGN §2.2). Thin: arguments, reading, Libs/Landmarks, writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Landmarks/ColonLandmarks.h"

#include <filesystem>

namespace {

using namespace colonmap;
namespace fs = std::filesystem;

void Run(cli::ModuleContext& ctx) {
  const std::string inPath = ctx.args.GetString("inputSurface");
  const std::string out = ctx.args.GetString("outputDirectory");
  if (inPath.empty()) throw Error("input surface: no file given");
  if (out.empty()) throw Error("output folder: no folder given");
  ctx.outputs.PrepareDirectory(out, "output folder");
  landmarks::LandmarkOptions options;
  options.segments.capMm = ctx.args.GetDouble("capDistance");
  ctx.progress.Plan({{"Reading", 1}, {"Landmarks", 10}, {"Writing", 2}});

  ctx.progress.StartStage("Reading", "closed colon surface");
  TriangleMesh surface = io::ReadMesh(inPath, "input surface");
  ctx.progress.EndStage();

  ctx.progress.StartStage("Landmarks", "centreline, flexures, segments, taeniae");
  landmarks::LandmarkResult r;
  try {
    r = landmarks::FindLandmarks(std::move(surface), options, ctx.progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    throw InputError("input surface", inPath, e.what());
  }
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "landmark files");
  const auto file = [&](const std::string& name) {
    return ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name);
  };
  io::WriteMesh(r.segments.open, file("colon_open.vtp"), "opened colon");
  for (int s = 0; s < 5; ++s) {
    const std::string name = std::string("segment_") + landmarks::SegmentName(s) + ".vtp";
    io::WriteMesh(r.segments.segment[s], file(name), name);
    ctx.progress.Report(0.1 + 0.12 * s);
  }
  io::WriteMarkups(landmarks::CenterlineMarkups(r), file("centerline.mrk.json"), "centerline");
  io::WriteMarkups(landmarks::FlexureMarkups(r), file("flexures.mrk.json"), "flexures");
  io::WritePolylines(landmarks::TaeniaPolylines(r), file("taeniae.vtp"), "taeniae");
  io::WriteText(landmarks::SummaryJson(r, ctx.args.GetBool("recordTimes")), file("landmarks.json"), "landmarks.json");
  ctx.progress.EndStage();

  std::string arcs, times;
  for (int k = 0; k < 4; ++k) {
    arcs += (k ? "," : "") + cli::FormatFixed(r.flexures.arc[k], 1);
  }
  for (const auto& [name, sec] : r.times) times += " " + name + " " + cli::FormatFixed(sec, 2) + " s";
  ctx.SetReturn("centerlineLength", cli::FormatFixed(r.centerline.Length(), 1));
  ctx.SetReturn("flexureArcLengths", arcs);
  ctx.progress.Note("ColonLandmarks: centreline " + cli::FormatFixed(r.centerline.Length(), 0) +
                    " mm; flexures HF,SF,DSJ,RSJ at " + arcs + " mm from the anal end; " +
                    std::to_string(r.segments.open.F.rows()) + " faces opened, " +
                    std::to_string(r.segments.relabelledFaces) + " relabelled;" + times +
                    (r.flippedOrientation ? "; input normals pointed outwards (flipped)" : ""));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonLandmarks, Run)
