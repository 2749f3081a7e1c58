#!/usr/bin/python3
"""put_section.py — put a generated section into a Markdown file.

Usage: put_section.py FILE TITLE TEXT
Replaces the section "## TITLE" of FILE (up to the next "## " heading) with
TITLE and TEXT, or appends it when FILE has no such section (a FILE that
does not exist yet is made with the section alone, so a bench script can
write to a scratch report).  The bench scripts write their figures into
docs/benchmarks.md with it."""
import re
import sys

path, title, body = sys.argv[1:4]
try:
    text = open(path).read()
except FileNotFoundError:
    text = ""
section = f"## {title}\n\n{body.strip()}\n"
pat = re.compile(r"## " + re.escape(title) + r"\n.*?(?=\n## |\Z)", re.S)
if pat.search(text):
    # the match ends before the newline that precedes the next heading, so
    # the section keeps its own newline: a blank line before that heading
    text = pat.sub(lambda _: section, text)
else:
    text = (text.rstrip("\n") + "\n\n" if text.strip() else "") + section
open(path, "w").write(text)
