#!/usr/bin/env python3
"""reproduce_page.py — docs/reproduction.md from what `make reproduce` ran.

Design.  scripts/reproduce.sh leaves one directory per study, each with
meta.json, rows.jsonl and conventions.jsonl (scripts/reproduce/rows.py) and
status (the module's exit code, wall time and budget).  This script reads
them all and writes the page: where and when it was made (commit, machine,
budget), a summary of verdicts per study, then each study's section (the
reference's place, models, command lines, wall time, plots copied to
docs/img/reproduce/, the table of claims), the defaults of sinew that
differ from the reference's code with their measured effects, and the rows
whose figures are not bitwise reproducible, with why.  Nothing here is
typed by hand: a study that did not run says so, with its log.

  reproduce_page.py OUTDIR --budget quick --page docs/reproduction.md --studies S...
"""
import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOOD = ("agree", "holds")


def sh(*cmd):
    try:
        return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True).stdout.strip()
    except OSError:
        return ""


def cpu():
    for line in sh("lscpu").splitlines():
        if line.startswith("Model name:"):
            return line.split(":", 1)[1].strip()
    return platform.processor() or "unknown"


def isa():
    flags = open("/proc/cpuinfo").read() if os.path.exists("/proc/cpuinfo") else ""
    return "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE"


def load(d):
    def js(name, default):
        p = os.path.join(d, name)
        if not os.path.exists(p):
            return default
        with open(p) as f:
            return json.load(f)

    def jl(name):
        p = os.path.join(d, name)
        if not os.path.exists(p):
            return []
        with open(p) as f:
            return [json.loads(line) for line in f if line.strip()]

    return js("meta.json", None), jl("rows.jsonl"), jl("conventions.jsonl"), js("status", None)


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def duration(s):
    s = int(round(s))
    return "%d s" % s if s < 120 else "%d min %02d s" % (s // 60, s % 60) if s < 7200 else \
        "%d h %02d min" % (s // 3600, (s % 3600) // 60)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--budget", default="quick")
    ap.add_argument("--page", default="docs/reproduction.md")
    ap.add_argument("--studies", nargs="*", default=None)
    a = ap.parse_args()
    studies = a.studies or sorted(os.listdir(a.outdir))
    page = os.path.join(ROOT, a.page) if not os.path.isabs(a.page) else a.page
    imgdir = os.path.join(os.path.dirname(page), "img", "reproduce")
    os.makedirs(imgdir, exist_ok=True)

    commit = sh("git", "rev-parse", "--short=12", "HEAD")
    # the sources against the commit: the page and its plots, which this
    # writes, do not count
    mine = [os.path.relpath(p, ROOT) for p in (page, imgdir)]
    dirty = sh("git", "status", "--porcelain", "--untracked-files=no", "--", ".",
               *[":(exclude)" + p for p in mine if not p.startswith("..")])
    out = []
    w = out.append
    w("# The reference reproduced\n")
    w("sinew against Zhang et al., *Modeling and simulation of complex dynamic musculoskeletal "
      "architectures*, Nat. Commun. 10, 4825 (2019), its Supplementary Information: every study "
      "it holds, run by one command. This page is written by that command from what the runs "
      "measured; nothing in its tables is typed by hand.\n")
    w("```sh\nmake && make reproduce %s\n```\n" % a.budget)
    w("| | |\n|---|---|")
    w("| budget | `%s`%s |" % (a.budget, " (shortened runs: each study's notes say what is cut)"
                                if a.budget == "quick" else " (the reference's settings)"))
    w("| page written at | `%s`%s, %s |" % (commit, " with uncommitted changes" if dirty else "",
                                           datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")))
    w("| machine | %s (%s), %d logical CPUs |\n" % (cpu(), isa(), os.cpu_count() or 0))
    w("Verdicts: **agree** (a number within the stated tolerance of the reference's), **differ** "
      "(it is not; the row says why, with the evidence), **holds** or **fails** (a statement of the "
      "reference's, tested on this run).\n")

    loaded = []
    for s in studies:
        d = os.path.join(a.outdir, s)
        if not os.path.isdir(d):
            continue
        loaded.append((s, d) + load(d))

    w("## Summary\n")
    w("| study | reference | claims | agree or hold | differ or fail | wall (load average at its start) | run at (commit; + uncommitted changes) |")
    w("|---|---|--:|--:|--:|--:|---|")
    total = [0, 0, 0, 0.0]
    for s, d, meta, rows, conv, status in loaded:
        good = sum(r["verdict"] in GOOD for r in rows)
        wall = status["wall"] if status else 0
        title = meta["title"] if meta else s
        ref = meta["reference"] if meta else ""
        state = "" if status and status["exit"] == 0 else " (**run failed**)"
        when = "`%s`, %s" % (status.get("commit", "?"), status.get("made", "?")) if status else "-"
        w("| [%s](#%s)%s | %s | %d | %d | %d | %s | %s |" % (cell(title), s, state, cell(ref), len(rows), good,
                                                        len(rows) - good, duration(wall) +
                                                        (" (%.1f)" % status["load"] if status and "load" in status else ""),
                                                        when))
        total[0] += len(rows)
        total[1] += good
        total[2] += len(rows) - good
        total[3] += wall
    w("| **all** | | %d | %d | %d | %s | |\n" % (total[0], total[1], total[2], duration(total[3])))

    conventions = []
    nonbitwise = []
    for s, d, meta, rows, conv, status in loaded:
        title = meta["title"] if meta else s
        w('<a id="%s"></a>\n' % s)
        w("## %s\n" % title)
        if not status or status["exit"] != 0:
            w("**The run failed** (exit %s); its log is `%s/module.log` on the machine that ran it.\n"
              % (status["exit"] if status else "unknown", d))
        if not meta:
            w("No results were written.\n")
            continue
        w("Reference: %s. Models: %s. Wall time: %s.\n" % (
            meta["reference"], ", ".join("`%s`" % m for m in meta["models"]) or "-",
            duration(status["wall"]) if status else "-"))
        if meta["commands"]:
            w("```sh\n%s\n```\n" % "\n".join(meta["commands"]))
        for p in meta["plots"]:
            src = os.path.join(d, p)
            if os.path.exists(src):
                name = "%s_%s" % (s, os.path.basename(p))
                shutil.copyfile(src, os.path.join(imgdir, name))
                w("![%s](img/reproduce/%s)\n" % (p, name))
        if rows:
            w("| figure | the reference | sinew, this run | verdict | why |")
            w("|---|---|---|---|---|")
            for r in rows:
                v = r["verdict"] if r["verdict"] in GOOD else "**%s**" % r["verdict"]
                w("| %s | %s | %s | %s | %s |" % (cell(r["figure"]), cell(r["claim"]), cell(r["sinew"]), v,
                                                 cell(r["why"])))
                if not r["bitwise"]:
                    nonbitwise.append((title, r))
            w("")
        if meta["notes"]:
            w(meta["notes"] + "\n")
        conventions += [(title, c) for c in conv]

    w("## sinew's defaults that are not the reference code's\n")
    if conventions:
        w("| sinew's default | the reference's code | scenes | effect, measured |")
        w("|---|---|---|---|")
        for title, c in conventions:
            w("| %s | %s | %s | %s |" % (cell(c["default"]), cell(c["reference"]), cell(c["scenes"]),
                                         cell(c["effect"])))
        w("")
    else:
        w("None was measured in this run.\n")

    w("## Run to run\n")
    w("Every figure above depends only on the model, the step and the budget, and is bitwise "
      "identical when the page is made again, except these:\n" if nonbitwise else
      "Every figure above depends only on the model, the step and the budget, and is bitwise "
      "identical when the page is made again.\n")
    for title, r in nonbitwise:
        w("- %s, %s: %s" % (title, r["figure"], r["why"]))
    if nonbitwise:
        w("")
    with open(page, "w") as f:
        f.write("\n".join(out))
    bad = [s for s, d, meta, rows, conv, status in loaded if not status or status["exit"] != 0]
    print("reproduce_page.py: %d studies, %d claims (%d agree or hold, %d differ or fail)%s" %
          (len(loaded), total[0], total[1], total[2],
           "; failed runs: " + ", ".join(bad) if bad else ""))


if __name__ == "__main__":
    sys.exit(main())
