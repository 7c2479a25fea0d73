#!/usr/bin/env python3
"""Plays 3D Slicer 5 running each module as a program (DESIGN §3.1a).

For every module table (Modules/CLI/<Name>/Testing/SlicerHost.json) it builds the command line
Slicer would build from the module's XML: --returnparameterfile first when the module declares
return parameters, flags in XML order, numbers and enumerations always passed, booleans only
when true, empty values left out, index arguments last; file parameters get Slicer-style
temporary names (a temp folder, digits in node names turned into letters, the extension from
fileExtensions or Slicer's default). It then checks the exit code, that stderr is empty, the
progress tags on stdout, the outputs and the return parameter file. A second run is killed with
SIGKILL once its progress reaches abortAtProgress and must leave no output file.
"""
import argparse
import json
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
                   "fileExtensions": p.get("fileExtensions", ""),
                   "coordinateSystem": p.get("coordinateSystem", "")}


def build_command(exe, xml_text, values, tempdir, returnfile):
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
            temp = os.path.join(tempdir, slicer_node_name(p["tag"], counter) + ext)
            if p["channel"] == "input":
                shutil.copyfile(v, temp)
            else:
                renamed[temp] = v
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
        cmd, renamed = build_command(exe, xml_text, substitute(table["quick"], out), slicer_tmp, returnfile)
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
        for temp, final in renamed.items():
            if check(os.path.isfile(temp), f"{name}: output {temp} missing"):
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
