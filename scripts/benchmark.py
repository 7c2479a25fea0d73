#!/usr/bin/env python3
"""ColonMap benchmarks (not timed tests): runs modules on benchmark-size inputs and writes JSON
with wall time, per-stage times (from the modules' <filter-end> tags) and peak memory.

    python3 scripts/benchmark.py [--build build/ColonMap-build] [--output benchmark.json]

ColonPhantom at clinical size (0.7 x 0.7 x 1.0 mm, 512 x 512 x 450) and at test size; then
ColonCleansing -> ColonSegmentation -> ColonSurface on the clinical supine scan, one process
each (per-module peak memory); then the whole pipeline, ColonSupineProne, on the clinical pair
with the phantom's polyps as findings and its truth: time and peak memory of the whole, each
stage's time, the registration error, and the paper's per-segment times beside ours. Then the
real-colon pairs (issue 17): ColonPhantom --realColon at 1 mm for each real colon in the shared
data (time, peak memory, its step times), CT to surface on the GCA supine scan, the whole
pipeline on the HuBMAP male pair at 1 mm and at the clinical spacing, and ColonSurface on the GCA colon voxelised at 2 and
1 mm as a mask from another tool (label only, hundreds of handles).
"""
import argparse
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import tempfile
import time


def machine():
    model = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem_kb = 0
    try:
        for line in open("/proc/meminfo"):
            if line.startswith("MemTotal"):
                mem_kb = int(line.split()[1])
    except OSError:
        pass
    return {"cpu": model, "cores": os.cpu_count(), "memoryGB": round(mem_kb / 1024 / 1024, 1),
            "system": platform.platform()}


def run(cmd):
    """Runs one command; returns wall seconds, stage times and the child's peak RSS (MB)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    start = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.time() - start
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if r.returncode != 0:
        raise SystemExit(f"benchmark command failed: {' '.join(cmd)}\n{r.stderr}")
    stages = {m.group(1): float(m.group(2)) for m in re.finditer(
        r"<filter-end><filter-name>(.*?)</filter-name><filter-time>([0-9.]+)</filter-time>", r.stdout)}
    # The modules' own step times: a note "<Module>: steps: name 1.23 s, other 0.45 s".
    steps = {}
    for line in re.findall(r"^\w+: steps: (.*)$", r.stdout, re.M):
        steps.update({m.group(1): float(m.group(2)) for m in re.finditer(r"\s*([^,]+?) ([0-9.]+) s(?:,|$)", line)})
    # ru_maxrss of children is the largest so far: valid for the first run that exceeds it.
    return {"seconds": round(seconds, 3), "stages": stages, "steps": steps,
            "peakMemoryMB": round(peak / 1024, 1) if peak > before else None}


def run_with_peak(cmd):
    """Like run(), with the peak memory and the CPU seconds (user + system, every thread) of this
    one process from GNU time when available; coresBusy = CPU / wall."""
    if shutil.which("/usr/bin/time") is None:
        return run(cmd)
    with tempfile.NamedTemporaryFile("r", suffix=".txt") as t:
        result = run(["/usr/bin/time", "-f", "%M %U %S", "-o", t.name] + cmd)
        try:
            peak_kb, user, system = open(t.name).read().split()[-3:]
            result["peakMemoryMB"] = round(int(peak_kb) / 1024, 1)
            result["cpuSeconds"] = round(float(user) + float(system), 2)
            result["coresBusy"] = round(result["cpuSeconds"] / max(result["seconds"], 1e-3), 2)
        except (ValueError, IndexError):
            pass
    return result


# Zeng et al., TVCG 2010, on real data (one CPU of 2010): conformal flattening 20-27 s per segment
# of 70-90K faces, features + matching + harmonic registration about 30 s per segment.
PAPER_SECONDS_PER_SEGMENT = {"flattening": [20.0, 27.0], "registration": [30.0, 30.0]}


def pipeline(cli, phantom, out, *extra):
    """ColonSupineProne on a phantom pair: whole time and peak memory, stage times, errors."""
    cmd = [os.path.join(cli, "ColonSupineProne"), "--supine", os.path.join(phantom, "supine.nrrd"),
           "--prone", os.path.join(phantom, "prone.nrrd"), "--outputDirectory", out,
           "--findings", os.path.join(phantom, "supine_polyps.mrk.json"), "--groundTruth", phantom, *extra]
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
        cmd = ["xvfb-run", "-a"] + cmd
    whole = run_with_peak(cmd)
    whole.pop("stages", None)
    summary = json.load(open(os.path.join(out, "summary.json")))
    errors = json.load(open(os.path.join(out, "evaluation", "errors.json")))
    stages = {s["name"]: round(s["seconds"], 3) for s in summary["stages"]}
    # Issue 22: how many of the cores each stage kept busy (CPU seconds of the whole process over
    # the stage's wall seconds; 2 = both cores of the benchmark machine). The two scans' jobs run
    # side by side (stageBlocks): the block has the process's CPU, each of its stages only its own
    # thread's (threadCpuSeconds, without the toolkits' worker threads).
    cpu = {s["name"]: {"seconds": round(s["seconds"], 3), "cpuSeconds": round(s["cpuSeconds"], 3),
                       "coresBusy": round(s["cpuSeconds"] / max(s["seconds"], 1e-3), 2)}
           for s in summary["stages"] if "cpuSeconds" in s}
    for s in summary["stages"]:
        if "threadCpuSeconds" in s:
            cpu[s["name"]] = {"seconds": round(s["seconds"], 3), "threadCpuSeconds": round(s["threadCpuSeconds"], 3),
                              "block": s.get("block")}
    for b in summary.get("stageBlocks", []):
        cpu["block: " + b["name"]] = {"seconds": round(b["seconds"], 3), "cpuSeconds": round(b["cpuSeconds"], 3),
                                      "coresBusy": round(b["cpuSeconds"] / max(b["seconds"], 1e-3), 2),
                                      "sideBySide": b["sideBySide"]}
    ours = {"flattening": (stages.get("flattening supine", 0) + stages.get("flattening prone", 0)) / 10,
            "registration": stages.get("registration", 0) / 5}
    return {"whole": whole, "stages": stages, "stageCpu": cpu, "quality": summary["quality"],
            "error3D": errors["overall"]["error3D"], "polyps": errors.get("polyps", {}).get("error3D"),
            "secondsPerSegment": {k: {"ours": round(v, 3), "paper": PAPER_SECONDS_PER_SEGMENT[k]}
                                  for k, v in ours.items()}}


def flattening_vs_cgal(build, work):
    """Issue 6: our conformal flattening against CGAL's LSCM on the same cut segments, in one run
    (Libs/Flattening/Benchmark/FlatteningVsCgal, not built by default: built here if missing).
    Inputs: the phantom's true-wall T segment at 1 mm x 160 around (117K faces) and at 2 mm x 96;
    plus, if given in COLONMAP_FLATTEN_BENCH_DIRS (colon-separated 'landmarksDir:segment' pairs
    joined by ';'), segments of our own CT pipeline. Returns the program's JSON (None if the
    program cannot be built, e.g. no CGAL)."""
    exe = os.path.join(build, "Libs", "Flattening", "Benchmark", "FlatteningVsCgal")
    if not os.path.exists(exe):
        r = subprocess.run(["cmake", "--build", build, "--target", "FlatteningVsCgal", "-j1"],
                           capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(exe):
            print("FlatteningVsCgal: not built:", r.stderr.strip()[-300:])
            return None
    out = os.path.join(work, "flattening_vs_cgal.json")
    cmd = [exe, "--json", out, "--runs", "5", "--phantom", "1", "160", "2", "--phantom", "2", "96", "2"]
    for pair in filter(None, os.environ.get("COLONMAP_FLATTEN_BENCH_DIRS", "").split(";")):
        directory, segment = pair.rsplit(":", 1)
        cmd += [directory, segment]
    r = subprocess.run(cmd, capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print("FlatteningVsCgal failed:", r.stderr.strip())
        return None
    with open(out) as f:
        return json.load(f)


def ct_to_surface(cli, ct, work, label):
    """ColonCleansing -> ColonSegmentation -> ColonSurface (with the cleansed CT) on one scan, one
    process each: time, peak memory and stage times of each, and their total."""
    cleansed, lumen = os.path.join(work, "cleansed.nrrd"), os.path.join(work, "lumen.nrrd")
    chain = [("ColonCleansing", [ct, cleansed]), ("ColonSegmentation", [cleansed, lumen]),
             ("ColonSurface", [lumen, os.path.join(work, "surface.vtp"), "--referenceCT", cleansed])]
    out, total = {}, 0.0
    for module, module_args in chain:
        if not os.path.exists(os.path.join(cli, module)):
            break
        out[f"{module} {label}"] = run_with_peak([os.path.join(cli, module)] + module_args)
        total += out[f"{module} {label}"]["seconds"]
        print(module, label, json.dumps(out[f"{module} {label}"]))
    out[f"CT to surface, {label}, total seconds"] = round(total, 3)
    return out


def foreign_masks(cli, build, data, work):
    """Issue 18: ColonSurface on lumen masks as another tool delivers them (the GCA colon
    voxelised at 2 and 1 mm: hundreds of handles), label only."""
    maker = os.path.join(build, "Modules", "CLI", "ColonSurface", "Testing", "ColonSurfaceMakeAtlasMask")
    folder = os.path.join(data, "gca-00020")
    out = {}
    if not (os.path.exists(maker) and os.path.isdir(folder)):
        return out
    for spacing in ("2", "1"):
        mask = os.path.join(work, f"gca_mask_{spacing}.nii.gz")
        made = subprocess.run([maker, folder, mask, spacing], capture_output=True, text=True)
        handles = re.search(r"handles (\d+)", made.stdout)
        r = run_with_peak([os.path.join(cli, "ColonSurface"), mask, os.path.join(work, "mask_surface.vtp")])
        r["maskHandles"] = int(handles.group(1)) if handles else None
        out[f"ColonSurface label only, GCA voxelised {spacing} mm"] = r
        print("ColonSurface mask", spacing, json.dumps(r))
    return out


def real_colons(cli, data, work):
    """Issue 17: a real-colon pair at 1 mm per atlas (time, peak memory, steps), and the whole
    pipeline on one of them (the HuBMAP male colon) with its truth."""
    out = {}
    for atlas in ("gca-00020", "hubmap-vhm-00070", "hubmap-vhf-00080"):
        folder = os.path.join(data, atlas)
        if not os.path.isdir(folder):
            continue
        pair = os.path.join(work, "real-" + atlas)
        r = run_with_peak([os.path.join(cli, "ColonPhantom"), "--outputDirectory", pair, "--realColon", folder,
                           "--spacing", "1,1,1"])
        truth = json.load(open(os.path.join(pair, "truth.json")))
        r["colonLengthMm"] = round(truth["colonLengthMm"], 1)
        r["noRegistrationMeanMm"] = round(truth["noRegistration"]["mean"], 2)
        r["ctSize"] = truth["ct"]["size"]
        out[f"ColonPhantom --realColon {atlas} 1 mm"] = r
        print(atlas, json.dumps(r))
        if atlas == "gca-00020":
            out.update(ct_to_surface(cli, os.path.join(pair, "supine.nrrd"), work, "gca-00020 1 mm supine"))
        if atlas == "hubmap-vhm-00070" and os.path.exists(os.path.join(cli, "ColonSupineProne")):
            out["pipeline hubmap-vhm-00070 1 mm"] = pipeline(cli, pair, os.path.join(work, "real-pipeline"))
            print("ColonSupineProne real pair", json.dumps(out["pipeline hubmap-vhm-00070 1 mm"]["whole"]))
            # Issue 22: the same colon at the clinical spacing (the real-anatomy time target).
            clinical = os.path.join(work, "real-clinical")
            subprocess.run([os.path.join(cli, "ColonPhantom"), "--outputDirectory", clinical, "--realColon", folder,
                            "--spacing", "0.7,0.7,1.0"], check=True, capture_output=True)
            key = "pipeline hubmap-vhm-00070 clinical 0.7x0.7x1.0 mm"
            out[key] = pipeline(cli, clinical, os.path.join(work, "real-clinical-pipeline"))
            print("ColonSupineProne real pair, clinical spacing", json.dumps(out[key]["whole"]))
            shutil.rmtree(clinical, ignore_errors=True)
        shutil.rmtree(pair, ignore_errors=True)
    return out


def main():
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(repo, "build", "ColonMap-build"))
    parser.add_argument("--output", default=os.path.join(repo, "build", "benchmark.json"))
    args = parser.parse_args()
    cli = os.path.join(args.build, "lib", "ColonMap", "cli-modules")
    work = tempfile.mkdtemp(prefix="colonmap-benchmark-")
    results = {"machine": machine(), "date": time.strftime("%Y-%m-%d %H:%M:%S"), "runs": {}}
    try:
        # Largest first, so that the children's peak memory belongs to it; then the CT-to-surface
        # chain on the clinical supine scan (peak memory is then per process, see run()).
        clinical = os.path.join(work, "clinical")
        for label, spacing, out in (("ColonPhantom clinical 0.7x0.7x1.0 mm", "0.7,0.7,1.0", clinical),
                                    ("ColonPhantom test size 2.5 mm", "2.5,2.5,2.5", os.path.join(work, "test"))):
            results["runs"][label] = run([os.path.join(cli, "ColonPhantom"), "--outputDirectory", out,
                                          "--spacing", spacing])
            print(label, json.dumps(results["runs"][label]))
        results["runs"].update(ct_to_surface(cli, os.path.join(clinical, "supine.nrrd"), work, "clinical supine"))
        if os.path.exists(os.path.join(cli, "ColonSupineProne")):
            results["pipeline"] = pipeline(cli, clinical, os.path.join(work, "pipeline"))
            print("ColonSupineProne clinical pair", json.dumps(results["pipeline"]["whole"]))
            # The same with the two scans one after the other (issue 22: what side by side gains).
            results["pipelineSequential"] = pipeline(cli, clinical, os.path.join(work, "pipeline-seq"), "--sequential")
            print("ColonSupineProne clinical pair, --sequential",
                  json.dumps(results["pipelineSequential"]["whole"]))
        results["flatteningVsCgal"] = flattening_vs_cgal(args.build, work)
        data = os.path.join(os.path.dirname(repo), "shared", "data")
        results["realColon"] = real_colons(cli, data, work)
        results["foreignMasks"] = foreign_masks(cli, args.build, data, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w") as f:
        json.dump(results, f, indent=2)
    print("benchmark written to", args.output)


if __name__ == "__main__":
    main()
