#!/usr/bin/env bash
# What the docs and comments name exists: every repository path (tools/..., scenarios/...,
# docs/..., tests/..., bench/..., src/..., include/...) in README.md, docs/*.md, the public
# headers, the sources and the tools, and every src-relative file (engine/contact.c) in the
# headers and sources; and every option written after `rockdem SUBCOMMAND` or a tool's name in
# the README and docs is in that command's --help. CHANGELOG.md is history and names the paths
# of its day. One FAIL line per stale name, with file and line.
set -u
BIN=${RD_BIN:-bin/rockdem}
cd "$(dirname "$0")/../.."
/usr/bin/python3 - "$BIN" <<'PY'
import glob, os, re, subprocess, sys
BIN = sys.argv[1]
# paths the reader makes (the tutorial's own scene) or the build writes
MADE = ("scenarios/myrock.dat", "tools/dist/", "tools/build/", "tools/rockdem/bin",
        "tools/rockdem/librockdem.so", "tests/fuzz/found/", "bench/results.txt")
DOCS = ["README.md"] + sorted(glob.glob("docs/*.md"))
CODE = sorted(glob.glob("include/rockdem/*.h") + glob.glob("src/*/*.[ch]") + glob.glob("tools/*.py")
              + glob.glob("tools/*/*.py") + glob.glob("tests/*.c") + glob.glob("bench/*.sh")
              + glob.glob("tests/cli/*.sh") + ["Makefile"])
TOP = re.compile(r"(?<![\w./-])((?:tools|scenarios|docs|tests|bench|src|include)/[A-Za-z0-9_.*/-]*[A-Za-z0-9_*/])")
SRC = re.compile(r"(?<![\w./-])((?:%s)/[A-Za-z0-9_]+\.[ch])\b" % "|".join(sorted(os.listdir("src"))))
fails = checked = 0

def fail(where, what):
    global fails
    print("FAIL doc-paths %s: %s" % (where, what))
    fails += 1

for f in DOCS + CODE:
    for n, line in enumerate(open(f, errors="replace"), 1):
        if f.startswith("tests/") and "tests/data/" in line and "rd_scenario_parse" in line:
            continue  # a scenario's name for its error messages, not a file
        for m in TOP.finditer(line):
            p = m.group(1).rstrip(".")
            checked += 1
            if not p.startswith(MADE) and not glob.glob(p):
                fail("%s:%d" % (f, n), "%s does not exist" % p)
        if f.endswith((".c", ".h")):
            for m in SRC.finditer(line):
                checked += 1
                if not os.path.exists("src/" + m.group(1)):
                    fail("%s:%d" % (f, n), "src/%s does not exist" % m.group(1))

def helptext(cmd):
    p = subprocess.run(cmd + ["--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.stdout

SUBS = ("run", "check", "reference", "threshold", "restitution", "study", "sweep", "assess", "keys")
common = helptext([BIN])
helps = {}
CMD = re.compile(r"rockdem (%s)\b([^`\n]*)" % "|".join(SUBS))
TOOL = re.compile(r"tools/(rd\w+|study|make_pbr)\.py((?: (?:planes|select|calibrate)\b)?)([^`\n]*)")
OPT = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)")

def has(opt, text):
    return re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(opt), text)

for f in DOCS:
    for n, line in enumerate(open(f), 1):
        for m in CMD.finditer(line):
            sub = m.group(1)
            if sub not in helps:
                helps[sub] = helptext([BIN, sub]) + common
            for o in OPT.findall(m.group(2)):
                checked += 1
                if not has(o, helps[sub]):
                    fail("%s:%d" % (f, n), "rockdem %s has no option %s (rockdem %s --help)" % (sub, o, sub))
        for m in TOOL.finditer(line):
            key = "tools/" + m.group(1) + m.group(2)
            if key not in helps:
                # rdparaview needs pvpython to run: its options are read from its source
                helps[key] = open("tools/rdparaview.py").read() if m.group(1) == "rdparaview" else \
                    helptext(["/usr/bin/python3", "tools/%s.py" % m.group(1)] + m.group(2).split())
            for o in OPT.findall(m.group(3)):
                checked += 1
                if not has(o, helps[key]):
                    fail("%s:%d" % (f, n), "tools/%s.py%s has no option %s" % (m.group(1), m.group(2), o))
if not fails:
    print("CHECK doc-paths: %d paths and options named in the docs and comments exist" % checked)
sys.exit(1 if fails else 0)
PY
