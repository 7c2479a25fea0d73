#!/usr/bin/env python3
"""The documentation a user reads (README.md and docs/) against the tree and the programs.

(a) Every relative link in README.md and docs/**/*.md (outside code) resolves to an existing file
    or folder, and every #anchor to a heading of the target page (GitHub's heading ids).
(b) Every module description Modules/CLI/<Name>/<Name>.xml has a <documentation-url> ending in
    docs/modules/<Name>.md, that page exists and names every parameter of the description (its
    --longflag, or its name for positional and return parameters); every page in docs/modules/
    belongs to a module.
(c) README.md is at most 8192 bytes.
(d) The shell commands of the README's "First run" section run and exit 0, at a small size: the
    section's `cli=` is set to the given cli-modules folder, its `out=` to a temporary folder, and
    every `--spacing` to 5,5,5 (a ColonPhantom command without --spacing would run at clinical
    size and is an error). The files the section names under its output folder must then exist.

Usage: docs_test.py <cli-modules folder> [--root <repository>]
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Python"))
from colonmap_testing import Checks  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("cli", help="folder holding the module programs (lib/ColonMap/cli-modules)")
parser.add_argument("--root", default=os.path.normpath(os.path.join(HERE, "..", "..")), help="repository root")
options = parser.parse_args()
root = os.path.abspath(options.root)
cli = os.path.abspath(options.cli)
checks = Checks()
check = checks.check

README_LIMIT = 8192
SMALL_SPACING = "5,5,5"
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


def rel(path):
    return os.path.relpath(path, root)


def prose_lines(text):
    """The lines outside fenced code blocks, with inline code spans blanked: (number, line)."""
    inside = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, re.sub(r"`[^`]*`", "``", line)


def slug(heading):
    """GitHub's id of a heading: links reduced to their text, lower case, punctuation dropped."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading).replace("`", "").strip().lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(path):
    ids, seen = set(), {}
    inside = False
    for line in open(path, encoding="utf-8").read().splitlines():
        if FENCE.match(line):
            inside = not inside
            continue
        m = None if inside else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            base = slug(m.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            ids.add(base if n == 0 else f"{base}-{n}")
    return ids


# (a) Links.
pages = [os.path.join(root, "README.md")]
for folder, _, files in os.walk(os.path.join(root, "docs")):
    pages += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
anchor_cache = {}
links = 0
for page in pages:
    text = open(page, encoding="utf-8").read()
    for number, line in prose_lines(text):
        targets = INLINE_LINK.findall(line)
        m = REFERENCE_DEF.match(line)
        if m:
            targets.append(m.group(1))
        for target in targets:
            if SCHEME.match(target):
                continue  # web and mail links are not checked here
            links += 1
            where = f"{rel(page)}:{number}: link '{target}'"
            path_part, _, anchor = target.partition("#")
            target_path = os.path.normpath(os.path.join(os.path.dirname(page), path_part)) if path_part else page
            if not check(os.path.exists(target_path), f"{where}: {rel(target_path)} does not exist"):
                continue
            if anchor:
                if not check(target_path.endswith(".md"), f"{where}: an anchor into a file that is not Markdown"):
                    continue
                if target_path not in anchor_cache:
                    anchor_cache[target_path] = anchors(target_path)
                check(anchor in anchor_cache[target_path], f"{where}: no heading with id '{anchor}' in {rel(target_path)}")
print(f"links: {links} relative links in {len(pages)} pages")

# (b) Module descriptions and their pages.
modules_dir = os.path.join(root, "Modules", "CLI")
modules = sorted(n for n in os.listdir(modules_dir) if os.path.isfile(os.path.join(modules_dir, n, n + ".xml")))
check(modules, f"no module descriptions under {rel(modules_dir)}")
MODULE_FIELDS = {"label", "description", "category", "title", "version", "documentation-url", "license",
                 "acknowledgements", "contributor", "location", "index"}
for name in modules:
    xml_path = os.path.join(modules_dir, name, name + ".xml")
    root_element = ET.parse(xml_path).getroot()
    url = (root_element.findtext("documentation-url") or "").strip()
    page_rel = f"docs/modules/{name}.md"
    if not check(url.endswith(page_rel), f"{rel(xml_path)}: documentation-url '{url}' does not end in {page_rel}"):
        continue
    page = os.path.join(root, page_rel)
    if not check(os.path.isfile(page), f"{rel(xml_path)}: documentation-url names {page_rel}, which does not exist"):
        continue
    text = open(page, encoding="utf-8").read()
    for group in root_element.findall("parameters"):
        for parameter in group:
            if parameter.tag in MODULE_FIELDS:
                continue
            pname = (parameter.findtext("name") or "").strip()
            flag = (parameter.findtext("longflag") or "").strip().lstrip("-")
            if flag:
                check(re.search(r"--" + re.escape(flag) + r"(?![\w-])", text),
                      f"{page_rel}: does not document --{flag} of {name}.xml")
            else:
                check(re.search(r"(?<![\w-])" + re.escape(pname) + r"(?![\w-])", text),
                      f"{page_rel}: does not document the parameter {pname} of {name}.xml")
for page in sorted(os.listdir(os.path.join(root, "docs", "modules"))):
    if page.endswith(".md"):
        check(page[:-3] in modules, f"docs/modules/{page}: no module {page[:-3]} in Modules/CLI")
print(f"modules: {len(modules)} descriptions checked against docs/modules/")

# (c) README size.
size = os.path.getsize(os.path.join(root, "README.md"))
check(size <= README_LIMIT, f"README.md is {size} bytes, more than {README_LIMIT}")
print(f"README.md: {size} bytes")


# (d) The README's first-run commands.
def section(text, title_pattern):
    """The lines of the level-2 section whose title matches, up to the next level-2 heading."""
    lines, inside_fence, taking = [], False, False
    for line in text.splitlines():
        if FENCE.match(line):
            inside_fence = not inside_fence
        if not inside_fence and re.match(r"^##\s", line):
            taking = bool(re.match(r"^##\s+" + title_pattern, line))
            continue
        if taking:
            lines.append(line)
    return lines


def shell_blocks(lines):
    """Logical lines (continuations joined) of the sh/bash/shell fenced blocks."""
    commands, block, language = [], None, ""
    for line in lines:
        m = FENCE.match(line)
        if m:
            if block is None:
                language = line.strip()[3:].strip().lower()
                block = []
            else:
                if language in ("sh", "bash", "shell", "console"):
                    commands += block
                block = None
            continue
        if block is not None:
            block.append(line)
    logical, pending = [], ""
    for line in commands:
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        full = (pending + line).strip()
        pending = ""
        if full and not full.startswith("#"):
            logical.append(full)
    return logical


readme = open(os.path.join(root, "README.md"), encoding="utf-8").read()
first_run = section(readme, r"First run\b")
commands = shell_blocks(first_run)
check(commands, "README.md: no shell commands in a '## First run' section")
if not check(os.path.isfile(os.path.join(cli, "ColonPhantom")), f"{cli}: no ColonPhantom program (give the cli-modules folder)"):
    sys.exit(checks.finish())

work = tempfile.mkdtemp(prefix="colonmap-docs-test-")
try:
    out_dir = os.path.join(work, "first-run")
    assignments, runs, readme_out = [], [], None
    for command in commands:
        m = re.match(r"^(\w+)=(\S+)$", command)
        if m and m.group(1) == "cli":
            assignments.append("cli=" + shlex.quote(cli))
        elif m and m.group(1) == "out":
            readme_out = m.group(2)
            assignments.append("out=" + shlex.quote(out_dir))
        elif m:
            assignments.append(command)
        else:
            if "ColonPhantom" in command and not check(
                    "--spacing" in command, f"README first run: ColonPhantom without --spacing (clinical size by default): {command}"):
                command += " --spacing " + SMALL_SPACING  # run it small all the same
            runs.append(re.sub(r"--spacing\s+\S+", "--spacing " + SMALL_SPACING, command))
    check(any(a.startswith("cli=") for a in assignments), "README first run: the commands must set cli= (the cli-modules folder)")
    check(readme_out is not None, "README first run: the commands must set out= (the output folder)")
    prelude = "set -euo pipefail\n" + "\n".join(assignments) + "\n"
    for command in runs:
        try:
            r = subprocess.run(["bash", "-c", prelude + command], cwd=work, capture_output=True, text=True,
                               stdin=subprocess.DEVNULL, timeout=240)
            tail = "\n".join((r.stderr or r.stdout).strip().splitlines()[-5:])
            ok = check(r.returncode == 0, f"README first run: exit {r.returncode}: {command}\n{tail}")
        except subprocess.TimeoutExpired:
            ok = check(False, f"README first run: more than 240 s: {command}")
        print(("ran: " if ok else "FAILED: ") + command)
    # Files the section names under its output folder, e.g. `colonmap-demo/first-run/report.html`.
    if readme_out:
        named = set()
        for line in first_run:
            for token in re.findall(r"`([^`\s]+)`", line):
                if token.startswith(readme_out.rstrip("/") + "/"):
                    named.add(token[len(readme_out.rstrip("/")) + 1:])
        for name in sorted(named):
            check(os.path.exists(os.path.join(out_dir, name)), f"README first run names {readme_out}/{name}, which the commands did not write")
        print(f"first run: {len(runs)} commands, {len(named)} named outputs checked")
finally:
    shutil.rmtree(work, ignore_errors=True)

sys.exit(checks.finish())
