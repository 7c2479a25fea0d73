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


def expect_refused(name, module, args, user_file, words, outputs, cwd=None):
    """Runs module with args (in folder cwd); checks the failure contract."""
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
    check(all(w in r.stderr for w in words), f"{name}: the message does not say {words}")
    for o in outputs:
        check(not os.path.exists(o), f"{name}: {o} left behind")


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
                                ("a triangle past the points", index_past_end, ["triangle 1", "names point"])):
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
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
