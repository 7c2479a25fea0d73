// Image reading and writing: the real CT as NIfTI and as DICOM, round trips, bad inputs.
#include "Core/Error.h"
#include "IO/ImageIO.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace colonmap;

namespace {

const std::string kData = COLONMAP_SHARED_DIR "/data/totalseg-example-ct";

fs::path TempDir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("colonmap-imageio-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

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
  EXPECT_NE(ErrorOf((dir / "truncated.nrrd").string()).find("cannot be read"), std::string::npos);
  // NaN spacing.
  std::ofstream(dir / "nan.nrrd") << "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\n"
                                     "spacings: nan 1 1\nencoding: raw\nendian: little\n\n" << std::string(16, '\0');
  const std::string nan = ErrorOf((dir / "nan.nrrd").string());
  EXPECT_EQ(nan, "input CT '" + (dir / "nan.nrrd").string() + "': header field 'spacings:' holds NaN");
  std::ofstream(dir / "nan.mha") << "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = nan 1 1\n"
                                    "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" << std::string(16, '\0');
  EXPECT_NE(ErrorOf((dir / "nan.mha").string()).find("nan.mha': "), std::string::npos);
  for (const std::string& m : {nan, ErrorOf((dir / "truncated.nrrd").string())}) EXPECT_EQ(m.find('\n'), std::string::npos);
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
