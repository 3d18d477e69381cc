#!/usr/bin/python3
"""rdassess — the assessment report of `rockdem assess` (docs/ASSESS.md): reads DIR/assess.json,
the matched records and the DEM runs the program wrote, and writes DIR/report.md with its
figures (300 dpi PNG: the design spectrum and the records' spectra, the records, the rocking and
sliding histories, the allowable PGA of every method) and DIR/report.pdf where pandoc is
installed (a note in the report where it is not).

    /usr/bin/python3 tools/rdassess.py DIR

The records' 5 % spectra are computed here independently of the C matcher (scipy.signal.lsim,
exact for the piecewise-linear record), so the figure checks the band the program reports.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

import numpy as np

G = 9.80665  # standard gravity: accelerations printed in g, as the program does
DPI = 300
# legends beside the axes, never over the data
OUTSIDE = dict(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)


def psa(t, acc, periods, zeta):
    """Pseudo-spectral acceleration w^2 max|u| of u'' + 2 zeta w u' + w^2 u = -acc (m/s^2)."""
    from scipy import signal
    out = np.empty(len(periods))
    for i, T in enumerate(periods):
        w = 2 * np.pi / T
        sys_ = signal.lti([-1.0], [1.0, 2 * zeta * w, w * w])
        _, u, _ = signal.lsim(sys_, acc, t, interp=True)
        out[i] = w * w * np.max(np.abs(u))
    return out


def read_record(path):
    """time (s) and acceleration (m/s^2) of a record the program wrote (a comment, a header)."""
    d = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
    return d[:, 0], d[:, 1]


def run_histories(path, body, h):
    """time, tilt (rad) and the base centre's horizontal slide on its pad (m) of `body`, whose
    base centre lies h (m) below its centre of mass at rest."""
    import h5py
    with h5py.File(path, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["body"][()]]
        k = names.index(body)
        t = f["time"][()]
        x = f["position"][:, k, :]
        q = f["quaternion"][:, k, :]
        tilt = f["tilt"][:, k]
    # base centre: the centre of mass plus the rest vector (0, 0, -h) turned by q q0^-1
    base = x + rotate(qmul(q, qconj(q[0])), np.array([0.0, 0.0, -h]))
    return t, tilt, np.hypot(base[:, 0] - base[0, 0], base[:, 1] - base[0, 1])


def qmul(a, b):
    w1, x1, y1, z1 = np.moveaxis(np.atleast_2d(a), -1, 0)
    w2, x2, y2, z2 = np.moveaxis(np.broadcast_to(b, np.atleast_2d(a).shape), -1, 0)
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2], -1)


def qconj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def rotate(q, v):
    u = q[:, 1:]
    w = q[:, :1]
    t = 2 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def fig_spectrum(a, d, plt):
    s, ev = a["spectrum"], a["evidence"]
    T, sa = np.array(s["T"]), np.array(s["sa"])
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.loglog(T, sa / G, "k-", lw=2, label="design spectrum, %.3g %%" % (100 * s["damping"]))
    ax.loglog(T, np.array(s["sa_rocking"]) / G, "k--", lw=1,
              label="at the rocking damping %.1f %%" % (100 * a["rocking"]["damping"]))
    meas = {}
    if ev:
        band = (T >= ev["tmin"]) & (T <= ev["tmax"])
        ax.loglog(T[band], ev["lo"] * sa[band] / G, "k:", lw=1, label="band %.2f-%.2f x target" % (ev["lo"], ev["hi"]))
        ax.loglog(T[band], ev["hi"] * sa[band] / G, "k:", lw=1)
        Tm = T[band][::3]
        spectra = []
        for k, r in enumerate(ev["records"]):
            t, acc = read_record(os.path.join(d, r["h"]))
            spectra.append(psa(t, acc, Tm, s["damping"]))
            ax.loglog(Tm, spectra[-1] / G, "-", lw=0.7, alpha=0.8, label="record %d" % (k + 1) if k < 5 else None)
        spectra = np.array(spectra)
        ratio = spectra / np.interp(Tm, T, sa)
        meas = {"min": float(ratio.min()), "max": float(ratio.max()),
                "mean_min": float(ratio.mean(0).min())}
        ax.loglog(Tm, spectra.mean(0) / G, "r-", lw=1.5, label="mean of the records")
    rk = a["rocking"]
    if rk["phi"] and rk["freq"]:
        ax.axvline(1 / rk["freq"], color="tab:blue", lw=0.8, ls="-.")
        ax.text(1 / rk["freq"], ax.get_ylim()[0] * 1.3, " A.2", color="tab:blue", fontsize=8)
    sl = a["sliding"]
    if sl["distance"] and sl["freq"]:
        ax.axvline(1 / sl["freq"], color="tab:green", lw=0.8, ls="-.")
        ax.text(1 / sl["freq"], ax.get_ylim()[0] * 2, " A.1", color="tab:green", fontsize=8)
    ax.set_xlabel("period T (s)")
    ax.set_ylabel("spectral acceleration Sa (g)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(**OUTSIDE)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig_spectrum.png"), dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return meas


def fig_records(a, d, plt):
    ev = a["evidence"]
    n = len(ev["records"])
    fig, axs = plt.subplots(n, 1, figsize=(6.5, 1.1 * n + 0.6), sharex=True)
    for k, (ax, r) in enumerate(zip(np.atleast_1d(axs), ev["records"])):
        t, acc = read_record(os.path.join(d, r["h"]))
        ax.plot(t, acc / G, "k-", lw=0.4)
        if r["v"]:
            tv, av = read_record(os.path.join(d, r["v"]))
            ax.plot(tv, av / G, "tab:orange", lw=0.3)
        ax.set_ylabel("%d (g)" % (k + 1), fontsize=8)
        ax.tick_params(labelsize=7)
    np.atleast_1d(axs)[-1].set_xlabel("time (s); black horizontal, orange vertical")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig_records.png"), dpi=DPI)
    plt.close(fig)


def fig_histories(a, d, plt):
    ev = a["evidence"]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 5), sharex=True)
    peaks = []
    for k, r in enumerate(ev["records"]):
        t, tilt, slide = run_histories(os.path.join(d, r["run"]), a["body"]["name"], a["body"]["h"])
        peaks.append((tilt.max(), slide.max()))
        ax1.plot(t, tilt, lw=0.6, label="record %d" % (k + 1))
        ax2.plot(t, 1e3 * slide, lw=0.6)
    limit = a["body"]["alpha"] / ev["sf_rock"]
    top = max(p[0] for p in peaks)
    if limit < 5 * top:  # the limit drawn only where it does not flatten the histories
        ax1.axhline(limit, color="k", ls=":", lw=0.8, label="alpha / %.0f" % ev["sf_rock"])
    ax1.set_ylabel("tilt (rad)\nlimit alpha / %.0f = %.3g rad" % (ev["sf_rock"], limit))
    ax1.legend(**OUTSIDE)
    ax2.set_ylabel("base slide on the pad (mm)")
    ax2.set_xlabel("time (s)")
    for ax in (ax1, ax2):
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig_histories.png"), dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return peaks


def allowable(a):
    rows = [("%s, rocking" % s["code"], s["pga_rock"]) for s in a["static"]]
    rows += [("%s, sliding" % s["code"], s["pga_slide"]) for s in a["static"]]
    rows += [("ASCE 43-05 A.2 rocking (SF 2.0)", a["rocking"]["pga_allow"]),
             ("ASCE 43-05 A.1 sliding (SF 2.0)", a["sliding"]["pga_allow"])]
    return rows


def fig_margins(a, d, plt):
    rows = allowable(a)
    fig, ax = plt.subplots(figsize=(6.5, 0.35 * len(rows) + 1.2))
    y = np.arange(len(rows))
    ax.barh(y, [r[1] / G for r in rows], color=["tab:blue" if "rocking" in r[0] else "tab:green" for r in rows])
    ax.axvline(a["pga"] / G, color="r", lw=1.2, label="design PGA %.3g g" % (a["pga"] / G))
    ax.set_yticks(y)
    ax.set_yticklabels([r[0] for r in rows], fontsize=7)
    ax.set_xlabel("allowable PGA (g)")
    ax.legend(**OUTSIDE)
    ax.grid(True, axis="x", lw=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "fig_margins.png"), dpi=DPI, bbox_inches="tight")
    plt.close(fig)


def ok(m):
    return "n/a" if m is None else ("pass" if m >= 1 else "**FAIL**")


def fmt(x, spec=".4g"):
    return "inf" if x is None else format(x, spec)


def markdown(a, meas, peaks, pdf_note):
    b, s, rk, sl, ev = a["body"], a["spectrum"], a["rocking"], a["sliding"], a["evidence"]
    L = []
    L.append("# Seismic assessment: %s\n" % (a["title"] or a["scene"]))
    L.append("Scene `%s`, body `%s` (%s), rockdem %s. Every number below comes from `assess.json`; "
             "the method and its sources are in the repository's docs/ASSESS.md.\n"
             % (a["scene"], b["name"], b["shape"], a["version"]))
    L.append("## Body and spectrum\n")
    L.append("| quantity | value |\n|---|---|")
    L.append("| half-width to the pivot b | %.4g m |" % b["b"])
    L.append("| centre-of-mass height h | %.4g m |" % b["h"])
    L.append("| mass; inertia about the pivot | %.4g kg; %.4g kg m^2 |" % (b["mass"], b["inertia"]))
    L.append("| critical angle alpha = atan(b/h) | %.4g rad (%.2f deg) |" % (b["alpha"], np.degrees(b["alpha"])))
    L.append("| Housner restitution r (seed 001 eq. 5) | %.4f |" % b["restitution"])
    mu_src = ("tan(%.3g deg), the pad joint's friction angle" % np.degrees(b["friction_angle"])
              if b["friction_angle"] is not None else "given (--mu)")
    L.append("| friction coefficient mu | %.4g (%s) |" % (b["mu"], mu_src))
    if s["kind"] == "en1998":
        L.append("| spectrum | EN 1998-1 type %d, ground %s, a_g = %.4g g, S = %g, T_B/T_C/T_D = %g/%g/%g s, 5 %% |"
                 % (s["type"], s["ground"], s["ag"] / G, s["S"], s["TB"], s["TC"], s["TD"]))
    else:
        L.append("| spectrum | table `%s`, %.3g %% damping |" % (s["file"], 100 * s["damping"]))
    L.append("| PGA (horizontal); vertical | %.4g g; %.4g x horizontal = %.4g g |" % (a["pga"] / G, a["kv"], a["av"] / G))
    L.append("| allowable sliding distance | %.4g m |\n" % a["slide_limit"])
    L.append("## Static checks (seed 001 Table 2), horizontal acceleration = PGA\n")
    L.append("| code | dead-load factor | upward a (g) | M_over (N m) | M_resist (N m) | rocking margin | "
             "mu required | sliding margin |\n|---|---|---|---|---|---|---|---|")
    for c in a["static"]:
        L.append("| %s | %g | %.4f | %.4g | %.4g | %s %s | %s | %s %s |" % (
            c["code"], c["dead"], c["a_up"] / G, c["m_over"], c["m_resist"], fmt(c["rock_margin"], ".3f"),
            ok(c["rock_margin"]), fmt(c["mu_required"]), fmt(c["slide_margin"], ".3f"), ok(c["slide_margin"])))
    L.append("\nMargin = resisting / overturning moment, and available / required friction coefficient.\n")
    L.append("## ASCE/SEI 43-05 Appendix A\n")
    L.append("| method | best estimate | safety factor | factored | limit | margin |\n|---|---|---|---|---|---|")
    L.append("| A.2 rocking (D = %.2f %%, f = %.3g Hz) | %.4g rad | %.1f | %.4g rad | alpha %.4g rad | %s %s |" % (
        100 * rk["damping"], rk["freq"] or 0, rk["phi"], rk["sf"], rk["sf"] * rk["phi"], b["alpha"],
        fmt(rk["margin"], ".3f"), ok(rk["margin"])))
    L.append("| A.1 sliding (mu_e = %.4g, f_e = %.3g Hz) | %.4g m | %.1f | %.4g m | %.4g m | %s %s |\n" % (
        sl["mu_e"], sl["freq"] or 0, sl["distance"], sl["sf"], sl["sf"] * sl["distance"], a["slide_limit"],
        fmt(sl["margin"], ".3f"), ok(sl["margin"])))
    L.append("## Allowable peak ground acceleration per method\n")
    L.append("The spectrum's shape scaled until each check reaches its limit (vertical %.4g x horizontal).\n" % a["kv"])
    L.append("| method | allowable PGA (g) | / design PGA |\n|---|---|---|")
    for name, p in allowable(a):
        L.append("| %s | %.4f | %.3f |" % (name, p / G, p / a["pga"]))
    en = [c for c in a["static"] if c["code"].startswith("EN")]
    if en:
        L.append("\nASCE 43-05 A.2 over the EN static rocking check: %.3f (seed 001 states 4.1 for its cask, "
                 "EN type 1 ground A, vertical 2/3).\n" % (rk["pga_allow"] / en[0]["pga_rock"]))
    L.append("![allowable PGA](fig_margins.png)\n")
    if ev:
        L.append("## Time-history evidence (DEM)\n")
        L.append("%d Kanai-Tajimi records (seed %d on), %g s at %g s, each matched to the design spectrum at "
                 "%.3g %% over %g-%g s until its ordinates at %d log-spaced periods lie within %.2f-%.2f x the target%s; the scene's "
                 "motion replaced by them, the body on its pad as the scene defines it.\n" % (
                     ev["n"], ev["seed"], ev["duration"], ev["dt"], 100 * s["damping"], ev["tmin"], ev["tmax"],
                     ev["nperiods"], ev["lo"], ev["hi"], ", with a vertical record matched to %.4g x it" % a["kv"] if a["kv"] else ""))
        if meas:
            L.append("Recomputed here (scipy, independent of the matcher) at every third curve period in the band: "
                     "Sa / target from %.3f to %.3f over all records; the mean of the records is at least %.3f "
                     "of the target (EN 1998-1 3.2.3.1.2 asks 0.90).\n" % (meas["min"], meas["max"], meas["mean_min"]))
        L.append("| record | PGA (g) | Sa/target (band) | peak tilt (rad) | peak slide (mm) | overturned |\n"
                 "|---|---|---|---|---|---|")
        for k, r in enumerate(ev["records"]):
            L.append("| %d | %.4g | %.3f-%.3f %s | %.4g | %.4g | %s |" % (
                k + 1, r["pga"] / G, r["ratio_min"], r["ratio_max"], "" if r["in_band"] else "**out of band**",
                r["tilt"], 1e3 * r["slide"], "yes" if r["overturned"] else "no"))
        L.append("| mean (sd) | | | %.4g (%.3g) | %.4g (%.3g) | |\n" % (
            ev["tilt_mean"], ev["tilt_sd"], 1e3 * ev["slide_mean"], 1e3 * ev["slide_sd"]))
        L.append("![spectra](fig_spectrum.png)\n\n![records](fig_records.png)\n\n![histories](fig_histories.png)\n")
    L.append("## Verdicts side by side\n")
    L.append("| method | rocking | sliding |\n|---|---|---|")
    for c in a["static"]:
        L.append("| %s (static) | %s | %s |" % (c["code"], ok(c["rock_margin"]), ok(c["slide_margin"])))
    L.append("| ASCE 43-05 A.2 / A.1 (SF 2.0) | %s | %s |" % (ok(rk["margin"]), ok(sl["margin"])))
    if ev:
        L.append("| DEM time histories, mean of %d | %s (SF %.1f x mean tilt vs alpha%s) | %s (SF %.1f x mean slide "
                 "vs limit) |" % (ev["n"], "pass" if ev["rock_ok"] else "**FAIL**", ev["sf_rock"],
                                  ", no overturn", "pass" if ev["slide_ok"] else "**FAIL**", ev["sf_slide"]))
    L.append("")
    L.append(pdf_note + "\n")
    return "\n".join(L)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", help="the folder `rockdem assess --out DIR` wrote")
    args = ap.parse_args(argv)
    path = os.path.join(args.dir, "assess.json")
    try:
        with open(path) as f:
            a = json.load(f)
    except (OSError, ValueError) as e:
        print("rdassess: %s: %s" % (path, e), file=sys.stderr)
        return 2
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    meas, peaks = {}, []
    fig_margins(a, args.dir, plt)
    if a["evidence"]:
        meas = fig_spectrum(a, args.dir, plt)
        fig_records(a, args.dir, plt)
        peaks = fig_histories(a, args.dir, plt)
    md = os.path.join(args.dir, "report.md")
    pandoc = shutil.which("pandoc")
    note = ("PDF: report.pdf (pandoc)." if pandoc else
            "PDF: not written: no pandoc on this machine (install pandoc and a PDF engine, then rerun).")
    with open(md, "w") as f:
        f.write(markdown(a, meas, peaks, note))
    if pandoc:
        p = subprocess.run([pandoc, md, "-o", os.path.join(args.dir, "report.pdf"),
                            "--resource-path", args.dir], capture_output=True, text=True)
        if p.returncode:
            with open(md, "a") as f:
                f.write("\nPDF: pandoc failed: %s\n" % p.stderr.strip().splitlines()[-1:])
    print("report: %s" % md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
