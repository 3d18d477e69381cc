#!/usr/bin/python3
"""docgen: the numbers in the docs come from runs.

    /usr/bin/python3 tools/docgen.py write [BLOCK ...]   (make docs: rewrite the blocks)
    /usr/bin/python3 tools/docgen.py check               (make test: tests/cli/docs_current.sh)
    /usr/bin/python3 tools/docgen.py list
    options: --bin bin/rockdem

A generated block in a Markdown file is the text between the two lines

    <!-- gen:NAME: ... -->
    <!-- /gen:NAME -->

and is written only by this script; edit the generator below, never the block. `write` reruns
what the block shows and replaces it. `check` reruns the cheap blocks and compares exactly
(the runs are deterministic: docs/TESTING.md), and for the expensive ones compares the block
with the stored results it was written from and reruns a sample of them. Timings are compared
within the noise stated next to them (TIME_NOISE). Each finding prints one FAIL line; a block
that matches prints CHECK. Blocks and their sources:

  readme-run        README.md           `make run`'s output (the lines that do not vary by machine)
  contact-layout    docs/CONTACT.md     bench/contact_table.sh (about a minute); check: one row
  contact-presets   docs/CONTACT.md     `rockdem restitution` of each preset (3 x 3 s)
  contact-ks-threshold docs/CONTACT.md  `rockdem threshold` of a brick and the PBR at two KS
                                        (make docs only: about a minute)
  switch-impulse    docs/CONTACT.md     tools/validate/switch_impulse.py
  fragility-pbr     docs/FRAGILITY.md   the 72-run PBR sweep (docs/pbr_sweep.h5, 1-4 min) and
                                        its timing; check: the table against docs/pbr_sweep.h5,
                                        and 6 of its cases rerun (every result to the bit,
                                        time within noise)
  assess-cask       docs/ASSESS.md      `rockdem assess` of the shipped cask at 0.6 g (7 s of CPU)
  assess-stronger   docs/ASSESS.md      the same at 1.2 g and of the drum cask (make docs only)
  cpu-times         docs/PERFORMANCE.md CPU seconds of three fixed commands; check: rerun
  physics-residuals docs/PHYSICS.md     the energy residual of each shipped scene (5 s of CPU)
  perf-kernel, perf-yade, perf-impact, perf-columns, perf-study
                    docs/PERFORMANCE.md the output of each `make bench` script, from
                                        build/bench/out/*.txt (`make docs-bench` writes them);
                                        kept as committed when that file is absent
  validation        docs/validation.md  rendered from build/validate/results.json when it exists
                                        (`make docs-validation` runs `make validate`); the fast
                                        ladder of `make test` compares its rows with the committed
                                        report (tests/cli/validation.sh, ladder.py --against)
  (check only)      docs/CONTACT.md     its table of named constants against the #defines
  figures           docs/*.png          tools/doc_figures.sh; check: redrawn into a scratch
                                        folder and compared pixel for pixel (tolerance 0: the same
                                        matplotlib draws the same pixels; measured: reruns are
                                        byte-identical)
"""
import argparse
import glob
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PY = "/usr/bin/python3"
BIN = os.path.join(ROOT, "bin", "rockdem")
# Timing noise: a CPU time measured by `check` may differ from the committed one by this factor
# either way. Source: on the shared 2-vCPU machines these docs are written on, the same runs'
# CPU time grows with the other jobs' use of the shared core and caches, besides the machine's two
# speed states (1.5x, docs/PERFORMANCE.md "How the figures are measured"): the PBR study's CPU
# seconds per run (bench/pbr_study.sh, the same 12 runs) were 0.8-0.9 at load 1 (2026-11-28),
# 1.47 at load 10-13 (2026-12-01) and 1.94 at load 16 (2026-12-02), a spread of 2.3; a factor 3
# covers it, and a slowdown past it is a finding.
TIME_NOISE = 3.0
CPU_LINE = re.compile(r"CPU ([0-9.]+) s")


def die(msg):
    print("docgen: " + msg, file=sys.stderr)
    sys.exit(2)


# ---- blocks in files ---------------------------------------------------------------------------
def begin_re(name):
    return re.compile(r"^<!-- gen:%s:.*-->$" % re.escape(name))


def find_block(path, name):
    """(lines, start, end): lines[start] is the begin marker, lines[end] the end marker."""
    with open(path) as f:
        lines = f.read().split("\n")
    b = begin_re(name)
    starts = [i for i, l in enumerate(lines) if b.match(l)]
    ends = [i for i, l in enumerate(lines) if l == "<!-- /gen:%s -->" % name]
    if len(starts) != 1 or len(ends) != 1 or ends[0] < starts[0]:
        die("%s: block %s: expected one '<!-- gen:%s: ... -->' line and one '<!-- /gen:%s -->' "
            "after it (found %d and %d)" % (os.path.relpath(path, ROOT), name, name, name, len(starts), len(ends)))
    return lines, starts[0], ends[0]


def read_block(path, name):
    lines, s, e = find_block(path, name)
    return "\n".join(lines[s + 1:e])


def write_block(path, name, text):
    lines, s, e = find_block(path, name)
    new = lines[:s + 1] + text.rstrip("\n").split("\n") + lines[e:]
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(new))
    os.replace(tmp, path)


def fenced(text, lang=""):
    return "```%s\n%s\n```" % (lang, text.rstrip("\n"))


def unfence(text):
    """The lines of the first fenced block of text."""
    m = re.search(r"^```[a-z]*\n(.*?)\n```", text, re.S | re.M)
    return m.group(1) if m else ""


# ---- running -----------------------------------------------------------------------------------
def run(args, cwd=None, ok=(0,)):
    """(stdout+stderr, CPU seconds of the child)."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run([str(a) for a in args], cwd=cwd or ROOT, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, stdin=subprocess.DEVNULL)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode not in ok:
        die("%s: exit %d\n%s" % (" ".join(map(str, args)), p.returncode, p.stdout[-3000:]))
    return p.stdout, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def stamp():
    load = open("/proc/loadavg").read().split()[:3]
    rev = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True).stdout.strip() or "?"
    return "%s on %s, %s (%d cores, load average %s)" % (
        time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), rev, cpu_model(), os.cpu_count(), " ".join(load))


def cpu_model():
    try:
        for l in open("/proc/cpuinfo"):
            if l.startswith("model name"):
                return l.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


class Checker:
    def __init__(self, times=True):
        self.fails = 0
        self.times = times  # False: CPU times are not compared (a sanitizer build runs 3-20x slower)

    def ok(self, what):
        print("CHECK docs %s" % what)

    def fail(self, what, why, hint="make docs rewrites it; tools/docgen.py"):
        print("FAIL docs %s: %s (%s)" % (what, why, hint))
        self.fails += 1

    def same(self, what, committed, now):
        if committed.rstrip("\n") == now.rstrip("\n"):
            self.ok(what)
        else:
            import difflib
            d = difflib.unified_diff(committed.rstrip("\n").split("\n"), now.rstrip("\n").split("\n"),
                                     "committed", "now", lineterm="", n=1)
            print("\n".join(list(d)[:40]))
            self.fail(what, "the committed block differs from what the program prints now")

    def time(self, what, committed, now):
        if not self.times:
            print("CHECK docs %s: CPU %.2f s not compared (--no-times)" % (what, now))
            return
        lo, hi = committed / TIME_NOISE, committed * TIME_NOISE
        if lo <= now <= hi:
            self.ok("%s: CPU %.2f s against the committed %.2f s (noise x%g)" % (what, now, committed, TIME_NOISE))
        else:
            self.fail(what, "CPU %.2f s, outside the committed %.2f s x/ %g" % (now, committed, TIME_NOISE))


# ---- readme-run: the quick start's output ------------------------------------------------------
def gen_readme_run(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    try:
        out, _ = run([a.bin, "run", os.path.join(ROOT, "scenarios", "default.dat"), "-o",
                      os.path.join(tmp, "default.h5")], cwd=tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    keep = [l for l in out.split("\n") if l and not re.match(r"^(perf|output): ", l)]
    return fenced("\n".join(keep))


# ---- contact-layout: bench/contact_table.sh ----------------------------------------------------
def gen_contact_layout(a, env=None):
    e = dict(os.environ, **(env or {}))
    p = subprocess.run(["bash", os.path.join(ROOT, "bench", "contact_table.sh"), a.bin], cwd=ROOT, env=e,
                       stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    if p.returncode:
        die("bench/contact_table.sh: exit %d" % p.returncode)
    return p.stdout.rstrip("\n")


def check_contact_layout(a, c, committed):
    # the defaults' row (corners, KS = 10 KN, e = 0) rerun; the others cost a minute (make docs)
    row = gen_contact_layout(a, dict(LAYOUTS="vertices", RATIOS="10", ES="0")).split("\n")[-1]
    if row in committed.split("\n"):
        c.ok("contact-layout: the defaults' row %s" % row)
    else:
        c.fail("contact-layout", "the defaults' row now reads %s" % row)


# ---- contact-presets: rockdem restitution of each preset ---------------------------------------
PRESET_SCENE = """block create brick size 2 2 0.4 position 0 0 -0.2 fixed name floor
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name block
contact preset %s
model solve time 5
"""


def gen_contact_presets(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    parts = []
    try:
        for name in ("default", "rigid", "3dec"):
            path = os.path.join(tmp, "%s.dat" % name)
            with open(path, "w") as f:
                f.write(PRESET_SCENE % name)
            out, _ = run([a.bin, "restitution", path, "--target", "0.7"], ok=(0, 1, 3, 4))
            parts.append("$ rockdem restitution free.dat --target 0.7     # contact preset %s\n%s" % (name, out.rstrip("\n")))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    scene = (PRESET_SCENE % "NAME").rstrip("\n")
    return "free.dat:\n\n" + fenced(scene) + "\n\n" + fenced("\n\n".join(parts))


# ---- switch-impulse: tools/validate/switch_impulse.py --------------------------------------------
def gen_switch_impulse(a):
    out, _ = run([PY, os.path.join(ROOT, "tools", "validate", "switch_impulse.py")])
    return out.rstrip("\n")


# ---- contact-ks-threshold: rockdem threshold at KS = 10 KN and KN/10 ----------------------------
KS_BRICK = """block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base
block create brick size 0.5 0.5 1.0 seat-on base density 2500 name block
ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 0
model overturn tilt-ratio 1.0
model solve time 3
"""


def gen_contact_ks_threshold(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    rows = ["| scene | KS (Pa/m) | `rockdem threshold` |", "|---|---|---|"]
    try:
        brick = os.path.join(tmp, "brick.dat")
        with open(brick, "w") as f:
            f.write(KS_BRICK)
        for label, path, extra in (("brick 0.5 x 0.5 x 1.0 m (defaults)", brick, []),
                                   ("shipped PBR (scenarios/pbr.dat: 2 Hz one-sine)", os.path.join(ROOT, "scenarios", "pbr.dat"), [])):
            for ks in ("1e11", "1e9"):
                out, _ = run([a.bin, "threshold", path, "-j", str(os.cpu_count()),
                              "--set", "contact.stiffness-shear=" + ks] + extra)
                line = [l for l in out.split("\n") if "minimum overturning amplitude" in l]
                rows.append("| %s | %s | %s |" % (label, ks, line[-1].strip() if line else out.strip().split("\n")[-1]))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return "\n".join(rows) + "\n\n_Measured by `make docs`, %s._" % stamp()


# ---- assess-cask, assess-stronger: rockdem assess of the shipped casks --------------------------
def assess(a, scene, ag, keep=None):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    try:
        out, _ = run([a.bin, "assess", "scenarios/" + scene, "--ag", ag, "--out", os.path.join(tmp, "a"), "-q"])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    lines = [l for l in out.rstrip("\n").split("\n") if not l.startswith("output: ")]
    if keep:
        lines = [l for l in lines if l.lstrip().startswith(keep)]
    return "$ rockdem assess scenarios/%s --ag %s\n%s" % (scene, ag, "\n".join(lines))


def gen_assess_cask(a):
    return fenced(assess(a, "cask.dat", "0.6g"))


def gen_assess_stronger(a):
    keep = ("ASCE 43-05", "mean peak")
    return fenced(assess(a, "cask.dat", "1.2g", keep) + "\n\n" + assess(a, "cask_drum.dat", "0.6g", keep))


# ---- fragility-pbr: the 72-run worked example of docs/FRAGILITY.md -----------------------------
FRAG_SCALES = ("0.15g", "0.25g", "0.35g", "0.5g", "0.7g", "1.0g")
FRAG_SWEEP = ["sweep", "scenarios/pbr_fragility.dat", "--axis", "motion.seed=1,2,3,4,5,6",
              "--directions", "0,90", "--scales", ",".join(FRAG_SCALES), "-q"]
FRAG_SAMPLE = ["sweep", "scenarios/pbr_fragility.dat", "--axis", "motion.seed=1,2,3,4,5,6",
               "--directions", "0", "--scales", "0.35g", "-j", "1", "-q"]
FRAG_H5 = os.path.join(ROOT, "docs", "pbr_sweep.h5")
# every column of the table that the runs determine: all but the timing (wall_seconds), so a
# change of the engine that moves any result, not only the outcome, marks docs/pbr_sweep.h5 stale
FRAG_COLUMNS = ("overturned", "max_tilt_ratio", "max_slide", "overturn_time", "status", "pga", "pgv",
                "end_time", "energy_residual", "final_twist", "max_twist", "max_slip", "mode", "arias",
                "d5_95", "pgd", "pgv_pga", "sa_0_2", "sa_1", "hash", "body_final_twist", "body_max_slide",
                "body_max_slip", "body_max_tilt_ratio", "body_max_twist", "body_mode",
                "body_overturn_time", "body_overturned")


def frag_table(path):
    import h5py
    import numpy as np
    with h5py.File(path, "r") as f:
        s = f["sweep"]
        scale, dirn, over = s["scale"][()], s["direction"][()], s["overturned"][()]
    levels = sorted(set(np.round(scale, 9)))
    lines = ["| direction | " + " | ".join(FRAG_SCALES) + " |", "|---|" + "---|" * len(FRAG_SCALES)]
    if len(levels) != len(FRAG_SCALES):
        die("%s: %d PGA levels, expected %d" % (path, len(levels), len(FRAG_SCALES)))
    for d, label in ((0.0, "0° (thin side)"), (90.0, "90° (long side)")):
        cells = []
        for lv in levels:
            m = (np.abs(scale - lv) < 1e-9) & (np.abs(dirn - d) < 1e-9)
            cells.append("%d/%d" % (int(over[m].sum()), int(m.sum())))
        lines.append("| %s | %s |" % (label, " | ".join(cells)))
    return "\n".join(lines)


def frag_rows(path):
    """{(seed, direction, scale): {column: value}} of a sweep table."""
    import h5py
    rows = {}
    with h5py.File(path, "r") as f:
        s = f["sweep"]
        cols = {k: s[k][()] for k in FRAG_COLUMNS + ("motion.seed", "direction", "scale", "wall_seconds")}
    for i in range(len(cols["scale"])):
        key = (float(cols["motion.seed"][i]), float(cols["direction"][i]), round(float(cols["scale"][i]), 9))
        rows[key] = {k: cols[k][i] for k in cols}
    return rows


def frag_sample(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    try:
        out = os.path.join(tmp, "sample.h5")
        _, cpu = run([a.bin] + FRAG_SAMPLE + ["-o", out])
        return frag_rows(out), cpu
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def gen_fragility_pbr(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    try:
        out = os.path.join(tmp, "pbr_sweep.h5")
        t0 = time.time()
        _, cpu = run([a.bin] + FRAG_SWEEP + ["-o", out])
        wall = time.time() - t0
        shutil.copy(out, FRAG_H5)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    rows = frag_rows(FRAG_H5)
    stand = sorted(r["wall_seconds"] for r in rows.values() if not r["overturned"])
    fall = sorted(r["wall_seconds"] for r in rows.values() if r["overturned"])
    med = lambda v: v[len(v) // 2] if v else float("nan")
    _, scpu = frag_sample(a)
    fit = frag_fit()
    return "\n".join([
        frag_table(FRAG_H5), "",
        "Measured by `make docs` (tools/docgen.py), %s: the 72 runs took %.0f s wall with `-j %d`, "
        "CPU %.0f s in all (the median run: %.1f s wall if it stands, %.1f s if it overturns and stops). "
        "`make test` reruns the 6 cases at 0.35 g along 0° one after the other (CPU %.1f s here) and "
        "compares every result but the wall time with `docs/pbr_sweep.h5` (to the bit), and their "
        "CPU time within a factor %g." % (
            stamp(), wall, os.cpu_count(), cpu, med(stand), med(fall), scpu, TIME_NOISE), "",
        "The fit across the thin side (`rdfragility.py docs/pbr_sweep.h5 --where direction=0 --bins 2`):", "",
        fenced(fit)])


def frag_fit():
    tmp = tempfile.mkdtemp(prefix="docgen_")
    try:
        out, _ = run([PY, os.path.join(ROOT, "tools", "rdfragility.py"), FRAG_H5, "--where", "direction=0",
                      "--bins", "2", "-o", os.path.join(tmp, "f.png")])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return "\n".join(l for l in out.rstrip("\n").split("\n") if not l.startswith("wrote "))


def check_fragility_pbr(a, c, committed):
    table_now = frag_table(FRAG_H5)
    c.same("fragility-pbr: the table against docs/pbr_sweep.h5", committed.split("\n\n")[0], table_now)
    c.same("fragility-pbr: the fit of docs/pbr_sweep.h5", unfence(committed), frag_fit())
    import numpy as np
    stored = frag_rows(FRAG_H5)
    rows, cpu = frag_sample(a)
    bad = []
    for key, r in sorted(rows.items()):
        s = stored.get(key)
        if s is None:
            bad.append("case %s is not in docs/pbr_sweep.h5" % (key,))
            continue
        for k in FRAG_COLUMNS:
            if not np.array_equal(r[k], s[k]):   # deterministic runs: the same bits
                bad.append("seed %g: %s now %s, stored %s" % (key[0], k, r[k], s[k]))
    if bad:
        c.fail("fragility-pbr: 6 cases rerun", "; ".join(bad[:6]))
    else:
        c.ok("fragility-pbr: 6 cases rerun at 0.35 g along 0°, every result as in docs/pbr_sweep.h5")
    m = re.search(r"CPU ([0-9.]+) s here", committed)
    if not m:
        c.fail("fragility-pbr", "no 'CPU ... s here' in the block")
    else:
        c.time("fragility-pbr: the 6 cases' CPU time", float(m.group(1)), cpu)


# ---- physics-residuals: the energy residual of the shipped scenes -------------------------------
RESIDUAL_SCENES = (("default.dat", "the cask of `make run`, 0.6 g one-sine"),
                   ("cask.dat", "the assessed cask on its pad"),
                   ("statue.dat", "a statue on its pedestal, two free blocks"),
                   ("pbr.dat", "the scanned-style PBR on its pedestal"),
                   ("seed000_topple.dat", "seed 000: a block that trips over its edge"),
                   ("seed001_cask.dat", "seed 001: casks released from a tilt"))
RESIDUAL_LINE = re.compile(r"^run: status (\w+),.* energy residual ([0-9.e+-]+)$", re.M)


def gen_physics_residuals(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    rows = ["| scenario | scene | status | energy residual |", "|---|---|---|---|"]
    try:
        for name, what in RESIDUAL_SCENES:
            out, _ = run([a.bin, "run", os.path.join("scenarios", name), "-o", os.path.join(tmp, "r.h5")],
                         ok=(0, 3))
            m = RESIDUAL_LINE.search(out)
            if not m:
                die("scenarios/%s: no 'run: status ..., energy residual' line" % name)
            rows.append("| `scenarios/%s` | %s | %s | %s |" % (name, what, m.group(1), m.group(2)))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return "\n".join(rows)


# ---- cpu-times: CPU seconds of fixed commands --------------------------------------------------
CPU_CMDS = [
    ("scenarios/default.dat (6 s, `make run`)", ["run", "scenarios/default.dat", "-q"]),
    ("scenarios/pbr.dat, 2 s", ["run", "scenarios/pbr.dat", "--set", "model.duration=2", "-q"]),
    ("scenarios/column.dat, 0.2 s", ["run", "scenarios/column.dat", "--set", "model.duration=0.2", "-q"]),
]


def cpu_times(a):
    tmp = tempfile.mkdtemp(prefix="docgen_")
    res = []
    try:
        for label, args in CPU_CMDS:
            _, cpu = run([a.bin] + args + ["-o", os.path.join(tmp, "r.h5")], ok=(0, 3))
            res.append((label, args, cpu))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return res


def gen_cpu_times(a):
    lines = ["| command | CPU (s) |", "|---|---|"]
    for label, args, cpu in cpu_times(a):
        lines.append("| `rockdem %s` | CPU %.2f s |" % (" ".join(args), cpu))
    return "\n".join(lines) + "\n\n_Measured by `make docs`, %s; `make test` reruns them and compares within a factor %g._" % (stamp(), TIME_NOISE)


def check_cpu_times(a, c, committed):
    if "| `rockdem " not in committed:
        c.fail("cpu-times", "the block holds no timings")
        return
    got = {" ".join(args): cpu for _, args, cpu in cpu_times(a)}
    for l in committed.split("\n"):
        m = re.match(r"^\| `rockdem (.*)` \| CPU ([0-9.]+) s \|$", l)
        if m:
            if m.group(1) not in got:
                c.fail("cpu-times", "no command `rockdem %s` in the generator" % m.group(1))
            else:
                c.time("cpu-times: rockdem %s" % m.group(1), float(m.group(2)), got[m.group(1)])


# ---- perf-*: the make bench outputs ------------------------------------------------------------
BENCH = {"perf-kernel": "kernel", "perf-yade": "run", "perf-impact": "impact_cost",
         "perf-columns": "columns", "perf-study": "pbr_study"}


def gen_bench(name):
    path = os.path.join(ROOT, "build", "bench", "out", BENCH[name] + ".txt")
    if not os.path.exists(path):
        return None
    text = open(path).read().rstrip("\n").split("\n")
    head = text[0].lstrip("# ") if text and text[0].startswith("# ") else ""
    tail = text[-1].lstrip("# ") if text and text[-1].startswith("# end") else ""
    body = [l for l in text if not (l.startswith("# bench/") or l.startswith("# end"))]
    loads = [float(x) for x in re.findall(r"load ([0-9.]+)", head + " " + tail)]
    warn = ""
    if loads and max(loads) > os.cpu_count():
        warn = ("\n\n_Measured at a load average above the machine's %d cores: wall times are inflated by "
                "the other jobs (up to the load over the cores); only ratios measured in the same round "
                "compare. Rerun `make docs-bench` on a quiet machine before quoting them._" % os.cpu_count())
    return "_`%s`_%s\n\n%s" % ("; ".join(x for x in (head, tail) if x), warn, fenced("\n".join(body)))


# ---- validation: docs/validation.md from the results file --------------------------------------
VALIDATION_JSON = os.path.join(ROOT, "build", "validate", "results.json")


def gen_validation(a):
    md = os.path.join(ROOT, "docs", "validation.md")
    if not os.path.exists(VALIDATION_JSON):
        return "kept (no %s: `make docs-validation` runs `make validate`)" % os.path.relpath(VALIDATION_JSON, ROOT)
    run([PY, os.path.join(ROOT, "tools", "validate", "ladder.py"), "--render", VALIDATION_JSON, "--md", md])
    return "rendered from %s" % os.path.relpath(VALIDATION_JSON, ROOT)


# ---- figures -----------------------------------------------------------------------------------
CHEAP_FIGS = "rdplot pbr gallery study assess"   # rdfragility_example's 64 runs: make docs only


def gen_figures(a):
    run(["bash", os.path.join(ROOT, "tools", "doc_figures.sh"), a.bin])
    return "redrawn"


PRINT_DPI = 300   # issue 46: every figure of the docs prints at 300 dpi


def png_dpi(path):
    """The resolution a PNG states in its pHYs chunk (dots per inch), or None without one."""
    import struct
    with open(path, "rb") as f:
        data = f.read()
    at = data.find(b"pHYs")
    if data[:8] != b"\x89PNG\r\n\x1a\n" or at < 0:
        return None
    x, y, unit = struct.unpack(">IIB", data[at + 4:at + 13])
    return (x * 0.0254, y * 0.0254) if unit == 1 else None


def check_dpi(c):
    bad = 0
    for path in sorted(glob.glob(os.path.join(ROOT, "docs", "**", "*.png"), recursive=True)):
        dpi = png_dpi(path)
        if dpi is None or max(abs(d - PRINT_DPI) for d in dpi) > 0.5:
            stated = "no stated" if dpi is None else "%.0f" % dpi[0]
            c.fail("figure %s" % os.path.relpath(path, ROOT), "%s dpi, not %d" % (stated, PRINT_DPI),
                   "draw it with dpi=%d" % PRINT_DPI)
            bad += 1
    if not bad:
        c.ok("figures: every PNG under docs/ states %d dpi" % PRINT_DPI)


def check_figures(a, c):
    check_dpi(c)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mi
    import numpy as np
    tmp = tempfile.mkdtemp(prefix="docgen_fig_")
    try:
        env = dict(os.environ, FIGS=CHEAP_FIGS, FIG_OUT=os.path.join(tmp, "out"))
        p = subprocess.run(["bash", os.path.join(ROOT, "tools", "doc_figures.sh"), a.bin, os.path.join(tmp, "w")],
                           cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if p.returncode:
            c.fail("figures", "tools/doc_figures.sh failed: %s" % p.stdout[-500:])
            return
        out = os.path.join(tmp, "out")
        for d, _, files in os.walk(out):
            for fn in sorted(files):
                new = os.path.join(d, fn)
                rel = os.path.relpath(new, out)
                old = os.path.join(ROOT, "docs", rel)
                if not os.path.exists(old):
                    c.fail("figure docs/%s" % rel, "not committed")
                    continue
                A, B = mi.imread(old), mi.imread(new)
                if A.shape != B.shape:
                    c.fail("figure docs/%s" % rel, "%s pixels committed, %s drawn now" % (A.shape[:2], B.shape[:2]))
                elif not np.array_equal(A, B):
                    rms = float(np.sqrt(np.mean((A.astype(float) - B.astype(float)) ** 2)))
                    c.fail("figure docs/%s" % rel, "pixels differ from a redraw (RMS %.3g of 1)" % rms)
                else:
                    c.ok("figure docs/%s" % rel)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


# ---- python-example: docs/examples/pbr_study.py's output ----------------------------------------
def gen_python_example(a):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "tools"),
               ROCKDEM_LIB=os.path.join(ROOT, "build", "librockdem.so"))
    t0 = time.time()
    p = subprocess.run([PY, os.path.join(ROOT, "docs", "examples", "pbr_study.py")], cwd=ROOT, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode:
        die("docs/examples/pbr_study.py: exit %d\n%s" % (p.returncode, p.stdout[-2000:]))
    return "Its output (`/usr/bin/python3 docs/examples/pbr_study.py`, %.0f s wall; %s):\n\n%s" % (
        time.time() - t0, stamp(), fenced(p.stdout))


# ---- contact-constants: docs/CONTACT.md's table of named constants against the code ----------
def check_constants(a, c):
    """Each row `| `RD_X` | value | file | meaning |` must give the #define's value: a number,
    `cos D deg`, or `N bands` / `N steps` (a count; `(10 * RD_CONTACT_BAND)` reads as 10 bands)."""
    import math
    text = open(os.path.join(ROOT, "docs", "CONTACT.md")).read()
    rows = re.findall(r"^\| `(RD_[A-Z_]+)` \| ([^|]+) \| ([^|]+) \| [^|]+ \|$", text, re.M)
    if not rows:
        c.fail("contact-constants", "no table of named constants in docs/CONTACT.md")
    for name, value, where in rows:
        src = open(os.path.join(ROOT, where.strip())).read()
        m = re.search(r"#define %s\s+(\S[^\n/]*)" % name, src)
        if not m:
            c.fail("contact-constants", "%s is not #defined in %s" % (name, where.strip()))
            continue
        code = m.group(1).strip()
        v = value.strip()
        if re.match(r"^[0-9.]+ bands", v) and "RD_CONTACT_BAND" in code:
            doc, got = float(v.split()[0]), float(eval(code.replace("RD_CONTACT_BAND", "1.0")))
        elif re.match(r"^[0-9.]+ (bands|steps)", v):
            doc, got = float(v.split()[0]), float(code)
        elif v.startswith("cos "):
            doc, got = math.cos(math.radians(float(v.split()[1]))), float(code)
        else:
            doc, got = float(v.split()[0]), float(code)
        if abs(doc - got) <= 1e-9 * max(1.0, abs(got)):
            c.ok("contact constant %s = %s (%s)" % (name, v, where.strip()))
        else:
            c.fail("contact constant %s" % name, "docs/CONTACT.md says %s, %s defines %s" % (v, where.strip(), code),
                   "correct the table by hand")


# ---- the list ----------------------------------------------------------------------------------
BLOCKS = [  # name, file, generator, checker (None: the exact rerun)
    ("readme-run", "README.md", gen_readme_run, None),
    ("contact-presets", "docs/CONTACT.md", gen_contact_presets, None),
    ("contact-layout", "docs/CONTACT.md", gen_contact_layout, check_contact_layout),
    ("contact-ks-threshold", "docs/CONTACT.md", gen_contact_ks_threshold, "skip"),
    ("switch-impulse", "docs/CONTACT.md", gen_switch_impulse, None),
    ("fragility-pbr", "docs/FRAGILITY.md", gen_fragility_pbr, check_fragility_pbr),
    ("assess-cask", "docs/ASSESS.md", gen_assess_cask, None),
    ("assess-stronger", "docs/ASSESS.md", gen_assess_stronger, "skip"),
    ("cpu-times", "docs/PERFORMANCE.md", gen_cpu_times, check_cpu_times),
    ("physics-residuals", "docs/PHYSICS.md", gen_physics_residuals, None),
    ("python-example", "docs/PYTHON.md", gen_python_example, "skip"),
] + [(n, "docs/PERFORMANCE.md", None, "skip") for n in BENCH]
OTHER = ("validation", "figures", "constants")


def with_debian_python():
    """The generators read HDF5 with h5py and draw with matplotlib, which Debian's /usr/bin/python3
    has (tools/install-deps.sh); another python3 first on PATH (pyenv, a venv) may lack them:
    rerun under Debian's, or say what is missing."""
    try:
        import h5py  # noqa: F401
        import matplotlib  # noqa: F401
    except ImportError as e:
        if os.path.realpath(sys.executable) != os.path.realpath(PY) and os.access(PY, os.X_OK):
            os.execv(PY, [PY] + sys.argv)
        die("%s: %s (tools/install-deps.sh installs python3-h5py and python3-matplotlib)" % (sys.executable, e))


def main():
    with_debian_python()
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=("write", "check", "list"))
    ap.add_argument("blocks", nargs="*")
    ap.add_argument("--bin", default=BIN)
    ap.add_argument("--no-times", action="store_true",
                    help="check: leave the CPU times uncompared (a sanitizer build)")
    a = ap.parse_args()
    a.bin = os.path.abspath(a.bin)
    names = [b[0] for b in BLOCKS] + list(OTHER)
    for n in a.blocks:
        if n not in names:
            die("unknown block '%s' (known: %s)" % (n, ", ".join(names)))
    want = lambda n: not a.blocks or n in a.blocks
    if a.mode == "list":
        for n, f, _, _ in BLOCKS:
            print("%-16s %s" % (n, f))
        print("%-16s %s\n%-16s %s\n%-16s %s" % ("validation", "docs/validation.md", "figures", "docs/*.png",
                                                 "constants", "docs/CONTACT.md (check only)"))
        return 0
    if not os.access(a.bin, os.X_OK):
        die("no rockdem executable at %s (make)" % a.bin)
    if a.mode == "write":
        for n, f, gen, _ in BLOCKS:
            if not want(n):
                continue
            path = os.path.join(ROOT, f)
            find_block(path, n)   # the markers exist before anything runs
            text = gen_bench(n) if gen is None else gen(a)
            if text is None:
                print("docgen: %s: kept as committed (no build/bench/out/%s.txt: make docs-bench)" % (n, BENCH[n]))
                continue
            write_block(path, n, text)
            print("docgen: wrote %s in %s" % (n, f))
        if want("validation"):
            print("docgen: validation: " + gen_validation(a))
        if want("figures"):
            print("docgen: figures: " + gen_figures(a))
        return 0
    c = Checker(times=not a.no_times)
    for n, f, gen, chk in BLOCKS:
        if not want(n) or chk == "skip":
            continue
        committed = read_block(os.path.join(ROOT, f), n)
        if chk is None:
            c.same("%s (%s)" % (n, f), committed, gen(a))
        else:
            chk(a, c, committed)
    if want("constants"):
        check_constants(a, c)
    if want("figures"):
        check_figures(a, c)
    return 1 if c.fails else 0


if __name__ == "__main__":
    sys.exit(main())
