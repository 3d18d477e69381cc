#!/usr/bin/python3
"""Compare two runs stored in rockdem's HDF5 layout (a rockdem run and a YADE run written by
tools/yade/translate.py, or two YADE runs at different steps).

    /usr/bin/python3 tools/yade/compare.py free    A.h5 B.h5 [--tol-time S] [--tol-amp REL]
    /usr/bin/python3 tools/yade/compare.py outcome A.h5 B.h5 [--tol-tilt REL] [--body NAME] [--fell-tilt RAD]
    /usr/bin/python3 tools/yade/compare.py slide   A.h5 B.h5 [--tol REL] [--body NAME]
    /usr/bin/python3 tools/yade/compare.py show    A.h5 [B.h5 ...]
    /usr/bin/python3 tools/yade/compare.py overturned A.h5 [--body NAME]   (prints 0 or 1)

free:    first impact time t1 (first sign change of the signed rocking angle, linear
         interpolation between samples) and the peak |tilt| between the first and second
         impacts (amplitude after one impact), both bodies' first free body. The amplitude's
         difference is relative to B (the reference run): (a - b) / b, which is unbounded, so a
         tolerance means what it says; without --tol-amp it is printed, not checked.
outcome: per free body, overturned (must agree) and, for bodies standing in both runs, max tilt
         (relative difference <= --tol-tilt, measured against max(max tilt) so that two tiny
         tilts do not fail on noise: an absolute floor of 1e-3 rad). --fell-tilt RAD judges
         "overturned" as max tilt >= RAD in both files instead of the stored flags (drum columns:
         rockdem's tilt-ratio flag needs a per-body alpha, which it gives as 0 for the bottom drum).
slide:   max slide (horizontal drift of the base centre), relative difference.
Prints one line per metric: `metric A B diff tol ok|FAIL`; exit 1 when any metric fails.
"""
import argparse
import sys

import numpy as np

try:
    import h5py
except ImportError:
    raise SystemExit("compare: needs h5py: run with /usr/bin/python3")


def s(v):
    if isinstance(v, (bytes, np.bytes_)):
        return v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        return s(v[()])
    return v


class RunFile:
    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as f:
            self.program = s(f.attrs.get("program", "?"))
            self.names = [s(n) for n in np.atleast_1d(f["bodies/names"][()])]
            self.time = f["time"][()]
            self.tilt = f["tilt"][()]
            self.quat = f["quaternion"][()]
            self.rot = f["rotation"][()] if "rotation" in f else None
            self.dt = float(f.attrs.get("dt", np.nan))
            self.summary = {k: (s(v) if not isinstance(v, np.ndarray) or v.dtype.kind in "SO" else v)
                            for k, v in f["summary"].attrs.items()} if "summary" in f else {}

    def body(self, name):
        if name is None:
            return 0
        if name not in self.names:
            raise SystemExit("compare: %s has no body '%s' (bodies: %s)" % (self.path, name, ", ".join(self.names)))
        return self.names.index(name)

    def sumval(self, key, k):
        v = np.atleast_1d(self.summary.get(key, [np.nan] * len(self.names)))
        return float(v[k])

    def signed_rocking(self, k):
        if self.rot is not None:  # in-plane rocking (both codes write it)
            return self.rot[:, k, 0]
        q = self.quat[:, k, :]
        w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
        zx, zy = 2 * (x * z + w * y), 2 * (y * z - w * x)
        hor = np.hypot(zx, zy)
        i = int(np.argmax(hor > 1e-3 * max(hor.max(), 1e-30)))
        ax = np.array([zx[i], zy[i]]) / max(hor[i], 1e-300)
        return np.sign(zx * ax[0] + zy * ax[1]) * self.tilt[:, k]

    def impacts(self, k):
        r, t = self.signed_rocking(k), self.time
        out = []
        for i in range(1, len(r)):
            if r[i - 1] * r[i] < 0:
                f = r[i - 1] / (r[i - 1] - r[i])
                out.append((t[i - 1] + f * (t[i] - t[i - 1]), i))
        return out


def line(metric, a, b, diff, tol, ok):
    print("%-34s %12.6g %12.6g  diff %10.4g  tol %8.3g  %s" % (metric, a, b, diff, tol, "ok" if ok else "FAIL"))
    return ok


def free(A, B, args):
    ka, kb = A.body(args.body), B.body(args.body)
    ok = True
    ia, ib = A.impacts(ka), B.impacts(kb)
    if not ia or not ib:
        print("free: no impact in %s" % (A.path if not ia else B.path))
        return False
    ta, tb = ia[0][0], ib[0][0]
    ok &= line("first impact time (s)", ta, tb, tb - ta, args.tol_time, abs(tb - ta) <= args.tol_time)

    def amp(R, k, imp):
        i0 = imp[0][1]
        i1 = imp[1][1] if len(imp) > 1 else len(R.time)
        return float(np.max(R.tilt[i0:i1, k])), float(R.tilt[0, k])
    aa, a0 = amp(A, ka, ia)
    bb, b0 = amp(B, kb, ib)
    d = (aa - bb) / bb
    if args.tol_amp is None:
        print("%-34s %12.6g %12.6g  diff %10.4g  (not checked)" % ("amplitude after 1st impact (rad)", aa, bb, d))
    else:
        ok &= line("amplitude after 1st impact (rad)", aa, bb, d, args.tol_amp, abs(d) <= args.tol_amp)
    print("%-34s %12.6g %12.6g" % ("  ratio to release tilt", aa / a0, bb / b0))
    print("%-34s %12d %12d" % ("  impacts in window", len(ia), len(ib)))
    return ok


def outcome(A, B, args):
    ok = True
    names = [args.body] if args.body else A.names
    for n in names:
        ka, kb = A.body(n), B.body(n)
        ma, mb = A.sumval("max_tilt", ka), B.sumval("max_tilt", kb)
        if args.fell_tilt is not None:
            oa, ob = int(ma >= args.fell_tilt), int(mb >= args.fell_tilt)
        else:
            oa, ob = int(A.sumval("overturned", ka)), int(B.sumval("overturned", kb))
        ok &= line("%s overturned" % n, oa, ob, ob - oa, 0, oa == ob)
        if not oa and not ob:
            ref = max(ma, mb, 1e-3)
            ok &= line("%s max tilt (rad)" % n, ma, mb, (mb - ma) / ref, args.tol_tilt,
                       abs(mb - ma) / ref <= args.tol_tilt)
        else:
            print("%-34s %12.6g %12.6g  (overturned: not compared)" % ("%s max tilt (rad)" % n, ma, mb))
    return ok


def slide(A, B, args):
    ka, kb = A.body(args.body), B.body(args.body)
    sa, sb = A.sumval("max_slide", ka), B.sumval("max_slide", kb)
    ref = max(sa, sb, 1e-9)
    return line("max slide (m)", sa, sb, (sb - sa) / ref, args.tol, abs(sb - sa) / ref <= args.tol)


def show(paths):
    for p in paths:
        R = RunFile(p)
        print("%s: program %s, dt %g, %d samples to t = %g s, status %s" % (
            p, R.program, R.dt, len(R.time), R.time[-1], R.summary.get("status", "?")))
        for k, n in enumerate(R.names):
            imp = R.impacts(k)
            print("  %-10s overturned %d  max_tilt %.5g rad  ratio %.4g  max_slide %.4g m  first impact %s" % (
                n, int(R.sumval("overturned", k)), R.sumval("max_tilt", k), R.sumval("max_tilt_ratio", k),
                R.sumval("max_slide", k), ("%.5f s" % imp[0][0]) if imp else "-"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=["free", "outcome", "slide", "show", "overturned"])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--body")
    ap.add_argument("--tol-time", type=float, default=0.01)
    ap.add_argument("--tol-amp", type=float)
    ap.add_argument("--tol-tilt", type=float, default=0.25)
    ap.add_argument("--tol", type=float, default=0.1)
    ap.add_argument("--fell-tilt", type=float)
    a = ap.parse_args(argv)
    if a.mode == "show":
        show(a.files)
        return 0
    if a.mode == "overturned":
        R = RunFile(a.files[0])
        print(int(R.sumval("overturned", R.body(a.body))))
        return 0
    if len(a.files) != 2:
        raise SystemExit("compare: %s needs two files" % a.mode)
    A, B = RunFile(a.files[0]), RunFile(a.files[1])
    print("A = %s (%s, dt %g)   B = %s (%s, dt %g)" % (A.path, A.program, A.dt, B.path, B.program, B.dt))
    ok = {"free": free, "outcome": outcome, "slide": slide}[a.mode](A, B, a)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
