// ColonTransferPoints: markups in one scan -> the same findings in the other scan, through a
// ColonRegistration result (issue 7, DESIGN §2.0). Thin: arguments, reading, Libs/Registration,
// writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "Registration/PointTransfer.h"

#include <cstdio>

namespace {

using namespace colonmap;
using namespace colonmap::registration;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};

std::string Fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

void Run(cli::ModuleContext& ctx) {
  const std::string reg = ctx.args.GetString("registration"), in = ctx.args.GetString("input"),
                    out = ctx.args.GetString("output");
  if (reg.empty()) throw Error("registration: no file given (--registration)");
  if (in.empty()) throw Error("input points: no file given (--input)");
  if (out.empty()) throw Error("output points: no file given (--output)");
  const bool toProne = ctx.args.GetString("direction") != "proneToSupine";
  ctx.progress.Plan({{"Read", 1.0}, {"Transfer", 1.0}, {"Write", 0.1}});
  ctx.progress.StartStage("Read", "reading the registration");
  const MarkupList points = io::ReadMarkups(in, "input points");
  if (points.points.empty()) throw InputError("input points", in, "holds no points (nothing to carry across)");
  const RegistrationMeshes meshes = ReadRegistration(reg, ctx.args.GetString("proneMesh"));
  ctx.progress.Report(0.6);
  const PointTransfer transfer(toProne ? meshes.supine : meshes.prone, toProne ? meshes.prone : meshes.supine,
                               toProne ? "Prone" : "Supine", toProne ? "registration '" + reg + "'" : "prone registration mesh");
  ctx.progress.EndStage();
  ctx.progress.StartStage("Transfer", "carrying points across");
  MarkupList result = points;
  result.name = points.name.empty() ? std::string(toProne ? "Prone" : "Supine") : points.name;
  double sum = 0;
  long unreliable = 0, invisible = 0;
  for (std::size_t i = 0; i < points.points.size(); ++i) {
    const TransferredPoint t = transfer.Transfer(points.points[i].position);
    ControlPoint& c = result.points[i];
    c.position = t.position;
    // reliable=false: the registration cannot be trusted here, whatever the bound says.
    std::string d = "uncertaintyMm=" + Fixed(t.uncertaintyMm, 2) + " reliable=" + (t.reliable ? "true" : "false");
    unreliable += !t.reliable;
    invisible += !t.visible;
    // Collapsed stretches: no true position on virtual wall (PointTransfer.h).
    if (!t.visible)
      d += std::string(" visible=false") + (t.sourceVirtual ? " notSeenIn=source" : " notSeenIn=target") +
           (t.targetVirtual ? " alongColonToOpenMm=" + Fixed(t.openDistanceMm, 1) : "");
    if (t.segment >= 0 && t.segment < 5) d += std::string(" segment=") + kNames[t.segment];
    d += " offsetMm=" + Fixed(t.offset, 2) + " dilatation=" + Fixed(t.dilatation, 3);
    if (!points.points[i].description.empty()) d += " source: " + points.points[i].description;
    c.description = d;
    sum += t.uncertaintyMm;
    if ((i & 255) == 0) ctx.progress.Report(static_cast<double>(i) / points.points.size());
  }
  ctx.progress.EndStage();
  ctx.progress.StartStage("Write", "writing the points");
  io::WriteMarkups(result, ctx.outputs.Stage(out, "output points"), "output points");
  ctx.progress.EndStage();
  ctx.SetReturn("points", std::to_string(points.points.size()));
  if (unreliable > 0)
    ctx.progress.Note("ColonTransferPoints: WARNING: " + std::to_string(unreliable) +
                      " point(s) lie where the registration cannot be trusted (reliable=false in their description)");
  ctx.SetReturn("unreliablePoints", std::to_string(unreliable));
  if (invisible > 0)
    ctx.progress.Note("ColonTransferPoints: WARNING: " + std::to_string(invisible) +
                      " point(s) lie on wall collapsed in one scan (visible=false; those on collapsed target wall are "
                      "placed at the nearest open wall along the colon)");
  ctx.SetReturn("invisiblePoints", std::to_string(invisible));
  ctx.SetReturn("meanUncertainty", cli::FormatNumber(points.points.empty() ? 0.0 : sum / points.points.size()));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonTransferPoints, Run)
