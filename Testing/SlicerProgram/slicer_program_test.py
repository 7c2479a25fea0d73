#!/usr/bin/env python3
"""Plays 3D Slicer 5 running each module as a program (DESIGN §3.1a).

For every module table (Modules/CLI/<Name>/Testing/SlicerHost.json) it builds the command line
Slicer would build from the module's XML: --returnparameterfile first when the module declares
return parameters, flags in XML order, numbers and enumerations always passed, booleans only
when true, empty values left out, index arguments last; file parameters get Slicer-style
temporary names (a temp folder, digits in node names turned into letters, the extension from
fileExtensions or Slicer's default). It then checks the exit code, that stderr is empty, the
progress tags on stdout, the outputs and the return parameter file. Every output file parameter
the table gives (the nodes Slicer loads back into its scene) must then be readable in the format
its temporary name's extension names: .vtp/.vtk by VTK (with the point or cell arrays the table's
"arrays" lists), .mrk.json as a markups file of the pointfile's type with finite control points,
.nrrd/.nii(.gz) by their headers, .tsv/.csv as a table with rows; a table's "extensions" may ask
for another extension than the first declared one, as Slicer does for another file type. A second
run is killed with SIGKILL once its progress reaches abortAtProgress and must leave no output file.
"""
import argparse
import gzip
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

DEFAULT_EXT = {"image": ".nrrd", "geometry": ".vtp", "pointfile": ".fcsv", "table": ".tsv",
               "transform": ".h5"}
FILE_TAGS = {"image", "geometry", "pointfile", "table", "transform", "file"}
failures = []
DATA = ""


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)
    return condition


def slicer_node_name(tag, counter):
    """Slicer turns the digits of a node id into letters for temporary file names."""
    node = {"image": "vtkMRMLScalarVolumeNode", "geometry": "vtkMRMLModelNode",
            "pointfile": "vtkMRMLMarkupsFiducialNode", "table": "vtkMRMLTableNode"}.get(tag, "vtkMRMLNode")
    digits = str(counter + 1)
    return "BACDE_" + node + "".join(chr(ord("A") + int(d)) for d in digits)


def parameters(xml_text):
    root = ET.fromstring(xml_text)
    for group in root.findall("parameters"):
        for p in group:
            if p.tag in ("label", "description"):
                continue
            get = lambda name: (p.findtext(name) or "").strip()
            yield {"tag": p.tag, "name": get("name"), "flag": get("flag").lstrip("-"),
                   "longflag": get("longflag").lstrip("-"), "index": get("index"),
                   "channel": get("channel"), "default": get("default"),
                   "fileExtensions": p.get("fileExtensions", ""), "type": p.get("type", ""),
                   "coordinateSystem": p.get("coordinateSystem", "")}


def build_command(exe, xml_text, values, tempdir, returnfile, extensions=None):
    params = list(parameters(xml_text))
    is_return = lambda p: p["channel"] == "output" and not p["index"] and not p["flag"] and not p["longflag"]
    cmd = [exe]
    if any(is_return(p) for p in params):
        cmd += ["--returnparameterfile", returnfile]
    renamed = {}
    flagged, indexed = [], []
    for p in params:
        if is_return(p):
            continue
        (indexed if p["index"] else flagged).append(p)
    def value_of(p, counter):
        v = values.get(p["name"])
        if v is None:
            always = p["tag"] in ("integer", "float", "double") or p["tag"].endswith("-enumeration")
            return p["default"] if always else ""
        if p["tag"] in FILE_TAGS:
            ext = p["fileExtensions"].split(",")[0] if p["fileExtensions"] else DEFAULT_EXT.get(p["tag"], "")
            ext = (extensions or {}).get(p["name"], ext)
            temp = os.path.join(tempdir, slicer_node_name(p["tag"], counter) + ext)
            if p["channel"] == "input":
                shutil.copyfile(v, temp)
            else:
                renamed[temp] = (v, p)
            return temp
        return v
    for i, p in enumerate(flagged):
        v = value_of(p, i)
        flag = "--" + p["longflag"] if p["longflag"] else "-" + p["flag"]
        if p["tag"] == "boolean":
            if v == "true":
                cmd.append(flag)
        elif v != "":
            cmd += [flag, v]
    for i, p in enumerate(sorted(indexed, key=lambda p: int(p["index"]))):
        cmd.append(value_of(p, 100 + i))
    return cmd, renamed


MARKUPS_TYPE = {"point": "Fiducial", "curve": "Curve", "closedcurve": "ClosedCurve", "line": "Line", "angle": "Angle"}


def check_node_file(module, p, path, arrays):
    """The output file Slicer reads back as a node: readable in the format of its extension."""
    what = f"{module}: output {p['name']} ({os.path.basename(path)})"
    lower = path.lower()
    try:
        if lower.endswith((".vtp", ".vtk")):
            from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
            from vtkmodules.vtkIOLegacy import vtkPolyDataReader
            reader = vtkXMLPolyDataReader() if lower.endswith(".vtp") else vtkPolyDataReader()
            reader.SetFileName(path)
            reader.Update()
            data = reader.GetOutput()
            check(data.GetNumberOfPoints() > 0 and data.GetNumberOfCells() > 0, f"{what}: VTK reads no points or cells")
            for a in arrays:
                check(data.GetPointData().HasArray(a) or data.GetCellData().HasArray(a), f"{what}: no array {a}")
        elif lower.endswith(".mrk.json"):
            doc = json.load(open(path))
            m = doc["markups"][0]
            want = MARKUPS_TYPE.get(p.get("type", ""), "")
            check(not want or m.get("type") == want, f"{what}: markups type {m.get('type')}, the XML asks for {want}")
            check(m.get("coordinateSystem") in ("LPS", "RAS"), f"{what}: coordinateSystem {m.get('coordinateSystem')}")
            points = m.get("controlPoints", [])
            check(points and all(len(c["position"]) == 3 and all(math.isfinite(x) for x in c["position"]) for c in points),
                  f"{what}: no control points, or one not finite")
            check(all(c.get("label") for c in points), f"{what}: a control point without label")
        elif lower.endswith(".fcsv"):
            rows = [l for l in open(path) if l.strip() and not l.startswith("#")]
            check(rows, f"{what}: no points")
        elif lower.endswith(".nrrd"):
            head = open(path, "rb").read(4096)
            check(head.startswith(b"NRRD000") and b"sizes:" in head and b"space directions:" in head,
                  f"{what}: not a NRRD header with sizes and space directions")
        elif lower.endswith((".nii", ".nii.gz")):
            opener = gzip.open if lower.endswith(".gz") else open
            with opener(path, "rb") as f:
                header = f.read(348)
            check(len(header) == 348 and int.from_bytes(header[:4], "little") == 348
                  and header[344:348] in (b"n+1\0", b"ni1\0"), f"{what}: not a NIfTI-1 header")
        elif lower.endswith((".tsv", ".csv", ".txt")):
            sep = "," if lower.endswith(".csv") else "\t"
            lines = [l.rstrip("\n") for l in open(path) if l.strip()]
            check(len(lines) >= 2, f"{what}: a table needs a header and at least one row")
            if lines:
                n = len(lines[0].split(sep))
                check(n >= 2 and all(len(l.split(sep)) == n for l in lines), f"{what}: rows of different lengths")
        else:
            check(os.path.getsize(path) > 0, f"{what}: empty")
    except Exception as e:  # noqa: BLE001 - any failure to read is the finding
        check(False, f"{what}: cannot be read ({e})")


def substitute(table, out):
    return {k: v.replace("{out}", out).replace("{data}", DATA) for k, v in table.items()}


def progress_values(stdout):
    return [float(v) for v in re.findall(r"<filter-progress>([0-9.]+)</filter-progress>", stdout)]


def run_module(cli_dir, name, table):
    exe = os.path.join(cli_dir, name)
    xml_text = subprocess.run([exe, "--xml"], capture_output=True, text=True, check=True).stdout
    # Conventions that keep Slicer from guessing (DESIGN §3.1a).
    for p in parameters(xml_text):
        if p["tag"] == "pointfile":
            check(p["fileExtensions"].split(",")[0] == ".mrk.json",
                  f"{name}: pointfile {p['name']} must declare fileExtensions=\".mrk.json\"")
        if p["tag"] in ("point", "region"):
            check(p["coordinateSystem"] == "lps", f"{name}: {p['tag']} {p['name']} must declare coordinateSystem=\"lps\"")
        if p["tag"] == "boolean":
            check(p["default"] in ("", "false"), f"{name}: boolean {p['name']} defaults to true (Slicer cannot switch it off)")
    work = tempfile.mkdtemp(prefix="colonmap-program-" + name + "-")
    try:
        # A normal run.
        out = os.path.join(work, "out")
        os.makedirs(out)
        slicer_tmp = os.path.join(work, "SlicerTemp")
        os.makedirs(slicer_tmp)
        returnfile = os.path.join(slicer_tmp, "BACDE_params.txt")
        cmd, renamed = build_command(exe, xml_text, substitute(table["quick"], out), slicer_tmp, returnfile,
                                     table.get("extensions"))
        print("running:", " ".join(cmd))
        started = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
        seconds = time.time() - started
        check(r.returncode == 0, f"{name}: exit code {r.returncode}, stderr: {r.stderr.strip()}")
        check(r.stderr == "", f"{name}: stderr not empty on success: {r.stderr.strip()[:300]}")
        check("<filter-start>" in r.stdout and "<filter-end>" in r.stdout, f"{name}: no filter-start/filter-end tags")
        values = progress_values(r.stdout)
        check(values and values[-1] == 1.0, f"{name}: progress does not end at 1")
        for line in r.stdout.splitlines():
            if line.startswith("<filter-progress>"):
                check(re.fullmatch(r"<filter-progress>[0-9.]+</filter-progress>", line) is not None,
                      f"{name}: malformed progress line {line!r}")
        check(not [f for f in os.listdir(out) if f.startswith(".colonmap-tmp")], f"{name}: temporaries left")
        # Slicer reads each output from its temporary name; hand it to the table's path.
        for temp, (final, p) in renamed.items():
            if check(os.path.isfile(temp), f"{name}: output {temp} missing"):
                check_node_file(name, p, temp, table.get("arrays", {}).get(p["name"], []))
                shutil.move(temp, final)
        for f in table.get("outputs", []):
            check(os.path.isfile(os.path.join(out, f)), f"{name}: output {f} missing")
        if table.get("returns"):
            text = open(returnfile).read() if os.path.exists(returnfile) else ""
            for ret in table["returns"]:
                m = re.search(r"^" + ret + r" = (\S+)$", text, re.M)
                check(m is not None, f"{name}: return parameter {ret} missing in {text!r}")
        print(f"{name}: program run {seconds:.2f} s")

        # A run killed part way leaves no output file.
        killed = os.path.join(work, "killed")
        os.makedirs(killed)
        cmd, killed_renamed = build_command(exe, xml_text, substitute(table["long"], killed), slicer_tmp,
                                            returnfile + ".k")
        # Killed part way, as Slicer's Cancel does: once the progress reaches abortAtProgress.
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        abort_at = table.get("abortAtProgress", 0.3)
        if isinstance(abort_at, list):  # the in-process test cancels at each; one kill is enough here
            abort_at = abort_at[len(abort_at) // 2]
        still_running = False
        for line in p.stdout:
            m = re.match(r"<filter-progress>([0-9.]+)</filter-progress>", line)
            if m and abort_at <= float(m.group(1)) < 1.0:
                still_running = p.poll() is None
                break
        p.send_signal(signal.SIGKILL)
        p.communicate()
        check(still_running, f"{name}: the long run ended before it could be killed")
        left = [f for f in os.listdir(killed) if not f.startswith(".colonmap-tmp")]
        left += [t for t in killed_renamed if os.path.exists(t)]
        check(not left, f"{name}: files left after SIGKILL: {left}")
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli-dir", required=True)
    parser.add_argument("--data", required=True, help="folder of test inputs, {data} in the tables")
    parser.add_argument("tables", nargs="+", help="Name=path/to/SlicerHost.json")
    args = parser.parse_args()
    global DATA
    DATA = args.data
    for item in args.tables:
        name, path = item.split("=", 1)
        with open(path) as f:
            run_module(args.cli_dir, name, json.load(f))
    n = len(args.tables)
    print(f"{n - len(set(f.split(':')[0] for f in failures))} passed, "
          f"{len(set(f.split(':')[0] for f in failures))} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
