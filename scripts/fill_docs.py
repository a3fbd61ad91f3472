#!/usr/bin/python3
"""Write the registry's numbers (doc/results/*.json, scripts/reproduce.sh)
into the Markdown pages, between markers (doc/results/README.md):

  in a sentence:
    <!-- result: CASE.QUANTITY [FORMAT] -->12.3<!-- /result -->
  a table, rendered from the template inside the opening comment:
    <!-- result-table
    | t [us] | v [m/s] |
    |---|---|
    | 10 | {CASE.v_10us .2f} |
    -->
    (the rendered table)
    <!-- /result-table -->

QUANTITY is a key of the entry's "quantities", or one of commit, date,
machine, wall_s, level, command. FORMAT is a Python format spec (.2f,
+.2f, .3g; a ',' groups thousands with a space: ',.0f' gives 83 464),
optionally preceded by a scale, '*1e-3 .1f'. A text value (none, no) is
written as it is.

An entry is stale when a commit after its own changed what it depends on
(its "depends" paths: by default source, include and prm), or when it was
run on a tree with uncommitted changes there: its numbers are written with
its commit appended, "29.91 (at a1b2c3d)". A model's own folders (OWN_CODE:
the fabric's) count for the code (source, include, prm) of an entry only
if its command names the model, and only while no code outside them
includes their headers: the other models and the run never see them
(doc/architecture.md).

  fill_docs.py [FILE...]          rewrite the markers (README.md and
                                  doc/*.md by default)
  fill_docs.py --check [FILE...]  change nothing; exit 1 listing every
                                  marked number that differs from the
                                  registry's and every marker naming an
                                  entry or quantity the registry lacks
                                  (--strict: a stale entry not shown as
                                  stale too)
"""
import glob
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REGISTRY = os.path.join(ROOT, "doc", "results")
INLINE = re.compile(r"<!-- result: (\S+)((?: [^>]*?)?) -->(.*?)<!-- /result -->",
                    re.S)
TABLE = re.compile(r"<!-- result-table\n(.*?)-->\n(.*?)<!-- /result-table -->",
                   re.S)
PLACEHOLDER = re.compile(r"\{([\w-]+\.[^\s{}]+)((?: [^{}]*?)?)\}")
META = ("commit", "date", "machine", "wall_s", "level", "command")
CODE = ("source", "include", "prm")
# A model's own folders, which nothing else includes: a change there
# outdates only the entries whose command names the model.
OWN_CODE = {"fabric": ("source/fabric", "include/yarn_impact/fabric",
                       "prm/fabric")}


class Missing(Exception):
    pass


class Registry:
    def __init__(self, root=ROOT):
        self.root = root
        self.entries = {}
        for path in glob.glob(os.path.join(root, "doc", "results", "*.json")):
            with open(path) as f:
                entry = json.load(f)
            self.entries[entry["case"]] = entry
        self._stale = {}
        self._apart = {}

    def git(self, *args):
        return subprocess.run(["git", "-C", self.root] + list(args),
                              capture_output=True, text=True)

    def apart(self, paths):
        """Whether no source or header outside PATHS includes a header of
        PATHS' include folder (then a change in PATHS cannot reach a run of
        another model). Asked once per PATHS."""
        if paths not in self._apart:
            headers = [p[len("include/"):] for p in paths if p.startswith("include/")]
            args = ["grep", "-l", "-E",
                    "#include *[<\"](" + "|".join(re.escape(h) for h in headers) + ")/",
                    "--", "source", "include"] + [":(exclude)" + p for p in paths]
            result = self.git(*args) if headers else None
            self._apart[paths] = bool(result and result.returncode == 1
                                      and not result.stdout.strip())
        return self._apart[paths]

    def stale(self, case):
        """None if the entry is current, else its short commit."""
        if case not in self._stale:
            e = self.entries[case]
            deps = list(e.get("depends") or CODE)
            if any(d in CODE for d in deps):
                for model, paths in OWN_CODE.items():
                    if model not in e.get("command", "") and self.apart(paths):
                        deps += [":(exclude)" + p for p in paths]
            last = self.git("log", "-1", "--format=%H", "--", *deps).stdout.strip()
            fresh = True
            if last:
                fresh = self.git("merge-base", "--is-ancestor", last,
                                 e.get("commit_full", e["commit"])
                                 ).returncode == 0
            if e.get("dirty") and any(
                    p == d or p.startswith(d.rstrip("/") + "/")
                    for p in e.get("dirty_paths", []) for d in deps):
                fresh = False
            self._stale[case] = None if fresh else e["commit"]
        return self._stale[case]

    def value(self, ref, fmt):
        """The text of CASE.QUANTITY in FORMAT, and whether it is stale."""
        case, _, quantity = ref.partition(".")
        if case not in self.entries:
            raise Missing("no registry entry '%s' (doc/results/%s.json)"
                          % (case, case))
        e = self.entries[case]
        if quantity in META:
            v = e[quantity]
            if quantity == "machine":
                v = "%s, %s, %d cores" % (v["cpu"], v["arch"], v["cores"])
            return (format(v, fmt.strip()) if fmt.strip() else str(v)), None
        if quantity not in e["quantities"]:
            raise Missing("entry '%s' has no quantity '%s'" % (case, quantity))
        return render(e["quantities"][quantity], fmt), self.stale(case)


def render(v, fmt):
    fmt = fmt.strip()
    scale = 1.0
    m = re.match(r"([*/])(\S+)\s*(.*)$", fmt)
    if m:
        scale = float(m.group(2)) if m.group(1) == "*" else 1 / float(m.group(2))
        fmt = m.group(3)
    if isinstance(v, str):
        return v
    v = v * scale
    if not fmt:
        return ("%d" % v) if float(v).is_integer() else repr(v)
    text = format(v, fmt)
    return text.replace(",", " ") if "," in fmt else text


def with_stale(text, stale):
    return "%s (at %s)" % (text, stale) if stale else text


def fill(text, reg, problems, where):
    """The page with every marker rendered; problems gets (kind, message)
    for what does not render or differs from the page."""

    def line_of(pos):
        return "%s:%d" % (where, text.count("\n", 0, pos) + 1)

    def inline(m):
        ref, fmt, old = m.group(1), m.group(2), m.group(3)
        try:
            value, stale = reg.value(ref, fmt)
        except Missing as e:
            problems.append(("missing", "%s: %s: %s" % (line_of(m.start()), ref, e)))
            return m.group(0)
        new = with_stale(value, stale)
        compare(old, new, value, ref, line_of(m.start()), problems)
        return "<!-- result: %s%s -->%s<!-- /result -->" % (ref, fmt, new)

    def table(m):
        template, old = m.group(1), m.group(2)
        failed = []

        def cell(p):
            try:
                value, stale = reg.value(p.group(1), p.group(2))
                return with_stale(value, stale)
            except Missing as e:
                failed.append("%s: %s: %s" % (line_of(m.start()), p.group(1), e))
                return p.group(0)
        new = PLACEHOLDER.sub(cell, template)
        if failed:
            problems.extend(("missing", f) for f in failed)
            return m.group(0)
        plain = PLACEHOLDER.sub(
            lambda p: reg.value(p.group(1), p.group(2))[0], template)
        compare(old, new, plain, "table", line_of(m.start()), problems)
        return "<!-- result-table\n%s-->\n%s<!-- /result-table -->" % (
            template, new)

    # Markers inside code blocks (``` fences) are examples, not markers.
    parts = re.split(r"(^```.*?^```[^\n]*$)", text, flags=re.S | re.M)
    out = []
    offset = 0
    for k, part in enumerate(parts):
        if k % 2 == 0:
            base = offset

            def shifted(fn):
                def run(m):
                    return fn(_Shift(m, base))
                return run
            part = TABLE.sub(shifted(table), INLINE.sub(shifted(inline), part))
        offset += len(parts[k])
        out.append(part)
    return "".join(out)


class _Shift:
    """A match whose start() counts from the start of the page."""

    def __init__(self, m, base):
        self.m, self.base = m, base

    def group(self, *a):
        return self.m.group(*a)

    def start(self):
        return self.base + self.m.start()


def compare(old, new, plain, ref, where, problems):
    if old == new:
        return
    strip = re.sub(r" \(at [0-9a-f]{7,}\)", "", old)
    if strip == plain:
        problems.append(("stale", "%s: %s is stale: the registry's entry is "
                         "older than the code it describes; fill_docs.py "
                         "marks it" % (where, ref)))
    else:
        shown = old if "\n" not in old else "the table above the marker"
        problems.append(("differs", "%s: %s reads '%s', the registry "
                         "gives '%s'" % (where, ref, shown,
                                         new if "\n" not in new else
                                         "another table")))


def pages(args):
    if args:
        return args
    out = [os.path.join(ROOT, "README.md")]
    out += sorted(glob.glob(os.path.join(ROOT, "doc", "*.md")))
    out += sorted(glob.glob(os.path.join(ROOT, "doc", "*", "*.md")))
    return out


def main():
    args = sys.argv[1:]
    check = "--check" in args
    strict = "--strict" in args
    files = [a for a in args if not a.startswith("--")]
    reg = Registry()
    errors = []
    changed = []
    for page in pages(files):
        rel = os.path.relpath(page, ROOT)
        text = open(page, encoding="utf-8").read()
        problems = []
        new = fill(text, reg, problems, rel)
        for kind, message in problems:
            if kind == "missing" or kind == "differs" or strict:
                errors.append(message)
            elif check:
                print("warning: " + message)
        if not check and new != text:
            with open(page, "w", encoding="utf-8") as f:
                f.write(new)
            changed.append(rel)
    if check:
        for e in errors:
            print(e)
        if errors:
            print("fill_docs.py --check: %d problem(s); run "
                  "/usr/bin/python3 scripts/fill_docs.py (after "
                  "bash scripts/reproduce.sh for missing entries)"
                  % len(errors))
            return 1
        return 0
    for e in errors:
        if "no registry entry" in e or "has no quantity" in e:
            print(e)
    for rel in changed:
        print("filled " + rel)
    stale = sorted({c for c in reg.entries if reg.stale(c)})
    if stale:
        print("stale entries (shown with their commit): " + ", ".join(stale))
    return 1 if any("no registry entry" in e or "has no quantity" in e
                    for e in errors) else 0


if __name__ == "__main__":
    sys.exit(main())
