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
Every code runs the same geometry at several fixed steps (rockdem: its contact preset `rigid` at
KN 1e10 and at the preset's own 1e11, the automatic step; the column its file's fixed step); overturning is a tilt past 1.5 alpha in
every code (the reference: certain overturning). The threshold search is rd_threshold's for
all (24 coarse steps from 0.9 to 10 g tan(alpha), bisection to 0.005), run on one core
(rockdem -j 1). "Meets" = first-impact error <= 1 % and threshold error <= 2 % (issues 10 and
11: 1 % on event times, 2 % on amplitudes); time to solution = the wall time of that search.
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
IMPACT_TOL, THRESHOLD_TOL = 0.01, 0.02
OVERTURN = "model overturn tilt-ratio 1.5"
PEER_DT = {"pybullet": (1 / 240, 1e-3, 2.5e-4, 1e-4),   # 1/240 s: PyBullet's default step
           "mujoco": (2e-3, 5e-4, 1e-4, 2.5e-5)}         # 2 ms: MuJoCo's default step
YADE_DT = 5e-5        # s: the step of tests/data/yade/ (YADE's stability limit for this KN)


def scene_text(kind, motion="", init="", T=3.0, rigid=True, kf=1.0):
    """The ladder's block or stack scene at KN = kf x KN0 (the ladder's 1e10 Pa/m; the preset's
    own KN is 10 KN0); rigid=False: the same without the preset (YADE's translator reads KN, KS
    and friction only: KS 1e9, friction 80 deg, fixed step)."""
    base = ladder.BLOCK if kind == "block" else ladder.STACK
    text = base.format(kn=kf * ladder.KN0, ks=10 * kf * ladder.KN0, damping=init, motion=motion, T=T)
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


def peer(py, code, dt, *task):
    p = subprocess.run([py, os.path.join(HERE, "peers_rigid.py"), code, repr(dt)] + [str(t) for t in task],
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

        # ---- rockdem: the rigid preset at KN 1e10 and at its own 1e11 (its ladder of stiffness,
        # as the peers' ladder of steps); the column is its file's own setting, run once ----------
        col = os.path.join(ROOT, "tests", "data", "yade", "column.dat")
        wps_c, pc = B.perf(col, "model.duration=2.5")
        peak_c = float(ladder.h5(pc, "summary:max_tilt")[-1])  # the top drum
        for kf in (1.0, 10.0):
            t1, _ = B.first_impact(B.write("free_rd", scene_text("block", init=init, T=1.5, kf=kf)), "run")
            blk_k = B.write("block_rd", scene_text("block", motion=pulse, kf=kf))
            stk_k = B.write("stack_rd", scene_text("stack", motion=pulse, kf=kf))
            a1, n1, w1 = B.threshold(blk_k, "dem")
            s1, ns1, ws1 = B.threshold(stk_k, "dem")
            wps_b, p = B.perf(blk_k, "motion.amplitude=%.6g" % a_ref)
            wps_s, _ = B.perf(stk_k, "motion.amplitude=%.6g" % s_ref)
            dt_rd = float(ladder.h5(p, "summary:dt"))
            rows.append(dict(code="rockdem (preset rigid, KN %g)" % (kf * ladder.KN0), dt=dt_rd, imp=rel(t1, t_ref),
                             thr=rel(a1, a_ref), wps=wps_b, search=w1, runs=n1, sthr=rel(s1, s_ref), swps=wps_s,
                             ssearch=ws1, cwps=wps_c, cpeak=peak_c))
            print("rockdem KN %g done" % (kf * ladder.KN0), flush=True)

        # ---- PyBullet, MuJoCo -------------------------------------------------------------------
        if a.venv_python:
            for code, dts in PEER_DT.items():
                for dt in dts:
                    try:
                        f = peer(a.venv_python, code, dt, "free")
                        tb = peer(a.venv_python, code, dt, "threshold", "block", FREQ, static_b)
                        ts = peer(a.venv_python, code, dt, "threshold", "stack", FREQ, static_s)
                        c = peer(a.venv_python, code, dt, "history", "column", 0.5, 2.5)
                    except RuntimeError as e:
                        notes.append("%s at dt %g: failed (%s)" % (code, dt, str(e).splitlines()[-1]))
                        continue
                    rows.append(dict(code=code, dt=dt, imp=rel(f["impact_time"], t_ref), thr=rel(tb["threshold"], a_ref),
                                     wps=tb["wall_s"] / tb["sim_s"], search=tb["search_wall_s"], runs=tb["runs"],
                                     sthr=rel(ts["threshold"], s_ref), swps=ts["wall_s"] / ts["sim_s"],
                                     ssearch=ts["search_wall_s"], cwps=c["wall_s"] / c["sim_s"], cpeak=c["max_tilt"][-1]))
                    print("%s dt %g done" % (code, dt), flush=True)
        else:
            notes.append("PyBullet and MuJoCo skipped: %s" % (a.skip_reason or "no virtual environment"))

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
            rows.append(dict(code="YADE (Polyhedra, -j1)", dt=YADE_DT, imp=rel(ty, t_ref), thr=rel(ay, a_ref), wps=wpsy,
                             search=wy, runs=ny, sthr=rel(ays, s_ref), swps=wpsys, ssearch=wys, cwps=wpsc, cpeak=peaks[-1]))
            print("yade done", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    report(rows, notes, a.out)
    return 0


def pct(x):
    return "n/a" if x != x else "%.2f %%" % (100 * x)


def report(rows, notes, out):
    load = open("/proc/loadavg").read().split()[:3]
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown")
    lines = ["Time to solution at equal accuracy (bench/peers.sh), %s, %s (%d cpus), load average %s"
             % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), cpu, os.cpu_count(), " ".join(load)), "",
             "| code | step (s) | block: first impact err | block: 2 Hz threshold err | block wall-s / sim-s "
             "| block threshold search (s, runs) | meets 1 % / 2 % | stack: 2 Hz threshold err | stack wall-s / sim-s "
             "| stack search (s) | column wall-s / sim-s | column top drum peak tilt (rad) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        meets = r["imp"] <= IMPACT_TOL and r["thr"] <= THRESHOLD_TOL
        lines.append("| %s | %.3g | %s | %s | %.3g | %.1f (%d) | %s | %s | %.3g | %.1f | %.3g | %.4f |"
                     % (r["code"], r["dt"], pct(r["imp"]), pct(r["thr"]), r["wps"], r["search"], r["runs"],
                        "yes" if meets else "no", pct(r["sthr"]), r["swps"], r["ssearch"], r["cwps"], r["cpeak"]))
    best = {}
    for r in rows:
        if r["imp"] <= IMPACT_TOL and r["thr"] <= THRESHOLD_TOL:
            k = r["code"].split()[0]
            if k not in best or r["search"] < best[k]["search"]:
                best[k] = r
    lines.append("")
    for k in sorted(set(r["code"].split()[0] for r in rows)):
        if k in best:
            lines.append("- %s: time to solution at the accuracy asked (block, 2 Hz threshold search): %.1f s at step %.3g s"
                         % (k, best[k]["search"], best[k]["dt"]))
        else:
            rk = [r for r in rows if r["code"].split()[0] == k]
            b = min(rk, key=lambda r: max(r["imp"] / IMPACT_TOL, r["thr"] / THRESHOLD_TOL))
            lines.append("- %s: does not reach 1 %% / 2 %% at any step tried (best: first impact %s, threshold %s at %.3g s)"
                         % (k, pct(b["imp"]), pct(b["thr"]), b["dt"]))
    lines += ["- %s" % n for n in notes]
    text = "\n".join(lines)
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
