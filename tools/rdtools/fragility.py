"""Fragility of overturning from binary outcomes (overturned or not) against ground-motion
intensity measures. Fits: statsmodels GLMs (binomial family, logit and probit links, with their
standard errors); bootstrap: scipy.stats.bootstrap; Firth's correction (hand-written: statsmodels
has none) only where the outcomes are separated.

1. Binned logistic regression, seed 002 eq. (3):
       P(overturning | x1 = PGA, x2 = PGV/PGA) = 1 / (1 + exp(-(b0 + b1 x1)))
   The data are binned on x2 = PGV/PGA and the regression is done on x1 = PGA within each bin;
   each bin's fragility is placed at the median PGV/PGA of the bin. form='linear' is the seed's
   exact form (x1 = PGA); form='log' uses x1 = ln PGA (the usual lognormal-like variant).
2. A 2-D logistic surface over (PGA, PGV/PGA):
       logit P = c0 + c1 ln PGA + c2 ln(PGV/PGA)
   with its 10/50/95 % contours PGA_p(T) = exp((logit p - c0 - c2 ln T) / c1).
3. A lognormal fragility in PGA, P = Phi(ln(PGA/theta) / beta): a probit GLM on ln PGA fitted to
   the individual binary outcomes. Confidence: the GLM's covariance (inverse Fisher information),
   the delta method for theta and beta, and a pointwise 95 % band Phi(z +- 1.96 sd(z)) with
   z = (ln x - ln theta)/beta; optionally scipy.stats.bootstrap (paired resampling of the rows,
   percentile intervals) gives bands instead.
4. Classification metrics, seed 002 Table 4: accuracy, precision, recall, F1.

When the outcomes are (quasi-)completely separated — common for deterministic pulse sweeps,
where a bin flips from 0 to 1 at one PGA — the ML estimate does not exist (coefficients run to
infinity). Separation is detected exactly with the linear program of Konis (2007); method='auto'
then uses Firth's bias-reduced penalised likelihood (Firth 1993), which always has a finite
estimate, and says so in the result ('firth').

Degenerate input (a constant PGA or PGV/PGA, fewer than two runs) raises DegenerateInput with a
sentence saying what cannot be fitted and why, instead of returning nan standard errors."""
import math

import warnings

import numpy as np
from scipy import optimize, special, stats

try:
    import statsmodels.api as sm
    from statsmodels.tools.sm_exceptions import PerfectSeparationError
except ImportError:  # Debian python3-statsmodels (tools/install-deps.sh)
    raise SystemExit("rdtools: needs statsmodels: run with /usr/bin/python3 (Debian python3-statsmodels)")

LEVELS = (0.10, 0.50, 0.95)


class DegenerateInput(ValueError):
    """The data cannot support the requested fit (the message says why)."""


def check_varies(name, values, what):
    """DegenerateInput unless `values` take at least two distinct finite values."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if len(v) < 2:
        raise DegenerateInput("%s: fewer than two runs with a finite %s" % (what, name))
    if np.ptp(v) <= 1e-12 * max(np.abs(v).max(), 1e-300):
        raise DegenerateInput("%s: %s is the same (%.4g) in every run, so its effect cannot be "
                              "estimated; vary it (other records, scales or directions) or fit "
                              "without it" % (what, name, v[0]))


def _link(name):
    """statsmodels link instance: Logit()/Probit() (>= 0.14) or logit()/probit() (0.13)."""
    L = sm.families.links
    return (getattr(L, name.capitalize(), None) or getattr(L, name))()


def _glm(X, y, link):
    """statsmodels binomial GLM; (params, cov) or None when it does not converge."""
    fam = sm.families.Binomial(link=link)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            r = sm.GLM(y, X, family=fam).fit()
        except (PerfectSeparationError, np.linalg.LinAlgError, ValueError):
            return None
    if not getattr(r, "converged", True):
        return None
    return np.asarray(r.params), np.asarray(r.cov_params()), float(r.llf)


# ---------------------------------------------------------------- logistic regression
def is_separated(X, y):
    """True if the binary outcomes y are completely or quasi-completely separated by a linear
    function of the columns of X (then no finite ML estimate exists). Konis' LP: maximise
    sum_i s_i x_i.b subject to s_i x_i.b >= 0, |b_j| <= 1, s_i = 2 y_i - 1; separated iff the
    optimum is positive."""
    X = np.asarray(X, float)
    s = 2.0 * np.asarray(y, float) - 1.0
    A = s[:, None] * X
    if A.shape[0] == 0:
        return True
    scale = np.maximum(np.abs(X).max(axis=0), 1e-300)  # column scaling keeps the LP well posed
    As = A / scale
    res = optimize.linprog(-As.sum(axis=0), A_ub=-As, b_ub=np.zeros(len(As)),
                           bounds=[(-1, 1)] * X.shape[1], method="highs")
    if res.status != 0:
        return False
    return -res.fun > 1e-7 * len(As)


def _irls(X, y, firth, maxit=200, tol=1e-10):
    n, k = X.shape
    b = np.zeros(k)

    def objective(b):
        eta = X @ b
        ll = float(np.sum(y * eta - np.logaddexp(0.0, eta)))
        if firth:
            p = special.expit(eta)
            w = p * (1 - p)
            sign, logdet = np.linalg.slogdet(X.T @ (w[:, None] * X))
            ll += 0.5 * logdet if sign > 0 else -np.inf
        return ll

    ll = objective(b)
    converged = False
    for it in range(maxit):
        eta = X @ b
        p = special.expit(eta)
        w = np.maximum(p * (1 - p), 1e-300)
        info = X.T @ (w[:, None] * X)
        resid = y - p
        if firth:  # Firth's modified score: X'(y - p + h (1/2 - p)), h = hat-matrix diagonal
            try:
                Iinv = np.linalg.inv(info)
            except np.linalg.LinAlgError:
                break
            h = w * np.einsum("ij,jk,ik->i", X, Iinv, X)
            resid = resid + h * (0.5 - p)
        score = X.T @ resid
        try:
            step = np.linalg.solve(info, score)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while True:  # step halving keeps the (penalised) likelihood increasing
            nb = b + t * step
            nll = objective(nb)
            if nll >= ll - 1e-12 * abs(ll) or t < 1e-8:
                break
            t *= 0.5
        b, ll_old, ll = nb, ll, nll
        if np.max(np.abs(t * step)) < tol * (1 + np.max(np.abs(b))) or abs(ll - ll_old) < 1e-14 * (1 + abs(ll)):
            converged = True
            break
    p = special.expit(X @ b)
    w = p * (1 - p)
    info = X.T @ (w[:, None] * X)
    try:
        cov = np.linalg.inv(info)
    except np.linalg.LinAlgError:
        cov = np.full((k, k), np.nan)
    return b, cov, converged, ll, it + 1


def logistic_fit(X, y, method="auto"):
    """Logistic regression of binary y on design X (include a column of ones for the intercept).
    method: 'ml' (statsmodels GLM, binomial family, logit link), 'firth', or 'auto' (ML unless
    the data are separated, then Firth). Returns dict: beta, se, cov (inverse Fisher information
    at the estimate), method, separated, converged, loglik, n, iterations."""
    X = np.asarray(X, float)
    y = np.asarray(y, float)
    if X.ndim != 2 or len(X) != len(y):
        raise ValueError("X must be [n, k] and y [n]")
    sep = is_separated(X, y)
    use_firth = method == "firth" or (method == "auto" and sep)
    if not use_firth:
        g = _glm(X, y, _link("logit"))
        if g is not None:
            b, cov, ll = g
            return dict(beta=b, cov=cov, se=np.sqrt(np.abs(np.diag(cov))), method="ml",
                        separated=bool(sep), converged=True, loglik=ll, n=int(len(y)),
                        iterations=0)
    b, cov, conv, ll, it = _irls(X, y, use_firth)
    return dict(beta=b, cov=cov, se=np.sqrt(np.abs(np.diag(cov))),
                method="firth" if use_firth else "ml", separated=bool(sep), converged=bool(conv),
                loglik=ll, n=int(len(y)), iterations=it)


def logit(p):
    return math.log(p / (1 - p))


# ---------------------------------------------------------------- binned fits (seed 002)
def bin_edges(T, nbins=None, edges=None):
    """PGV/PGA bin edges: given, or nbins quantile bins (equal counts) spanning the data."""
    T = np.asarray(T, float)
    if edges is not None:
        e = np.asarray(sorted(edges), float)
        if len(e) < 2:
            raise ValueError("need at least two bin edges")
        return e
    nbins = max(1, int(nbins or 1))
    e = np.quantile(T, np.linspace(0, 1, nbins + 1))
    e = np.unique(e)
    if len(e) < 2:
        e = np.array([T.min(), T.max()])
    return e


def binned_fits(pga, pgv, y, nbins=4, edges=None, form="linear", method="auto", levels=LEVELS):
    """Seed 002: bin on T = PGV/PGA, fit P = expit(b0 + b1 x1) in each bin (x1 = PGA, or ln PGA
    for form='log'), place it at the bin's median T. Returns a list of dicts (one per bin)."""
    pga, pgv, y = (np.asarray(a, float) for a in (pga, pgv, y))
    T = pgv / pga
    e = bin_edges(T, nbins, edges)
    out = []
    for i in range(len(e) - 1):
        last = i == len(e) - 2
        m = (T >= e[i]) & ((T <= e[i + 1]) if last else (T < e[i + 1]))
        d = dict(lo=float(e[i]), hi=float(e[i + 1]), n=int(m.sum()), n_over=int(y[m].sum()),
                 T_median=float(np.median(T[m])) if m.any() else float("nan"), form=form)
        d["pga_at"] = {p: float("nan") for p in levels}
        if d["n"] < 2 or d["n_over"] in (0, d["n"]):
            d["note"] = ("empty bin" if d["n"] == 0 else "fewer than 2 runs" if d["n"] < 2 else
                         "all overturned" if d["n_over"] == d["n"] else "none overturned")
            out.append(d)
            continue
        x1 = np.log(pga[m]) if form == "log" else pga[m]
        if np.ptp(x1) == 0:
            d["note"] = "a single PGA value"
            out.append(d)
            continue
        X = np.column_stack([np.ones(m.sum()), x1])
        f = logistic_fit(X, y[m], method)
        b0, b1 = f["beta"]
        d.update(b0=float(b0), b1=float(b1), se_b0=float(f["se"][0]), se_b1=float(f["se"][1]),
                 method=f["method"], separated=f["separated"], converged=f["converged"],
                 cov=[[float(v) for v in row] for row in f["cov"]])
        if b1 > 0:
            for p in levels:
                x = (logit(p) - b0) / b1
                d["pga_at"][p] = float(math.exp(x)) if form == "log" else (float(x) if x > 0 else float("nan"))
        else:
            d["note"] = "slope <= 0 (no increasing fragility)"
        out.append(d)
    return out


def binned_prob(d, pga):
    """P from one bin's fit at PGA values."""
    x1 = np.log(pga) if d["form"] == "log" else np.asarray(pga, float)
    return special.expit(d["b0"] + d["b1"] * x1)


# ---------------------------------------------------------------- 2-D logistic surface
def surface_fit(pga, pgv, y, method="auto"):
    """logit P = c0 + c1 ln PGA + c2 ln(PGV/PGA)."""
    pga, pgv, y = (np.asarray(a, float) for a in (pga, pgv, y))
    check_varies("PGA", pga, "2-D surface")
    check_varies("PGV/PGA", pgv / pga, "2-D surface")
    X = np.column_stack([np.ones(len(y)), np.log(pga), np.log(pgv / pga)])
    return logistic_fit(X, y, method)


def surface_prob(fit, pga, T):
    c0, c1, c2 = fit["beta"]
    return special.expit(c0 + c1 * np.log(pga) + c2 * np.log(T))


def surface_contour(fit, p, T):
    """PGA at probability p along PGV/PGA = T (nan if c1 <= 0)."""
    c0, c1, c2 = fit["beta"]
    if c1 <= 0:
        return np.full(np.shape(T), np.nan)
    return np.exp((logit(p) - c0 - c2 * np.log(T)) / c1)


# ---------------------------------------------------------------- lognormal fragility
def _probit_ml(lx, y):
    """P = Phi(a + b lx): statsmodels binomial GLM with the probit link. Returns (a, b), the
    covariance of (a, b) and the log-likelihood, or None when the fit does not converge."""
    X = np.column_stack([np.ones(len(lx)), lx])
    return _glm(X, y, _link("probit"))


def lognormal_fit(x, y, bootstrap=0, seed=1):
    """Lognormal fragility P(x) = Phi(ln(x/theta)/beta) by maximum likelihood on binary y.
    Returns dict: theta (median), beta, se_theta, se_beta, se_ln_theta, cov_ab (of a = -ln theta /
    beta, b = 1/beta; inverse expected Fisher information), loglik, n, separated, band(xs) ->
    (lo, hi) pointwise 95 %, band_method ('fisher' or 'bootstrap N')."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    check_varies("PGA", x, "lognormal fit")
    lx = np.log(x)
    X = np.column_stack([np.ones(len(lx)), lx])
    res = dict(n=int(len(y)), n_over=int(y.sum()))
    if y.sum() in (0, len(y)) or is_separated(X, y):
        # no finite MLE: beta -> 0 (a step) or nothing to fit
        lo = x[y == 0].max() if (y == 0).any() else 0.0
        hi = x[y == 1].min() if (y == 1).any() else np.inf
        if 0 < y.sum() < len(y):  # a finite curve all the same: Firth's logistic in ln PGA
            res["firth"] = logistic_fit(X, y, "firth")
        res.update(separated=True, theta=float("nan"), beta=float("nan"),
                   theta_range=(float(lo), float(hi)),
                   note="outcomes separated by PGA: no finite ML estimate (beta -> 0); the "
                        "median lies between the largest PGA without and the smallest with "
                        "overturning")
        return res
    g = _probit_ml(lx, y)
    if g is None:
        raise DegenerateInput("lognormal fit: the probit GLM did not converge on %d runs" % len(y))
    b, cov, ll = g
    a_, b_ = b
    theta, beta = math.exp(-a_ / b_), 1.0 / b_
    # delta method: ln theta = -a/b, beta = 1/b
    J = np.array([[-1.0 / b_, a_ / b_ ** 2], [0.0, -1.0 / b_ ** 2]])
    C = J @ cov @ J.T
    se_lnth, se_beta = math.sqrt(C[0, 0]), math.sqrt(C[1, 1])
    res.update(separated=False, theta=theta, beta=beta, se_ln_theta=se_lnth,
               se_theta=theta * se_lnth, se_beta=se_beta, cov_ab=cov, loglik=ll,
               theta_ci=(theta * math.exp(-1.96 * se_lnth), theta * math.exp(1.96 * se_lnth)),
               beta_ci=(beta - 1.96 * se_beta, beta + 1.96 * se_beta), band_method="fisher")

    def band_fisher(xs):
        L = np.log(np.asarray(xs, float))
        z = a_ + b_ * L
        sd = np.sqrt(cov[0, 0] + 2 * L * cov[0, 1] + L * L * cov[1, 1])
        return special.ndtr(z - 1.96 * sd), special.ndtr(z + 1.96 * sd)

    res["band"] = band_fisher
    if bootstrap and bootstrap > 0:
        _bootstrap_band(res, x, y, int(bootstrap), seed)
    return res


BAND_GRID = 60  # points of the bootstrap band in PGA (log-spaced over the data)


def _bootstrap_band(res, x, y, n, seed):
    """scipy.stats.bootstrap over paired (x, y) rows: percentile intervals of theta, beta and of
    P on a grid of x; a resample without a finite MLE (separated) gives nan and is left out."""
    grid = np.geomspace(x.min(), x.max(), BAND_GRID)
    Lg = np.log(grid)

    def stat(xs, ys):
        lx = np.log(xs)
        if ys.sum() in (0, len(ys)) or is_separated(np.column_stack([np.ones(len(lx)), lx]), ys):
            return np.full(2 + BAND_GRID, np.nan)
        g = _probit_ml(lx, ys)
        if g is None:
            return np.full(2 + BAND_GRID, np.nan)
        a_, b_ = g[0]
        return np.concatenate([[math.exp(-a_ / b_), 1.0 / b_], special.ndtr(a_ + b_ * Lg)])

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bs = stats.bootstrap((x, y), stat, paired=True, vectorized=False, n_resamples=n,
                             method="percentile", random_state=np.random.default_rng(seed))
    dist = bs.bootstrap_distribution  # [2 + BAND_GRID, n]
    ok = np.all(np.isfinite(dist), axis=0)
    res["bootstrap_used"], res["bootstrap_requested"] = int(ok.sum()), n
    if ok.sum() < 20:
        return
    d = dist[:, ok]
    res["theta_ci"] = tuple(float(v) for v in np.percentile(d[0], [2.5, 97.5]))
    res["beta_ci"] = tuple(float(v) for v in np.percentile(d[1], [2.5, 97.5]))
    res["band_method"] = "bootstrap %d" % ok.sum()
    lo, hi = np.percentile(d[2:], 2.5, axis=1), np.percentile(d[2:], 97.5, axis=1)

    def band_boot(xs):
        L = np.log(np.asarray(xs, float))
        return np.interp(L, Lg, lo), np.interp(L, Lg, hi)

    res["band"] = band_boot


def lognormal_prob(theta, beta, x):
    return special.ndtr(np.log(np.asarray(x, float) / theta) / beta)


# ---------------------------------------------------------------- metrics (seed 002 Table 4)
def confusion(predicted, observed):
    """(TP, TN, FP, FN) with 'positive' = overturned; predicted = the model's outcome (e.g. the
    simulation), observed = the ground truth (e.g. the shake-table experiment)."""
    p = np.asarray(predicted).astype(bool)
    o = np.asarray(observed).astype(bool)
    if p.shape != o.shape:
        raise ValueError("predicted and observed differ in length")
    return (int(np.sum(p & o)), int(np.sum(~p & ~o)), int(np.sum(p & ~o)), int(np.sum(~p & o)))


def metrics(tp, tn, fp, fn):
    """Seed 002 Table 4: accuracy = (TP+TN)/total, precision = TP/(TP+FP), recall = TP/(TP+FN),
    F1 = 2 precision recall / (precision + recall). nan where a denominator is 0."""
    total = tp + tn + fp + fn
    acc = (tp + tn) / total if total else float("nan")
    prec = tp / (tp + fp) if tp + fp else float("nan")
    rec = tp / (tp + fn) if tp + fn else float("nan")
    f1 = 2 * prec * rec / (prec + rec) if (tp + fp and tp + fn and prec + rec > 0) else float("nan")
    return dict(TP=tp, TN=tn, FP=fp, FN=fn, accuracy=acc, precision=prec, recall=rec, F1=f1)
