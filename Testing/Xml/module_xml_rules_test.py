#!/usr/bin/env python3
"""What a 3D Slicer user reads in a module's panel, checked on every module's --xml output.

- category: "ColonMap" for the clinical modules, "ColonMap.Testing" for the test tools;
- the module <description> at most 300 characters (the detail is in the module's page), and a
  <documentation-url> ending in docs/modules/<Name>.md, a page that exists;
- no reference to internal documents in user-facing text (titles, labels, descriptions,
  enumeration elements): no "DESIGN", no "§", no "issue";
- required parameters marked: SlicerExecutionModel has no "required" attribute, so their label
  ends in "(required)": every positional parameter and the flagged ones in REQUIRED below; no
  boolean and no parameter with a default carries the mark; and a run without any argument fails
  with exit code 1 and one line on stderr (the modules check their required parameters);
- units in labels: every number whose description speaks of mm, degrees, ml, HU or seconds has a
  unit in parentheses in its label, and the labels in UNITS have exactly that unit.

Usage: module_xml_rules_test.py --cli-dir <cli-modules folder> --root <repository> Name [Name ...]
"""
import argparse
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from colonmap_testing import Checks  # noqa: E402

TESTING = {"ColonPhantom", "ColonEvaluateRegistration"}
MAX_DESCRIPTION = 300
# Flagged parameters a module cannot run without (positional ones are always required).
REQUIRED = {
    "ColonPhantom": ["outputDirectory"],
    "ColonTransferPoints": ["registration", "input", "output"],
    "ColonEvaluateRegistration": ["registration", "truthSupine", "truthProne"],
    "ColonEndoluminalViews": ["supineVolume", "proneVolume", "registration"],
    "ColonSupineProne": ["supine", "prone", "outputDirectory"],
}
UNITS = {
    ("ColonEndoluminalViews", "viewAngle"): "(degrees)",
    ("ColonEndoluminalViews", "cameraDistance"): "(mm)",
    ("ColonEndoluminalViews", "cropRadius"): "(mm)",
    ("ColonEndoluminalViews", "sampleDistance"): "(mm)",
    ("ColonPhantom", "spacing"): "(mm)",
    ("ColonFlattening", "mmPerPixel"): "(mm)",
    ("ColonLandmarks", "capDistance"): "(mm)",
    ("ColonRegistration", "reliableBoundMm"): "(mm)",
}
INTERNAL = [re.compile(r"\bDESIGN\b"), re.compile("§"), re.compile(r"\bissues?\b", re.I)]
UNIT_WORDS = re.compile(r"(?<![\w/])(mm|degrees?|ml|HU|seconds)(?![\w/])")
NUMBERS = {"integer", "float", "double", "integer-vector", "float-vector", "double-vector"}
PARAMETER_FIELDS = {"label", "description"}
checks = Checks()
check = checks.check


def text(element, tag):
    return (element.findtext(tag) or "").strip()


def check_module(cli_dir, root_dir, name):
    exe = os.path.join(cli_dir, name)
    xml_text = subprocess.run([exe, "--xml"], capture_output=True, text=True, check=True).stdout
    root = ET.fromstring(xml_text)
    category = text(root, "category")
    want = "ColonMap.Testing" if name in TESTING else "ColonMap"
    check(category == want, f"{name}: category '{category}', expected '{want}'")
    description = text(root, "description")
    check(0 < len(description) <= MAX_DESCRIPTION,
          f"{name}: description has {len(description)} characters (at most {MAX_DESCRIPTION}; the detail goes to its page)")
    url = text(root, "documentation-url")
    page = f"docs/modules/{name}.md"
    if check(url.endswith(page), f"{name}: documentation-url '{url}' does not end in {page}"):
        check(os.path.isfile(os.path.join(root_dir, page)), f"{name}: {page} does not exist")

    user_text = [("title", text(root, "title")), ("description", description)]
    for group in root.findall("parameters"):
        user_text += [("group label", text(group, "label")), ("group description", text(group, "description"))]
        for p in group:
            if p.tag in PARAMETER_FIELDS:
                continue
            pname = text(p, "name")
            label = text(p, "label")
            user_text += [(f"{pname} label", label), (f"{pname} description", text(p, "description"))]
            user_text += [(f"{pname} element", e.text or "") for e in p.findall("element")]
            is_return = text(p, "channel") == "output" and not text(p, "index") and not text(p, "longflag") \
                and not text(p, "flag")
            marked = label.endswith("(required)")
            if text(p, "index") and not is_return:
                check(marked, f"{name}: positional parameter {pname} is required: its label '{label}' must end in (required)")
            if pname in REQUIRED.get(name, []):
                check(marked, f"{name}: {pname} is required: its label '{label}' must end in (required)")
            if marked:
                check(p.tag != "boolean" and not text(p, "default"),
                      f"{name}: {pname} is marked (required) but has a default or is a boolean")
                check(text(p, "index") or pname in REQUIRED.get(name, []),
                      f"{name}: {pname} is marked (required): add it to REQUIRED in this test")
            if p.tag in NUMBERS and not is_return and UNIT_WORDS.search(text(p, "description")):
                check(re.search(r"\([^)]*\)", label), f"{name}: {pname}: its description has a unit, its label '{label}' none")
            if (name, pname) in UNITS:
                check(UNITS[(name, pname)] in label, f"{name}: {pname}: label '{label}' lacks {UNITS[(name, pname)]}")
    for where, t in user_text:
        for pattern in INTERNAL:
            m = pattern.search(t)
            check(m is None, f"{name}: {where} refers to an internal document ('{m.group(0) if m else ''}'): {t[:80]!r}")

    # The required parameters are checked in code: a run without them fails cleanly.
    r = subprocess.run([exe], capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=60)
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    check(r.returncode == 1, f"{name}: a run without arguments exits {r.returncode}, expected 1")
    check(len(lines) == 1, f"{name}: a run without arguments must say what is missing in one stderr line, got {lines}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli-dir", required=True)
    parser.add_argument("--root", required=True)
    parser.add_argument("modules", nargs="+")
    args = parser.parse_args()
    for name in args.modules:
        check_module(args.cli_dir, args.root, name)
    print(f"{len(args.modules)} modules checked")
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
