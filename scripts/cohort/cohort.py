"""The case table and the per-case stage list of the cohort workflow (issue 25), shared by the
Snakefile, the report rule, the cohort summary and the tests.

Case table: a CSV file with a header row. Columns (any order, names case-insensitive):
  case      case id: letters, digits, '.', '_', '-' (the case's output folder name)
  supine    supine CT (file or DICOM folder), relative to the table's folder or absolute
  prone     prone CT
  findings  optional: findings (.mrk.json or .fcsv) in the supine scan
  truth     optional: a ColonPhantom output folder (ground truth: errors are measured)
Empty lines and lines starting with '#' are skipped.
"""
import csv
import json
import os
import re

# Stages in the order ColonSupineProne runs them: (stage name in summary.json, module, record slug).
SCANS = ("supine", "prone")


def stages(case):
    """The stages the workflow runs for a case (dict from read_cases), in pipeline order."""
    out = []
    for scan in SCANS:
        out += [(f"cleansing {scan}", "ColonCleansing"), (f"segmentation {scan}", "ColonSegmentation"),
                (f"surface {scan}", "ColonSurface")]
    out.append(("landmarks", "ColonLandmarks"))
    out += [(f"flattening {scan}", "ColonFlattening") for scan in SCANS]
    out.append(("registration", "ColonRegistration"))
    if not case.get("skip_views"):
        out.append(("flat views", "ColonFlatViews"))
    if case.get("findings"):
        out.append(("transfer findings", "ColonTransferPoints"))
        if not case.get("skip_views"):
            out.append(("endoluminal views", "ColonEndoluminalViews"))
    if case.get("truth"):
        out.append(("evaluation", "ColonEvaluateRegistration"))
    out.append(("report", "ColonSupineProne"))
    return out


def slug(stage):
    return stage.replace(" ", "_")


class TableError(Exception):
    pass


def read_cases(table):
    """The case table as an ordered list of dicts (case, supine, prone, findings, truth; absolute
    paths, '' when not given). Raises TableError listing every problem found."""
    base = os.path.dirname(os.path.abspath(table))
    try:
        with open(table, newline="") as f:
            rows = [r for r in csv.reader(f) if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")]
    except OSError as e:
        raise TableError(f"case table '{table}': cannot be read: {e.strerror}")
    if not rows:
        raise TableError(f"case table '{table}': empty (a header row case,supine,prone[,findings][,truth] and one row per case)")
    header = [h.strip().lower() for h in rows[0]]
    for need in ("case", "supine", "prone"):
        if need not in header:
            raise TableError(f"case table '{table}': no '{need}' column in the header ({','.join(header)})")
    unknown = [h for h in header if h not in ("case", "supine", "prone", "findings", "truth")]
    if unknown:
        raise TableError(f"case table '{table}': unknown column(s) {', '.join(unknown)} "
                         "(case, supine, prone, findings, truth)")
    cases, problems, seen = [], [], set()
    for n, row in enumerate(rows[1:], start=2):
        cell = {h: (row[i].strip() if i < len(row) else "") for i, h in enumerate(header)}
        cid = cell["case"]
        where = f"case table '{table}' line {n}"
        if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._-]*", cid or ""):
            problems.append(f"{where}: case id '{cid}' must be letters, digits, '.', '_' or '-'")
            continue
        if cid in seen:
            problems.append(f"{where}: case id '{cid}' appears twice")
            continue
        seen.add(cid)
        case = {"case": cid}
        for col in ("supine", "prone", "findings", "truth"):
            value = cell.get(col, "")
            if not value:
                if col in ("supine", "prone"):
                    problems.append(f"{where}: case '{cid}' has no {col} scan")
                case[col] = ""
                continue
            path = os.path.normpath(os.path.join(base, value))
            if not os.path.exists(path):
                problems.append(f"{where}: case '{cid}': {col} '{value}' does not exist ({path})")
            elif col == "truth" and not os.path.isfile(os.path.join(path, "supine_eval.mrk.json")):
                problems.append(f"{where}: case '{cid}': truth '{value}' has no supine_eval.mrk.json "
                                "(a ColonPhantom output folder)")
            case[col] = path
        cases.append(case)
    if problems:
        raise TableError("\n".join(problems))
    if not cases:
        raise TableError(f"case table '{table}': no cases")
    return cases


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def stage_records(case, case_dir):
    """The stage records of a case in pipeline order (the report stage excluded), and the notes
    of optional stages that were skipped: the --stageRecords input of ColonSupineProne --reportOnly."""
    records, notes = [], []
    for stage, _module in stages(case):
        if stage == "report":
            continue
        r = read_json(os.path.join(case_dir, "logs", slug(stage) + ".json"))
        if r is None:
            raise FileNotFoundError(f"{case_dir}/logs/{slug(stage)}.json: stage '{stage}' has not finished")
        if r.get("skipped"):
            notes.append(r.get("note", f"{stage} skipped"))
        else:
            records.append({k: r[k] for k in ("name", "module", "seconds", "results")})
    return {"stages": records, "notes": notes}
