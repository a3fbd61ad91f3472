#!/usr/bin/python3
"""The docs' numbers are the registry's, and the docs speak of the
project, not of who worked on it or when (doc/results/README.md):

- scripts/fill_docs.py --check passes: every number between result markers
  in README.md and doc/ is its registry entry's (doc/results/*.json), and
  every marker names an entry and a quantity the registry has (stale
  entries are warned about, not failed);
- no page (README.md, doc/*.md, doc/results/README.md, outside code
  blocks) speaks of people, branches, work periods or issue numbers;
- the pages in HISTORY_PAGES describe the code as it is, not how it
  changed ("today", "no longer", "is now", "not merged", "earlier code").

Usage: doc_results.py SOURCE_DIR. Prints one line per problem and exits 1
if there is any.
"""
import glob
import os
import re
import subprocess
import sys

PATTERNS = [re.compile(p, re.I) for p in (
    # issue and pull-request numbers, tickets
    r"\bissues?\s*#?\d+", r"(^|\s)#\d+\b", r"\bPR\s*#?\d+",
    r"\bpull requests?\b", r"\btickets?\b",
    # branches and working copies
    r"\bbranch\s+[`'\"]", r"\b(main|master)\s+branch\b", r"\bworktrees?\b",
    r"\bwt-\w+", r"\bmerged?\s+(into|to|from)\s+(main|master)\b",
    # work periods
    r"\bwork periods?\b", r"\bsprints?\b", r"\byesterday\b", r"\btomorrow\b",
    r"\bthis (morning|afternoon|week)\b", r"\blast (night|week)\b",
    r"\bsessions?\b",
    # people
    r"\bthe engineer\b", r"\bcolleagues?\b", r"\breviewers?\b",
    r"\bassignees?\b", r"\bhelpers? (agent|session)\b",
)]

# Wording of the project's history. Some of it has a physical sense too
# ("the broken yarn no longer decelerates it"), so it is checked on the
# pages that are written without it.
HISTORY = [re.compile(p, re.I) for p in (
    r"\btoday'?s?\b", r"\bnot merged\b", r"\bno longer\b", r"\bused to\b",
    r"\bbefore this (commit|change)", r"\bearlier (code|versions?|commits?)\b",
    r"\bis now\b", r"\bprevious (code|versions?|commits?)\b",
    r"\bfirst version\b", r"\b(we|our)\b",
)]
HISTORY_PAGES = ("README.md", "doc/fe-model.md", "doc/theory.md",
                 "doc/user-guide.md", "doc/dem.md", "doc/performance.md",
                 "doc/performance-dem.md")


def pages(src):
    yield os.path.join(src, "README.md")
    yield from sorted(glob.glob(os.path.join(src, "doc", "*.md")))
    yield from sorted(glob.glob(os.path.join(src, "doc", "*", "*.md")))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: doc_results.py SOURCE_DIR")
    src = sys.argv[1]
    problems = []
    for page in pages(src):
        rel = os.path.relpath(page, src)
        in_code = False
        for n, line in enumerate(open(page, encoding="utf-8"), 1):
            if line.startswith("```"):
                in_code = not in_code
            if in_code:
                continue
            for p in PATTERNS:
                m = p.search(line)
                if m:
                    problems.append(f"{rel}:{n}: speaks of people, branches, "
                                    f"work periods or issues ('{m.group(0).strip()}')")
            if rel in HISTORY_PAGES:
                for p in HISTORY:
                    m = p.search(line)
                    if m:
                        problems.append(f"{rel}:{n}: speaks of the project's "
                                        f"history or of its authors "
                                        f"('{m.group(0).strip()}')")
    check = subprocess.run(
        ["/usr/bin/python3", os.path.join(src, "scripts", "fill_docs.py"),
         "--check"], capture_output=True, text=True)
    print(check.stdout, end="")
    if check.returncode != 0:
        problems.append("scripts/fill_docs.py --check failed (above)")
    for p in problems:
        print(p)
    print(f"{len(problems)} problem(s)")
    sys.exit(1 if problems else 0)


main()
