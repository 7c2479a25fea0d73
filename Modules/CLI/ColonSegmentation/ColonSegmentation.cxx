// ColonSegmentation: CT (or cleansed CT) -> colon lumen label map, one component of genus 0
// (issue 4, DESIGN 2.1). Thin: options from the XML, the math in Libs/Segmentation, files
// through Libs/IO.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "Segmentation/LumenSegmentation.h"

#include <string>

namespace {

using namespace colonmap;
using namespace colonmap::segmentation;

void Run(cli::ModuleContext& ctx) {
  const std::string input = ctx.args.GetString("inputCT");
  const std::string output = ctx.args.GetString("outputLabel");
  if (input.empty()) throw Error("parameter inputCT: an input CT is required");
  if (output.empty()) throw Error("parameter outputLabel: an output label map is required");
  SegmentationOptions options;
  options.airThresholdHU = ctx.args.GetDouble("airThreshold");
  options.minColonVolumeMl = ctx.args.GetDouble("minColonVolume");
  options.maxColonRadiusMm = ctx.args.GetDouble("maxColonRadius");
  options.minElongation = ctx.args.GetDouble("minElongation");
  options.bridgePieces = ctx.args.GetBool("bridgePieces");
  const std::string bridgeOutput = ctx.args.GetString("bridgeLabel");
  if (!bridgeOutput.empty() && !options.bridgePieces)
    throw Error("parameter --bridgeLabel: the virtual lumen label map needs --bridgePieces");
  // Staged first, so that an unwritable output fails before the work.
  const std::string staged = ctx.outputs.Stage(output, "output label map");
  const std::string stagedBridge = bridgeOutput.empty() ? "" : ctx.outputs.Stage(bridgeOutput, "virtual lumen label map");
  ctx.progress.Plan({{"Reading", 2}, {"Segmentation", 10}, {"Writing", 1}});

  ctx.progress.StartStage("Reading", "reading the CT");
  // Read only: shared with the pipeline's other readers of this CT (no copy).
  const std::shared_ptr<const Volume<short>> ct =
      io::ReadImageShared<short>(ctx.shelf, input, "input CT", ctx.ReaderNotes(), &ctx.progress);
  ctx.progress.EndStage();

  ctx.progress.StartStage("Segmentation", "air components, colon selection, topology-preserving growth");
  LumenSegmentation s;
  try {
    s = SegmentColonLumen(*ct, options, ctx.progress);
  } catch (const NoColonFound& e) {
    throw InputError("input CT", input, e.what());
  }
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "writing the label map");
  io::WriteImage(s.label, staged, "output label map");
  ctx.progress.Report(0.5);  // also a poll of Cancel between the two files
  if (!stagedBridge.empty()) {
    Volume<unsigned char> bridge = s.bridgeLabel.voxels.empty() ? s.label.Like<unsigned char>(0) : std::move(s.bridgeLabel);
    io::WriteImage(bridge, stagedBridge, "virtual lumen label map");
    if (ctx.shelf) ctx.shelf->Put(bridgeOutput, std::move(bridge));
  }
  if (ctx.shelf) ctx.shelf->Put(output, std::move(s.label));  // for the next stage (not used below)
  ctx.progress.EndStage();

  // Report: the kept component, then every dropped one of 1 ml or more (the rest counted).
  const auto describe = [](const AirComponent& c) {
    std::string line = cli::FormatFixed(c.volumeMl, 1) + " ml at LPS (" + cli::FormatFixed(c.centroid.x(), 0) + ", " +
                       cli::FormatFixed(c.centroid.y(), 0) + ", " + cli::FormatFixed(c.centroid.z(), 0) + ")";
    if (c.maxRadiusMm >= 0.0)
      line += ", inscribed radius " + cli::FormatFixed(c.maxRadiusMm, 1) + " mm, elongation " +
              cli::FormatFixed(c.elongation, 1);
    return line + ": " + DecisionName(c.decision) + ", " + c.reason;
  };
  std::size_t tiny = 0;
  for (const AirComponent& c : s.components) {
    if (c.decision == Decision::Colon || c.decision == Decision::Piece || c.volumeMl >= 1.0)
      ctx.progress.Note("ColonSegmentation: air component " + describe(c));
    else
      ++tiny;
  }
  if (tiny) ctx.progress.Note("ColonSegmentation: " + std::to_string(tiny) + " further air components under 1 ml dropped");
  std::string reasons, keys;  // for people, and a space-free form for the return parameter
  const std::pair<Decision, const char*> kinds[6] = {{Decision::OutsideBody, "outsideBody"}, {Decision::AtSuperiorBorder, "atSuperiorBorder"}, {Decision::TooSmall, "tooSmall"},
                                                    {Decision::TooThick, "tooThick"}, {Decision::NotElongated, "notElongated"},
                                                    {Decision::NotLargest, "notLargest"}};
  for (const auto& [d, key] : kinds) {
    if (!reasons.empty()) reasons += ", ", keys += ",";
    reasons += std::string(DecisionName(d)) + " " + std::to_string(s.Dropped(d));
    keys += std::string(key) + ":" + std::to_string(s.Dropped(d));
  }
  const std::size_t kept = s.pieces.size();
  std::string order, lengths, gaps, pieces;
  for (std::size_t k = 0; k < kept; ++k) {
    const ColonPiece& p = s.pieces[k];
    const AirComponent& c = s.components[p.component];
    order += (k ? "," : "") + std::to_string(p.labelValue);
    if (kept > 1) lengths += (k ? "," : "") + cli::FormatFixed(c.lengthMm, 0);
    if (k + 1 < kept) gaps += (k ? "," : "") + cli::FormatFixed(p.gapAfterMm, 0);
    pieces += (k ? "; gap " + cli::FormatFixed(s.pieces[k - 1].gapAfterMm, 0) + " mm; " : std::string()) + "label " +
              std::to_string(p.labelValue) + " " + cli::FormatFixed(c.volumeMl, 0) + " ml, " + cli::FormatFixed(c.lengthMm, 0) + " mm";
  }
  const double virtualMl = s.bridges.empty() ? 0.0 : s.lumenVolumeMl - s.piecesVolumeMl;
  if (kept > 1)
    ctx.progress.Note("ColonSegmentation: the colon is in " + std::to_string(kept) +
                      " pieces (collapsed or fluid-filled stretches between), from the caecum: " + pieces +
                      (s.bridges.empty() ? "; later stages read label 1, the largest piece"
                                         : "; joined by " + cli::FormatFixed(virtualMl, 1) +
                                               " ml of virtual lumen into label 1 (the whole colon)"));
  ctx.progress.Note("ColonSegmentation: lumen " + cli::FormatFixed(s.lumenVolumeMl, 1) + " ml, " + std::to_string(kept) +
                    (kept == 1 ? " component" : " components") + " kept, " +
                    std::to_string(s.components.size() - kept) + " dropped (" + reasons + "); " +
                    std::to_string(s.cavityVoxelsFilled) + " cavity voxels filled, " +
                    std::to_string(s.handleVoxelsRemoved) + " voxels left out to cut handles (growth " +
                    cli::FormatFixed(s.growth.seconds, 2) + " s)");
  std::string steps;
  for (const auto& [step, seconds] : s.stepSeconds) steps += (steps.empty() ? "" : ", ") + step + " " + cli::FormatFixed(seconds, 2) + " s";
  ctx.progress.Note("ColonSegmentation: times: " + steps);
  ctx.SetReturn("lumenVolume", cli::FormatFixed(s.lumenVolumeMl, 1));
  ctx.SetReturn("componentsKept", std::to_string(kept));
  ctx.SetReturn("componentsDropped", std::to_string(s.components.size() - kept));
  ctx.SetReturn("pieceOrder", order);
  ctx.SetReturn("pieceLengths", lengths);
  ctx.SetReturn("pieceGaps", gaps);
  ctx.SetReturn("piecesVolume", cli::FormatFixed(s.piecesVolumeMl, 1));
  ctx.SetReturn("virtualVolume", cli::FormatFixed(virtualMl, 1));
  ctx.SetReturn("droppedReasons", keys);
  ctx.SetReturn("cavityVoxelsFilled", std::to_string(s.cavityVoxelsFilled));
  ctx.SetReturn("handleVoxelsRemoved", std::to_string(s.handleVoxelsRemoved));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonSegmentation, Run)
