// ColonCleansing: electronic cleansing of tagged fluid and stool (issue 4, DESIGN §2.1).
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Cleansing/ElectronicCleansing.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"

namespace {

using namespace colonmap;

void Run(cli::ModuleContext& ctx) {
  cleansing::CleansingParameters p;
  p.tagThresholdHU = ctx.args.GetDouble("tagThreshold");
  p.wallHU = ctx.args.GetDouble("wallHU");
  const std::string gravity = ctx.args.GetString("gravity");
  if (gravity == "posterior") p.gravity = Eigen::Vector3d(0, 1, 0);  // LPS: +y is posterior
  if (gravity == "anterior") p.gravity = Eigen::Vector3d(0, -1, 0);

  const std::string input = ctx.args.GetString("inputCT");
  const std::string outputTemp = ctx.outputs.Stage(ctx.args.GetString("outputCT"), "cleansed CT");
  const bool wantLabel = ctx.args.Has("taggedLabel");
  const std::string labelTemp = wantLabel ? ctx.outputs.Stage(ctx.args.GetString("taggedLabel"), "tagged label") : "";
  ctx.progress.Plan({{"Reading", 1}, {"Cleansing", 6}, {"Writing", 2}});

  ctx.progress.StartStage("Reading", "reading the CT");
  Volume<short> ct = io::ReadImage<short>(input, "input CT", ctx.ReaderNotes());
  const double voxelMl = ct.spacing.prod() / 1000.0;
  ctx.progress.EndStage();

  ctx.progress.StartStage("Cleansing", "tagged material to air");
  cleansing::CleansingResult r = cleansing::Cleanse(std::move(ct), p, ctx.progress);  // in place
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "writing the cleansed CT");
  // Uncompressed: CT noise makes gzip slow for little gain (see docs/performance.md).
  io::WriteImage(r.cleansed, outputTemp, "cleansed CT", io::Compression::None);
  if (ctx.shelf) ctx.shelf->Put(ctx.args.GetString("outputCT"), std::move(r.cleansed));  // for the next stages
  ctx.progress.Report(0.8);  // also a poll of Cancel between the two files
  if (wantLabel) io::WriteImage(r.tagged, labelTemp, "tagged label");
  ctx.progress.EndStage();

  std::size_t taggedCount = 0;
  for (unsigned char v : r.tagged.voxels) taggedCount += v;
  const double ml = double(taggedCount) * voxelMl;
  ctx.SetReturn("cleansedVoxels", std::to_string(r.taggedVoxels));
  ctx.SetReturn("taggedVolume", cli::FormatFixed(ml, 2));
  if (r.regions == 0) {
    ctx.progress.Note("ColonCleansing: no tagged material touching air found; the CT is written unchanged");
  } else {
    ctx.progress.Note("ColonCleansing: " + std::to_string(r.regions) + " tagged regions (" + cli::FormatFixed(ml, 1) +
                      " ml, fluid " + cli::FormatFixed(r.fluidHU, 0) + " HU) became air; " +
                      std::to_string(r.regionsDropped) + " bright regions without air contact kept; gravity (LPS) " +
                      cli::FormatFixed(r.down.x(), 2) + "," + cli::FormatFixed(r.down.y(), 2) + "," +
                      cli::FormatFixed(r.down.z(), 2) + (r.gravityEstimated ? " estimated" : " given"));
  }
}

}  // namespace

COLONMAP_MODULE_BODY(ColonCleansing, Run)
