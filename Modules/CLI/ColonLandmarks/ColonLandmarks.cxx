// ColonLandmarks: closed colon surface -> centreline, flexures, opened colon, five segment
// cylinders, taeniae (issue 5, DESIGN §2.2). Thin: arguments, reading, Libs/Landmarks, writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Landmarks/ColonLandmarks.h"

#include <array>
#include <filesystem>
#include <vector>

namespace {

using namespace colonmap;
namespace fs = std::filesystem;

void WriteLandmarks(cli::ModuleContext& ctx, const landmarks::LandmarkResult& r, const std::string& out) {
  const auto file = [&](const std::string& name) {
    return ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name);
  };
  io::WriteMesh(r.segments.open, file("colon_open.vtp"), "opened colon");
  for (int s = 0; s < 5; ++s) {
    const std::string name = std::string("segment_") + landmarks::SegmentName(s) + ".vtp";
    io::WriteMesh(r.segments.segment[s], file(name), name);
  }
  io::WriteMarkups(landmarks::CenterlineMarkups(r), file("centerline.mrk.json"), "centerline");
  io::WriteMarkups(landmarks::FlexureMarkups(r), file("flexures.mrk.json"), "flexures");
  io::WritePolylines(landmarks::TaeniaPolylines(r), file("taeniae.vtp"), "taeniae");
  io::WriteText(landmarks::SummaryJson(r, ctx.args.GetBool("recordTimes")), file("landmarks.json"), "landmarks.json");
}

// The first scan's centreline (a curve), flexures (points) and opened colon (with SegmentId) as
// nodes for the scene, when asked for: the same data as the folder's files.
void WriteSceneOutputs(cli::ModuleContext& ctx, const landmarks::LandmarkResult& r) {
  if (const std::string p = ctx.args.GetString("centerlineCurve"); !p.empty())
    io::WriteMarkups(landmarks::CenterlineMarkups(r), ctx.outputs.Stage(p, "centerline curve"), "centerline curve");
  if (const std::string p = ctx.args.GetString("flexurePoints"); !p.empty())
    io::WriteMarkups(landmarks::FlexureMarkups(r), ctx.outputs.Stage(p, "flexure points"), "flexure points");
  if (const std::string p = ctx.args.GetString("openColonModel"); !p.empty())
    io::WriteMesh(r.segments.open, ctx.outputs.Stage(p, "opened colon model"), "opened colon model");
}

std::string ArcList(const landmarks::LandmarkResult& r) {
  std::string arcs;
  for (int k = 0; k < 4; ++k) arcs += (k ? "," : "") + cli::FormatFixed(r.flexures.arc[k], 1);
  return arcs;
}

std::string Summary(const std::string& name, const landmarks::LandmarkResult& r) {
  std::string times;
  for (const auto& [step, sec] : r.times) times += " " + step + " " + cli::FormatFixed(sec, 2) + " s";
  std::string joint;
  if (r.joint) {
    for (int k = 0; k < 4; ++k)
      if (r.joint->how[k] != "agreed")
        joint += std::string(joint.empty() ? "" : ", ") + landmarks::Flexures::Names()[k] + " " + r.joint->how[k] +
                 " (own rules " + cli::FormatFixed(r.joint->ownRuleArc[k], 0) + " mm)";
    joint = "; joint with " + r.joint->pairedWith + ": " + (joint.empty() ? "all four flexures agreed" : joint);
  }
  return "ColonLandmarks: " + name + "centreline " + cli::FormatFixed(r.centerline.Length(), 0) +
         " mm; flexures HF,SF,DSJ,RSJ at " + ArcList(r) + " mm from the anal end" + joint + "; " +
         std::to_string(r.segments.open.F.rows()) + " faces opened, " + std::to_string(r.segments.relabelledFaces) +
         " relabelled;" + times + (r.flippedOrientation ? "; input normals pointed outwards (flipped)" : "");
}

void Run(cli::ModuleContext& ctx) {
  const std::string inPath = ctx.args.GetString("inputSurface");
  const std::string out = ctx.args.GetString("outputDirectory");
  const std::string pairedPath = ctx.args.GetString("pairedSurface");
  const std::string pairedOut = ctx.args.GetString("pairedOutputDirectory");
  if (inPath.empty()) throw Error("input surface: no file given");
  if (out.empty()) throw Error("output folder: no folder given");
  if (pairedPath.empty() != pairedOut.empty())
    throw Error("paired scan: give both --pairedSurface and --pairedOutputDirectory, or neither");
  const bool pair = !pairedPath.empty();
  const auto folder = [](const std::string& p) {
    fs::path f = fs::weakly_canonical(fs::path(p));
    return f.filename().empty() ? f.parent_path() : f;  // "dir/" is "dir"
  };
  if (pair && folder(out) == folder(pairedOut))
    throw Error("paired output folder '" + pairedOut + "': the same folder as the output folder; the two scans need their own");
  std::array<std::string, 2> names{"input", "paired"};
  if (const std::vector<std::string> n = ctx.args.GetStringVector("scanNames"); n.size() == 2) names = {n[0], n[1]};
  else if (!n.empty()) throw Error("scan names: two names needed (--scanNames supine,prone)");
  ctx.outputs.PrepareDirectory(out, "output folder");
  if (pair) ctx.outputs.PrepareDirectory(pairedOut, "paired output folder");
  landmarks::LandmarkOptions options;
  options.segments.capMm = ctx.args.GetDouble("capDistance");
  ctx.progress.Plan({{"Reading", pair ? 2.0 : 1.0}, {"Landmarks", pair ? 20.0 : 10.0}, {"Writing", pair ? 4.0 : 2.0}});

  ctx.progress.StartStage("Reading", "closed colon surface");
  TriangleMesh surface = io::ReadMesh(inPath, "input surface");
  TriangleMesh paired;
  if (pair) paired = io::ReadMesh(pairedPath, "paired surface");
  ctx.progress.EndStage();

  ctx.progress.StartStage("Landmarks", pair ? "both scans, flexures chosen jointly" : "centreline, flexures, segments, taeniae");
  std::vector<landmarks::LandmarkResult> r;
  try {
    if (pair) {
      auto both = landmarks::FindLandmarksForPair(std::move(surface), std::move(paired), names, options, ctx.progress);
      r = {std::move(both[0]), std::move(both[1])};
    } else {
      r.push_back(landmarks::FindLandmarks(std::move(surface), options, ctx.progress));
    }
  } catch (const Cancelled&) {
    throw;
  } catch (const Error& e) {
    // A pair error starts with the scan's name; name the user's file it came from.
    const std::string what = e.what();
    const bool second = pair && what.rfind(names[1] + " surface: ", 0) == 0;
    const bool first = pair && what.rfind(names[0] + " surface: ", 0) == 0;
    const std::string reason = first || second ? what.substr(what.find(": ") + 2) : what;
    throw InputError(second ? "paired surface" : "input surface", second ? pairedPath : inPath, reason);
  }
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "landmark files");
  WriteLandmarks(ctx, r[0], out);
  if (pair) WriteLandmarks(ctx, r[1], pairedOut);
  WriteSceneOutputs(ctx, r[0]);
  ctx.progress.EndStage();

  ctx.SetReturn("centerlineLength", cli::FormatFixed(r[0].centerline.Length(), 1));
  ctx.SetReturn("flexureArcLengths", ArcList(r[0]));
  if (pair) {
    ctx.SetReturn("pairedCenterlineLength", cli::FormatFixed(r[1].centerline.Length(), 1));
    ctx.SetReturn("pairedFlexureArcLengths", ArcList(r[1]));
  }
  ctx.progress.Note(Summary(pair ? names[0] + " " : "", r[0]));
  if (pair) ctx.progress.Note(Summary(names[1] + " ", r[1]));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonLandmarks, Run)
