// Image reading and writing: the real CT as NIfTI and as DICOM, round trips, bad inputs.
#include "Core/Testing/FreshTempDir.h"
#include "Core/RecordingProgress.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;

namespace {

const std::string kData = COLONMAP_SHARED_DIR "/data/totalseg-example-ct";

fs::path TempDir(const std::string& name) { return colonmap::FreshTempDir("imageio", name); }

std::string ErrorOf(const std::string& path) {
  try {
    io::ReadImage<short>(path, "input CT");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// The shared NIfTI and DICOM are two different scans (3 mm 122x101x112 and 0.98 x 0.98 x 2 mm
// 512x512x20, z ranges 94..430 and -804..-766 mm), so each is checked against what its own
// headers say, and the DICOM series against its own NRRD round trip.
TEST(ImageIO, RealCtAsNifti) {
  const Volume<short> v = io::ReadImage<short>(kData + "/example_ct.nii.gz", "CT");
  EXPECT_EQ(v.size, (std::array<std::size_t, 3>{{122, 101, 112}}));
  EXPECT_TRUE(v.spacing.isApprox(Eigen::Vector3d(3, 3, 3), 1e-6));
  // NIfTI is RAS on disk; ITK hands it over in LPS: the first two axes flip.
  EXPECT_LT((v.direction - Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()).norm(), 1e-6);
  const auto [lo, hi] = std::minmax_element(v.voxels.begin(), v.voxels.end());
  EXPECT_LE(*lo, -1000);  // air outside the body
  EXPECT_GE(*hi, 1000);   // bone
}

TEST(ImageIO, RealCtAsDicomSeries) {
  const Volume<short> v = io::ReadImage<short>(kData + "/example_ct_dicom", "CT");
  EXPECT_EQ(v.size, (std::array<std::size_t, 3>{{512, 512, 20}}));
  EXPECT_NEAR(v.spacing.x(), 0.976562, 1e-5);
  EXPECT_NEAR(v.spacing.y(), 0.976562, 1e-5);
  EXPECT_NEAR(v.spacing.z(), 2.0, 1e-4);  // from the slice positions, not the slice thickness tag
  EXPECT_LT((v.direction - Eigen::Matrix3d::Identity()).norm(), 1e-6);
  const auto [lo, hi] = std::minmax_element(v.voxels.begin(), v.voxels.end());
  EXPECT_EQ(*lo, -1024);  // rescale slope/intercept applied: stored 0 is -1024 HU
  EXPECT_GT(*hi, 1000);
  // Written as NRRD and read back: same geometry and values.
  const fs::path dir = TempDir("dicom");
  io::WriteImage(v, (dir / "ct.nrrd").string(), "CT");
  const Volume<short> r = io::ReadImage<short>((dir / "ct.nrrd").string(), "CT");
  EXPECT_EQ(r.size, v.size);
  EXPECT_TRUE(r.spacing.isApprox(v.spacing, 1e-9));
  EXPECT_LT((r.origin - v.origin).norm(), 1e-6);
  EXPECT_EQ(r.voxels, v.voxels);
  fs::remove_all(dir);
}

TEST(ImageIO, RoundTripKeepsGeometryAndValues) {
  const fs::path dir = TempDir("roundtrip");
  Volume<short> v;
  v.size = {{4, 3, 2}};
  v.spacing = {0.7, 0.8, 1.5};
  v.origin = {-10.0, 20.0, 5.5};
  // An oblique direction (rotation about z by 30 degrees).
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  v.direction << c, -s, 0, s, c, 0, 0, 0, 1;
  v.Allocate();
  for (std::size_t i = 0; i < v.voxels.size(); ++i) v.voxels[i] = static_cast<short>(i * 37 - 400);
  for (const std::string ext : {".nrrd", ".nii.gz", ".mha"}) {
    const std::string path = (dir / ("v" + ext)).string();
    io::WriteImage(v, path, "test image");
    const Volume<short> r = io::ReadImage<short>(path, "test image");
    EXPECT_EQ(r.size, v.size) << ext;
    EXPECT_TRUE(r.spacing.isApprox(v.spacing, 1e-6)) << ext;
    EXPECT_LT((r.origin - v.origin).norm(), 1e-4) << ext;
    EXPECT_LT((r.direction - v.direction).norm(), 1e-5) << ext;
    EXPECT_EQ(r.voxels, v.voxels) << ext;
  }
  fs::remove_all(dir);
}

TEST(ImageIO, BadInputsGiveClearErrors) {
  const fs::path dir = TempDir("bad");
  EXPECT_EQ(ErrorOf((dir / "missing.nrrd").string()), "input CT '" + (dir / "missing.nrrd").string() + "': file does not exist");
  EXPECT_NE(ErrorOf(dir.string()).find("folder holds no DICOM series"), std::string::npos);
  std::ofstream(dir / "x.unknownext") << "hello";
  EXPECT_NE(ErrorOf((dir / "x.unknownext").string()).find("unknown or unsupported image format"), std::string::npos);
  // A truncated NRRD: header promises more voxels than the file holds.
  std::ofstream(dir / "truncated.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 64 64 64\n"
                                           "encoding: raw\nendian: little\n\n" << std::string(100, '\0');
  EXPECT_EQ(ErrorOf((dir / "truncated.nrrd").string()),
            "input CT '" + (dir / "truncated.nrrd").string() + "': is truncated: its voxel data holds 100 of 524288 bytes");
  // Detached voxel data (.nhdr): cut short, or missing.
  std::ofstream(dir / "detached.raw") << std::string(10, '\0');
  std::ofstream(dir / "detached.nhdr") << "NRRD0004\ntype: unsigned short\ndimension: 3\nsizes: 2 2 2\n"
                                          "encoding: raw\nendian: little\ndata file: detached.raw\n";
  EXPECT_EQ(ErrorOf((dir / "detached.nhdr").string()), "input CT '" + (dir / "detached.nhdr").string() +
                                                           "': is truncated: its voxel data file 'detached.raw' holds 10 of 16 bytes");
  std::ofstream(dir / "lost.nhdr") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                      "encoding: raw\nendian: little\ndata file: lost.raw\n";
  EXPECT_EQ(ErrorOf((dir / "lost.nhdr").string()),
            "input CT '" + (dir / "lost.nhdr").string() + "': its voxel data file 'lost.raw' does not exist");
  // NaN spacing.
  std::ofstream(dir / "nan.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                     "spacings: nan 1 1\nencoding: raw\nendian: little\n\n" << std::string(16, '\0');
  const std::string nan = ErrorOf((dir / "nan.nrrd").string());
  EXPECT_EQ(nan, "input CT '" + (dir / "nan.nrrd").string() + "': header field 'spacings:' holds NaN");
  std::ofstream(dir / "nan.mha") << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = nan 1 1\n"
                                    "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" << std::string(16, '\0');
  // MetaIO printed 4 lines of its own and ITK then blamed a missing file.
  EXPECT_EQ(ErrorOf((dir / "nan.mha").string()),
            "input CT '" + (dir / "nan.mha").string() + "': header field 'ElementSpacing' holds 'nan', not a finite number");
  for (const std::string& m : {nan, ErrorOf((dir / "truncated.nrrd").string())}) EXPECT_EQ(m.find('\n'), std::string::npos);
  fs::remove_all(dir);
}

// Found by fuzzing (issue 24): an infinite NRRD spacing or origin was let through to ITK; header
// sizes beyond a long long (NIfTI, MetaImage) were cast to one for the message (undefined
// behaviour); a NIfTI-2 dim[0] beyond an int was cast before it was checked.
TEST(ImageIO, FuzzFoundHeadersGiveClearErrors) {
  const fs::path dir = TempDir("fuzz");
  std::ofstream(dir / "inf.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                     "spacings: 0.7 inf 1\nencoding: raw\nendian: little\n\n" << std::string(16, '\0');
  EXPECT_EQ(ErrorOf((dir / "inf.nrrd").string()),
            "input CT '" + (dir / "inf.nrrd").string() + "': header field 'spacings:' holds an infinite number ('inf')");
  std::ofstream(dir / "huge.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                      "space: left-posterior-superior\nspace origin: (0,1e999,0)\nencoding: raw\nendian: little\n\n"
                                   << std::string(16, '\0');
  EXPECT_EQ(ErrorOf((dir / "huge.nrrd").string()), "input CT '" + (dir / "huge.nrrd").string() +
                                                       "': header field 'space origin:' holds an infinite number ('1e999')");
  std::ofstream(dir / "huge.mha") << "ObjectType = Image\nNDims = 3\nDimSize = 100000000000 100000000000 1000\n"
                                     "ElementType = MET_DOUBLE\nElementDataFile = LOCAL\n" << std::string(16, '\0');
  EXPECT_NE(ErrorOf((dir / "huge.mha").string()).find("huge.mha': is truncated: its voxel data holds 16 of 8"), std::string::npos);
  // NIfTI-1 with 7 axes of 32767 voxels (about 3e32 bytes), and a NIfTI-2 with dim[0] = 1e15.
  const auto put = [](std::string& h, std::size_t at, const auto value) { std::memcpy(&h[at], &value, sizeof value); };
  std::string one(352, '\0');
  put(one, 0, std::int32_t(348));
  put(one, 40, std::int16_t(7));
  for (int k = 1; k <= 7; ++k) put(one, 40 + 2 * k, std::int16_t(32767));
  put(one, 70, std::int16_t(64));
  put(one, 72, std::int16_t(64));
  for (int k = 0; k < 8; ++k) put(one, 76 + 4 * k, 1.0f);
  put(one, 108, 352.0f);
  one.replace(344, 4, std::string("n+1\0", 4));
  std::ofstream(dir / "huge.nii", std::ios::binary) << one;
  const std::string huge = ErrorOf((dir / "huge.nii").string());
  EXPECT_NE(huge.find("huge.nii': is truncated: 352 of 3244"), std::string::npos) << huge;
  std::string two(552, '\0');
  put(two, 0, std::int32_t(540));
  put(two, 16, std::int64_t(1000000000000000));
  std::ofstream(dir / "ndim.nii", std::ios::binary) << two;
  EXPECT_EQ(ErrorOf((dir / "ndim.nii").string()),
            "input CT '" + (dir / "ndim.nii").string() + "': NIfTI header has 1000000000000000 dimensions");
  // More spacings than axes: the note named axes 4 and 5 of a 3-D image.
  std::ofstream(dir / "many.mha") << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = 1 -1 1 -1 -1\n"
                                     "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" << std::string(16, '\0');
  std::vector<std::string> notes;
  io::ReadImage<short>((dir / "many.mha").string(), "input CT", [&](const std::string& n) { notes.push_back(n); });
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("many.mha': negative voxel spacing on axis 2 in the file"), std::string::npos) << notes[0];
  fs::remove_all(dir);
}

// Negative spacings in a header are read as positive spacings along flipped axes (as ITK and
// Slicer do), and the user is told in one note (issue 24); an ordinary file gets no note.
TEST(ImageIO, NegativeSpacingReadAsFlippedAxisWithOneNote) {
  const fs::path dir = TempDir("negative");
  std::ofstream(dir / "neg.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                     "spacings: 0.7 -0.8 1.5\nencoding: raw\nendian: little\n\n" << std::string(16, '\0');
  std::vector<std::string> notes;
  const Volume<short> v = io::ReadImage<short>((dir / "neg.nrrd").string(), "input CT",
                                               [&](const std::string& n) { notes.push_back(n); });
  EXPECT_TRUE(v.spacing.isApprox(Eigen::Vector3d(0.7, 0.8, 1.5), 1e-9));
  EXPECT_NEAR(v.direction(1, 1), -1.0, 1e-9);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("neg.nrrd': negative voxel spacing on axis 2"), std::string::npos) << notes[0];
  notes.clear();
  io::ReadImage<short>(kData + "/example_ct_dicom", "CT", [&](const std::string& n) { notes.push_back(n); });
  EXPECT_TRUE(notes.empty());
  fs::remove_all(dir);
}

// Voxel data shorter than the header says: MetaIO only complained on stderr (issue 24); a DICOM
// slice cut short: GDCM aborted the process.
TEST(ImageIO, CutShortMetaImageAndDicomSliceRefused) {
  const fs::path dir = TempDir("cut");
  std::ofstream(dir / "cut.mha") << "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementSpacing = 1 1 1\n"
                                    "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" << std::string(100, '\0');
  EXPECT_NE(ErrorOf((dir / "cut.mha").string()).find("cut.mha': is truncated: its voxel data holds 100 of 128 bytes"),
            std::string::npos);
  const fs::path series = dir / "series";
  fs::create_directories(series);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kData + "/example_ct_dicom")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) fs::copy_file(f, series / f.filename());
  const fs::path victim = series / files[5].filename();
  fs::permissions(victim, fs::perms::owner_write, fs::perm_options::add);
  fs::resize_file(victim, 2000);
  const std::string m = ErrorOf(series.string());
  EXPECT_NE(m.find("'" + series.string() + "': slice file '" + files[5].filename().string() + "' is cut short"),
            std::string::npos) << m;
  fs::remove_all(dir);
}

namespace {

std::string CheckErrorOf(const std::string& path) {
  try {
    io::CheckImageFile(path, "input CT");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// The door check of a pipeline's scans (issue 24): no voxels read, and for each problem it finds
// the very message ReadImage gives.
TEST(ImageIO, CheckImageFileReadsNoVoxelsAndSaysWhatReadImageSays) {
  const fs::path dir = TempDir("check");
  const auto path = [&](const char* name) { return (dir / name).string(); };
  const std::string header = "NRRD0004\ntype: short\nendian: little\nencoding: raw\n";
  // Compressed voxel data that is corrupt: only a voxel read can tell, so the check passes where
  // ReadImage fails (raw data cut short is found from the file size, by both).
  std::ofstream(path("bad_gzip.nrrd")) << "NRRD0004\ntype: short\nendian: little\nencoding: gzip\n"
                                       << "dimension: 3\nsizes: 64 64 64\n\n" << std::string("\x1f\x8b\x08\x00garbage", 12);
  EXPECT_EQ(CheckErrorOf(path("bad_gzip.nrrd")), "");
  EXPECT_NE(ErrorOf(path("bad_gzip.nrrd")).find("cannot be read"), std::string::npos);
  std::ofstream(path("short_voxels.nrrd")) << header << "dimension: 3\nsizes: 64 64 64\n\n" << std::string(100, '\0');
  for (const std::string& good : {kData + "/example_ct.nii.gz", kData + "/example_ct_dicom"})
    EXPECT_EQ(CheckErrorOf(good), "") << good;
  EXPECT_NO_THROW(io::CheckImageFile("slicer:0x1234#vtkMRMLScalarVolumeNode1", "input CT"));

  std::ofstream(path("x.unknownext")) << "hello";
  std::ofstream(path("nan.nrrd")) << header << "dimension: 3\nsizes: 2 2 2\nspacings: nan 1 1\n\n" << std::string(16, '\0');
  std::ofstream(path("four.nrrd")) << header << "dimension: 4\nsizes: 2 2 2 3\n\n" << std::string(48, '\0');
  std::ofstream(path("garbage.nrrd")) << "NRRD0004\nsizes: x y\n";
  std::ofstream(path("zero.mha")) << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = 0.7 0 1\n"
                                     "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" << std::string(16, '\0');
  std::ofstream(path("cut.nii"), std::ios::binary) << std::string(200, '\0');
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "no-dicom");
  std::ofstream(dir / "no-dicom" / "README.txt") << "no images here\n";
  const fs::path series = dir / "cut-series";
  fs::create_directories(series);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kData + "/example_ct_dicom")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) fs::copy_file(f, series / f.filename());
  fs::permissions(series / files[3].filename(), fs::perms::owner_write, fs::perm_options::add);
  fs::resize_file(series / files[3].filename(), 2000);
  for (const std::string& bad : {path("missing.nrrd"), path("short_voxels.nrrd"), path("x.unknownext"), path("nan.nrrd"), path("four.nrrd"),
                                path("garbage.nrrd"), path("zero.mha"), path("cut.nii"), path("empty"),
                                path("no-dicom"), series.string(), std::string()}) {
    const std::string m = CheckErrorOf(bad);
    EXPECT_NE(m, "") << bad;
    EXPECT_EQ(m, ErrorOf(bad)) << bad;
  }
  EXPECT_EQ(CheckErrorOf(path("four.nrrd")),
            "input CT '" + path("four.nrrd") + "': is a 4-D image (2 x 2 x 2 x 3 voxels), not a 3-D volume");
  fs::remove_all(dir);
}

// A pipeline's stages in one process hand volumes on in memory (Core/VolumeShelf.h): only the
// files the pipeline expects are kept, each for as many reads as it said, converted to the type
// asked for as a reader would, the last read taking it off the shelf; the rest come from the file.
TEST(ImageIO, ShelfHandsOnExpectedVolumesAndFallsBackToTheFile) {
  const fs::path dir = TempDir("shelf");
  Volume<unsigned char> label;
  label.size = {{3, 2, 2}};
  label.spacing = {0.7, 0.7, 1.0};
  label.Allocate(0);
  label.voxels[4] = 1;
  const std::string kept = (dir / "lumen.nrrd").string(), notKept = (dir / "other.nrrd").string();
  io::WriteImage(label, kept, "label");
  Volume<unsigned char> other = label;
  other.voxels[5] = 2;
  io::WriteImage(other, notKept, "label");
  // In memory the kept volume differs from its file, so where each read came from shows.
  Volume<unsigned char> inMemory = label;
  inMemory.voxels[0] = 7;

  VolumeShelf shelf;
  shelf.Expect(kept, 2);
  shelf.Put(kept, Volume<unsigned char>(inMemory));
  shelf.Put(notKept, Volume<unsigned char>(other));  // not expected: not kept
  const Volume<float> first = io::ReadImageKept<float>(&shelf, kept, "label");
  EXPECT_EQ(first.voxels[0], 7.0f);  // from the shelf, as float
  EXPECT_EQ(first.voxels[4], 1.0f);
  EXPECT_TRUE(first.spacing.isApprox(label.spacing));
  const Volume<unsigned char> second = io::ReadImageKept<unsigned char>(&shelf, kept, "label");
  EXPECT_EQ(second.voxels, inMemory.voxels);  // the second and last expected read
  EXPECT_EQ(io::ReadImageKept<unsigned char>(&shelf, kept, "label").voxels, label.voxels);  // now the file
  EXPECT_EQ(io::ReadImageKept<unsigned char>(&shelf, notKept, "label").voxels, other.voxels);
  EXPECT_EQ(io::ReadImageKept<unsigned char>(nullptr, kept, "label").voxels, label.voxels);

  // Mapped as it is taken (ColonSurface's lumen mask of one label): label 7 only.
  shelf.Expect(kept, 1);
  shelf.Put(kept, Volume<unsigned char>(inMemory));
  const std::optional<Volume<unsigned char>> mask =
      shelf.TakeMapped<unsigned char>(kept, [](unsigned char v) { return v == 7 ? 1 : 0; });
  ASSERT_TRUE(mask);
  EXPECT_EQ(std::count(mask->voxels.begin(), mask->voxels.end(), 1), 1);
  EXPECT_EQ(mask->voxels[0], 1);
  EXPECT_FALSE(shelf.TakeMapped<unsigned char>(kept, [](unsigned char v) { return v; }));  // taken: gone

  // Stages that only read a volume share the kept one (no copy), also with a stage that takes it:
  // the taker then gets a copy, and the sharers keep theirs after the last read.
  shelf.Expect(kept, 3);
  shelf.Put(kept, Volume<unsigned char>(inMemory));
  const std::shared_ptr<const Volume<unsigned char>> a = io::ReadImageShared<unsigned char>(&shelf, kept, "label");
  const std::shared_ptr<const Volume<unsigned char>> b = io::ReadImageShared<unsigned char>(&shelf, kept, "label");
  EXPECT_EQ(a.get(), b.get());  // one volume
  EXPECT_EQ(a->voxels, inMemory.voxels);
  const Volume<unsigned char> taken = io::ReadImageKept<unsigned char>(&shelf, kept, "label");  // the last read
  EXPECT_EQ(taken.voxels, inMemory.voxels);
  EXPECT_EQ(a->voxels, inMemory.voxels);  // not moved from under the sharers
  const std::shared_ptr<const Volume<float>> asFloat = io::ReadImageShared<float>(&shelf, kept, "label");  // gone: the file
  EXPECT_EQ(asFloat->voxels[0], 0.0f);
  shelf.Expect(kept, 1);
  shelf.Put(kept, Volume<unsigned char>(inMemory));
  EXPECT_EQ(io::ReadImageShared<float>(&shelf, kept, "label")->voxels[0], 7.0f);  // converted from the shelf

  // A conversion taken from the shelf polls the host between its pieces: a cancelled host stops it.
  RecordingProgress cancelling(1);
  shelf.Expect(kept, 1);
  shelf.Put(kept, Volume<unsigned char>(inMemory));
  EXPECT_THROW(io::ReadImageKept<float>(&shelf, kept, "label", {}, &cancelling), Cancelled);
  EXPECT_EQ(cancelling.fractions.size(), 1u);
  fs::remove_all(dir);
}
