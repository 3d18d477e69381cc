#!/usr/bin/python3
"""rockdem's validation ladder: one list of cases, run at two depths.

    /usr/bin/python3 tools/validate/ladder.py --depth fast            (make test: tests/cli/validation.sh)
    /usr/bin/python3 tools/validate/ladder.py --depth full --md docs/validation.md   (make validate)
    /usr/bin/python3 tools/validate/ladder.py --depth full --contact surface --md docs/validation-surface.md
                                                                     (make validate-surface)
    options: --bin bin/rockdem  --only GROUP[,GROUP]  --tmp DIR  --contact vertex|surface

Each case runs bin/rockdem (run / reference / threshold / restitution) and reads its HDF5, and
compares one quantity with an independent reference: a closed form (tools/validate/
closed_forms.py), the CVODE rigid-body solvers (`rockdem reference`: Housner for one block,
Kounadis for a two-block stack; themselves checked against closed forms in
tests/test_reference.c), or stored YADE runs (tests/data/yade, made by tools/yade/regen.py).

Tolerances (the `tol source` column) are never taken from rockdem's own answer:
  - "two-KN study": the DEM is run at KN and 10 KN (the step follows KN). If its error against a
    rigid reference is a discretisation error of order >= 1/2 in KN, the error at KN is at most
    1.5 x |q(KN) - q(10 KN)| (Richardson: 1 / (1 - 10^-0.5) = 1.46). Plus the measurement's own
    resolution (bisection bracket, output sampling), stated per case.
  - "dt/2 (both codes)": for YADE, the change of YADE's answer when its step is halved (stored
    half-step runs in tests/data/yade/half) plus the change of rockdem's answer at dt/2.
  - closed-form allowances (the volumetric pivot inset) are computed, not chosen.
A known disagreement is an expected failure (XFAIL, in XFAILS below with its reason): it prints
its measured gap on every run and does not fail; when it starts to pass it prints XPASS and the
run fails, so that the mark is removed. Output lines: CHECK / XFAIL / XPASS / FAIL (tests/run.sh).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tools", "yade"))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import closed_forms as cf  # noqa: E402
import relative_slide as rs  # noqa: E402  (tools/relative_slide.py)

try:
    import h5py  # noqa: E402
except ImportError:
    raise SystemExit("ladder: needs h5py: run with /usr/bin/python3")

YADE = os.path.join(ROOT, "tests", "data", "yade")
RICHARDSON = 1.5   # error bound factor from a two-KN study with KN ratio 10, order >= 1/2
KN_RATIO = 10.0

# Known gaps (issue numbers refer to the project's tracker). Each key is a row id; the check is
# made with its derived tolerance and reported XFAIL with the measured gap while it misses.
XFAILS = {
    "energy/every-run-yade": "the YADE stack at KS 2e10 (twice KN) and 0.6 g, at YADE's fixed 5e-5 s (0.54 of the critical step): a block's flat landing after both overturn (a 0.4 x 0.8 m face at about 3.4 m/s, omega dt 1.1 for the shear springs) leaves 0.3e-3 to 1.6e-3 of the 4 kJ in play with where its touch falls in the step, which round-off moves: a touch that stays takes up to KN A' (|vn| dt)^2 / 8 (11.6 J here) from leapfrog's conserved energy, exactly that with the mean force, given back only at the let-go; 1.51e-3 since the face law (451061a, the lower block landing flat), 3.4e-4 before it; 0.9e-4 to 2.6e-4 at 2.5e-5 s (docs/CONTACT.md section 6)",
    "block-free/impact2-time": "rigid preset: the plastic drop is placed to within a step of the end of compression; 0.1 %, inside the 1 % asked by issue 10 but above the two-KN bound (docs/CONTACT.md)",
    "other-r/threshold-2Hz": "mid-line layout at the steep 2 Hz region: 1.7 % high at KN 1e12, inside the 2 % asked by issue 11 but above its two-KN bound (1e12, 1e13); its free-rocking r is the same for releases from 0.3 to 0.9 alpha there, so the impact's speed is not the cause (open, docs/CONTACT.md section 2)",
    "other-r/rigid-0.9": "with a knife-edge pivot transfer (the rigid preset) r cannot exceed ~0.76 without the block bouncing on its new edge; r = 0.9 for h/b = 2 lies above what a plastic multi-point base keeps too (docs/CONTACT.md)",
    "block-free/amp1": "rigid preset at KN 1e10: 0.3 %, inside the 2 % asked by issue 11 but above the two-KN bound (impact timing, docs/CONTACT.md)",
    "stack-history/undamped-stack-uplift-time-1pct": "1.4 % at the rigid preset's KN 1e11: the elastic joints' rocking mode (192 Hz) set off by the pulse onset, inside its bound 1/(omega cos(2 pi f t)) + one step (2.0 %); 0.4 % before the statue's joint took its full KN (pairs.c faces_within: it had half of it, and the ringing's phase fell elsewhere); within 1 % at KN 1e12 (row -kn1e+12, full depth)",
    "stack-threshold/undamped-2.5Hz-kn1e+12-3pct": "3.4-3.6 % at KN 1e12 (2.9 % at the rigid preset's KN 1e11, within the 3 %, since the time step is bounded per pair of bodies): at w/p 4.3, the edge of the reference's validity, the undamped elastic joints' ringing moves the threshold (the same stack with dashpots at 20 % of critical is within 0.1 % of the same reference at 2.5 Hz, row damped-2.5Hz); its two-KN bound (5.5 %) holds",
    "stack-history/equal4-stack-uplift-time-1pct": "6.1 % at the rigid preset's KN 1e11: the elastic joints' rocking mode (56 Hz) set off by the pulse onset, inside its bound 1/(omega cos(2 pi f t)); within 1 % at KN 1e13 (docs/CONTACT.md)",
    "column-walk/4-drum-0.5g/base-walk": "shaken along a vertex (direction 0) each 12-sided drum rocks on a single rim vertex, which has no torsional friction: after the pulse the column turns to wobbling (the bottom drum's axis leans 0.067 rad across the shaking plane by 5 s) and twists about its pivots (up to 13 mrad), so the bottom drum's footprint moves 2.4-3.4 mm (two trajectories that differ at round-off) with 0.017 mm of Coulomb slip, not a compliance or step effect (5.1 mm at KN 1e12, 3.7 mm at half the step); shaken face-on (row 4-drum-0.5g-face-on: rocking on an edge) it moves 0.36 mm (docs/CONTACT.md)",
    "yade-free/impact-time": "rockdem's edge pivot vs YADE's volumetric wedge: the gap exceeds the wedge estimate",
    "yade-free/amp-after-impact": "undamped impact: DEM point contacts vs YADE volumetric bed keep different energy",
    "yade-overturn/bracket-scenario-ks": "shear stiffness per point, not per face: with the scenario's KS the pivot slides (docs/YADE.md)",
    "yade-stack/0.3g-lower-tilt": "stack rocking amplitude: contact law difference (docs/YADE.md)",
    "yade-stack/0.3g-upper-tilt": "stack rocking amplitude: contact law difference (docs/YADE.md)",
    "yade-column/0.7g-d1-tilt": "drum %s at 0.7 g: the column's peak tilts are not converged in the step (rockdem's drums 0.0964-0.1046 / 0.0909-0.0932 / 0.1098-0.1113 rad at dt 5e-5 / 2.5e-5 / 1.25e-5 s, up and down; YADE's own dt/2 moves them 7-20 %%), so rockdem's dt/2 change is no bound (step_bound); the rows passed before only on dt/2 changes that happened to be small or large (docs/YADE.md)" % "d1",
    "yade-column/0.7g-d2-tilt": "drum %s at 0.7 g: not converged in the step (see yade-column/0.7g-d1-tilt)" % "d2",
    "yade-column/0.7g-d3-tilt": "drum %s at 0.7 g: not converged in the step (see yade-column/0.7g-d1-tilt)" % "d3",
    "yade-column/0.7g-d4-tilt": "drum %s at 0.7 g: not converged in the step (see yade-column/0.7g-d1-tilt)" % "d4",
    "yade-column/1.6g-d1-tilt": "drum d1 at 1.6 g, under the three drums falling off it: not converged in the step (rockdem 0.2348 / 0.3086 / 0.2348 rad at dt 5e-5 / 2.5e-5 / 1.25e-5 s: where a falling drum strikes it moves with the step), so rockdem's dt/2 change is no bound (step_bound); before 1224fee its peak was the same at all three steps and the 1.3 % gap to YADE exceeded their 0.3 % bound: 12-sided drums, point contacts vs volumetric bed (docs/YADE.md)",
    "yade-column/1.0g-d1-tilt": "12-sided drums: point contacts vs volumetric bed, shear stiffness not matched for polygon faces (docs/YADE.md); rockdem's peak is converged (0.1219 / 0.1219 / 0.1220 rad at dt / dt/2 / dt/4), but its dt/4 change is the larger at that level, so step_bound gives no bound: the 2.2 % gap is the contact-law difference",
    "yade-column/1.0g-d2-tilt": "12-sided drums: point contacts vs volumetric bed, shear stiffness not matched for polygon faces (docs/YADE.md)",
    "yade-column/1.0g-d3-tilt": "12-sided drums: point contacts vs volumetric bed, shear stiffness not matched for polygon faces (docs/YADE.md); the row passed before the level entrance rule (docs/CONTACT.md section 1) only because rockdem's own dt/2 change was then 1.0 % (0.1750 -> 0.1768 rad); now 0.1750 -> 0.1752, and the 1.2 % gap to YADE is its sibling drums' contact-law difference",
    "yade-column/1.0g-d4-tilt": "12-sided drums: point contacts vs volumetric bed, shear stiffness not matched for polygon faces (docs/YADE.md)",
}


# --contact surface (make validate-surface, docs/validation-surface.md): every DEM run (run,
# threshold --engine dem, restitution) gets --set contact.model=surface. The surface model has no
# permanent set (docs/CONTACT.md section 8.6): a scene whose joint restitution e is below 1 gets
# restitution 1 and, for a plastic joint (e = 0, the rigid and default presets), the patch dashpot
# in place of any dashpot the scene gives. A plastic joint is the one whose impacts give Housner's
# r, at every KN (the vertex model's plastic set does); the dashpot's r moves with KN at a fixed
# ratio (zeta 3.2: r = 0.6994 / 0.7102 / 0.7096 at KN 1e10 / 1e11 / 1e12, section 8.4), so the
# ratio is the one `rockdem restitution --target r_H` calibrates on the rigid-theory block (h/b =
# 2, KS = 10 KN) at the run's KN (Ladder.plastic_zeta, once per KN). A scene with 0 < e < 1 is run
# as it is and is refused: the surface model has no measure of it; the mid-line layouts' case
# (other-r, e = 0.2 and 0.5) runs its dashpot analogue instead (surface_other_r: the ratio
# calibrated by `rockdem restitution` to r = 0.80).
# The calibration's stop, |r - r_H| < 1e-4 (`rockdem restitution --rtol`, its least): 0.014 % of
# r, so its part in an amplitude after impact 3 (0.04 %) is a tenth of the tightest tolerance
# it meets (block-free-rigid/amp3, about 0.4 %), where the default 0.002 would be 0.9 %.
PLASTIC_RTOL = 1e-4
PRESET_KN = {"rigid": 1e11}   # the other presets' (and the defaults') KN: 1e10 (docs/CONTACT.md section 3)


def scene_kn(dat, sets):
    """The joint's normal stiffness KN (Pa/m) a scene gives: its preset's (rigid 1e11, the others
    and none 1e10), then the last stiffness-normal of a 'contact property' line, then a --set
    contact.stiffness-normal."""
    kn = 1e10
    with open(dat) as f:
        for line in f:
            w = line.split(";")[0].split()
            if w[:2] == ["contact", "preset"] and len(w) > 2:
                kn = PRESET_KN.get(w[2], 1e10)
            elif w[:2] == ["contact", "property"] and "stiffness-normal" in w:
                kn = float(w[w.index("stiffness-normal") + 1])
    for s in sets:
        if s.startswith("contact.stiffness-normal="):
            kn = float(s.split("=", 1)[1])
    return kn


def scene_restitution(dat, sets):
    """The joint restitution e a scene gives: presets rigid and default (and none) 0, 3dec 1, then
    the last 'restitution' of a 'contact property' line, then a --set contact.restitution."""
    e = 0.0
    with open(dat) as f:
        for line in f:
            w = line.split(";")[0].split()
            if w[:3] == ["contact", "preset", "3dec"]:
                e = 1.0
            elif w[:2] == ["contact", "preset"]:
                e = 0.0
            elif w[:2] == ["contact", "property"] and "restitution" in w:
                e = float(w[w.index("restitution") + 1])
    for s in sets:
        if s.startswith("contact.restitution="):
            e = float(s.split("=", 1)[1])
    return e


class Ladder:
    def __init__(self, bin_, tmp, depth, contact="vertex", extra=()):
        self.bin, self.tmp, self.depth, self.contact = bin_, tmp, depth, contact
        self.extra = list(extra)   # --set KEY=VALUE given to the ladder: last on every DEM run
        self.rows, self.failed, self.xpassed = [], 0, 0
        self.residuals = []   # (energy residual, scene and settings, case group) of every `run`
        self.group = None     # the group of the case running
        self.nrun = 0
        self.errors = []      # (case, message) of the cases that could not run
        self.zetas = {}       # KN -> (dashpot ratio, r) of the surface model's plastic joint

    # ---- running rockdem ---------------------------------------------------------------------
    def rockdem(self, *args, ok=(0,)):
        self.nrun += 1
        p = subprocess.run([self.bin] + [str(a) for a in args], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True, stdin=subprocess.DEVNULL)
        if p.returncode == 3 and args[0] == "run" and "left the scene" in p.stdout:
            return p.stdout   # a body fell off the model (status lost): the file holds the run
        if p.returncode not in ok:
            raise RuntimeError("rockdem %s: exit %d\n%s" % (" ".join(map(str, args)), p.returncode, p.stdout[-2000:]))
        return p.stdout

    def scene(self, name, text):
        path = os.path.join(self.tmp, name + ".dat")
        with open(path, "w") as f:
            f.write(text)
        return path

    def dem_sets(self, dat, sets):
        """sets for a DEM run of dat under the ladder's contact model (a plastic joint under the
        surface model: plastic_zeta)."""
        if self.contact == "vertex":
            return list(sets) + self.extra
        extra = ["contact.model=surface"]
        if scene_restitution(dat, sets) == 0:
            zeta = self.plastic_zeta(scene_kn(dat, sets))[0]
            extra += ["contact.restitution=1", "model.damping=viscous %.6g" % zeta]
        return [s for s in sets if not (extra[1:] and s.startswith("model.damping="))] + extra + self.extra

    def plastic_zeta(self, kn):
        """(ratio, r): the surface model's dashpot ratio that gives Housner's r on the rigid-theory
        block at KN kn, calibrated by `rockdem restitution` once per KN (to PLASTIC_RTOL in r)."""
        if kn not in self.zetas:
            cal = self.scene("plastic_cal_%g" % kn, BLOCK.format(kn=kn, ks=10 * kn, damping="contact property restitution 1",
                                                                motion="", T=3))
            sets = sum((["--set", s] for s in ["contact.model=surface"] + self.extra), [])
            out = self.rockdem("restitution", cal, "--target", "%.6f" % R_HOUSNER, "--rtol", "%g" % PLASTIC_RTOL,
                               "-q", *sets)
            m = re.search(r"model damping viscous ([0-9.]+) gives r = ([0-9.]+)", out)
            if not m:
                raise RuntimeError("restitution: no calibrated ratio in\n" + out)
            self.zetas[kn] = (float(m.group(1)), float(m.group(2)))
            print("NOTE surface model's plastic joint at KN %g: model damping viscous %s gives r = %s (Housner's %.4f)" % (
                kn, m.group(1), m.group(2), R_HOUSNER))
        return self.zetas[kn]

    def zeta_list(self):
        """[(KN, ratio, r)] of the plastic joint's calibrations made."""
        return [(kn, z, r) for kn, (z, r) in sorted(self.zetas.items())]

    def run(self, dat, out, *sets):
        args = ["run", dat, "-q", "-o", os.path.join(self.tmp, out)]
        for s in self.dem_sets(dat, sets):
            args += ["--set", s]
        self.rockdem(*args)
        path = os.path.join(self.tmp, out)
        # every run's energy residual, for the closing check (case_energy_every_run)
        label = os.path.basename(dat) + "".join(" " + s for s in sets)
        self.residuals.append((float(h5(path, "summary:energy_residual_max")), label, self.group))
        return path

    def reference(self, dat, out, *sets):
        args = ["reference", dat, "-o", os.path.join(self.tmp, out)]
        for s in sets:
            args += ["--set", s]
        self.rockdem(*args)
        return os.path.join(self.tmp, out)

    def threshold(self, dat, engine, *sets, rtol=0.005):
        """(amplitude m/s^2, relative bracket width) of the minimum overturning amplitude; the
        search scans from 0.9 to 10 x g tan(alpha) (the whole range: an early overturning is
        seen) and bisects to rtol (rockdem's default 0.005)."""
        args = ["threshold", dat, "--engine", engine, "--rtol", "%g" % rtol]
        for s in (self.dem_sets(dat, sets) if engine == "dem" else sets):
            args += ["--set", s]
        out = self.rockdem(*args)
        m = re.search(r"minimum overturning amplitude ([0-9.e+-]+) m/s\^2 .*bracket ([0-9.e+-]+) \.\. ([0-9.e+-]+)", out)
        if not m:
            raise RuntimeError("threshold: no answer in\n" + out)
        a, lo, hi = (float(x) for x in m.groups())
        return a, (hi - lo) / hi

    # ---- verdicts ----------------------------------------------------------------------------
    def check(self, rid, quantity, ref, ref_src, got, err, tol, tol_src, unit=""):
        """err and tol are in the same measure (stated in `quantity`); ok when err <= tol."""
        ok = bool(err <= tol)
        mode = "xfail" if rid in XFAILS else "strict"
        if mode == "xfail":
            verdict = "xpass" if ok else "xfail"
        else:
            verdict = "pass" if ok else "FAIL"
        line = "%s %s: rockdem %s, reference %s, error %.3g, tol %.3g" % (
            rid, quantity, fmt(got), fmt(ref), err, tol)
        if verdict == "pass":
            print("CHECK " + line)
        elif verdict == "xfail":
            print("XFAIL: %s gap=%.3g tol=%.3g (%s)" % (rid, err, tol, XFAILS[rid]))
        elif verdict == "xpass":
            print("XPASS: %s gap=%.3g tol=%.3g: remove it from XFAILS in tools/validate/ladder.py" % (rid, err, tol))
            self.xpassed += 1
        else:
            print("FAIL " + line)
            self.failed += 1
        sys.stdout.flush()
        self.rows.append(dict(id=rid, quantity=quantity, ref=ref, ref_src=ref_src, got=got, err=err,
                              tol=tol, tol_src=tol_src, verdict=verdict, unit=unit))

    def kn_pair(self, fn):
        """fn(kn_factor) -> value; returns (q at KN, q at 10 KN)."""
        return fn(1.0), fn(KN_RATIO)


def fmt(v):
    if isinstance(v, str):
        return v
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return "%.5g" % v


def jsonable(v):
    """A value as the results file keeps it: what fmt() prints from it stays the same."""
    if isinstance(v, (str, bool, np.bool_)):
        return bool(v) if isinstance(v, np.bool_) else v
    if isinstance(v, (int, np.integer)):
        return int(v)
    return float(v)


def against(rows, md):
    """Rows of this run that the committed report also has must print the same rockdem value:
    the runs are deterministic, so a difference is a change of the program since the report
    (rerun `make docs-validation`). Returns the number of differences (each a FAIL line)."""
    committed = {}
    for line in open(md):
        c = [x.strip() for x in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
        if len(c) == 9 and c[0] not in ("case", "---"):
            committed[c[0]] = c[4]
    bad = same = 0
    for r in rows:
        if r["id"] in committed:
            if fmt(r["got"]).replace("|", "\\|") == committed[r["id"]]:
                same += 1
            else:
                print("FAIL %s: rockdem now %s, %s says %s (make docs-validation)" % (r["id"], fmt(r["got"]), md, committed[r["id"]]))
                bad += 1
    print("%s %d rows of this run against %s: %d the same, %d differ" % ("CHECK" if not bad else "FAIL", same + bad, md, same, bad))
    return bad


def h5(path, *keys):
    """Read datasets (and "summary:<attr>" attributes) into memory and close the file, so that
    rockdem can overwrite it in the next run."""
    with h5py.File(path, "r") as f:
        out = [f["summary"].attrs[k[8:]] if k.startswith("summary:") else f[k][()] for k in keys]
    return out if len(out) > 1 else out[0]


def attr(v):
    return v.decode() if isinstance(v, bytes) else v


def event_times(path, kind, body=None):
    """Times (s) of the events of one type ("impact", "overturn", ...), in file order, of one
    body (by name) or of all. HDF5 layout 2: /events is a group of columns and /events/type an
    enum (docs/HDF5-LAYOUT.md)."""
    with h5py.File(path, "r") as f:
        e = f["events"]
        if isinstance(e, h5py.Dataset):   # layout 1: a compound table (time, body, type, value)
            return [float(r[0]) for r in e[()] if attr(r[2]) == kind and body in (None, attr(r[1]))]
        names = {v: k for k, v in (h5py.check_enum_dtype(e["type"].dtype) or {}).items()}
        types = [names.get(int(t), attr(t)) for t in e["type"][()]]
        bodies = [attr(b) for b in e["body"][()]]
        return [float(t) for t, k, b in zip(e["time"][()], types, bodies) if k == kind and body in (None, b)]


# ==== scenes =====================================================================================
# One block: 0.5 x 0.5 x 1.0 m (b 0.25, h 0.5, alpha = atan 0.5 = 0.4636 rad, p = 3.628 1/s) on a
# fixed base with the contact preset that reproduces rigid rocking theory (docs/CONTACT.md:
# corner subcontacts, perfectly plastic point impacts, KS = 10 KN, friction 80 deg: mu g = 5.7 g,
# the rigid models do not slide), undamped. Stack: the same block with a 0.4 x 0.4 x 0.8 m block
# on top. The two-KN studies run KN0 and 10 KN0.
KN0 = 1e10
SCENE = """block create brick size 4 4 1 position 0 0 -0.5 fixed name base
{blocks}
contact preset rigid
contact property stiffness-normal {{kn}} stiffness-shear {{ks}}
{{damping}}
{{motion}}
model solve time {{T}}
output hdf5 'x.h5' interval 0.001
"""
BLOCK = SCENE.format(blocks="block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b")
STACK = SCENE.format(blocks="block create brick size 0.5 0.5 1.0 position 0 0 0.5 name lower\n"
                            "block create brick size 0.4 0.4 0.8 position 0 0 1.4 name upper")
EQUAL4 = SCENE.format(blocks="block create brick size 0.4 0.4 1.6 position 0 0 0.8 name lower\n"
                             "block create brick size 0.4 0.4 1.6 position 0 0 2.4 name upper")
ALPHA = math.atan(0.5)
R_HOUSNER = cf.housner_r(ALPHA)   # 0.70: the reference's e, a closed form, not a DEM measurement


def block_scene(L, name, kf=1.0, damping="", motion="", T=3):
    return L.scene(name, BLOCK.format(kn=KN0 * kf, ks=10 * KN0 * kf, damping=damping, motion=motion, T=T))


def stack_scene(L, name, kf=1.0, damping="", motion="", T=3):
    return L.scene(name, STACK.format(kn=KN0 * kf, ks=10 * KN0 * kf, damping=damping, motion=motion, T=T))


def equal_stack_scene(L, name, kf=1.0, damping="", motion="", T=3):
    return L.scene(name, EQUAL4.format(kn=KN0 * kf, ks=10 * KN0 * kf, damping=damping, motion=motion, T=T))


# ==== rung 1: single block, free rocking vs CVODE Housner ========================================
def impacts_and_amps(path, k=0, n=3):
    t, tilt = h5(path, "time", "tilt")
    ti = event_times(path, "impact")[:n]
    th = tilt[:, k]
    amps = []
    for i in range(len(ti)):
        sel = (t > ti[i]) & ((t < ti[i + 1]) if i + 1 < len(ti) else (t < ti[i] + 10))
        amps.append(float(th[sel].max()))
    return ti, amps


def case_block_free(L):
    th0 = 0.5 * ALPHA
    init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
    ref = L.reference(block_scene(L, "free_ref", damping=init, T=1.6),
                      "free_ref.h5", "reference.restitution=%.6f" % R_HOUSNER)
    rt, ra = impacts_and_amps(ref)

    def dem(kf):
        p = L.run(block_scene(L, "free%g" % kf, kf, init, T=1.6), "free%g.h5" % kf)
        return impacts_and_amps(p)
    (t1, a1), (t2, a2) = L.kn_pair(dem)
    src = "CVODE Housner, e = Housner's r = 1 - 1.5 sin^2(alpha) = 0.70"
    dt_out = 1e-3
    for i in range(2):
        tol = RICHARDSON * abs(t1[i] - t2[i]) + 1e-5 * rt[i]
        L.check("block-free/impact%d-time" % (i + 1), "impact %d time (s), relative error" % (i + 1), rt[i], src, t1[i],
                abs(t1[i] - rt[i]) / rt[i], tol / rt[i], "two-KN study (+ event location 1e-5)")
    for i in range(2):
        # sampling at 1 ms misses a peak by at most p^2 theta dt^2 / 8 (parabola at the top)
        samp = 3.628 ** 2 * dt_out ** 2 / 8
        tol = RICHARDSON * abs(a1[i] - a2[i]) + samp * ra[i]
        L.check("block-free/amp%d" % (i + 1), "rocking amplitude after impact %d (rad), relative error" % (i + 1), ra[i], src,
                a1[i], abs(a1[i] - ra[i]) / ra[i], tol / ra[i], "two-KN study + 1 ms sampling")


# ==== rung 2: single block thresholds vs CVODE Housner ===========================================
def threshold_case(L, rid, scene_fn, freq, damping, ref_sets, src):
    motion = "ground-motion pulse one-sine amplitude 1g frequency %g" % freq

    def dem(kf):
        return L.threshold(scene_fn(L, "thr_%s_%g" % (rid.replace("/", "_"), kf), kf, damping, motion), "dem")
    ref, wr = L.threshold(scene_fn(L, "thr_ref", 1.0, damping, motion), "reference", *ref_sets)
    (a1, w1), (a2, w2) = L.kn_pair(dem)
    tol = RICHARDSON * abs(a1 - a2) / ref + w1 + wr
    L.check(rid, "minimum overturning amplitude at %g Hz (g), relative error" % freq, ref / cf.G0, src,
            a1 / cf.G0, abs(a1 - ref) / ref, tol, "two-KN study + both bisection brackets (rtol 0.005)")


def case_block_free_rigid(L):
    """Free rocking with the rigid preset as documented (KN 1e11, KS 10 KN, default step), the
    setting README recommends for comparison with rigid theory: amplitudes after impacts 1-3
    against CVODE Housner, with a two-KN study at 1e11 / 1e12 as the convergence bound and
    issue 11's 2 % as the requirement."""
    th0 = 0.5 * ALPHA
    init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
    ref = L.reference(block_scene(L, "rfree_ref", damping=init, T=1.6),
                      "rfree_ref.h5", "reference.restitution=%.6f" % R_HOUSNER)
    ra = impacts_and_amps(ref)[1]

    def dem(kf):
        return impacts_and_amps(L.run(block_scene(L, "rfree%g" % kf, kf, init, T=1.6), "rfree%g.h5" % kf))[1]
    a1, a2 = dem(10.0), dem(100.0)   # KN 1e11 (the preset's) and 1e12
    src = "CVODE Housner, e = Housner's r = 0.70"
    samp = 3.628 ** 2 * 1e-3 ** 2 / 8   # 1 ms sampling misses a peak by p^2 theta dt^2 / 8
    for i in range(3):
        err = abs(a1[i] - ra[i]) / ra[i]
        tol = (RICHARDSON * abs(a1[i] - a2[i]) + samp * ra[i]) / ra[i]
        L.check("block-free-rigid/amp%d" % (i + 1), "rigid preset (KN 1e11): amplitude after impact %d (rad), relative error" % (i + 1),
                ra[i], src, a1[i], err, tol, "two-KN study (1e11, 1e12) + 1 ms sampling")
        L.check("block-free-rigid/amp%d-2pct" % (i + 1), "rigid preset (KN 1e11): amplitude after impact %d (rad), relative error" % (i + 1),
                ra[i], src, a1[i], err, 0.02, "issue 11's requirement (2 %)")


def long_block_scene(L, name, kf=1.0, damping="", motion=""):
    """The block over 6 s: a 0.6 Hz one-sine pulse lasts 1.7 s, and a block that overturns
    after it must be seen to."""
    return block_scene(L, name, kf, damping, motion, T=6)


def case_block_threshold(L):
    # 0.6 Hz is w/p = 1.04 (p = 3.628 1/s), the low end of issue 11's range 1-6
    freqs = (1.5, 2.0) if L.depth == "fast" else (0.6, 1.0, 1.5, 2.0)
    for f in freqs:
        threshold_case(L, "block-threshold/%gHz" % f, long_block_scene if f < 1 else block_scene, f, "",
                       ["reference.restitution=%.6f" % R_HOUSNER], "CVODE Housner, e = 0.70 (closed form r)")


# w/p 5 and 6: the 0.5 x 1.0 m block's rigid reference lifts off there (its pivot's reaction
# turns negative before it overturns: a / a_uplift 7.4 and 8.5), and a larger block of the same
# alpha does the same (the threshold in units of g tan(alpha) depends on w/p and alpha only). A
# slender block, 0.25 x 0.25 x 1.0 m (h/b = 4, alpha 0.2450 rad, p = 3.778 1/s, Housner's r
# 0.912), overturns at 2.9 and 4.6 g tan(alpha) there, rocking without lift-off.
SLENDER = SCENE.format(blocks="block create brick size 0.25 0.25 1.0 position 0 0 0.5 name b")
SLENDER_ALPHA = math.atan(0.25)
SLENDER_P = math.sqrt(3 * cf.G0 / (4 * math.hypot(0.125, 0.5)))


def slender_scene(L, name, kf=1.0, damping="", motion="", T=4):
    return L.scene(name, SLENDER.format(kn=KN0 * kf, ks=10 * KN0 * kf, damping=damping, motion=motion, T=T))


def case_slender_threshold(L):
    r = cf.housner_r(SLENDER_ALPHA)
    for wp in ((6.0,) if L.depth == "fast" else (5.0, 6.0)):
        f = wp * SLENDER_P / (2 * math.pi)
        threshold_case(L, "slender-threshold/w-p-%g" % wp, slender_scene, f, "",
                       ["reference.restitution=%.6f" % r], "CVODE Housner, e = %.4f (closed form r), h/b = 4" % r)


# ==== rung 3: two-block stack vs CVODE Kounadis ==================================================
# Damped: normal dashpots at 20 % of critical at every subcontact (the README's example), on top
# of the plastic point impacts. They leave the block's impact restitution within 0.5 % of
# Housner's r (0.7003 at 50 % of critical against 0.6974 undamped, docs/CONTACT.md), so the
# reference is the same plastic Kounadis model; they cost 1.8 times the steps.
DAMPED = "model damping viscous 0.2"


STACK_RTOL = 0.002   # bisection of the stack thresholds: brackets well inside the 3 % asked
STACK_ASKED = 0.03   # issue 10: stack thresholds within 3 % of the Kounadis reference
STACK_P = math.sqrt(3 * cf.G0 / (4 * math.hypot(0.25, 0.5)))   # 1/s: the lower block's p (3.628)
STIFF_WP = 3.0       # above this w/p the undamped thresholds are also checked at KN 1e12 (convergence in KN)


def case_stack_threshold(L):
    """The stack's minimum overturning amplitude of one-sine pulses at 1, 1.5, 2 and 2.5 Hz
    (w/p 1.7 to 4.3 of the lower block; above 4.3 the rigid reference lifts off), undamped and
    damped, at the setting docs/CONTACT.md recommends for comparison with rigid theory: the
    rigid preset's KN (10 KN0). Its error bound is the two-KN study against KN0 (as the stack
    histories) plus both bisection brackets; issue 10's 3 % is checked as its own row.
    Undamped: plastic point impacts are Kounadis' plastic impacts; damped: the same with
    dashpots."""
    runs = [("undamped", "", (1.5,) if L.depth == "fast" else (1.0, 1.5, 2.0, 2.5))]
    if L.depth == "full":
        runs.append(("damped", DAMPED, (1.0, 1.5, 2.0, 2.5)))
    src = "CVODE Kounadis (plastic impacts)"
    for label, damping, freqs in runs:
        for f in freqs:
            rid = "stack-threshold/%s-%gHz" % (label, f)
            motion = "ground-motion pulse one-sine amplitude 1g frequency %g" % f

            def dem(kf):
                return L.threshold(stack_scene(L, "thr_%s_%g" % (rid.replace("/", "_"), kf), kf, damping, motion),
                                   "dem", rtol=STACK_RTOL)
            ref, wr = L.threshold(stack_scene(L, "thr_ref", 1.0, damping, motion), "reference", rtol=STACK_RTOL)
            (a1, w1), (a2, w2) = L.kn_pair(dem)
            err = abs(a2 - ref) / ref
            what = "minimum overturning amplitude at %g Hz (g), rigid preset's KN %g, relative error" % (f, 10 * KN0)
            L.check(rid, what, ref / cf.G0, src, a2 / cf.G0, err, RICHARDSON * abs(a1 - a2) / ref + w2 + wr,
                    "two-KN study (%g, %g) + both bisection brackets (rtol %g)" % (KN0, 10 * KN0, STACK_RTOL))
            L.check(rid + "-3pct", what, ref / cf.G0, src, a2 / cf.G0, err, STACK_ASKED, "issue 10's requirement (3 %)")
            if L.depth == "full" and not damping and 2 * math.pi * f / STACK_P > STIFF_WP:
                # above w/p 3 (the steep region) the undamped threshold at ten times the preset's KN as well:
                # the 3 % asked must not hang on the preset's stiffness (docs/CONTACT.md, stack thresholds)
                a3, _ = dem(100.0)
                L.check(rid + "-kn%g-3pct" % (100 * KN0), "minimum overturning amplitude at %g Hz (g), KN %g, relative error"
                        % (f, 100 * KN0), ref / cf.G0, src, a3 / cf.G0, abs(a3 - ref) / ref, STACK_ASKED,
                        "issue 10's requirement (3 %), at ten times the rigid preset's KN")


def stack_events(path):
    """Times (s) of the stack uplift (the lower block's first uplift), the upper block's
    separation (its first uplift) and the first ground impact (the lower block's first impact);
    None where the run has none."""
    ev = [event_times(path, "uplift", "lower"), event_times(path, "uplift", "upper"), event_times(path, "impact", "lower")]
    return [e[0] if e else None for e in ev]


STACK_EVENTS = ("stack-uplift", "upper-separation", "first-impact")


def case_stack_history(L):
    """Each block's tilt against Kounadis' ODE up to the reference's first impact (error =
    max |difference| / peak tilt), and the times of the stack uplift, the upper block's
    separation and the first ground impact at the rigid preset's KN (10 KN0). Two stacks:
    unequal (0.5 x 1.0 under 0.4 x 0.8, 0.5 g at 2 Hz) and equal widths h/b = 4 (0.4 x 1.6
    twice, 0.2 g at 2 Hz: 1.6 x its static uplift acceleration g b / 2h = 0.125 g; the rigid
    equal stack never separates)."""
    stacks = [("undamped", stack_scene, "0.5g", "", [(0.25, 0.5), (0.2, 0.4)]),
              ("damped", stack_scene, "0.5g", DAMPED, [(0.25, 0.5), (0.2, 0.4)])]
    if L.depth == "full":
        stacks.append(("equal4", equal_stack_scene, "0.2g", "", [(0.2, 0.8), (0.2, 0.8)]))
    for label, scene_fn, amp, damping, halves in stacks:
        motion = "ground-motion pulse one-sine amplitude %s frequency 2" % amp
        ref = L.reference(scene_fn(L, "sh_ref_" + label, 1.0, "", motion, T=2), "sh_ref.h5")
        tr, thr = h5(ref, "time", "tilt")
        t_imp = event_times(ref, "impact")[0]
        sel = tr < t_imp
        ev_ref = stack_events(ref)

        def dem(kf):   # run to just past the reference's first impact: the history compared
            p = L.run(scene_fn(L, "sh_%s%g" % (label, kf), kf, damping, motion, T="%.4f" % (t_imp + 0.05)), "sh%g.h5" % kf)
            td, thd = h5(p, "time", "tilt")
            out = []
            for b in range(2):
                d = np.interp(tr[sel], td, thd[:, b])
                peak = np.abs(thr[sel, b]).max()
                out.append(float(np.abs(d - np.abs(thr[sel, b])).max() / peak))
            return out, stack_events(p), float(h5(p, "summary:dt"))
        (e1, v1, _), (e2, v2, dt2) = L.kn_pair(dem)
        for b, name in enumerate(("lower", "upper")):
            # the reference's own error is nil here; the DEM's, by the two-KN study; 1 ms
            # interpolation of a smooth history adds < 1e-4 of the peak
            tol = RICHARDSON * abs(e1[b] - e2[b]) + 1e-4
            L.check("stack-history/%s-%s" % (label, name), "%s block tilt up to the first impact: max |diff| / peak" % name,
                    0.0, "CVODE Kounadis (%s)" % label, e1[b], e1[b], tol, "two-KN study (+1e-4 interpolation)")
        stack_event_checks(L, label, ev_ref, v1, v2, dt2, t_imp, halves)
        # issue 10's own measure: each block's largest tilt over the whole run (impacts and free
        # rocking included, the reference's 2 s) within 3 % of the reference's
        full = L.run(scene_fn(L, "sh_full_" + label, 10.0, damping, motion, T=2), "sh_full.h5")
        thd = h5(full, "tilt")
        for b, name in enumerate(("lower", "upper")):
            peak = float(np.abs(thr[:, b]).max())
            err = abs(float(np.abs(thd[:, b]).max()) - peak) / peak
            L.check("stack-history/%s-%s-max-tilt-3pct" % (label, name), "%s block's largest tilt over 2 s (rad), relative error"
                    % name, peak, "CVODE Kounadis (%s)" % label, float(np.abs(thd[:, b]).max()), err, STACK_ASKED,
                    "issue 10's requirement (3 %)")
        if L.depth == "full":
            # the KN docs/CONTACT.md recommends for uplift times to 1 %: the smallest decade whose
            # elastic bound (above) is under 1 % of the rigid uplift time
            kn = 10 * KN0
            while cf.pulse_onset_lag(cf.stack_rocking_omega(halves, kn, 2700.0, cf.SCENE_G), 2.0, ev_ref[0]) > 0.01 * ev_ref[0]:
                kn *= 10
            if kn > 10 * KN0:
                _, v, _ = dem(kn / KN0)
                err = abs(v[0] - ev_ref[0]) / ev_ref[0] if v[0] is not None else 1.0
                L.check("stack-history/%s-stack-uplift-time-kn%g" % (label, kn), "stack-uplift time (s) at KN %g, relative error" % kn,
                        ev_ref[0], "CVODE Kounadis (%s)" % label, v[0] if v[0] is not None else "none", err, 0.01,
                        "issue 10's requirement (1 %), at the KN whose elastic bound is under 1 %")


def stack_event_checks(L, label, ev_ref, v1, v2, dt, t_imp, halves):
    """The three event times at the preset's KN (v2; v1 at KN / 10) against the reference's."""
    src = "CVODE Kounadis (%s)" % label
    for k, what in enumerate(STACK_EVENTS):
        rid = "stack-history/%s-%s-time" % (label, what)
        if ev_ref[k] is None:
            # the rigid stack never does this before its first impact: neither may the DEM
            early = v2[k] is not None and v2[k] < t_imp
            L.check(rid, "%s before the first impact (count)" % what, "none", src,
                    "%.5g s" % v2[k] if early else "none", int(early), 0, "an event: must agree")
            continue
        if v2[k] is None:
            L.check(rid, "%s time (s)" % what, ev_ref[k], src, "none", 1.0, 0.0, "an event: must happen")
            continue
        err = abs(v2[k] - ev_ref[k]) / ev_ref[k]
        if what == "stack-uplift":
            # before uplift the elastic joints ring in their rocking mode, set off by the pulse's
            # onset: the DEM's uplift may lag or lead the rigid one by up to 1/(omega cos(2 pi f t))
            # (closed_forms.pulse_onset_lag, omega from the joints' stiffness and the blocks'
            # inertia), plus one step to locate the event
            omega = cf.stack_rocking_omega(halves, 10 * KN0, 2700.0, cf.SCENE_G)
            tol = (cf.pulse_onset_lag(omega, 2.0, ev_ref[k]) + dt) / ev_ref[k]
            tol_src = "elastic rocking mode %.0f Hz: 1/(omega cos(2 pi f t)) + one DEM step" % (omega / (2 * math.pi))
        else:
            # after uplift the elastic joint's error falls with KN: the two-KN study bounds it
            tol = (RICHARDSON * abs(v1[k] - v2[k]) + dt) / ev_ref[k] if v1[k] is not None else 0.0
            tol_src = "two-KN study + one DEM step"
        L.check(rid, "%s time (s) at KN %g, relative error" % (what, 10 * KN0), ev_ref[k], src, v2[k], err, tol, tol_src)
        # issue 10 asks for each event time within 1 % of the rigid reference
        L.check(rid + "-1pct", "%s time (s) at KN %g, relative error" % (what, 10 * KN0), ev_ref[k], src, v2[k], err,
                0.01, "issue 10's requirement (1 %)")


# ==== rung 3b: stacks and columns that must stay put ============================================
# Issue 10 items 2, 4 and 7 at the setting docs/CONTACT.md recommends for comparison with rigid
# theory (the rigid preset). Friction 80 deg (mu g = 5.7 g): a rigid block never slips under
# these motions, so every slip is the contact model's; the issue allows 1 mm over 5 s.
SLIP_ASKED = 1e-3   # m: issue 10, a high-friction block's slide on the one below over 5 s
QUIET = "ground-motion stochastic seed 1 pga 0.03g duration 5"
COLUMN4 = SCENE.format(blocks="\n".join(
    ["block create prism sides 12 radius 0.3 height 0.6 seat-on %s name d%d" % ("base" if k == 1 else "d%d" % (k - 1), k)
     for k in range(1, 5)]))
COLUMN10_RIGID = SCENE.format(blocks="block create column drums 10 diameter 0.8 height 0.6 sides 16 seat-on base name c")


def slip_checks(L, rid, path):
    """Every joint's slip (the engine's measure at the centre of pressure, elastic part removed)
    and, between free bodies, the upper body's footprint displacement in the lower body's frame
    at the end (tools/relative_slide.py, geometry only), against the 1 mm asked; the lowest
    body's footprint displacement on the fixed base, against the same 1 mm (a hop moves a block
    without any joint slip, so only the geometry sees it); and the energy residual against the
    1e-3 asked."""
    names, out = h5(path, "joints/joint", "joints/outcomes")
    cols = [attr(c) for c in h5(path, "joints/outcome")]
    worst = int(np.argmax(out[:, cols.index("max_slip")]))
    L.check(rid + "/joint-slip", "largest joint slip over 5 s (m), joint %s" % attr(names[worst]), 0.0,
            "rigid blocks, mu = 5.7", float(out[worst, cols.index("max_slip")]), float(out[worst, cols.index("max_slip")]),
            SLIP_ASKED, "issue 10's requirement (1 mm over 5 s)")
    base, *rel = rs.joint_slips(path)
    k = int(np.argmax([r[3] for r in rel]))
    L.check(rid + "/relative-slide", "upper body's final footprint shift on the lower (m), %s/%s" % rel[k][:2], 0.0,
            "rigid blocks, mu = 5.7", rel[k][3], rel[k][3], SLIP_ASKED, "issue 10's requirement (1 mm over 5 s)")
    L.check(rid + "/base-walk", "lowest body's final footprint shift on the fixed base (m), %s" % base[1], 0.0,
            "rigid blocks, mu = 5.7: no walk", base[3], base[3], SLIP_ASKED,
            "issue 10's 1 mm over 5 s, applied to the base joint (a rocking block must not walk)")
    r = float(h5(path, "summary:energy_residual_max"))
    L.check(rid + "/energy", "energy residual", 0.0, "energy conservation", r, r, RESIDUAL_ASKED, "issue 10's bound (1e-3)")


def case_stack_fidelity(L):
    """No spurious events, no walk, a closed energy balance: (a) the equal-width h/b 4 stack under
    a 0.03 g stochastic record (an eighth of its static uplift acceleration g b / 2h = 0.125 g,
    far below mu g), with the rigid preset and with the default contact: no uplift, no slip
    event; (b) the unequal stack under a 0.6 g 2 Hz pulse (0.9 of its overturning threshold: it
    rocks hard), (c) in full depth, a 4-drum column (12-sided drums, 0.5 g at 2 Hz) shaken along
    a vertex (the drums rock on one rim vertex) and face-on (15 deg: on an edge of two vertices),
    and a 10-drum column (16 sides, 0.2 g at 2 Hz): slip and residual checks (slip_checks)."""
    quiet = [("preset", equal_stack_scene(L, "quiet_preset", 10.0, "", QUIET, T=5)),
             ("default", L.scene("quiet_default", EQUAL4.replace("contact preset rigid\n", "")
                                 .replace("contact property stiffness-normal {kn} stiffness-shear {ks}\n", "")
                                 .format(damping="", motion=QUIET, T=5)))]
    for label, dat in quiet:
        p = L.run(dat, "quiet_%s.h5" % label)
        n = sum(len(event_times(p, kind)) for kind in ("uplift", "slip"))
        L.check("stack-quiet/%s-events" % label, "uplift and slip events of the equal stack at 0.03 g (count)", 0,
                "rigid stack at rest (a_g < g b / 2h, a_g < mu g)", n, n, 0, "an event: must agree (issue 10)")
        r = float(h5(p, "summary:energy_residual_max"))
        L.check("stack-quiet/%s-energy" % label, "energy residual", 0.0, "energy conservation", r, r, RESIDUAL_ASKED,
                "issue 10's bound (1e-3)")
    slip_checks(L, "stack-walk/unequal-0.6g", L.run(stack_scene(L, "walk", 10.0, "",
                "ground-motion pulse one-sine amplitude 0.6g frequency 2", T=5), "walk.h5"))
    if L.depth == "full":
        for name, text, motion in (("4-drum-0.5g", COLUMN4, "ground-motion pulse one-sine amplitude 0.5g frequency 2"),
                                   ("4-drum-0.5g-face-on", COLUMN4,
                                    "ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 15"),
                                   ("10-drum-0.2g", COLUMN10_RIGID, "ground-motion pulse one-sine amplitude 0.2g frequency 2")):
            dat = L.scene("walk_" + name, text.format(kn=10 * KN0, ks=100 * KN0, damping="", motion=motion, T=5))
            slip_checks(L, "column-walk/" + name, L.run(dat, "walk_%s.h5" % name))


# ==== rung 4: sliding vs Newmark ================================================================
SLIDE = """block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create brick size 1 1 0.25 position 0 0 0.125 density 2700 name block
contact property stiffness-normal {kn} stiffness-shear {ks} friction 20
model settle on
ground-motion pulse one-sine amplitude 0.6g frequency 2 direction 0
model solve time 1.5
output hdf5 'slide.h5' interval 0.005
"""


def case_slide(L):
    mu, A, f = math.tan(math.radians(20)), 0.6 * cf.G0, 2.0
    umax, ufin = cf.newmark_slide(mu, A, f, cf.SCENE_G)

    def dem(kf):
        p = L.run(L.scene("slide%g" % kf, SLIDE.format(kn=1e10 * kf, ks=1e9 * kf)), "slide%g.h5" % kf)
        return float(h5(p, "summary:max_slide")[0])
    s1, s2 = L.kn_pair(dem)
    # the elastic shear deflection mu m g / (KS A) is part of the DEM's slide and vanishes as
    # KS -> oo: it is inside the two-KN study (KS scaled with KN)
    tol = RICHARDSON * abs(s1 - s2) / umax + 1e-6
    L.check("slide/newmark", "max slide, 0.6 g one-sine 2 Hz, mu = tan 20 deg (m), relative error", umax,
            "Newmark rigid-plastic (closed form integrated, 1e-11)", s1, abs(s1 - umax) / umax, tol,
            "two-KN study (KS with KN)")


# ==== rung 5: static tipping g tan(alpha) =======================================================
def case_tipping(L):
    """A triangle pulse ramps the ground acceleration at k = g tan(alpha) per second (1 g over
    2 s): a rigid block uplifts when k t = g tan(alpha) (t = 1 s) and its tilt then grows from
    0. Quantity: the time the tilt first passes 1e-4 rad, DEM vs the CVODE rigid reference (the
    rigid solver's uplift is the closed form to 1e-6, tests/test_reference.c)."""
    k = cf.SCENE_G * math.tan(ALPHA)
    motion = "ground-motion pulse triangle amplitude %.10g duration 4" % (2 * k)

    def cross(path):
        t, th = h5(path, "time", "tilt")
        th = th[:, 0]
        i = int(np.argmax(th > 1e-4))
        return float(t[i - 1] + (1e-4 - th[i - 1]) / (th[i] - th[i - 1]) * (t[i] - t[i - 1]))
    tr = cross(L.reference(block_scene(L, "tip_ref", motion=motion, T=1.3), "tip_ref.h5"))

    def dem(kf):
        return cross(L.run(block_scene(L, "tip%g" % kf, kf, motion=motion, T=1.3), "tip%g.h5" % kf))
    t1, t2 = L.kn_pair(dem)
    tol = RICHARDSON * abs(t1 - t2) + 1e-3 * 0.05   # + linear interpolation over 1 ms samples
    L.check("tipping/ramp", "ground acceleration when the tilt passes 1e-4 rad (m/s^2), abs error", k * tr,
            "CVODE Housner (uplift at g tan(alpha) = %.4f m/s^2)" % k, k * t1, k * abs(t1 - tr), k * tol,
            "two-KN study + sampling")


# ==== rung 6: restitution vs amplitude decay ====================================================
def case_restitution(L):
    """With perfectly plastic point impacts at the corners (the rigid preset), the amplitude
    decay of a free-rocking run must give Housner's r through the rigid block's energy balance
    (closed form): the angular momentum about the new pivot is kept."""
    init = "block initial name b tilt %.10g direction 0" % math.degrees(0.5 * ALPHA)

    def dem(kf):
        p = L.run(block_scene(L, "rest%g" % kf, kf, init, T=1.6), "rest%g.h5" % kf)
        _, amps = impacts_and_amps(p, n=3)
        rs = [cf.restitution_from_amplitudes(ALPHA, 0.5 * ALPHA if i == 0 else amps[i - 1], amps[i]) for i in range(3)]
        return float(np.mean(rs))
    r1, r2 = L.kn_pair(dem)
    tol = RICHARDSON * abs(r1 - r2)
    L.check("restitution/amplitude-decay", "r from the amplitude decay of impacts 1-3 (mean), abs error", R_HOUSNER,
            "Housner's r = 1 - 1.5 sin^2(alpha) (closed form)", r1, abs(r1 - R_HOUSNER), tol,
            "two-KN study")


# ==== rung 6b: a restitution other than Housner's ===============================================
# A knife-edge pivot transfer keeps the angular momentum about the new edge: Housner's r (0.70
# here), whatever the point's restitution e (e > 0 makes the block bounce on its new edge,
# docs/CONTACT.md). More is kept when the impact is shared with the base's interior: angular
# momentum kept about an impulse centroid at distance x from the centre line gives
# r = (J - m x b) / (J + m x b), J = I_G + m h^2, which runs from Housner's r (x = b) to 1 (x = 0).
# A mid-line layout adds the base's centre lines to the corners (spacing b: a 3 x 3 layout) with
# a little point restitution. Two blocks: 0.5 x 0.5 x 1.0 m with e = 0.2 (r about 0.79, Housner
# 0.70) and 1/3 x 1/3 x 1.0 m with e = 0.5 (r about 0.90, Housner 0.85). At KN 1e10 the first
# one's third impact scatters by 7 %; at KN 1e11 its r still depends on the impact (the first,
# fastest impact keeps 0.787, the next ones 0.795-0.802, releases from 0.3 to 0.9 alpha), so no
# constant r predicts its amplitudes (1.7 % off after the first impact); at 1e12 and 1e13 every
# impact keeps the same (0.785-0.787 at 1e12, 0.785 at 1e13, same releases). Its two-KN study
# therefore runs KN 1e12 and 1e13; the second block's at 1e11 and 1e12.
MID = (  # (case id, base width b2 = 2b (m), point restitution, free-rocking run lengths (s),
         #  KN factors of the two-KN study)
    ("other-r", 0.5, 0.2, 2.0, (100.0, 1000.0)),
    ("other-r09", 1.0 / 3.0, 0.5, 3.0, (10.0, 100.0)),
)


def mid_scene(L, case, kf, name, extra, motion="", T=3):
    rid, w, e, _, _ = case
    blocks = "block create brick size %.10g %.10g 1.0 position 0 0 0.5 name b" % (w, w)
    text = SCENE.format(blocks=blocks).format(kn=KN0 * kf, ks=10 * KN0 * kf, damping=extra, motion=motion, T=T)
    text = text.replace("contact preset rigid\n", "contact preset rigid\ncontact property spacing %.10g restitution %g\n" % (w / 2, e))
    return L.scene("%s_%s_%g" % (rid, name, kf), text)


def mid_free(L, case, kf, th0, T):
    init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
    path = mid_scene(L, case, kf, "free%.4f" % th0, init, T=T)
    return impacts_and_amps(L.run(path, os.path.basename(path)[:-4] + ".h5"), n=3)


def calibration_check(L, rid, layout, scene, *patterns):
    """`rockdem restitution --target 0.9` on scene: the r it reached (or, exit status 4, the
    closest it gets), read by the first of patterns that matches, against the target."""
    sets = sum((["--set", s] for s in L.dem_sets(scene, ())), [])
    out = L.rockdem("restitution", scene, "--target", "0.9", "-q", *sets, ok=(0, 4))
    m = next((m for m in (re.search(p, out) for p in patterns) if m), None)
    if not m:
        raise RuntimeError("restitution: no answer in\n" + out)
    got = float(m.group(1))
    L.check(rid, "restitution calibrated to r = 0.9, %s (abs error)" % layout, 0.9,
            "target", got, abs(got - 0.9), 0.002, "the calibration's target accuracy (issue 11, must-have 1)")


def check_amplitudes(L, rid, ra, a1, a2, p, src, kns):
    """Rows rid/amp1-3: the DEM's amplitudes after impacts 1-3 at the two KN of kns (a1, a2)
    against the reference's ra, within the two-KN study plus the 1 ms sampling of a peak (p:
    the block's frequency parameter, rad/s)."""
    samp = p ** 2 * 1e-3 ** 2 / 8   # 1 ms sampling of a peak (parabola at the top)
    for i in range(3):
        tol = RICHARDSON * abs(a1[i] - a2[i]) / ra[i] + samp
        L.check("%s/amp%d" % (rid, i + 1), "rocking amplitude after impact %d (rad), relative error" % (i + 1),
                ra[i], src, a1[i], abs(a1[i] - ra[i]) / ra[i], tol, "two-KN study (%s, %s) + 1 ms sampling" % kns)


SURFACE_OTHER_R = 0.80   # the surface model's other r (h/b = 2 block): its dashpot calibrated to it


def surface_other_r(L):
    """Under the surface model the mid-line layouts' point restitution has no form (no
    permanent set, docs/CONTACT.md section 8.6); its loss is the joint dashpot, and `rockdem
    restitution` calibrates the dashpot's ratio. The layouts' test, for the h/b = 2 block: the
    ratio calibrated to r = 0.80 at KN 1e10 (its own target check), then, at that ratio, the r
    measured from a release at alpha / 2 (amplitude decay of impacts 1-3, never handed in) must
    predict, through CVODE Housner at that r, the amplitudes after impacts 1-3 of a release at
    0.8 alpha, within a two-KN study (1e10, 1e11: the ratio's r moves with KN, section 8.4)."""
    cal = block_scene(L, "sr_cal", 1.0, "contact property restitution 1")
    sets = sum((["--set", s] for s in L.dem_sets(cal, ())), [])
    out = L.rockdem("restitution", cal, "--target", "%g" % SURFACE_OTHER_R, "-q", *sets, ok=(0, 4))
    m = re.search(r"model damping viscous ([0-9.]+) gives r = ([0-9.]+)", out)
    if not m:
        raise RuntimeError("restitution: no calibrated ratio in\n" + out)
    zeta, got = float(m.group(1)), float(m.group(2))
    L.check("surface-other-r/calibrate-0.8", "restitution calibrated to r = 0.8, dashpot ratio (abs error)",
            SURFACE_OTHER_R, "target", got, abs(got - SURFACE_OTHER_R), 0.002,
            "the calibration's target accuracy (issue 11, must-have 1)")
    T, kfs = 2.0, (1.0, 10.0)
    loss = "contact property restitution 1\nmodel damping viscous %.6g" % zeta

    def free(kf, th0, T):
        init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
        path = block_scene(L, "sr_free%.4f_%g" % (th0, kf), kf, loss + "\n" + init, T=T)
        return impacts_and_amps(L.run(path, os.path.basename(path)[:-4] + ".h5"), n=3)[1]
    rs = {}
    for kf in kfs:
        amps = free(kf, 0.5 * ALPHA, T)
        rs[kf] = float(np.mean([cf.restitution_from_amplitudes(ALPHA, 0.5 * ALPHA if i == 0 else amps[i - 1], amps[i])
                                for i in range(3)]))
    r, th0 = rs[kfs[0]], 0.8 * ALPHA
    init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
    ref = L.reference(block_scene(L, "sr_free_ref", 1.0, init, T=T + 0.5), "sr_free_ref.h5",
                      "reference.restitution=%.6f" % r)
    _, ra = impacts_and_amps(ref)
    a1, a2 = (free(kf, th0, T + 0.5) for kf in kfs)
    kns = tuple("%.0e" % (KN0 * kf) for kf in kfs)
    src = "CVODE Housner at the measured r = %.4f (dashpot ratio %.4g, KN %s; %.4f at %s)" % (
        r, zeta, kns[0], rs[kfs[1]], kns[1])
    p = math.sqrt(3 * cf.SCENE_G / (4 * math.hypot(0.25, 0.5)))
    check_amplitudes(L, "surface-other-r", ra, a1, a2, p, src, kns)


def case_other_restitution(L):
    """Each mid-line layout against CVODE Housner run at the layout's own r, measured by the
    amplitude decay of impacts 1-3 of a release at alpha / 2 (never handed in): the amplitudes
    after impacts 1-3 of a release at 0.8 alpha (another run: a constant r must predict them),
    and the one-sine thresholds at 1.5 and 2 Hz (full depth). Then r = 0.9 for the 0.5 x 1.0 m
    block with the rigid preset: the calibrator must reach it to 0.002 (must-have 1 of issue 11);
    it cannot (expected failure, its gap printed). Under the surface model: surface_other_r, then
    the r = 0.9 check (the calibrator varies the dashpot's ratio there)."""
    if L.contact == "surface":
        surface_other_r(L)
        calibration_check(L, "other-r/rigid-0.9", "rigid preset", block_scene(L, "r09", 10.0),
                          r"gives r = ([0-9.]+)", r"gets is r = ([0-9.]+)")
        return
    for case in MID:
        rid, w, _, T, kfs = case
        alpha = math.atan(w)
        p = math.sqrt(3 * cf.G0 / (4 * math.hypot(w / 2, 0.5)))
        rs = {}
        for kf in kfs:
            _, amps = mid_free(L, case, kf, 0.5 * alpha, T)
            rs[kf] = float(np.mean([cf.restitution_from_amplitudes(alpha, 0.5 * alpha if i == 0 else amps[i - 1], amps[i])
                                    for i in range(3)]))
        r = rs[kfs[0]]
        th0 = 0.8 * alpha
        init = "block initial name b tilt %.10g direction 0" % math.degrees(th0)
        ref = L.reference(mid_scene(L, case, 1.0, "free_ref", init, T=T + 0.5), rid + "_free_ref.h5",
                          "reference.restitution=%.6f" % r)
        _, ra = impacts_and_amps(ref)
        (_, a1), (_, a2) = (mid_free(L, case, kf, th0, T + 0.5) for kf in kfs)
        kns = tuple("%.0e" % (KN0 * kf) for kf in kfs)
        src = "CVODE Housner at the layout's measured r = %.4f (KN %s; %.4f at %s; Housner's %.3f)" % (
            r, kns[0], rs[kfs[1]], kns[1], cf.housner_r(alpha))
        check_amplitudes(L, rid, ra, a1, a2, p, src, kns)
        if L.depth != "full":
            continue
        # the h/b 3 block also at w/p 1 and 5 (issue 11's range 1-6 for another r; the h/b 2
        # block's rigid reference lifts off at w/p 5), over 6 s at the low frequency
        wps = (1.0, 5.0) if rid == "other-r09" else ()
        for f in (1.5, 2.0) + tuple(round(wp * p / (2 * math.pi), 4) for wp in wps):
            motion = "ground-motion pulse one-sine amplitude 1g frequency %g" % f
            T = 6 if f < 1 else 3
            a_ref, wr = L.threshold(mid_scene(L, case, 1.0, "thr_ref", "", motion, T), "reference",
                                    "reference.restitution=%.6f" % r)
            (b1, w1), (b2, _) = (L.threshold(mid_scene(L, case, kf, "thr%g" % f, "", motion, T), "dem") for kf in kfs)
            tol = RICHARDSON * abs(b1 - b2) / a_ref + w1 + wr
            L.check("%s/threshold-%gHz" % (rid, f), "minimum overturning amplitude at %g Hz (g), relative error" % f,
                    a_ref / cf.G0, src, b1 / cf.G0, abs(b1 - a_ref) / a_ref, tol,
                    "two-KN study (%s, %s) + both bisection brackets (rtol 0.005)" % kns)
        if rid == "other-r09":
            # the calibrator on this layout, whose r(e) is not monotonic: it must find a crossing
            calibration_check(L, "other-r09/calibrate-0.9", "mid-line layout", mid_scene(L, case, 10.0, "cal", ""),
                              r"gives r = ([0-9.]+)", r"gets is r = ([0-9.]+)")
    # r = 0.9 with the rigid preset: the calibrator says how close it gets (exit status 4)
    calibration_check(L, "other-r/rigid-0.9", "rigid preset", block_scene(L, "r09", 10.0),
                      r"r = ([0-9.]+) at restitution", r"reached r = ([0-9.]+)")


# ==== rung 7: YADE stored runs ==================================================================
from compare import RunFile  # noqa: E402  (tools/yade/compare.py)

# rockdem's shear stiffness matched to YADE's law. YADE's Polyhedra law gives one interaction
# the shear stiffness ks = KS x A (A: the whole contact face, tools/yade/translate.py), kept in
# full while the block rocks on an edge. rockdem gives each subcontact point KS x its tributary
# area; the automatic spacing meshes a square face into 10 x 10 cells, and the edge row a block
# rocks on carries 10 half cells = A / 20. rockdem's KS = 20 x the scenario's KS gives the
# rocking block YADE's shear stiffness (2e10 x 0.0125 m^2 = 1e9 x 0.25 m^2 = 2.5e8 N/m).
YADE_KS_MATCH = 20


def yade_pair(L, scen, name, amp=None, sets=(), quarter=False):
    """rockdem at dt and dt/2 on a stored YADE scenario; YADE's stored dt and dt/2 files; with
    quarter, rockdem at dt/4 too (appended)."""
    dat = os.path.join(YADE, scen)
    base = list(sets) + (["motion.amplitude=%sg" % amp] if amp else [])
    fix = {}
    for line in open(dat):
        m = re.match(r"model timestep fixed ([0-9.e+-]+)", line)
        if m:
            fix["dt"] = float(m.group(1))
    rd1 = RunFile(L.run(dat, name + "_rd.h5", *base))
    rd2 = RunFile(L.run(dat, name + "_rd2.h5", *(base + ["model.timestep=%g" % (fix["dt"] / 2)])))
    stored = os.path.join(YADE, name + ".h5")
    half = os.path.join(YADE, "half", name + ".h5")
    for p in (stored, half):
        if not os.path.exists(p):
            raise RuntimeError("missing stored YADE file %s (make check-yade regenerates it)" % p)
    runs = (rd1, rd2, RunFile(stored), RunFile(half))
    if quarter:
        runs += (RunFile(L.run(dat, name + "_rd4.h5", *(base + ["model.timestep=%g" % (fix["dt"] / 4)]))),)
    return runs


def step_bound(m1, m2, m4):
    """rockdem's step error at dt, relative, from its answers at dt, dt/2 and dt/4: the dt/2
    change when the changes shrink as the step halves (|m2 - m4| <= |m1 - m2|: the runs lie in
    the scheme's asymptotic range, where the dt/2 change bounds the error at dt); NaN otherwise:
    no bound, and the row cannot pass. A chaotic response (a column's drums falling on each
    other) moves its peaks up and down with the step, and its dt/2 change was as likely small by
    chance as large (the 0.7 g column rows passed once on a lucky 25 %)."""
    return rel(m1, m2) if abs(m2 - m4) <= abs(m1 - m2) else float("nan")


def rel(a, b):
    return abs(a - b) / abs(b)


def case_yade_free(L):
    ks = "contact.stiffness-shear=%g" % (1e9 * YADE_KS_MATCH)
    rd1, rd2, y1, y2 = yade_pair(L, "free.dat", "free", sets=[ks])
    t = [R.impacts(0)[0][0] for R in (rd1, rd2, y1, y2)]
    wedge, edge = cf.winkler_inset_first_impact(0.25, 0.5, 0.5, 2700 * 0.25, 1e10, math.radians(10), 9.81)
    tol = abs(t[0] - t[1]) + abs(t[2] - t[3]) + (wedge - edge)
    L.check("yade-free/impact-time", "first impact time (s), abs difference", t[2], "YADE 2023.02a (stored, dt 5e-5)",
            t[0], abs(t[0] - t[2]), tol, "dt/2 (both codes) + Winkler-wedge pivot inset %.2g s (closed form)" % (wedge - edge))

    def amp(R):
        imp = R.impacts(0)
        return float(np.max(R.tilt[imp[0][1]:imp[1][1] if len(imp) > 1 else len(R.time), 0]))
    a = [amp(R) for R in (rd1, rd2, y1, y2)]
    tol = rel(a[0], a[1]) + rel(a[2], a[3])
    L.check("yade-free/amp-after-impact", "peak tilt between impacts 1 and 2 (rad), relative to YADE", a[2],
            "YADE (stored)", a[0], rel(a[0], a[2]), tol, "dt/2 (both codes)")
    L.check("yade-free/release-tilt", "release tilt (rad), relative", y1.sumval("max_tilt", 0), "YADE (stored)",
            rd1.sumval("max_tilt", 0), rel(rd1.sumval("max_tilt", 0), y1.sumval("max_tilt", 0)), 1e-6,
            "same initial condition; 1e-6 = YADE's 1 um lift over the 1 m block")


def overturns(L, dat, amp, sets):
    p = L.run(dat, "ovb.h5", *(list(sets) + ["motion.amplitude=%.6gg" % amp]))
    return int(h5(p, "summary:overturned")[0])


def case_yade_overturn(L):
    dat = os.path.join(YADE, "overturn.dat")
    y = {a: (RunFile(os.path.join(YADE, "overturn-%s.h5" % a)), RunFile(os.path.join(YADE, "half", "overturn-%s.h5" % a)))
         for a in ("0.77", "0.78")}
    yo = {a: (int(p.sumval("overturned", 0)), int(q.sumval("overturned", 0))) for a, (p, q) in y.items()}
    assert yo["0.77"] == (0, 0) and yo["0.78"] == (1, 1), "stored YADE bracket is not 0.77 / 0.78 g at dt and dt/2: %s" % yo
    ks = "contact.stiffness-shear=%g" % (1e9 * YADE_KS_MATCH)
    # matched law: rockdem must stand at 0.77 g and overturn at 0.78 g, at dt and at dt/2.
    # Error: how many of those 4 outcomes differ; tolerance 0 (the bracket is YADE's bisection
    # resolution, 1.3 %, and YADE's dt/2 leaves it in place).
    wrong = 0
    for dt in (None, 2.5e-5):
        sets = [ks] + (["model.timestep=%g" % dt] if dt else [])
        wrong += overturns(L, dat, 0.77, sets) != 0
        wrong += overturns(L, dat, 0.78, sets) != 1
    L.check("yade-overturn/bracket-matched-ks", "outcomes at 0.77 / 0.78 g, dt and dt/2 (count wrong)", "0.77 / 0.78 g",
            "YADE (stored, dt and dt/2)", "%d of 4 wrong" % wrong, wrong, 0,
            "YADE's bracket resolution 1.3 %%, unmoved at dt/2; KS matched x%d" % YADE_KS_MATCH)
    # the scenario's own KS (per point): bisect rockdem's threshold (1 % steps) for the gap
    lo, hi = 0.77, 4.0
    if overturns(L, dat, lo, []) == 1:
        hi = lo
    else:
        while hi / lo > 1.01:
            mid = math.sqrt(lo * hi)
            if overturns(L, dat, mid, []):
                hi = mid
            else:
                lo = mid
    L.check("yade-overturn/bracket-scenario-ks", "overturning amplitude (g), relative to YADE's 0.78 g", 0.78,
            "YADE (stored)", hi, rel(hi, 0.78), 0.013 + 0.01, "YADE's bracket 1.3 % + rockdem's 1 % bisection")


def flag_check(L, rid, quantity, dem, yade, yade_half):
    """An outcome flag (overturned, fell) that rockdem must share with YADE. Where halving YADE's
    step flips YADE's own flag, the answer at its dt is not converged in the step, and the run at
    dt/2 (the smaller step error) is the reference."""
    ref = yade if yade == yade_half else yade_half
    src = "YADE (stored; dt/2 agrees)" if yade == yade_half else "YADE at dt/2 (stored; its dt run DIFFERS)"
    L.check(rid, quantity, bool(ref), src, bool(dem), int(dem != ref), 0, "a flag: must agree")


def case_yade_stack(L):
    ks = "contact.stiffness-shear=%g" % (1e9 * YADE_KS_MATCH)
    amps = ("0.3", "1.0") if L.depth == "fast" else ("0.3", "0.6", "1.0")
    for a in amps:
        rd1, rd2, y1, y2 = yade_pair(L, "stack.dat", "stack-%s" % a, a, sets=[ks])
        for k, n in enumerate(("lower", "upper")):
            # a rockdem run that ends because a body left the scene (status lost) gives no
            # overturned flag: the scenario's own criterion (tilt ratio >= 1.5) is applied instead
            o = [int(R.sumval("overturned", k) or R.sumval("max_tilt_ratio", k) >= 1.5) for R in (rd1, y1, y2)]
            flag_check(L, "yade-stack/%sg-%s-overturned" % (a, n), "%s block overturned at %s g" % (n, a), *o)
            if not o[0] and not o[1]:
                m = [R.sumval("max_tilt", k) for R in (rd1, rd2, y1, y2)]
                tol = rel(m[0], m[1]) + rel(m[2], m[3])
                L.check("yade-stack/%sg-%s-tilt" % (a, n), "%s block max tilt at %s g (rad), relative" % (n, a), m[2],
                        "YADE (stored)", m[0], rel(m[0], m[2]), tol, "dt/2 (both codes)")


def case_yade_column(L):
    amps = ("1.6",) if L.depth == "fast" else ("0.4", "0.7", "1.0", "1.6")
    FELL = 0.8   # rad: past every 12-sided drum's own tipping angle (alpha 0.77-0.79 rad): it has fallen
    for a in amps:
        rd1, rd2, y1, y2, rd4 = yade_pair(L, "column.dat", "column-%s" % a, a, quarter=True)
        for k, n in enumerate(y1.names):
            m = [R.sumval("max_tilt", R.body(n)) for R in (rd1, rd2, y1, y2, rd4)]
            fell = [x >= FELL for x in m]
            flag_check(L, "yade-column/%sg-%s-fell" % (a, n), "drum %s fell (max tilt >= 0.8 rad) at %s g" % (n, a),
                       fell[0], fell[2], fell[3])
            if not fell[0] and not fell[2]:
                tol = step_bound(m[0], m[1], m[4]) + rel(m[2], m[3])
                L.check("yade-column/%sg-%s-tilt" % (a, n), "drum %s max tilt at %s g (rad), relative" % (n, a), m[2],
                        "YADE (stored)", m[0], rel(m[0], m[2]), tol,
                        "dt/2 (both codes; rockdem's only where its dt/4 change is smaller: %.4g / %.4g / %.4g rad)"
                        % (m[0], m[1], m[4]))


def case_yade_slide(L):
    rd1, rd2, y1, y2 = yade_pair(L, "slide.dat", "slide")
    s = [R.sumval("max_slide", 0) for R in (rd1, rd2, y1, y2)]
    umax, _ = cf.newmark_slide(math.tan(math.radians(20)), 0.6 * cf.G0, 2.0, cf.SCENE_G)
    # Both codes approximate Newmark's rigid-plastic slide. Each may be off it by its own error:
    # YADE's distance from the closed form (measured on the stored run) and rockdem's bound from
    # a two-KN study (KN and KS x 10, step / sqrt 10); plus each code's dt/2 change.
    r10 = RunFile(L.run(os.path.join(YADE, "slide.dat"), "slide_kn10.h5", "contact.stiffness-normal=1e11",
                        "contact.stiffness-shear=1e10", "model.timestep=%g" % (5e-5 / math.sqrt(10))))
    s10 = r10.sumval("max_slide", 0)
    tol = rel(s[0], s[1]) + rel(s[2], s[3]) + rel(s[2], umax) + RICHARDSON * abs(s[0] - s10) / umax
    L.check("yade-slide/max-slide", "max slide (m), relative to YADE", s[2], "YADE (stored)", s[0], rel(s[0], s[2]), tol,
            "dt/2 (both codes) + YADE's distance from Newmark (%.5g m) + rockdem's two-KN bound" % umax)


# ==== energy balance of drum columns ==============================================================
COLUMN10 = """block create brick size 4 4 1 position 0 0 -0.5 fixed name base
block create column drums 10 diameter 0.8 height 0.6 sides 16 seat-on base name c
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 37 spacing vertices
ground-motion pulse one-sine amplitude 0.3g frequency 1
model solve time 5
output hdf5 'c10.h5' interval 0.01
"""
RESIDUAL_ASKED = 1e-3   # issue 10: energy residual <= 1e-3 of the energy scale on every validation scene


def case_column_energy(L):
    """The energy residual of a 4-drum column (the YADE cross-check scene at its fixed step and
    half of it) and a 10-drum column (16 sides, corners, friction 37 deg, 0.3 g at 1 Hz: its
    drums slide and impact hard) at the default step safety 0.2 and at 0.1. The residual is the
    step's error: it must fall at least as the step (first order) when the step halves, and
    stay under the 1e-3 asked."""
    c10 = L.scene("column10", COLUMN10)
    c4 = os.path.join(YADE, "column.dat")
    # the 4-drum column also at a quarter of its step: a residual that stops falling there is
    # booking, not step error (a face wholly past the other body's edge dropped its points'
    # normal springs unbooked: 8.9e-4 at both 2.5e-5 and 1.25e-5 s before that was booked)
    pairs = [("4-drum", [L.run(c4, "c4a.h5", "motion.amplitude=0.5g"),
                         L.run(c4, "c4b.h5", "motion.amplitude=0.5g", "model.timestep=2.5e-5"),
                         L.run(c4, "c4c.h5", "motion.amplitude=0.5g", "model.timestep=1.25e-5")],
              ("dt 5e-5", "dt 2.5e-5", "dt 1.25e-5")),
             ("10-drum", [L.run(c10, "c10a.h5"), L.run(c10, "c10b.h5", "model.safety=0.1")], ("safety 0.2", "safety 0.1"))]
    for name, files, steps in pairs:
        r = [float(h5(f, "summary:energy_residual_max")) for f in files]
        for k in range(len(r)):
            L.check("column-energy/%s-%s" % (name, steps[k].replace(" ", "")), "%s column energy residual (%s)" % (name, steps[k]),
                    0.0, "energy conservation", r[k], r[k], RESIDUAL_ASKED, "issue 10's bound (1e-3)")
        for k in range(len(r) - 1):
            suffix = "" if k == 0 else "-%d" % (k + 1)
            L.check("column-energy/%s-order%s" % (name, suffix),
                    "%s column: residual at %s / at %s" % (name, steps[k], steps[k + 1]), 2.0,
                    "a first-order step error halves with the step", r[k] / r[k + 1], 2.0 - min(r[k] / r[k + 1], 2.0), 0.0,
                    "at least first order")


def case_energy_every_run(L):
    """Issue 10 asks the residual to stay under 1e-3 on every validation scene: per group of
    cases, the largest residual over every DEM run it made (thresholds excepted, whose runs
    write no file) and how many runs exceed 1e-3 (each printed). The fast depth makes fewer runs
    (its rows are named -fast: an expected failure of the full set need not be one of them)."""
    depth = "" if L.depth == "full" else "-" + L.depth
    for group in sorted({g for _, _, g in L.residuals}):
        res = sorted((r, label) for r, label, g in L.residuals if g == group)[::-1]
        over = [r for r in res if r[0] > RESIDUAL_ASKED]
        for r, label in over:
            print("  residual %.3g: %s" % (r, label))
        L.check("energy/every-run-%s%s" % (group, depth), "largest energy residual over the %d %s runs (%d above 1e-3); worst: %s" % (
            len(res), group, len(over), res[0][1]), 0.0, "energy conservation", res[0][0], res[0][0], RESIDUAL_ASKED,
            "issue 10's bound (1e-3)")


# ==== the case list: one definition, two depths =================================================
CASES = [
    # (group, function, in the fast subset)
    ("block", case_block_free, True),
    ("block", case_block_free_rigid, True),
    ("block", case_block_threshold, True),
    ("block", case_slender_threshold, True),
    ("stack", case_stack_history, True),
    ("stack", case_stack_threshold, True),
    ("stack", case_stack_fidelity, True),
    ("slide", case_slide, True),
    ("tipping", case_tipping, True),
    ("restitution", case_restitution, True),
    ("restitution", case_other_restitution, True),
    ("yade", case_yade_free, True),
    ("yade", case_yade_overturn, True),
    ("yade", case_yade_stack, True),
    ("yade", case_yade_slide, True),
    ("column", case_yade_column, True),
    ("column", case_column_energy, False),
    ("energy", case_energy_every_run, True),   # last: it reads every run made before it
]


def markdown(rows, nrun, wall, when, path, contact="vertex", depth="full", errors=(), zetas=()):
    n = {v: sum(r["verdict"] == v for r in rows) for v in ("pass", "FAIL", "xfail", "xpass")}
    make = "make validate" if contact == "vertex" else "make validate-surface"
    out = ["<!-- GENERATED by `%s` (tools/validate/ladder.py --depth %s%s): do not edit by hand. -->" % (
               make, depth, "" if contact == "vertex" else " --contact surface"),
           "# rockdem validation report" + ("" if contact == "vertex" else ": the surface contact model"), "",
           "Generated by `%s` from runs of `bin/rockdem` (%s%s); never edited by hand." % (
               make, when, "" if depth == "full" else ", depth " + depth),
           "The cases and their tolerances are defined once in `tools/validate/ladder.py`; `make test` runs a fast",
           "subset of the same definitions (`tests/cli/validation.sh`). How each tolerance is derived: the module's",
           "docstring. The rocking equations behind the references: [ROCKING-EQUATIONS.md](ROCKING-EQUATIONS.md).", ""]
    if contact == "surface":
        cal = "; ".join("KN %g: zeta %g, r %.4f" % (kn, z, r) for kn, z, r in sorted(zetas)) or "none run"
        out += ["Every DEM run has `--set contact.model=surface` ([CONTACT.md](CONTACT.md) section 8); a scene with",
                "plastic joints (restitution 0: the rigid and default presets) runs with restitution 1 and the patch",
                "dashpot in place of its own: the ratio (`model damping viscous`) that `rockdem restitution --target",
                "%.2f` calibrates to Housner's r on the rigid-theory block (h/b = 2, KS = 10 KN) at the run's KN" % R_HOUSNER,
                "(section 8.10; this run: %s). The vertex model's report is [validation.md](validation.md); the" % cal,
                "expected-failure marks are its own, so a surface-model miss on a row that passes there is a **FAIL**.", ""]
    out += [
           "Verdicts: **pass** (error <= tolerance), **FAIL**, **xfail** (a known gap, listed with its reason below;",
           "it prints its gap on every run), **xpass** (a known gap that closed: remove its mark).", "",
           "Totals: %d pass, %d FAIL, %d xfail, %d xpass%s; %d rockdem runs in %.0f s." % (
               n["pass"], n["FAIL"], n["xfail"], n["xpass"],
               ", %d cases that could not run" % len(errors) if errors else "", nrun, wall), "",
           "| case | quantity | reference | reference source | rockdem | error | tolerance | tolerance source | verdict |",
           "|---|---|---|---|---|---|---|---|---|"]
    cell = lambda v: str(v).replace("|", "\\|")   # a "|" inside a cell would split the table
    for r in rows:
        out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % tuple(cell(v) for v in (
            r["id"], r["quantity"], fmt(r["ref"]), r["ref_src"], fmt(r["got"]), "%.3g" % r["err"], "%.3g" % r["tol"], r["tol_src"],
            "**%s**" % r["verdict"] if r["verdict"] != "pass" else "pass")))
    out += ["", "## Known gaps (expected failures)", ""]
    for r in rows:
        if r["verdict"] in ("xfail", "xpass"):
            out.append("- `%s`: gap %.3g against %.3g. %s" % (r["id"], r["err"], r["tol"], r.get("why") or XFAILS[r["id"]]))
    if errors:   # a case that raised: its rows are missing, each counts as a failure
        out += ["", "## Cases that could not run (each a failure; their rows are missing)", ""]
        for case, msg in errors:
            lines = [x.strip() for x in msg.splitlines() if x.strip()]
            out.append("- `%s`: %s" % (case, cell(" / ".join(lines[:1] + lines[-1:]) if len(lines) > 1 else msg)))
    out.append("")
    with open(path, "w") as f:
        f.write("\n".join(out))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--depth", choices=["fast", "full"], default="fast")
    ap.add_argument("--bin", default=os.path.join(ROOT, "bin", "rockdem"))
    ap.add_argument("--only", help="groups: block,stack,slide,tipping,restitution,yade,column (the energy check of every run made always closes the list)")
    ap.add_argument("--contact", choices=["vertex", "surface"], default="vertex",
                    help="contact model of every DEM run (surface: see scene_kn and Ladder.plastic_zeta; make validate-surface)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a --set override given last to every DEM run (repeatable; `rockdem keys`): "
                    "bench/safety.sh runs the ladder at each step safety factor")
    ap.add_argument("--md", help="write the markdown report here")
    ap.add_argument("--tmp")
    ap.add_argument("--json", help="write the results file here (make validate: build/validate/results.json)")
    ap.add_argument("--render", metavar="JSON", help="run nothing: write --md from a results file (make docs)")
    ap.add_argument("--against", metavar="MD", help="compare every row run with the same row of a committed report "
                    "(docs/validation.md): the rockdem value as printed there must be the one printed now")
    a = ap.parse_args()
    if a.render:
        if not a.md:
            ap.error("--render needs --md")
        with open(a.render) as f:
            res = json.load(f)
        markdown(res["rows"], res["nrun"], res["wall"], res["when"], a.md, res.get("contact", "vertex"),
                 res.get("depth", "full"), res.get("errors", ()), res.get("zetas", ()))
        print("wrote %s from %s" % (a.md, a.render))
        return 0
    only = set(a.only.split(",")) if a.only else None
    tmp = a.tmp or tempfile.mkdtemp(prefix="rd_ladder_")
    os.makedirs(tmp, exist_ok=True)
    L = Ladder(os.path.abspath(a.bin), tmp, a.depth, a.contact, a.set)
    t0 = time.time()
    errors = 0
    for group, fn, fast in CASES:
        if (only and group not in only and group != "energy") or (a.depth == "fast" and not fast):
            continue
        try:
            L.group = group
            fn(L)
        except Exception as e:  # a case that cannot run is a failure, never a silent skip
            print("FAIL %s: %s" % (fn.__name__, e))
            L.errors.append((fn.__name__, str(e).replace(tmp, "$TMP")))   # a report that does not name a temp dir
            errors += 1
    wall = time.time() - t0
    when = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    if a.md:
        markdown(L.rows, L.nrun, wall, when, a.md, a.contact, a.depth, L.errors, L.zeta_list())
    if a.json:
        rows = [dict(r, ref=jsonable(r["ref"]), got=jsonable(r["got"]), err=float(r["err"]), tol=float(r["tol"]),
                     why=XFAILS.get(r["id"], "")) for r in L.rows]
        os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
        with open(a.json, "w") as f:
            json.dump(dict(depth=a.depth, contact=a.contact, when=when, wall=wall, nrun=L.nrun, rows=rows,
                           errors=L.errors, zetas=L.zeta_list()), f, indent=1)
    if a.against:
        errors += against(L.rows, a.against)
    if not a.tmp:
        shutil.rmtree(tmp, ignore_errors=True)
    n = {v: sum(r["verdict"] == v for r in L.rows) for v in ("pass", "FAIL", "xfail", "xpass")}
    print("ladder (%s, %s contact): %d pass, %d FAIL, %d xfail, %d xpass, %d errors; %d runs, %.0f s" % (
        a.depth, a.contact, n["pass"], n["FAIL"], n["xfail"], n["xpass"], errors, L.nrun, wall))
    return 1 if (L.failed or L.xpassed or errors) else 0


if __name__ == "__main__":
    sys.exit(main())
