#!/usr/bin/python3
"""The docs name only what exists, and speak of the project, not of its
history (doc/user-guide.md, "Tests"). A consistency check, no recorded
numbers:

- every repository path that README.md or a page of doc/ names in
  backquotes or as a Markdown link (prm/..., scripts/..., doc/...,
  tests/..., bench/..., source/..., include/..., figures/...) exists;
- every "doc/PAGE.md section N" (or "sections N to M") names a page that
  exists and a section heading it has;
- no page speaks of issue numbers, sessions, branches or people's roles.

Usage: doc_references.py SOURCE_DIR. Prints one line per problem and exits
1 if there is any.
"""
import os
import re
import sys

ROOTS = ("prm/", "scripts/", "doc/", "tests/", "bench/", "source/",
         "include/", "figures/", ".ci/")
# A git branch is named in backquotes after the word; "branch" alone is
# the law's (a branch of the softening curve).
HISTORY = [re.compile(p, re.I) for p in (
    r"\bissues?\s*#?\d+", r"\bsessions?\b", r"\bbranch\s+`",
    r"\bwork period", r"\bthe engineer\b")]


def pages(src):
    yield os.path.join(src, "README.md")
    for name in sorted(os.listdir(os.path.join(src, "doc"))):
        if name.endswith(".md"):
            yield os.path.join(src, "doc", name)


def headings(path):
    numbers = set()
    for line in open(path, encoding="utf-8"):
        m = re.match(r"#+\s+(\d+(?:\.\d+)*)\b", line)
        if m:
            numbers.add(m.group(1))
    return numbers


def path_exists(src, page, ref):
    ref = ref.rstrip(".,:;)")
    ref = ref.split("#")[0]
    if any(c in ref for c in "*<>{}$") or ref.endswith("/NNNN"):
        return True  # a pattern or a placeholder, not a path
    candidates = [os.path.join(src, ref),
                  os.path.join(os.path.dirname(page), ref)]
    # A test is named by its ctest name: tests/unit/smith_theory is
    # tests/unit/smith_theory.cc (or .sh).
    candidates += [c + ext for c in candidates for ext in (".cc", ".sh")]
    return any(os.path.exists(c) for c in candidates)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: doc_references.py SOURCE_DIR")
    src = sys.argv[1]
    problems = []
    section_ref = re.compile(
        r"(doc/[\w-]+\.md)[,)]?\s+sections?\s+(\d+(?:\.\d+)*)"
        r"(?:\s*(?:to|-|and)\s*(\d+(?:\.\d+)*))?")
    for page in pages(src):
        rel = os.path.relpath(page, src)
        in_code = False
        for n, line in enumerate(open(page, encoding="utf-8"), 1):
            if line.startswith("```"):
                in_code = not in_code
            refs = re.findall(r"`([^`\s]+)`", line)
            refs += re.findall(r"\]\(([^)\s]+)\)", line)
            for ref in refs:
                if ref.startswith(ROOTS) and not path_exists(src, page, ref):
                    problems.append(f"{rel}:{n}: names '{ref}', which does "
                                    "not exist")
            for m in section_ref.finditer(line):
                target = os.path.join(src, m.group(1))
                if not os.path.exists(target):
                    problems.append(f"{rel}:{n}: names {m.group(1)}, which "
                                    "does not exist")
                    continue
                have = headings(target)
                for s in filter(None, (m.group(2), m.group(3))):
                    if s not in have:
                        problems.append(f"{rel}:{n}: names {m.group(1)} "
                                        f"section {s}, which it does not "
                                        "have")
            if not in_code:
                for p in HISTORY:
                    if p.search(line):
                        problems.append(f"{rel}:{n}: speaks of the project's "
                                        f"history ('{p.search(line).group(0)}')")
    for p in problems:
        print(p)
    print(f"{len(problems)} problem(s)")
    sys.exit(1 if problems else 0)


main()
