#!/usr/bin/python3
"""Time to solution at equal accuracy: rockdem against the codes a user would pick instead
(issue 13, item 6): PyBullet and MuJoCo (bench/peers_rigid.py, in the virtual environment
bench/peers.sh makes) and YADE (tools/yade/translate.py), in one run.

    /usr/bin/python3 bench/peers.py --bin bin/rockdem [--venv-python PY] [--no-yade] [-o OUT.md]

Scenes and accuracy measures:
  block   the validation ladder's 0.5 x 0.5 x 1.0 m block (tools/validate/ladder.py): the first
          impact time after a release from 10 deg at rest, and the minimum overturning
          amplitude of a 2 Hz one-sine pulse, each as a relative error against the CVODE rigid
          reference (`rockdem reference` / `rockdem threshold --engine reference`: Housner's
          equation, e = Housner's r = 0.70);
  stack   the ladder's two-block stack (a 0.4 x 0.4 x 0.8 m block on the first): the 2 Hz
          threshold against the CVODE Kounadis reference (plastic impacts);
  column  tests/data/yade/column.dat (four 12-sided drums) under its 0.5 g 2 Hz pulse, 2.5 s:
          no rigid reference exists, so its row gives the cost and the top drum's peak tilt.
Every code runs the same geometry over the same kind of search of its settings, and is judged at
its best: the cheapest setting that meets the accuracy asked. The settings searched:
  PyBullet, MuJoCo  ground (an infinite plane, or a 20 x 20 x 1 m box) x friction (80 and 40 deg)
                    x 4 fixed steps (their defaults first: 1/240 s and 2 ms);
  rockdem           its contact preset `rigid` at KN 1e9, 1e10 and the preset's own 1e11 x
                    friction (80 and 40 deg) x the automatic step's safety factor (the default
                    0.2, 0.5 and 1.0): 18 settings against the peers' 16; its ground is always a
                    fixed box (a pedestal); the column its file's own setting.
Overturning is a tilt past 1.5 alpha in every code (the reference: certain overturning). The
threshold search is rd_threshold's for all (24 coarse steps from 0.9 to 10 g tan(alpha),
bisection to 0.005), run on one core (rockdem -j 1). "Meets" = first-impact error <= 1 %, block
threshold error <= 2 % (issues 10 and 11: 1 % on event times, 2 % on amplitudes) and stack
threshold error <= 3 % (issue 10); time to solution = the wall time of the block's search. The
settings of the codes are run interleaved (one setting of each code in turn), so a change of
the machine's load reaches every code alike; the load average is printed with the table.
With --readme FILE (repeatable: the README and docs/PERFORMANCE.md) each code's best row and the
sentence they support replace the part of FILE between the lines `<!-- peers:begin -->` and
`<!-- peers:end -->`.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tools", "validate"))
sys.path.insert(0, os.path.join(ROOT, "tools", "yade"))
import ladder  # noqa: E402  (scenes and HDF5 helpers of the validation ladder)

G0 = 9.80665         # m/s^2, the g of rockdem's "g" suffix
FREQ = 2.0            # Hz, the threshold pulse
TILT0 = 10.0          # deg, the free-rocking release
IMPACT_TOL, THRESHOLD_TOL, STACK_TOL = 0.01, 0.02, 0.03
GROUNDS = ("plane", "box")          # the peers' fixed base
FRICTIONS = (80.0, 40.0)             # deg, every code
RD_SAFETY = (0.2, 0.5, 1.0)          # rockdem's automatic step: the default safety factor, and larger
RD_KN = (0.1, 1.0, 10.0)             # rockdem's KN / the ladder's 1e10 Pa/m (10: the rigid preset's own)
OVERTURN = "model overturn tilt-ratio 1.5"
PEER_DT = {"pybullet": (1 / 240, 1e-3, 2.5e-4, 1e-4),   # 1/240 s: PyBullet's default step
           "mujoco": (2e-3, 5e-4, 1e-4, 2.5e-5)}         # 2 ms: MuJoCo's default step
YADE_DT = 5e-5        # s: the step of tests/data/yade/ (YADE's stability limit for this KN)


def scene_text(kind, motion="", init="", T=3.0, rigid=True, kf=1.0, friction=80.0, safety=None):
    """The ladder's block or stack scene at KN = kf x KN0 (the ladder's 1e10 Pa/m; the preset's
    own KN is 10 KN0), friction in deg, the automatic step's safety factor (None: the default);
    rigid=False: the same without the preset (YADE's translator reads KN, KS and friction only:
    KS 1e9, friction 80 deg, fixed step)."""
    base = ladder.BLOCK if kind == "block" else ladder.STACK
    text = base.format(kn=kf * ladder.KN0, ks=10 * kf * ladder.KN0, damping=init, motion=motion, T=T)
    if rigid:
        text = re.sub(r"(contact property stiffness-normal \S+ stiffness-shear \S+)", r"\1 friction %g" % friction, text)
        if safety is not None:
            text += "model timestep auto safety %g\n" % safety
    if not rigid:
        text = re.sub(r"contact preset rigid\ncontact property .*\n",
                      "contact property stiffness-normal %g stiffness-shear 1e9 friction 80\n" % ladder.KN0, text)
        text += "model timestep fixed %g\nmodel settle off\n" % YADE_DT
    return text + OVERTURN + "\n"


class Bench:
    def __init__(self, rockdem, tmp):
        self.rockdem, self.tmp = rockdem, tmp

    def write(self, name, text):
        path = os.path.join(self.tmp, name + ".dat")
        with open(path, "w") as f:
            f.write(text)
        return path

    def call(self, *args):
        p = subprocess.run([self.rockdem] + list(args), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, stdin=subprocess.DEVNULL)
        if p.returncode not in (0, 3):  # 3: a run that overturned or ended early still has its file
            raise RuntimeError("rockdem %s: exit %d\n%s" % (" ".join(args), p.returncode, p.stdout[-1500:]))
        return p.stdout

    def threshold(self, dat, engine):
        t0 = time.perf_counter()
        out = self.call("threshold", dat, "--engine", engine, "-j", "1", "-q")
        wall = time.perf_counter() - t0
        m = re.search(r"minimum overturning amplitude ([0-9.e+-]+) m/s\^2.*?, (\d+) runs", out)
        st = re.search(r"static uplift a_uplift = ([0-9.e+-]+) m/s\^2", out)
        if not m or not st:
            raise RuntimeError("threshold: no answer in\n" + out)
        self.static = float(st.group(1))  # the search's scale: every code scans from 0.9 x this
        return float(m.group(1)), int(m.group(2)), wall

    def first_impact(self, dat, cmd):
        out = os.path.join(self.tmp, "free.h5")
        self.call(cmd, dat, "-o", out, *(["-q"] if cmd == "run" else []))
        t = ladder.event_times(out, "impact")
        return t[0] if t else float("nan"), out

    def perf(self, dat, *sets):
        out = self.call("run", dat, "-o", os.path.join(self.tmp, "perf.h5"), *sum((["--set", s] for s in sets), []))
        line = re.findall(r"perf: (.*)", out)
        if not line:
            raise RuntimeError("rockdem printed no perf: line")
        kv = dict(w.split("=", 1) for w in line[-1].split() if "=" in w)
        return float(kv["wall_per_sim_s"]), os.path.join(self.tmp, "perf.h5")


def rel(a, b):
    return abs(a - b) / abs(b) if a is not None and b else float("nan")


def peer(py, code, dt, ground, friction, *task):
    p = subprocess.run([py, os.path.join(HERE, "peers_rigid.py"), "--ground", ground, "--friction", repr(friction),
                        code, repr(dt)] + [str(t) for t in task],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, stdin=subprocess.DEVNULL)
    if p.returncode:
        raise RuntimeError("%s %s: %s" % (code, task, p.stderr[-800:]))
    return json.loads(p.stdout.strip().splitlines()[-1])


def yade_run(tmp, dat, sets):
    """One YADE run through the translator: (overturned, wall/sim s, first impact time or None,
    peak tilt per body)."""
    out = os.path.join(tmp, "yade.h5")
    p = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tools", "yade", "translate.py"), dat, "-o", out]
                       + sum((["--set", s] for s in sets), []), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, stdin=subprocess.DEVNULL)
    m = re.search(r"yade-run: steps=(\d+) wall_s=([0-9.e+-]+) wall_per_sim_s=([0-9.e+-]+)", p.stdout)
    if p.returncode or not m:
        raise RuntimeError("yade: %s" % p.stdout[-800:])
    from compare import RunFile  # tools/yade/compare.py
    R = RunFile(out)
    imp = R.impacts(0)
    nb = len(R.tilt[0]) if R.tilt.ndim > 1 else 1
    over = any(int(R.sumval("overturned", k)) for k in range(nb))
    peaks = [float(R.sumval("max_tilt", k)) for k in range(nb)]
    return over, float(m.group(2)), float(m.group(3)), (imp[0][0] if imp else None), peaks


def yade_threshold(tmp, dat, static):
    """rd_threshold's search with YADE runs: (amplitude m/s^2, runs, wall s, wall/sim s)."""
    lo, hi, n = 0.9 * static, 10 * static, 24
    runs, walls, sims = 0, 0.0, []
    t0 = time.perf_counter()

    def over(a):
        nonlocal runs, walls
        runs += 1
        o, w, wps, _, _ = yade_run(tmp, dat, ["motion.amplitude=%.9g" % (a / G0) + "g"])
        walls += w
        sims.append(wps)
        return o
    below, above = lo, None
    for k in range(n + 1):
        a = lo + (hi - lo) * k / n
        if over(a):
            above = a
            break
        below = a
    while above is not None and above > lo and (above - below) / above > 0.005:
        mid = 0.5 * (below + above)
        if over(mid):
            above = mid
        else:
            below = mid
    return above, runs, time.perf_counter() - t0, sum(sims) / len(sims)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True)
    ap.add_argument("--venv-python", default="", help="python of the venv with pybullet and mujoco ('' = skip)")
    ap.add_argument("--skip-reason", default="", help="why the peers in the venv are skipped")
    ap.add_argument("--no-yade", action="store_true")
    ap.add_argument("-o", "--out", help="also write the table (markdown) here")
    ap.add_argument("--readme", action="append", default=[],
                    help="replace the part of this file between the peers markers (repeatable)")
    a = ap.parse_args(argv)
    tmp = tempfile.mkdtemp(prefix="rd_peers_")
    B = Bench(os.path.abspath(a.bin), tmp)
    rows, notes = [], []
    try:
        # ---- the CVODE references -------------------------------------------------------------
        init = "block initial name b tilt %g direction 0" % TILT0
        pulse = "ground-motion pulse one-sine amplitude 1g frequency %g" % FREQ
        t_ref, _ = B.first_impact(B.write("free_ref", scene_text("block", init=init, T=1.5)), "reference")
        blk = B.write("block", scene_text("block", motion=pulse))
        stk = B.write("stack", scene_text("stack", motion=pulse))
        a_ref, _, _ = B.threshold(blk, "reference")
        static_b = B.static
        s_ref, _, _ = B.threshold(stk, "reference")
        static_s = B.static
        print("CVODE reference: first impact %.6f s, 2 Hz threshold block %.4f g, stack %.4f g"
              % (t_ref, a_ref / G0, s_ref / G0), flush=True)

        # ---- rockdem and the peers, one setting of each in turn --------------------------------
        col = os.path.join(ROOT, "tests", "data", "yade", "column.dat")
        wps_c, pc = B.perf(col, "model.duration=2.5")
        peak_c = float(ladder.h5(pc, "summary:max_tilt")[-1])  # the top drum

        def rockdem_row(kf, friction, safety):
            t1, _ = B.first_impact(B.write("free_rd", scene_text("block", init=init, T=1.5, kf=kf, friction=friction,
                                                                 safety=safety)), "run")
            blk_k = B.write("block_rd", scene_text("block", motion=pulse, kf=kf, friction=friction, safety=safety))
            stk_k = B.write("stack_rd", scene_text("stack", motion=pulse, kf=kf, friction=friction, safety=safety))
            a1, n1, w1 = B.threshold(blk_k, "dem")
            s1, ns1, ws1 = B.threshold(stk_k, "dem")
            wps_b, p = B.perf(blk_k, "motion.amplitude=%.6g" % a_ref)
            wps_s, _ = B.perf(stk_k, "motion.amplitude=%.6g" % s_ref)
            dt_rd = float(ladder.h5(p, "summary:dt"))
            return dict(code="rockdem (preset rigid, KN %g, safety %g)" % (kf * ladder.KN0, safety), ground="box",
                        friction=friction, dt=dt_rd, imp=rel(t1, t_ref), thr=rel(a1, a_ref), wps=wps_b, search=w1,
                        runs=n1, sthr=rel(s1, s_ref), swps=wps_s, ssearch=ws1, cwps=wps_c, cpeak=peak_c)

        def peer_row(code, dt, ground, friction):
            f = peer(a.venv_python, code, dt, ground, friction, "free")
            tb = peer(a.venv_python, code, dt, ground, friction, "threshold", "block", FREQ, static_b)
            ts = peer(a.venv_python, code, dt, ground, friction, "threshold", "stack", FREQ, static_s)
            c = peer(a.venv_python, code, dt, ground, friction, "history", "column", 0.5, 2.5)
            return dict(code=code, ground=ground, friction=friction, dt=dt, imp=rel(f["impact_time"], t_ref),
                        thr=rel(tb["threshold"], a_ref), wps=tb["wall_s"] / tb["sim_s"], search=tb["search_wall_s"],
                        runs=tb["runs"], sthr=rel(ts["threshold"], s_ref), swps=ts["wall_s"] / ts["sim_s"],
                        ssearch=ts["search_wall_s"], cwps=c["wall_s"] / c["sim_s"], cpeak=c["max_tilt"][-1])

        rd_grid = [(kf, fr, sf) for kf in RD_KN for fr in FRICTIONS for sf in RD_SAFETY]
        peer_grid = {code: [(dt, g, fr) for g in GROUNDS for fr in FRICTIONS for dt in dts]
                     for code, dts in PEER_DT.items()} if a.venv_python else {}
        if not a.venv_python:
            notes.append("PyBullet and MuJoCo skipped: %s" % (a.skip_reason or "no virtual environment"))
        rounds = max([len(rd_grid)] + [len(g) for g in peer_grid.values()])
        for i in range(rounds):
            if i < len(rd_grid):
                rows.append(rockdem_row(*rd_grid[i]))
                print("rockdem KN %g friction %g safety %g done" % (rd_grid[i][0] * ladder.KN0, rd_grid[i][1],
                                                                    rd_grid[i][2]), flush=True)
            for code, grid in peer_grid.items():
                if i >= len(grid):
                    continue
                dt, g, fr = grid[i]
                try:
                    rows.append(peer_row(code, dt, g, fr))
                except RuntimeError as e:
                    notes.append("%s at dt %g, %s ground, friction %g: failed (%s)"
                                 % (code, dt, g, fr, str(e).splitlines()[-1]))
                    continue
                print("%s dt %g ground %s friction %g done" % (code, dt, g, fr), flush=True)

        # ---- YADE ---------------------------------------------------------------------------------
        if a.no_yade or not shutil.which("yade"):
            notes.append("YADE skipped: %s" % ("--no-yade" if a.no_yade else "`yade` is not on PATH (apt-get install yade)"))
        else:
            fy = B.write("free_yade", scene_text("block", init=init, T=1.5, rigid=False))
            _, _, _, ty, _ = yade_run(tmp, fy, [])
            by = B.write("block_yade", scene_text("block", motion=pulse, rigid=False))
            sy = B.write("stack_yade", scene_text("stack", motion=pulse, rigid=False))
            ay, ny, wy, wpsy = yade_threshold(tmp, by, static_b)
            ays, nys, wys, wpsys = yade_threshold(tmp, sy, static_s)
            _, _, wpsc, _, peaks = yade_run(tmp, col, ["model.duration=2.5"])
            rows.append(dict(code="YADE (Polyhedra, -j1)", ground="box", friction=80.0, dt=YADE_DT, imp=rel(ty, t_ref), thr=rel(ay, a_ref), wps=wpsy,
                             search=wy, runs=ny, sthr=rel(ays, s_ref), swps=wpsys, ssearch=wys, cwps=wpsc, cpeak=peaks[-1]))
            print("yade done", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    report(rows, notes, a.out, a.readme)
    return 0


def pct(x):
    return "n/a" if x != x else "%.2f %%" % (100 * x)


def meets(r):
    return r["imp"] <= IMPACT_TOL and r["thr"] <= THRESHOLD_TOL and r["sthr"] <= STACK_TOL


def family(r):
    return r["code"].split()[0]


def report(rows, notes, out, readme=None):
    load = open("/proc/loadavg").read().split()[:3]
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown")
    head = ("Time to solution at equal accuracy (bench/peers.sh), %s, %s (%d cpus), load average %s at the end"
            % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), cpu, os.cpu_count(), " ".join(load)))
    cols = ("| code | ground | friction (deg) | step (s) | block: first impact err | block: 2 Hz threshold err "
            "| block wall-s / sim-s | block threshold search (s, runs) | stack: 2 Hz threshold err | stack wall-s / sim-s "
            "| column wall-s / sim-s | column top drum peak tilt (rad) | meets 1 % / 2 % / 3 % |")
    rule = "|---|---|---|---|---|---|---|---|---|---|---|---|---|"

    def line(r):
        return ("| %s | %s | %g | %.3g | %s | %s | %.3g | %.1f (%d) | %s | %.3g | %.3g | %.4f | %s |"
                % (r["code"], r["ground"], r["friction"], r["dt"], pct(r["imp"]), pct(r["thr"]), r["wps"], r["search"],
                   r["runs"], pct(r["sthr"]), r["swps"], r["cwps"], r["cpeak"], "yes" if meets(r) else "no"))
    best = {}
    for r in rows:
        k = family(r)
        if meets(r) and (k not in best or r["search"] < best[k]["search"]):
            best[k] = r
    summary = []
    for k in sorted(set(family(r) for r in rows)):
        if k in best:
            b = best[k]
            summary.append("- %s at its best (%s ground, friction %g, step %.3g s): %.1f s to the block's threshold, "
                           "%.3g wall-s per simulated s" % (b["code"], b["ground"], b["friction"], b["dt"],
                                                            b["search"], b["wps"]))
        else:
            rk = [r for r in rows if family(r) == k]
            b = min(rk, key=lambda r: max(r["imp"] / IMPACT_TOL, r["thr"] / THRESHOLD_TOL, r["sthr"] / STACK_TOL))
            summary.append("- %s: meets 1 %% / 2 %% / 3 %% at no setting tried (closest: first impact %s, threshold %s, "
                           "stack %s at %s ground, friction %g, step %.3g s)" % (k, pct(b["imp"]), pct(b["thr"]),
                                                                              pct(b["sthr"]), b["ground"], b["friction"], b["dt"]))
    claim = ""
    if "rockdem" in best:
        rd = best["rockdem"]
        others = sorted((k for k in best if k != "rockdem"), key=lambda k: best[k]["search"])
        faster = [k for k in others if best[k]["search"] < rd["search"]]
        if faster:
            claim = ("At equal accuracy %s %s faster than rockdem (time to solution %s against rockdem's %.1f s)"
                     % (" and ".join(faster), "is" if len(faster) == 1 else "are",
                        ", ".join("%s %.1f s, %.2gx" % (k, best[k]["search"], rd["search"] / best[k]["search"])
                                  for k in faster), rd["search"]))
            slower = [k for k in others if k not in faster]
            if slower:
                claim += "; rockdem is faster than %s" % " and ".join(
                    "%s (%.2gx)" % (k, best[k]["search"] / rd["search"]) for k in slower)
            claim += "."
        elif others:
            claim = ("At equal accuracy rockdem is the fastest: %s."
                     % ", ".join("%.2gx faster than %s" % (best[k]["search"] / rd["search"], k) for k in others))
        missing = sorted(set(family(r) for r in rows) - set(best))
        if missing:
            claim += " %s meet%s the accuracy at no setting tried." % (" and ".join(missing), "s" if len(missing) == 1 else "")
    lines = [head, "", cols, rule] + [line(r) for r in rows] + [""] + summary + ["- %s" % n for n in notes]
    if claim:
        lines += ["", claim.strip()]
    text = "\n".join(lines)
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text + "\n")
    for path in readme or []:
        src = open(path).read()
        b, e = "<!-- peers:begin -->", "<!-- peers:end -->"
        if b not in src or e not in src:
            raise SystemExit("bench/peers.py: %s has no %s ... %s block" % (path, b, e))
        best_rows = [cols, rule] + [line(best[k]) for k in sorted(best)]
        block = "\n".join([b, "_Generated by `make bench-peers` (bench/peers.py): %s. Each code at its best setting; "
                                "the full search is in build/bench/peers.md._" % head[len("Time to solution at equal accuracy (bench/peers.sh), "):], ""]
                          + best_rows + [""] + summary + ["- %s" % n for n in notes]
                          + ([""] + [claim.strip()] if claim else []) + [e])
        with open(path, "w") as f:
            f.write(src[:src.index(b)] + block + src[src.index(e) + len(e):])


if __name__ == "__main__":
    sys.exit(main())
