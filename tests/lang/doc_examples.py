#!/usr/bin/env python3
"""doc_examples.py ROOT DOC... -- the shell sessions a page shows, run as shown.

A ```text block whose first line starts with "$ " is a session: its "$ "
lines are commands, the lines after each its output as the page shows it.
The commands run in order, one scratch directory per page (bin, examples,
models, scripts and tests of ROOT linked into it, so "bin/sinewc examples/x.sinew"
reads as on the page), stdout and stderr together.  A command passes when
its exit code is the one the page says (0 unless the text after the block
says "(exit N", for its last command), and every shown line is found in what it printed, in order
("..." on a line of its own stands for lines left out).  A command that
names a .sinew file the repository does not have (the tutorial's own
misspelt finger.sinew) is skipped, said as a TAP skip.  Prints TAP.
"""
import os, re, subprocess, sys, tempfile

root, docs = sys.argv[1], sys.argv[2:]
n = failed = 0

def ok(cond, what, diag=""):
    global n, failed
    n += 1
    print(("ok" if cond else "not ok"), n, "-", what)
    if not cond:
        failed += 1
        for line in diag.splitlines()[:40]:
            print("#", line)

for doc in docs:
    text = open(os.path.join(root, doc), encoding="utf-8").read()
    scratch = tempfile.mkdtemp(prefix="sinew-doc-")
    for d in ("bin", "examples", "models", "scripts", "build", "tests"):
        os.symlink(os.path.join(root, d), os.path.join(scratch, d))
    for m in re.finditer(r"```text\n(.*?)```", text, re.S):
        body, after = m.group(1), text[m.end():m.end() + 200]
        lines = body.rstrip("\n").split("\n")
        if not lines[0].startswith("$ "):
            continue
        line_no = text[:m.start()].count("\n") + 2
        exit_said = re.match(r"\s*\(exit (\d+)", after)
        # the session: [command, [shown lines]]
        session = []
        for line in lines:
            if line.startswith("$ "):
                session.append([line[2:], []])
            else:
                session[-1][1].append(line)
        for k, (cmd, shown) in enumerate(session):
            files = re.findall(r"(\S+\.sinew)", cmd)
            if any(not os.path.exists(os.path.join(scratch, f)) for f in files):
                n += 1
                print("ok", n, "- %s:%d: %s # SKIP its model is the page's own" % (doc, line_no, cmd))
                continue
            r = subprocess.run(cmd, shell=True, cwd=scratch, capture_output=True, text=True,
                               timeout=300)
            out = (r.stdout + r.stderr).split("\n")
            want_rc = int(exit_said.group(1)) if exit_said and k == len(session) - 1 else 0
            pos, missing = 0, None
            for s in shown:
                if s.strip() == "...":
                    continue
                while pos < len(out) and out[pos].rstrip() != s.rstrip():
                    pos += 1
                if pos == len(out):
                    missing = s
                    break
                pos += 1
            good = r.returncode == want_rc and missing is None
            why = "exit %d (the page: %d)\n" % (r.returncode, want_rc)
            if missing is not None:
                why += "shown but not printed: %s\nprinted:\n%s" % (missing, "\n".join(out))
            ok(good, "%s:%d: $ %s" % (doc, line_no, cmd), why)
print("1..%d" % n)
sys.exit(1 if failed else 0)
