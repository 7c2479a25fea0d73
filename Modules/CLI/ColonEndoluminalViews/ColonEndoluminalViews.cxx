// ColonEndoluminalViews: linked supine/prone endoluminal views (issue 8, DESIGN §2.0, §2.5).
// Thin: arguments, reading, Libs/Views (camera linking, ray casting, composition), staging the
// outputs, progress.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Views/CameraJson.h"
#include "Views/CameraLink.h"
#include "Views/EndoluminalImage.h"
#include "Views/EndoluminalRenderer.h"

#include <chrono>
#include <filesystem>
#include <set>

namespace colonmap::modules {

namespace {

using namespace colonmap::views;

const Rgb kFindingColour{255, 220, 40};  // the supine finding
const Rgb kMappedColour{60, 220, 255};   // where the registration puts it in the prone scan
const Rgb kAxisColour{200, 200, 200};

// A finding ring, when it projects into the view.
void Mark(RgbImage& image, const CameraPose& camera, double viewAngle, const Eigen::Vector3d& p, const Rgb& colour,
          const std::string& text) {
  Eigen::Vector2d px;
  if (!ProjectToPixel(camera, viewAngle, image.width, image.height, p, &px)) return;
  DrawMarker(image, px, colour, text, std::max(5, image.width / 40));
}

}  // namespace

void RunColonEndoluminalViews(cli::ModuleContext& ctx) {
  namespace fs = std::filesystem;
  const std::string supinePath = ctx.args.GetString("supineVolume"), pronePath = ctx.args.GetString("proneVolume"),
                    regPath = ctx.args.GetString("registration"), findingsPath = ctx.args.GetString("findings"),
                    camerasPath = ctx.args.GetString("cameras"), out = ctx.args.GetString("outputDirectory");
  if (supinePath.empty()) throw Error("supine CT: no file given (--supineVolume)");
  if (pronePath.empty()) throw Error("prone CT: no file given (--proneVolume)");
  if (regPath.empty()) throw Error("registration: no file given (--registration)");
  if (findingsPath.empty() == camerasPath.empty())
    throw Error("views: give exactly one of --findings (points to look at) and --cameras (supine camera poses)");
  if (out.empty()) throw Error("output folder: none given");
  const std::vector<long> size = ctx.args.GetIntVector("imageSize");
  if (size.size() != 2) throw Error("image size: give width,height");

  EndoluminalRenderOptions options;
  options.width = static_cast<int>(size[0]);
  options.height = static_cast<int>(size[1]);
  options.viewAngleDeg = ctx.args.GetDouble("viewAngle");
  options.sampleDistanceMm = ctx.args.GetDouble("sampleDistance");
  options.cropRadiusMm = ctx.args.GetDouble("cropRadius");
  options.preset = ctx.args.GetString("preset");
  const double distance = ctx.args.GetDouble("cameraDistance");

  ctx.progress.Plan({{"Read", 1.0}, {"Link", 0.3}, {"Render", 3.0}, {"Write", 0.1}});
  ctx.progress.StartStage("Read", "reading the registration, the views and the CTs");
  // Cheap inputs first, so that a bad one fails before the CTs are read.
  const TriangleMesh reg = io::ReadMesh(regPath, "registration");
  std::vector<NamedCamera> cameras;
  MarkupList findings;
  if (!camerasPath.empty()) {
    cameras = ReadCameras(camerasPath, "cameras");
  } else {
    findings = io::ReadMarkups(findingsPath, "findings");
    if (findings.points.empty()) throw InputError("findings", findingsPath, "has no points");
  }
  ctx.progress.Report(0.1);
  const CameraLinker linker(reg, "registration '" + regPath + "'");
  // The renderer checks the display before the CTs take their time to read.
  EndoluminalRenderer renderer(options);
  ctx.progress.Report(0.2);
  // In ColonSupineProne the cleansed CTs the surface stage read are still in memory (shared).
  const std::shared_ptr<const Volume<short>> supine =
      io::ReadImageShared<short>(ctx.shelf, supinePath, "supine CT", ctx.ReaderNotes());
  ctx.progress.Report(0.6);
  const std::shared_ptr<const Volume<short>> prone =
      io::ReadImageShared<short>(ctx.shelf, pronePath, "prone CT", ctx.ReaderNotes());
  ctx.progress.EndStage();

  ctx.progress.StartStage("Link", "carrying the cameras to the prone scan");
  std::vector<ViewRecord> records;
  std::set<std::string> used;
  const std::size_t n = cameras.empty() ? findings.points.size() : cameras.size();
  for (std::size_t i = 0; i < n; ++i) {
    ViewRecord r;
    const std::string fallback = "V" + std::to_string(i + 1);
    r.label = cameras.empty() ? findings.points[i].label : cameras[i].label;
    if (r.label.empty()) r.label = fallback;
    std::string safe = SafeLabel(r.label, fallback);
    if (used.count(safe)) safe += "_" + std::to_string(i + 1);
    used.insert(safe);
    r.image = "view_" + safe + ".png";
    try {
      r.view = cameras.empty() ? linker.LinkFinding(findings.points[i].position, distance)
                               : linker.LinkCamera(cameras[i].pose);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      throw Error((cameras.empty() ? "findings '" + findingsPath : "cameras '" + camerasPath) + "': view '" + r.label +
                  "': " + e.what());
    }
    records.push_back(r);
    ctx.progress.Report(static_cast<double>(i + 1) / n);
  }
  ctx.progress.EndStage();

  ctx.outputs.PrepareDirectory(out, "output folder");
  ctx.progress.StartStage("Render", "volume rendering the supine and prone views");
  double renderSeconds = 0;
  std::vector<std::pair<std::string, RgbImage>> pictures;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const ViewRecord& r = records[i];
    const auto start = std::chrono::steady_clock::now();
    // Each picture hears the host's Cancel while it renders (VTK's gradient pass alone takes
    // 0.3-0.9 s at clinical size).
    SubProgress leftProgress(ctx.progress, i / double(records.size()), (i + 0.5) / records.size());
    RgbImage left = renderer.Render(*supine, r.view.supine, "supine CT '" + supinePath + "', view '" + r.label + "'",
                                    &leftProgress);
    ctx.progress.Report((i + 0.5) / records.size());
    SubProgress rightProgress(ctx.progress, (i + 0.5) / records.size(), (i + 1.0) / records.size());
    RgbImage right = renderer.Render(*prone, r.view.prone, "prone CT '" + pronePath + "', view '" + r.label + "'",
                                     &rightProgress);
    renderSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    DrawViewAxisCross(left, kAxisColour);
    DrawViewAxisCross(right, kAxisColour);
    if (r.view.hasFinding) {
      Mark(left, r.view.supine, options.viewAngleDeg, r.view.finding, kFindingColour, r.label);
      Mark(right, r.view.prone, options.viewAngleDeg, r.view.proneFinding, kMappedColour, r.label);
    }
    pictures.emplace_back(r.image, SideBySide(left, "supine  " + r.label, right, "prone  " + r.label + " (linked)",
                                              std::clamp(options.height / 16, 14, 32)));
    ctx.progress.Report((i + 1.0) / records.size());
  }
  ctx.progress.EndStage();

  ctx.progress.StartStage("Write", "writing the pictures and cameras.json");
  for (const auto& [name, picture] : pictures) {
    const std::string what = "output " + name;
    WritePng(picture, ctx.outputs.Stage((fs::path(out) / name).string(), what), what);
  }
  io::WriteText(CamerasJsonText(records, options.viewAngleDeg, options.width, options.height),
                ctx.outputs.Stage((fs::path(out) / "cameras.json").string(), "output cameras.json"),
                "output cameras.json");
  ctx.progress.EndStage();
  ctx.SetReturn("views", std::to_string(records.size()));
  ctx.SetReturn("meanRenderTime", cli::FormatNumber(records.empty() ? 0.0 : renderSeconds / records.size()));
}

}  // namespace colonmap::modules
