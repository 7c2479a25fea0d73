#!/usr/bin/env python3
"""Bad inputs a user may hand the modules (issue 24), made here from the small test data: each
must give a non-zero exit, exactly one stderr line that names the user's file and the problem,
no output, and finish within seconds (no crash, no hang).

Cases: surfaces with a NaN or an infinite point coordinate (ColonLandmarks crashed on them), a
flat segment whose FlatUV holds NaN (ColonRegistration spun for minutes), a registration with
NaN barycentric coordinates or a triangle naming a point past the end (ColonTransferPoints moved
findings by up to 24 mm), .fcsv findings with NaN, infinite or unit-suffixed coordinates ("12.3mm"
was read as 12.3), a findings file without points (was an empty output and exit 0), and NIfTI CTs
with zero or NaN spacing or cut short (read as 1 mm, or as a partial image), and a DICOM series with
a slice missing (its z spacing was averaged without a word). Output folders (issue 23): ".",
"/" and someone else's non-empty folder, refused by each of the 7 modules that write a folder,
with the working folder and the other folder left as they were.

Then every file kind a module reads: images (missing, unknown format, NRRD/MetaImage/NIfTI cut
short or with bad spacing; DICOM series with a slice cut short, GDCM aborted the process on some,
or a slice of another size, made here as a small native series and from the shared JPEG 2000
series), outputs (unknown extension, unwritable or missing folder: the message names the user's
path, never our hidden temporary), surfaces, landmarks folders without a segment or taeniae.vtp
(ColonFlattening warned and exited 0) or with two segments swapped, registrations, stage reports
(landmarks.json, flattening.json, registration.json) with a field of the wrong type or missing, markups,
and the pipeline (a bad prone CT
refused before the first stage, not after the supine half; a failing stage names the user's
output folder, not the hidden stage folder). Last, valid but unusual inputs that
must work: MetaImage, NIfTI, negative spacings and a left-handed frame (read as flipped axes, with
one note on stdout), oblique NRRD and DICOM (geometry kept), native and JPEG 2000 DICOM, a legacy
.vtk surface, and findings in RAS (mapped where the same findings in LPS are).

Usage: bad_input_test.py <cli-modules folder> <TestData folder>
"""
import gzip
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

import vtk

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from colonmap_testing import Checks  # noqa: E402

cli, data = sys.argv[1], sys.argv[2]
checks = Checks()
check = checks.check
TIMEOUT = 60


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    out = vtk.vtkPolyData()
    out.DeepCopy(r.GetOutput())
    return out


def write(pd, path):
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(pd)
    w.Write()


def nifti(path, spacing=(1.0, 1.0, 1.0), size=(24, 20, 16), cut=0, gz=False):
    """A small NIfTI-1 CT (int16, -1000 HU air with a water block), optionally cut short by `cut` bytes."""
    hdr = bytearray(348)
    struct.pack_into("<i", hdr, 0, 348)
    struct.pack_into("<8h", hdr, 40, 3, *size, 1, 1, 1, 1)
    struct.pack_into("<hh", hdr, 70, 4, 16)  # datatype int16, bitpix
    struct.pack_into("<8f", hdr, 76, 1.0, *spacing, 1, 1, 1, 1)
    struct.pack_into("<f", hdr, 108, 352.0)
    struct.pack_into("<h", hdr, 252, 1)  # qform_code scanner
    struct.pack_into("<f", hdr, 112, 1.0)  # scl_slope
    hdr[344:348] = b"n+1\0"
    n = size[0] * size[1] * size[2]
    voxels = struct.pack(f"<{n}h", *[0 if (i // size[0]) % size[1] < 8 else -1000 for i in range(n)])
    blob = bytes(hdr) + b"\0" * 4 + voxels
    if gz:
        blob = gzip.compress(blob)
    open(path, "wb").write(blob[:len(blob) - cut] if cut else blob)


def _element(group, elem, vr, value):
    if isinstance(value, str):
        value = value.encode()
        if len(value) % 2:
            value += b"\0" if vr == "UI" else b" "
    if vr in ("OB", "OW", "SQ", "UN", "UT"):
        return struct.pack("<HH2sHI", group, elem, vr.encode(), 0, len(value)) + value
    return struct.pack("<HH2sH", group, elem, vr.encode(), len(value)) + value


def dicom_slice(path, k, rows=20, cols=24, series="1.2.826.0.1.3680043.9.7777.1", orientation=(1, 0, 0, 0, 1, 0), cut=0,
                headerless=False):
    """Slice k of a small native (uncompressed, explicit VR little endian) CT series, 0.7 x 0.7 x 1 mm,
    optionally cut short by `cut` bytes, optionally old-style (a data set without preamble and meta
    header, which GDCM reads too). The shared series is JPEG 2000: this one has plain pixel data."""
    sop = f"{series}.{k + 1}"
    u16 = lambda v: struct.pack("<H", v)  # noqa: E731
    meta = _element(2, 1, "OB", b"\0\1") + _element(2, 2, "UI", "1.2.840.10008.5.1.4.1.1.2") + \
        _element(2, 3, "UI", sop) + _element(2, 0x10, "UI", "1.2.840.10008.1.2.1")
    meta = _element(2, 0, "UL", struct.pack("<I", len(meta))) + meta
    r, c = orientation[:3], orientation[3:]
    normal = (r[1] * c[2] - r[2] * c[1], r[2] * c[0] - r[0] * c[2], r[0] * c[1] - r[1] * c[0])
    position = "\\".join(f"{k * x:.4f}" for x in normal)
    ds = _element(8, 0x16, "UI", "1.2.840.10008.5.1.4.1.1.2") + _element(8, 0x18, "UI", sop) + \
        _element(8, 0x60, "CS", "CT") + _element(0x10, 0x10, "PN", "Phantom^Bad") + _element(0x10, 0x20, "LO", "BAD24") + \
        _element(0x20, 0x0D, "UI", "1.2.826.0.1.3680043.9.7777") + _element(0x20, 0x0E, "UI", series) + \
        _element(0x20, 0x13, "IS", str(k + 1)) + _element(0x20, 0x32, "DS", position) + \
        _element(0x20, 0x37, "DS", "\\".join(f"{x:.6f}" for x in orientation)) + \
        _element(0x28, 0x02, "US", u16(1)) + _element(0x28, 0x04, "CS", "MONOCHROME2") + \
        _element(0x28, 0x10, "US", u16(rows)) + _element(0x28, 0x11, "US", u16(cols)) + \
        _element(0x28, 0x30, "DS", "0.7\\0.7") + _element(0x28, 0x100, "US", u16(16)) + \
        _element(0x28, 0x101, "US", u16(16)) + _element(0x28, 0x102, "US", u16(15)) + \
        _element(0x28, 0x103, "US", u16(1)) + _element(0x28, 0x1052, "DS", "0") + _element(0x28, 0x1053, "DS", "1")
    pixels = struct.pack(f"<{rows * cols}h", *[0 if j < rows // 2 else -1000 for j in range(rows) for i in range(cols)])
    blob = (b"" if headerless else b"\0" * 128 + b"DICM" + meta) + ds + _element(0x7FE0, 0x10, "OW", pixels)
    open(path, "wb").write(blob[:len(blob) - cut] if cut else blob)


def dicom_series(folder, slices=12, **kwargs):
    os.makedirs(folder, exist_ok=True)
    for k in range(slices):
        dicom_slice(os.path.join(folder, f"slice{k:03d}.dcm"), k, **kwargs)


def raw_image(path, header_fields, cut=0, size=(24, 20, 16)):
    """A small int16 NRRD (.nrrd) or MetaImage (.mha) with its voxels inline; header_fields set the geometry."""
    n = size[0] * size[1] * size[2]
    voxels = struct.pack(f"<{n}h", *[0 if (i // size[0]) % size[1] < 8 else -1000 for i in range(n)])
    if path.endswith(".nrrd"):
        header = ("NRRD0004\ntype: short\ndimension: 3\nsizes: %d %d %d\nendian: little\nencoding: raw\n" % size
                  + header_fields + "\n")
    else:
        header = ("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n" + header_fields
                  + "DimSize = %d %d %d\nElementType = MET_SHORT\nElementDataFile = LOCAL\n" % size)
    blob = header.encode() + voxels
    open(path, "wb").write(blob[:len(blob) - cut] if cut else blob)


def nrrd_geometry(path):
    """space directions and origin of a NRRD written by our modules."""
    fields = {}
    for line in open(path, "rb").read(4000).split(b"\n\n")[0].decode(errors="replace").splitlines():
        if ":" in line:
            key, value = line.split(":", 1)
            fields[key.strip()] = value.strip()
    return fields


bad_count, good_count = [0], [0]


def expect_refused(name, module, args, user_file, words, outputs, cwd=None):
    """Runs module with args (in folder cwd); checks the failure contract."""
    bad_count[0] += 1
    start = time.time()
    try:
        r = subprocess.run([os.path.join(cli, module)] + args, capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, timeout=TIMEOUT, cwd=cwd)
    except subprocess.TimeoutExpired:
        check(False, f"{name}: still running after {TIMEOUT} s (a hang)")
        return
    seconds = time.time() - start
    lines = r.stderr.strip().splitlines()
    print(f"{name}: exit {r.returncode} after {seconds:.1f} s: {r.stderr.strip()}")
    check(seconds < 15, f"{name}: refused only after {seconds:.0f} s (at the door means within seconds)")
    check(r.returncode > 0, f"{name}: exit {r.returncode} (a crash is negative, success 0)")
    check(len(lines) == 1, f"{name}: {len(lines)} stderr lines")
    check(user_file in r.stderr, f"{name}: the message does not name {user_file}")
    check(".colonmap-tmp" not in r.stderr, f"{name}: the message names our temporary, not the user's path")
    check(all(w in r.stderr for w in words), f"{name}: the message does not say {words}")
    for o in outputs:
        check(not os.path.exists(o), f"{name}: {o} left behind")
    return r


def expect_works(name, module, args, outputs, stdout_words=()):
    """Runs a valid but unusual input: exit 0, nothing on stderr, the outputs there, the notes said."""
    good_count[0] += 1
    start = time.time()
    try:
        r = subprocess.run([os.path.join(cli, module)] + args, capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        check(False, f"{name}: still running after {TIMEOUT} s (a hang)")
        return None
    print(f"{name}: exit {r.returncode} after {time.time() - start:.1f} s")
    check(r.returncode == 0 and not r.stderr.strip(), f"{name}: exit {r.returncode}: {r.stderr.strip()}")
    for o in outputs:
        check(os.path.exists(o), f"{name}: no {o}")
    for w in stdout_words:
        check(w in r.stdout, f"{name}: stdout does not say {w!r}")
    return r


work = tempfile.mkdtemp(prefix="colonmap-bad-input-")
try:
    # Surfaces with a non-finite point.
    surface = read(os.path.join(data, "landmarks-2mm", "supine_surface.vtp"))
    for label, value in (("nan", float("nan")), ("inf", float("inf"))):
        bad = vtk.vtkPolyData()
        bad.DeepCopy(surface)
        p = list(bad.GetPoint(17))
        p[1] = value
        bad.GetPoints().SetPoint(17, p)
        path = os.path.join(work, f"surface_{label}.vtp")
        write(bad, path)
        out = os.path.join(work, f"landmarks_{label}")
        expect_refused(f"surface with a {label} coordinate", "ColonLandmarks", [path, out], path,
                       ["point 17", "NaN or infinite"], [out])

    # A surface file that is not XML at all: VTK's parser printed its own log lines before ours.
    path = os.path.join(work, "garbage.vtp")
    open(path, "w").write("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" <<< not xml\n")
    out = os.path.join(work, "landmarks_garbage")
    expect_refused("surface that is not XML", "ColonLandmarks", [path, out], path, ["cannot be read"], [out])

    # A flat segment with NaN FlatUV.
    reg = os.path.join(data, "registration-2mm-96")
    supine = os.path.join(work, "supine-flat")
    shutil.copytree(os.path.join(reg, "supine"), supine)
    flat = read(os.path.join(supine, "flat_D.vtp"))
    uv = flat.GetPointData().GetArray("FlatUV")
    for i in range(0, uv.GetNumberOfTuples(), 97):
        uv.SetTuple2(i, float("nan"), 0.5)
    write(flat, os.path.join(supine, "flat_D.vtp"))
    out = os.path.join(work, "reg_nan")
    expect_refused("flat segment with NaN FlatUV", "ColonRegistration", [supine, os.path.join(reg, "prone"), out],
                   os.path.join(supine, "flat_D.vtp"), ["FlatUV", "NaN"], [out])

    # Two segments swapped in a flattening folder (was registered, mean error 76 mm).
    swapped = os.path.join(work, "supine-swapped")
    shutil.copytree(os.path.join(reg, "supine"), swapped)
    for a, b in (("flat_T.vtp", "tmp.vtp"), ("flat_D.vtp", "flat_T.vtp"), ("tmp.vtp", "flat_D.vtp")):
        os.rename(os.path.join(swapped, a), os.path.join(swapped, b))
    out = os.path.join(work, "reg_swapped")
    expect_refused("flattening folder with two segments swapped", "ColonRegistration",
                   [swapped, os.path.join(reg, "prone"), out], os.path.join(swapped, "flat_T.vtp"),
                   ["holds segment D", "not T"], [out])

    # Registrations with NaN barycentric coordinates, and with a triangle past the points.
    registration = read(os.path.join(reg, "registration", "registration.vtp"))
    prone_mesh = os.path.join(reg, "registration", "registration_prone.vtp")
    findings = os.path.join(reg, "supine_polyps.mrk.json")
    def nan_barycentric(pd):
        pd.GetPointData().GetArray("ProneBarycentric").SetTuple3(5, float("nan"), 0.5, 0.5)

    def index_past_end(pd):
        pd.GetPolys().GetConnectivityArray().SetValue(4, pd.GetNumberOfPoints() + 10)

    for label, spoil, words in (("NaN barycentric coordinates", nan_barycentric, ["ProneBarycentric", "NaN"]),
                                ("a triangle past the points", index_past_end, ["polygon 1", "names point"])):
        bad = vtk.vtkPolyData()
        bad.DeepCopy(registration)
        spoil(bad)
        path = os.path.join(work, f"registration_{spoil.__name__}.vtp")
        write(bad, path)
        out = os.path.join(work, f"out_{spoil.__name__}.mrk.json")
        expect_refused(f"registration with {label}", "ColonTransferPoints",
                       ["--registration", path, "--proneMesh", prone_mesh, "--input", findings, "--output", out], path,
                       words, [out])

    # Findings: .fcsv rows with bad coordinates; a list without points.
    header = "# Markups fiducial file version = 4.11\n# CoordinateSystem = LPS\n" \
             "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n"
    good_row = "1,10.0,20.0,30.0,0,0,0,1,1,1,0,F1,,\n"
    for label, row, words in (("nan", "2,nan,20.0,30.0,0,0,0,1,1,1,0,F2,,\n", ["row 2", "NaN or infinite"]),
                              ("inf", "2,1.0,inf,30.0,0,0,0,1,1,1,0,F2,,\n", ["row 2", "NaN or infinite"]),
                              ("unit", "2,1.0,2.0,12.3mm,0,0,0,1,1,1,0,F2,,\n", ["row 2", "'12.3mm' is not a number"])):
        path = os.path.join(work, f"findings_{label}.fcsv")
        open(path, "w").write(header + good_row + row)
        out = os.path.join(work, f"mapped_{label}.mrk.json")
        expect_refused(f"findings with a {label} coordinate", "ColonTransferPoints",
                       ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", path,
                        "--output", out], path, words, [out])
    # The whole pipeline reads its findings and truth before the first stage.
    phantom = os.path.join(data, "phantom-2.5mm")
    bad_findings = os.path.join(work, "findings_unit.fcsv")
    out = os.path.join(work, "pipeline_bad_findings")
    expect_refused("pipeline with bad findings", "ColonSupineProne",
                   ["--supine", os.path.join(phantom, "supine.nrrd"), "--prone", os.path.join(phantom, "prone.nrrd"),
                    "--outputDirectory", out, "--findings", bad_findings, "--skipViews"], bad_findings, ["'12.3mm'"], [out])
    truth = os.path.join(work, "truth")
    shutil.copytree(phantom, truth, ignore=shutil.ignore_patterns("*.nrrd", "*.vtp"))
    open(os.path.join(truth, "prone_eval.mrk.json"), "w").write("{ not json")
    out = os.path.join(work, "pipeline_bad_truth")
    expect_refused("pipeline with a corrupt truth file", "ColonSupineProne",
                   ["--supine", os.path.join(phantom, "supine.nrrd"), "--prone", os.path.join(phantom, "prone.nrrd"),
                    "--outputDirectory", out, "--groundTruth", truth, "--skipViews"],
                   os.path.join(truth, "prone_eval.mrk.json"), [], [out])
    empty = os.path.join(work, "findings_empty.mrk.json")
    doc = json.load(open(findings))
    doc["markups"][0]["controlPoints"] = []
    json.dump(doc, open(empty, "w"))
    out = os.path.join(work, "mapped_empty.mrk.json")
    expect_refused("findings without points", "ColonTransferPoints",
                   ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", empty, "--output", out],
                   empty, ["holds no points"], [out])

    # NIfTI: a valid small file reads; zero and NaN spacing, a cut file and a cut gzip
    # stream are refused (ITK read them as 1 mm and as partial images).
    good = os.path.join(work, "ct.nii.gz")
    nifti(good, gz=True)
    r = subprocess.run([os.path.join(cli, "ColonCleansing"), good, os.path.join(work, "good_cleansed.nrrd")],
                       capture_output=True, text=True, timeout=TIMEOUT)
    check(r.returncode == 0, f"valid NIfTI: {r.stderr}")
    for label, kwargs, words in (("zero spacing", {"spacing": (0.7, 0.0, 1.0)}, ["voxel spacing 2", "is 0"]),
                                 ("NaN spacing", {"spacing": (float("nan"), 0.7, 1.0)}, ["voxel spacing 1", "NaN"]),
                                 ("cut file", {"cut": 3000}, ["truncated"]),
                                 ("cut gzip stream", {"cut": 40, "gz": True}, [])):
        path = os.path.join(work, label.replace(" ", "_") + (".nii.gz" if kwargs.get("gz") else ".nii"))
        nifti(path, **kwargs)
        out = os.path.join(work, label.replace(" ", "_") + "_cleansed.nrrd")
        expect_refused(f"NIfTI with a {label}", "ColonCleansing", [path, out], path, words, [out])

    # Output folders: "." (what Slicer passes for a folder left unset), "/", someone else's folder.
    here = os.path.join(work, "working-folder")
    os.makedirs(here)
    foreign = os.path.join(work, "someone-else")
    os.makedirs(foreign)
    open(os.path.join(foreign, "thesis.tex"), "w").write("x")
    ct = os.path.join(data, "phantom-2.5mm")
    folder_calls = {
        "ColonPhantom": lambda o: ["--outputDirectory", o],
        "ColonLandmarks": lambda o: [os.path.join(data, "landmarks-2mm", "supine_surface.vtp"), o],
        "ColonFlattening": lambda o: [os.path.join(reg, "landmarks", "supine"), o],
        "ColonRegistration": lambda o: [os.path.join(reg, "supine"), os.path.join(reg, "prone"), o],
        "ColonFlatViews": lambda o: [os.path.join(reg, "supine"), os.path.join(reg, "prone"), os.path.join(reg, "registration"), o],
        "ColonEndoluminalViews": lambda o: ["--supineVolume", os.path.join(ct, "supine.nrrd"), "--proneVolume",
                                            os.path.join(ct, "prone.nrrd"), "--registration",
                                            os.path.join(reg, "registration", "registration.vtp"), "--findings", findings, o],
        "ColonSupineProne": lambda o: ["--supine", os.path.join(ct, "supine.nrrd"), "--prone", os.path.join(ct, "prone.nrrd"),
                                       "--outputDirectory", o],
    }
    for module, call in folder_calls.items():
        for folder, words in ((".", ["current folder"]), ("/", ["root of the file system"]),
                              (foreign, ["not empty", "no ColonMap output", "thesis.tex"])):
            expect_refused(f"{module} into {folder}", module, call(folder), f"output folder '{folder}'", words, [], cwd=here)
        check(os.listdir(here) == [] and os.listdir(foreign) == ["thesis.tex"], f"{module}: wrote into a refused folder")

    # A DICOM series with a slice missing (ITK averaged the z spacing and only warned).
    shared = os.path.join(os.path.dirname(os.path.abspath(__file__)), *[".."] * 3, "shared", "data",
                          "totalseg-example-ct", "example_ct_dicom")
    if os.path.isdir(shared):
        series = os.path.join(work, "dicom-missing")
        files = sorted(os.listdir(shared))
        os.makedirs(series)
        for f in files:
            shutil.copy(os.path.join(shared, f), series)
        middle = files[len(files) // 2]  # the names number the slices in order: this one is inside the stack
        os.remove(os.path.join(series, middle))
        out = os.path.join(work, "dicom_cleansed.nrrd")
        expect_refused("DICOM series with a slice missing", "ColonCleansing", [series, out], series,
                       ["not evenly spaced"], [out])
    else:
        check(False, f"no shared DICOM series at {shared}")

    # --- Images, every file kind (issue 24): refused at the door, one line naming the user's file.
    cleanse = lambda path, out: ["ColonCleansing", [path, out]]  # noqa: E731
    images = os.path.join(work, "images")
    os.makedirs(images)
    def image_case(name, filename, make, words, module="ColonCleansing", user_file=None):
        path = os.path.join(images, filename)
        make(path)
        out = os.path.join(images, filename.replace(".", "_").replace("/", "_") + "_out.nrrd")
        expect_refused(name, module, [path, out], user_file or path, words, [out])

    image_case("image that does not exist", "missing.nrrd", lambda p: None, ["does not exist"])
    image_case("image of an unknown format", "ct.xyz", lambda p: open(p, "w").write("not an image\n"),
               ["unknown or unsupported image format"])
    image_case("NRRD with NaN spacing", "nan_spacing.nrrd", lambda p: raw_image(p, "spacings: nan 0.7 1\n"),
               ["spacings", "NaN"])
    image_case("NRRD cut short", "cut.nrrd", lambda p: raw_image(p, "spacings: 0.7 0.7 1\n", cut=2000), ["is truncated"])
    image_case("NRRD header garbage", "garbage.nrrd", lambda p: open(p, "w").write("NRRD0004\nsizes: x y\n"),
               ["cannot be read"])
    image_case("MetaImage cut short", "cut.mha", lambda p: raw_image(p, "ElementSpacing = 0.7 0.7 1\n", cut=2000),
               ["truncated", "13360 of 15360 bytes"])
    def detached(p):
        open(p, "w").write("ObjectType = Image\nNDims = 3\nDimSize = 24 20 16\nElementSpacing = 0.7 0.7 1\n"
                           "ElementType = MET_SHORT\nElementDataFile = voxels.raw\n")
        open(os.path.join(os.path.dirname(p), "voxels.raw"), "wb").write(b"\0" * 1000)
    image_case("MetaImage whose data file is cut short", "detached.mhd", detached, ["voxels.raw", "truncated"])
    image_case("MetaImage with zero spacing", "zero.mha", lambda p: raw_image(p, "ElementSpacing = 0.7 0 1\n"),
               ["spacing"])
    image_case("MetaImage with NaN spacing", "nan.mha", lambda p: raw_image(p, "ElementSpacing = 0.7 nan 1\n"),
               ["ElementSpacing", "'nan', not a finite number"])
    def detached_nrrd(p):
        open(p, "w").write("NRRD0004\ntype: short\ndimension: 3\nsizes: 24 20 16\nencoding: raw\nendian: little\n"
                           "data file: voxels_nrrd.raw\n")
        open(os.path.join(os.path.dirname(p), "voxels_nrrd.raw"), "wb").write(b"\0" * 1000)
    image_case("NRRD whose data file is cut short", "detached.nhdr", detached_nrrd,
               ["voxels_nrrd.raw", "truncated", "1000 of 15360 bytes"])
    image_case("NIfTI with an infinite spacing", "inf.nii", lambda p: nifti(p, spacing=(0.7, float("inf"), 1.0)),
               ["voxel spacing 2", "infinite"])
    image_case("NIfTI shorter than its header", "short.nii", lambda p: open(p, "wb").write(b"\0" * 100),
               ["too short for a NIfTI header"])
    image_case("file that is not NIfTI", "text.nii", lambda p: open(p, "wb").write(b"hello" * 100),
               ["not a NIfTI file"])
    image_case("cut NIfTI to ColonSegmentation", "cut_seg.nii", lambda p: nifti(p, cut=500), ["truncated"],
               module="ColonSegmentation")
    image_case("cut NIfTI label map to ColonSurface", "cut_label.nii.gz", lambda p: nifti(p, cut=40, gz=True), [],
               module="ColonSurface")
    image_case("label map with zero spacing to ColonSurface", "zero_label.nii", lambda p: nifti(p, spacing=(0, 1, 1)),
               ["is 0"], module="ColonSurface")

    # DICOM: a native slice cut short (was read as a partial image), the shared JPEG 2000 series with
    # a slice cut before its pixel data (GDCM aborted the process), a slice of another size (was
    # dropped into a series of its own), a folder without DICOM.
    def dicom_case(name, folder, words):
        out = os.path.join(images, os.path.basename(folder) + "_out.nrrd")
        expect_refused(name, "ColonCleansing", [folder, out], folder, words, [out])

    native = os.path.join(images, "dicom-native-cut")
    dicom_series(native)
    dicom_slice(os.path.join(native, "slice005.dcm"), 5, cut=100)
    dicom_case("DICOM series with a native slice cut short", native, ["slice005.dcm", "cut short"])
    native = os.path.join(images, "dicom-pixels-short")
    dicom_series(native)
    dicom_slice(os.path.join(native, "slice007.dcm"), 7, cut=1)
    dicom_case("DICOM series with a slice one byte short", native, ["slice007.dcm", "cut short"])
    for label, cut in (("in its pixel data", 100), ("in its elements", 250)):
        native = os.path.join(images, "dicom-headerless-cut-" + label.split()[-1])
        dicom_series(native)
        dicom_slice(os.path.join(native, "slice006.dcm"), 6, headerless=True, cut=cut)
        dicom_case(f"DICOM series with an old-style slice (no preamble) cut {label}", native, ["slice006.dcm", "cut short"])
    native = os.path.join(images, "dicom-other-size")
    dicom_series(native)
    dicom_slice(os.path.join(native, "slice004.dcm"), 4, rows=18)
    dicom_case("DICOM series with a slice of another size", native, ["slice004.dcm", "18 rows x 24 columns", "20 x 24"])
    native = os.path.join(images, "dicom-first-other-size")
    dicom_series(native)
    dicom_slice(os.path.join(native, "slice000.dcm"), 0, cols=30)
    dicom_case("DICOM series whose first slice has another size", native, ["slice000.dcm", "30 columns"])
    native = os.path.join(images, "dicom-none")
    os.makedirs(native)
    open(os.path.join(native, "README.txt"), "w").write("no images here\n")
    dicom_case("folder without DICOM", native, ["holds no DICOM series"])
    if os.path.isdir(shared):
        files = sorted(os.listdir(shared))
        for label, size in (("in its header", 2000), ("in its meta header", 300), ("in its pixel data", 100000)):
            series = os.path.join(images, "dicom-cut-" + label.split()[-2])
            os.makedirs(series)
            for f in files:
                shutil.copy(os.path.join(shared, f), series)
            victim = os.path.join(series, files[len(files) // 2])
            os.chmod(victim, 0o644)
            os.truncate(victim, size)
            dicom_case(f"JPEG 2000 DICOM series with a slice cut {label}", series, [files[len(files) // 2], "cut short"])

    # --- Outputs: the user's name in the message, never our hidden temporary (issue 24).
    ct = os.path.join(phantom, "supine.nrrd")
    out = os.path.join(work, "cleansed.xyz")
    expect_refused("CT output with an unknown extension", "ColonCleansing", [ct, out], out,
                   ["unknown or unsupported image format"], [out])
    out = os.path.join(work, "surface.xyz")
    expect_refused("surface output with an unknown extension", "ColonSurface",
                   [os.path.join(data, "landmarks-2mm", "supine_label.nrrd"), out], out, ["unknown surface format"], [out])
    if os.path.isdir("/proc/self"):  # a folder nobody may create files in, even root (the tests may run as root)
        expect_refused("CT output into an unwritable folder", "ColonCleansing", [ct, "/proc/cleansed.nrrd"],
                       "/proc/cleansed.nrrd", ["cannot be written"], [])
    out = os.path.join(work, "mapped.txt")
    expect_refused("points output with an unknown extension", "ColonTransferPoints",
                   ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", findings,
                    "--output", out], out, ["unknown point list format"], [out])
    out = os.path.join(work, "no-such-folder", "mapped.mrk.json")
    expect_refused("points output into a missing folder", "ColonTransferPoints",
                   ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", findings,
                    "--output", out], out, ["folder does not exist"], [out])
    out = os.path.join(work, "findings.mrk.json.d")
    os.makedirs(out)
    expect_refused("points output that is a folder", "ColonTransferPoints",
                   ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", findings,
                    "--output", out], out, ["is a folder"], [])
    os.rmdir(out)

    # --- Surfaces and polylines.
    surfaces = os.path.join(work, "surfaces")
    os.makedirs(surfaces)
    def landmarks_case(name, filename, make, words):
        path = os.path.join(surfaces, filename)
        make(path)
        out = os.path.join(surfaces, filename.replace(".", "_") + "_landmarks")
        expect_refused(name, "ColonLandmarks", [path, out], path, words, [out])

    landmarks_case("surface that does not exist", "missing.vtp", lambda p: None, ["does not exist"])
    landmarks_case("surface of an unknown format", "surface.obj", lambda p: open(p, "w").write("v 0 0 0\n"),
                   ["unknown surface format"])
    landmarks_case("legacy .vtk surface that is garbage", "garbage.vtk", lambda p: open(p, "w").write("# vtk DataFile\nno\n"),
                   [])
    # Legacy files VTK's own reader trusted (our reader checks every count): a binary surface cut
    # short in its triangles, and an ASCII one whose polygon names a point past the end.
    def legacy(p, binary):
        w = vtk.vtkPolyDataWriter()
        w.SetInputData(surface)
        w.SetFileName(p)
        if binary:
            w.SetFileTypeToBinary()
        w.Write()
    def legacy_cut(p):
        legacy(p, True)
        data = open(p, "rb").read()
        open(p, "wb").write(data[:data.index(b"CONNECTIVITY") + 40])
    landmarks_case("legacy .vtk surface cut short", "cut.vtk", legacy_cut, ["cut short"])
    def legacy_past_end(p):
        legacy(p, False)
        text = open(p).read()
        start = text.index("\n", text.index("CONNECTIVITY")) + 1
        first = text.index(" ", start)
        open(p, "w").write(text[:start] + "999999" + text[first:])
    landmarks_case("legacy .vtk surface naming a point past the end", "past_end.vtk", legacy_past_end,
                   ["naming point 999999"])
    def past_end(p):
        bad = vtk.vtkPolyData()
        bad.DeepCopy(surface)
        bad.GetPolys().GetConnectivityArray().SetValue(7, bad.GetNumberOfPoints() + 3)
        write(bad, p)
    landmarks_case("surface with a triangle past the points", "past_end.vtp", past_end, ["polygon 2", "names point"])
    def points_only(p):
        bad = vtk.vtkPolyData()
        bad.SetPoints(surface.GetPoints())
        write(bad, p)
    landmarks_case("surface without triangles", "points_only.vtp", points_only, ["holds no triangles"])
    landmarks_case("empty surface", "empty.vtp", lambda p: write(vtk.vtkPolyData(), p), ["holds no points"])

    # --- Landmarks folders given to ColonFlattening: all five segments and taeniae.vtp, or refused.
    lm_folder = os.path.join(reg, "landmarks", "supine")
    def flattening_case(name, spoil, words, user_file=None):
        folder = os.path.join(work, "lm-" + name.replace(" ", "-"))
        shutil.copytree(lm_folder, folder)
        spoil(folder)
        out = os.path.join(work, "flat-" + name.replace(" ", "-"))
        expect_refused(name, "ColonFlattening", [folder, out], user_file(folder) if user_file else folder, words, [out])

    flattening_case("landmarks folder without segment T", lambda f: os.remove(os.path.join(f, "segment_T.vtp")),
                    ["segment_T.vtp is missing"])
    flattening_case("landmarks folder without taeniae.vtp", lambda f: os.remove(os.path.join(f, "taeniae.vtp")),
                    ["taeniae.vtp is missing"])
    flattening_case("landmarks folder with a garbage segment",
                    lambda f: open(os.path.join(f, "segment_D.vtp"), "w").write("<VTKFile <<<"),
                    ["cannot be read"], lambda f: os.path.join(f, "segment_D.vtp"))
    flattening_case("landmarks folder with garbage taeniae",
                    lambda f: open(os.path.join(f, "taeniae.vtp"), "w").write("<VTKFile <<<"),
                    ["cannot be read"], lambda f: os.path.join(f, "taeniae.vtp"))
    def swap_segments(f):  # was flattened and registered as if T were D (issue 24)
        for a, b in (("segment_T.vtp", "tmp.vtp"), ("segment_D.vtp", "segment_T.vtp"), ("tmp.vtp", "segment_D.vtp")):
            os.rename(os.path.join(f, a), os.path.join(f, b))
    flattening_case("landmarks folder with two segments swapped", swap_segments, ["holds segment D", "not T"],
                    lambda f: os.path.join(f, "segment_T.vtp"))
    flattening_case("landmarks folder whose landmarks.json has a number for pairedWith",  # was a json type_error
                    lambda f: json.dump({"jointChoice": {"pairedWith": 7, "consistent": True, "fallback": False}},
                                        open(os.path.join(f, "landmarks.json"), "w")),
                    ["'jointChoice.pairedWith' is a number, not a string"], lambda f: os.path.join(f, "landmarks.json"))
    missing = os.path.join(work, "no-landmarks-here")
    expect_refused("landmarks folder that does not exist", "ColonFlattening", [missing, os.path.join(work, "flat-x")],
                   missing, ["does not exist"], [os.path.join(work, "flat-x")])

    # --- Registration inputs.
    out = os.path.join(work, "reg-missing")
    expect_refused("prone flattening folder that does not exist", "ColonRegistration",
                   [os.path.join(reg, "supine"), os.path.join(work, "no-prone"), out], os.path.join(work, "no-prone"), [],
                   [out])
    # Stage reports handed on with a field of the wrong type (IO/StageReports): refused naming the report.
    def spoil_report(folder, file, spoil):
        path = os.path.join(folder, file)
        report = json.load(open(path))
        spoil(report)
        json.dump(report, open(path, "w"))
        return path
    wrong_width = os.path.join(work, "supine-width-string")
    shutil.copytree(os.path.join(reg, "supine"), wrong_width)
    report = spoil_report(wrong_width, "flattening.json", lambda j: j["segments"]["A"].update(flatWidth="1.0"))
    out = os.path.join(work, "reg-width-string")
    expect_refused("flattening.json with a string for a flat width", "ColonRegistration",
                   [wrong_width, os.path.join(reg, "prone"), out], report,
                   ["'segments.A.flatWidth' is a string, not a number"], [out])
    # A width of the right type but not the map's own (a hand edit, another segment's report): it
    # wrapped the map by the wrong period without a word, and sized ColonFlatViews' pictures.
    other_width = os.path.join(work, "supine-width-not-the-maps")
    shutil.copytree(os.path.join(reg, "supine"), other_width)
    report = spoil_report(other_width, "flattening.json",
                          lambda j: j["segments"]["A"].update(flatWidth=j["segments"]["A"]["flatWidth"] * 1000))
    out = os.path.join(work, "reg-width-not-the-maps")
    expect_refused("flattening.json with a flat width its map contradicts", "ColonRegistration",
                   [other_width, os.path.join(reg, "prone"), out], report,
                   ["gives segment A a flat width of"], [out])
    no_prone_uv = os.path.join(work, "registration-match-without-proneUV")
    shutil.copytree(os.path.join(reg, "registration"), no_prone_uv)
    report = spoil_report(no_prone_uv, "registration.json",  # read through a missing key before (undefined behaviour)
                          lambda j: j["segments"]["A"].update(features={"matches": [{"label": "FA1", "supineUV": [0.5, 0.5]}]}))
    out = os.path.join(work, "flatviews-match-without-proneUV")
    expect_refused("registration.json with a fold match without proneUV", "ColonFlatViews",
                   [os.path.join(reg, "supine"), os.path.join(reg, "prone"), no_prone_uv, out], report,
                   ["'segments.A.features.matches[0].proneUV' is missing"], [out])
    nan_points = os.path.join(work, "registration_nan_point.vtp")
    bad = vtk.vtkPolyData()
    bad.DeepCopy(registration)
    bad.GetPoints().SetPoint(3, (float("nan"), 0, 0))
    write(bad, nan_points)
    out = os.path.join(work, "mapped_nan_point.mrk.json")
    expect_refused("registration with a NaN point", "ColonTransferPoints",
                   ["--registration", nan_points, "--proneMesh", prone_mesh, "--input", findings, "--output", out],
                   nan_points, ["point 3", "NaN or infinite"], [out])
    missing = os.path.join(work, "no-registration.vtp")
    out = os.path.join(work, "mapped_noreg.mrk.json")
    expect_refused("registration that does not exist", "ColonTransferPoints",
                   ["--registration", missing, "--input", findings, "--output", out], missing, ["does not exist"], [out])

    # --- Markups.
    def markups_case(name, filename, text, words):
        path = os.path.join(work, filename)
        open(path, "w").write(text)
        out = os.path.join(work, "mapped_" + filename.replace(".", "_") + ".mrk.json")
        expect_refused(name, "ColonTransferPoints",
                       ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", path,
                        "--output", out], path, words, [out])

    markups_case("markups that are not JSON", "broken.mrk.json", "{ \"markups\": [", ["is not valid JSON"])
    markups_case("JSON that is not markups", "other.mrk.json", "{\"points\": []}", ["not a Slicer markups file"])
    markups_case("markups in an unknown frame", "frame.mrk.json",
                 json.dumps({"markups": [{"coordinateSystem": "IJK", "controlPoints": [{"position": [1, 2, 3]}]}]}),
                 ["unknown coordinateSystem 'IJK'"])
    markups_case("markups with a position of two numbers", "two.mrk.json",
                 json.dumps({"markups": [{"coordinateSystem": "LPS", "controlPoints": [{"position": [1, 2]}]}]}),
                 ["not 3 numbers"])
    markups_case(".fcsv with too few columns", "short.fcsv", header + "1,10.0,20.0\n", ["fewer than 4 columns"])
    markups_case("point list of an unknown format", "points.txt", "1 2 3\n", ["unknown point list format"])
    missing = os.path.join(work, "no-truth.mrk.json")
    out = os.path.join(work, "errors.json")
    expect_refused("evaluation truth that does not exist", "ColonEvaluateRegistration",
                   ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--truthSupine", missing,
                    "--truthProne", os.path.join(reg, "prone_eval.mrk.json"), "--output", out], missing, ["does not exist"],
                   [out])

    # --- The whole pipeline: inputs checked before the first stage; a failing stage names the
    # user's output folder, never the hidden stage folder.
    missing = os.path.join(work, "no-supine.nrrd")
    out = os.path.join(work, "pipeline_missing")
    expect_refused("pipeline with a supine CT that does not exist", "ColonSupineProne",
                   ["--supine", missing, "--prone", os.path.join(phantom, "prone.nrrd"), "--outputDirectory", out,
                    "--skipViews"], missing, ["does not exist"], [out])
    # A bad prone CT was found only by the prone cleansing stage, after the whole supine half; now
    # both scans are checked (header, no voxels) before the first stage. The 1.2 mm supine takes
    # seconds per stage here, so a refusal within 5 s and without a stage start is at the door.
    def four_d(p):
        n = 24 * 20 * 16 * 2
        open(p, "wb").write(b"NRRD0004\ntype: short\ndimension: 4\nsizes: 24 20 16 2\nendian: little\nencoding: raw\n"
                            b"spacings: 0.7 0.7 1 1\n\n" + struct.pack(f"<{n}h", *[-1000] * n))
    good_supine = os.path.join(data, "phantom-1.2mm", "supine.nrrd")
    for label, filename, make, words in (
            ("a truncated NIfTI", "cut.nii", lambda p: nifti(p, cut=3000), ["truncated"]),
            ("NaN spacing", "nan.nrrd", lambda p: raw_image(p, "spacings: nan 0.7 1\n"), ["spacings", "NaN"]),
            ("an unknown format", "ct.xyz", lambda p: open(p, "w").write("not an image\n"),
             ["unknown or unsupported image format"]),
            ("a 4-D image", "four.nrrd", four_d, ["4-D image", "24 x 20 x 16 x 2"]),
            ("an empty folder", "empty-folder", os.makedirs, ["holds no DICOM series"])):
        bad_prone = os.path.join(work, "prone_" + filename)
        make(bad_prone)
        out = os.path.join(work, "pipeline_prone_" + filename.replace(".", "_"))
        start = time.time()
        r = expect_refused(f"pipeline with a prone CT of {label}", "ColonSupineProne",
                           ["--supine", good_supine, "--prone", bad_prone, "--outputDirectory", out, "--skipViews"],
                           bad_prone, ["prone scan '"] + words, [out])
        if r is not None:
            check(time.time() - start < 5, f"pipeline with a prone CT of {label}: refused after {time.time() - start:.1f} s")
            check("<filter-start>" not in r.stdout, f"pipeline with a prone CT of {label}: a stage ran first")

    tiny = os.path.join(work, "tiny.nii.gz")
    nifti(tiny, gz=True)
    out = os.path.join(work, "pipeline_stage_fails")
    expect_refused("pipeline whose segmentation stage fails", "ColonSupineProne",
                   ["--supine", tiny, "--prone", tiny, "--outputDirectory", out, "--skipViews"], out,
                   ["ColonSegmentation"], [out])

    # A negative spacing is noted once per scan (both scans are this file here; the prone one runs
    # side by side with the supine one until its failure stops it), about the user's file, not
    # again for each stage's intermediate.
    tiny = os.path.join(work, "tiny_negative.nii")
    nifti(tiny, spacing=(-0.7, 0.7, 1.0))
    out = os.path.join(work, "pipeline_negative")
    r = expect_refused("pipeline on a negative-spacing CT without colon", "ColonSupineProne",
                       ["--supine", tiny, "--prone", tiny, "--outputDirectory", out, "--skipViews"], out,
                       ["ColonSegmentation", "no distended colon"], [out])
    if r is not None:
        notes = [line for line in r.stdout.splitlines() if "note:" in line]
        scans = [n.split(":")[0] for n in notes]
        check(1 <= len(notes) <= 2 and scans[0] == "supine" and len(set(scans)) == len(scans)
              and all(tiny in n and "negative voxel spacing on axis 1" in n for n in notes)
              and ".colonmap-tmp" not in r.stdout, f"pipeline on a negative-spacing CT: notes {notes}")

    # --- Valid but unusual inputs: they must work.
    unusual = os.path.join(work, "unusual")
    os.makedirs(unusual)
    for label, filename, make, note in (
            ("MetaImage", "ct.mha", lambda p: raw_image(p, "ElementSpacing = 0.7 0.7 1\n"), None),
            ("NIfTI", "ct.nii", lambda p: nifti(p), None),
            ("NIfTI with a negative spacing", "neg.nii", lambda p: nifti(p, spacing=(-0.7, 0.7, 1.0)),
             "negative voxel spacing on axis 1"),
            ("NRRD with a negative spacing", "neg.nrrd", lambda p: raw_image(p, "spacings: 0.7 -0.7 1\n"),
             "negative voxel spacing on axis 2"),
            ("MetaImage with a negative spacing", "neg.mha", lambda p: raw_image(p, "ElementSpacing = 0.7 0.7 -1\n"),
             "negative voxel spacing on axis 3"),
            ("NRRD with a left-handed frame", "flipped.nrrd",
             lambda p: raw_image(p, "space: left-posterior-superior\nspace directions: (-0.7,0,0) (0,0.7,0) (0,0,1)\n"
                                    "space origin: (0,0,0)\n"), "left-handed frame"),
            ("oblique NRRD", "oblique.nrrd",
             lambda p: raw_image(p, "space: left-posterior-superior\nspace directions: (0.606218,0.35,0) "
                                    "(-0.35,0.606218,0) (0,0,1)\nspace origin: (10,-20,30)\n"), None)):
        path = os.path.join(unusual, filename)
        make(path)
        out = os.path.join(unusual, filename.replace(".", "_") + "_cleansed.nrrd")
        r = expect_works(label, "ColonCleansing", [path, out], [out], [note, path] if note else [])
        if r and not note:
            check("note:" not in r.stdout, f"{label}: a note about an ordinary file: {r.stdout}")
    geometry = nrrd_geometry(os.path.join(unusual, "oblique_nrrd_cleansed.nrrd"))
    check(geometry.get("space directions", "").startswith("(0.60621") and "(10,-20,30)" in geometry.get("space origin", ""),
          f"oblique NRRD: geometry not kept: {geometry}")
    geometry = nrrd_geometry(os.path.join(unusual, "neg_nrrd_cleansed.nrrd"))
    check("(0,-0.7" in geometry.get("space directions", "").replace("0.69999999999999996", "0.7"),
          f"NRRD with a negative spacing: axis 2 not read as flipped: {geometry}")
    for label, folder, kwargs, direction in (("native DICOM", "dicom-native", {}, "(0.69999"),
                                             ("oblique DICOM", "dicom-oblique",
                                              {"orientation": (0.866025, 0.5, 0, -0.5, 0.866025, 0)}, "(0.60621")):
        series = os.path.join(unusual, folder)
        dicom_series(series, **kwargs)
        out = os.path.join(unusual, folder + "_cleansed.nrrd")
        if expect_works(label, "ColonCleansing", [series, out], [out]):
            geometry = nrrd_geometry(out)
            check(geometry.get("space directions", "").startswith(direction), f"{label}: geometry {geometry}")
            check(geometry.get("sizes") == "24 20 12", f"{label}: size {geometry.get('sizes')}")
    if os.path.isdir(shared):
        out = os.path.join(unusual, "shared_dicom_cleansed.nrrd")
        expect_works("JPEG 2000 DICOM series", "ColonCleansing", [shared, out], [out])
    # A legacy .vtk surface.
    legacy = os.path.join(unusual, "surface.vtk")
    w = vtk.vtkPolyDataWriter()
    w.SetFileName(legacy)
    w.SetInputData(surface)
    w.Write()
    out = os.path.join(unusual, "landmarks_vtk")
    expect_works("legacy .vtk surface", "ColonLandmarks", [legacy, out], [os.path.join(out, "segment_A.vtp")])
    # Findings in RAS: the same points as in LPS, so the same mapped points.
    ras = os.path.join(unusual, "findings_ras.mrk.json")
    doc = json.load(open(findings))
    doc["markups"][0]["coordinateSystem"] = "RAS"
    for p in doc["markups"][0]["controlPoints"]:
        p["position"] = [-p["position"][0], -p["position"][1], p["position"][2]]
    json.dump(doc, open(ras, "w"))
    mapped = {}
    for label, path in (("LPS", findings), ("RAS", ras)):
        out = os.path.join(unusual, f"mapped_{label}.mrk.json")
        if expect_works(f"findings in {label}", "ColonTransferPoints",
                        ["--registration", os.path.join(reg, "registration", "registration.vtp"), "--input", path,
                         "--output", out], [out]):
            m = json.load(open(out))["markups"][0]
            mapped[label] = [(pt["position"] if m.get("coordinateSystem", "LPS") == "LPS"
                              else [-pt["position"][0], -pt["position"][1], pt["position"][2]]) for pt in m["controlPoints"]]
    if len(mapped) == 2:
        check(all(abs(a - b) < 1e-6 for pa, pb in zip(mapped["LPS"], mapped["RAS"]) for a, b in zip(pa, pb))
              and len(mapped["LPS"]) == len(mapped["RAS"]) > 0, "RAS findings mapped elsewhere than the same LPS findings")
    print(f"corpus: {bad_count[0]} bad inputs refused as required, {good_count[0]} unusual inputs read")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
