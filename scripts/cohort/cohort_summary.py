#!/usr/bin/env python3
"""The cohort summary (issue 25): one row per case of the table, from what the workflow left in
the output folder; written at the end of every run (onsuccess / onerror of the Snakefile).

    cohort_summary.py CASES.csv OUT

Writes OUT/cohort_summary.csv, OUT/cohort_summary.json and OUT/cohort_summary.html. Status per
case: "done" (summary.json and every stage record), "failed" (a stage left logs/<stage>.failed:
its module's one-line error is the reason), "incomplete" (not run to the end, e.g. stopped or
after a failure upstream in the other scan). Failed cases are always listed, with the reason.
Prints one line per case that is not done, and the totals.
"""
import csv
import html
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cohort  # noqa: E402


def case_row(case, out):
    d = os.path.join(out, case["case"])
    stages = cohort.stages(case)
    row = {"case": case["case"], "status": "", "failed_stage": "", "reason": "", "warnings": "",
           "flags_not_ok": "", "total_seconds": "", "mean_error_mm": "", "p90_error_mm": "",
           "polyp_error_mm": "", "findings": "", "unreliable_findings": "", "report": "", "seconds": {},
           "failures": []}
    for stage, module in stages:
        r = cohort.read_json(os.path.join(d, "logs", cohort.slug(stage) + ".json"))
        if r and "seconds" in r:
            row["seconds"][stage] = r["seconds"]
        f = cohort.read_json(os.path.join(d, "logs", cohort.slug(stage) + ".failed"))
        if f:
            row["failures"].append({"stage": stage, "module": module, "reason": f.get("reason", "")})
    summary = cohort.read_json(os.path.join(d, "summary.json"))
    done = summary is not None and all(
        os.path.exists(os.path.join(d, "logs", cohort.slug(s) + ".json")) for s, _ in stages)
    if row["failures"]:
        row["status"] = "failed"
        row["failed_stage"] = row["failures"][0]["stage"]
        row["reason"] = row["failures"][0]["reason"]
    elif done:
        row["status"] = "done"
    else:
        row["status"] = "incomplete"
        missing = [s for s, _ in stages if not os.path.exists(os.path.join(d, "logs", cohort.slug(s) + ".json"))]
        row["failed_stage"] = missing[0] if missing else "report"
        row["reason"] = f"not finished: '{row['failed_stage']}' has not run to the end (stopped, or not run yet)"
    if summary is not None and row["status"] == "done":
        row["warnings"] = summary.get("warnings", "")
        row["flags_not_ok"] = "; ".join(q["name"] for q in summary.get("quality", []) if not q.get("ok"))
        row["total_seconds"] = round(summary.get("totalSeconds", 0.0), 2)
        findings = summary.get("findings", [])
        row["findings"] = len(findings)
        row["unreliable_findings"] = sum(1 for f in findings if f.get("reliable") is False)
        row["report"] = f"{case['case']}/report.html"
        errors = cohort.read_json(os.path.join(d, "evaluation", "errors.json"))
        if errors:
            e3 = errors.get("overall", {}).get("error3D", {})
            if "mean" in e3:
                row["mean_error_mm"] = round(e3["mean"], 3)
                row["p90_error_mm"] = round(e3.get("p90", float("nan")), 3)
            if "polyps" in errors and "mean" in errors["polyps"].get("error3D", {}):
                row["polyp_error_mm"] = round(errors["polyps"]["error3D"]["mean"], 3)
    return row


def all_stage_names(cases):
    names = []
    for c in cases:
        for s, _ in cohort.stages(c):
            if s not in names:
                names.append(s)
    return names


def write_csv(path, rows, stage_names):
    fields = ["case", "status", "failed_stage", "reason", "warnings", "flags_not_ok", "total_seconds",
              "mean_error_mm", "p90_error_mm", "polyp_error_mm", "findings", "unreliable_findings", "report"]
    tmp = path + ".part"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(fields + [f"seconds {s}" for s in stage_names])
        for r in rows:
            w.writerow([r[k] for k in fields] +
                       [("%.2f" % r["seconds"][s]) if s in r["seconds"] else "" for s in stage_names])
    os.replace(tmp, path)


def write_html(path, rows, stage_names, table):
    e = html.escape
    counts = {s: sum(1 for r in rows if r["status"] == s) for s in ("done", "failed", "incomplete")}
    css = ("body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse;margin:1em 0}"
           "td,th{border:1px solid #bbb;padding:3px 7px;font-size:13px;text-align:left;vertical-align:top}"
           "th{background:#eee}.failed{background:#fdd}.incomplete{background:#ffe9c2}.check{color:#a60;font-weight:bold}"
           ".ok{color:#080;font-weight:bold}code{font-size:12px}")
    out = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>ColonMap cohort</title><style>{css}</style></head><body>",
           "<h1>ColonMap cohort summary</h1>",
           f"<p>Case table: <code>{e(os.path.abspath(table))}</code>. {len(rows)} cases: {counts['done']} done, "
           f"{counts['failed']} failed, {counts['incomplete']} incomplete.</p>"]
    bad = [r for r in rows if r["status"] != "done"]
    if bad:
        out.append("<h2>Cases that did not finish</h2><table><tr><th>case</th><th>status</th><th>stage</th><th>reason (the module's stderr line)</th><th>log</th></tr>")
        for r in bad:
            log = f"{r['case']}/logs/{cohort.slug(r['failed_stage'])}.stderr" if r["status"] == "failed" else ""
            more = "".join(f"<br>{e(f['stage'])}: <code>{e(f['reason'])}</code>" for f in r["failures"][1:])
            out.append(f"<tr class='{r['status']}'><td>{e(r['case'])}</td><td>{r['status']}</td><td>{e(r['failed_stage'])}</td>"
                       f"<td><code>{e(r['reason'])}</code>{more}</td><td>" + (f"<a href='{e(log)}'>{e(log)}</a>" if log else "") + "</td></tr>")
        out.append("</table>")
    out.append("<h2>All cases</h2><table><tr><th>case</th><th>status</th><th>quality</th><th>mean error mm</th>"
               "<th>p90 error mm</th><th>polyp error mm</th><th>findings (unreliable)</th><th>seconds</th><th>report</th></tr>")
    for r in rows:
        if r["status"] == "done":
            q = ("<span class='ok'>OK</span>" if not r["warnings"] else
                 f"<span class='check'>CHECK {r['warnings']}</span>: {e(r['flags_not_ok'])}")
            link = f"<a href='{e(r['report'])}'>report</a>"
        else:
            q, link = f"{r['status']}: {e(r['reason'])}", ""
        total = r["total_seconds"] if r["total_seconds"] != "" else round(sum(r["seconds"].values()), 2)
        out.append(f"<tr class='{r['status'] if r['status'] != 'done' else ''}'><td>{e(r['case'])}</td><td>{r['status']}</td><td>{q}</td>"
                   f"<td>{r['mean_error_mm']}</td><td>{r['p90_error_mm']}</td><td>{r['polyp_error_mm']}</td>"
                   f"<td>{r['findings']}" + (f" ({r['unreliable_findings']})" if r["findings"] != "" else "") +
                   f"</td><td>{total}</td><td>{link}</td></tr>")
    out.append("</table><h2>Stage seconds</h2><table><tr><th>case</th>" + "".join(f"<th>{e(s)}</th>" for s in stage_names) + "</tr>")
    for r in rows:
        out.append(f"<tr><td>{e(r['case'])}</td>" + "".join(
            f"<td>{r['seconds'][s]:.2f}</td>" if s in r["seconds"] else "<td>-</td>" for s in stage_names) + "</tr>")
    out.append("</table><p>Per case: <code>CASE/summary.json</code>, <code>CASE/report.html</code>, stage folders as "
               "ColonSupineProne writes them, <code>CASE/logs/</code> (per stage: record, stdout, stderr).</p></body></html>\n")
    tmp = path + ".part"
    with open(tmp, "w") as f:
        f.write("\n".join(out))
    os.replace(tmp, path)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    table, out = sys.argv[1], sys.argv[2]
    cases = cohort.read_cases(table)
    rows = [case_row(c, out) for c in cases]
    names = all_stage_names(cases)
    write_csv(os.path.join(out, "cohort_summary.csv"), rows, names)
    write_html(os.path.join(out, "cohort_summary.html"), rows, names, table)
    tmp = os.path.join(out, "cohort_summary.json.part")
    with open(tmp, "w") as f:
        json.dump({"table": os.path.abspath(table), "cases": rows}, f, indent=2)
    os.replace(tmp, os.path.join(out, "cohort_summary.json"))
    for r in rows:
        if r["status"] != "done":
            print(f"cohort: {r['case']}: {r['status']} at '{r['failed_stage']}': {r['reason']}")
    n_done = sum(1 for r in rows if r["status"] == "done")
    print(f"cohort: {n_done} of {len(rows)} cases done; summary: {os.path.join(out, 'cohort_summary.html')}")


if __name__ == "__main__":
    main()
