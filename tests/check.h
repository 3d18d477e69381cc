/* Tolerance checks that print what they measure, for the CMocka tests (include after cmocka.h).
 *
 * Every check prints one line "CHECK <what>: rockdem <got>, reference <want>, error <e>,
 * tol <tol>" so that a run shows the margin of each test, not only its verdict. A check whose
 * tolerance the DEM misses today is an expected failure (a documented gap): it is marked
 * RD_XFAIL, prints "XFAIL: <what> gap=<error> tol=<tol>" and does not fail the test; when its
 * gap closes it prints "XPASS: ..." and tests/run.sh counts the case as failed, so that the mark
 * is removed and the check becomes strict. Tolerances are never widened to pass: the caller
 * states where each one comes from in a comment beside it. */
#ifndef RD_TESTS_CHECK_H
#define RD_TESTS_CHECK_H

#include <math.h>
#include <stdbool.h>

enum { RD_STRICT = 0, RD_XFAIL = 1 };

/* One verdict: ok is whether the error met the tolerance; mode RD_STRICT or RD_XFAIL. */
static inline void rd_verdict(const char *what, bool ok, double err, double tol, int mode)
{
    if (mode == RD_XFAIL) {
        if (ok)
            print_message("XPASS: %s gap=%.4g tol=%.4g (remove RD_XFAIL: it is met now)\n", what,
                          err, tol);
        else
            print_message("XFAIL: %s gap=%.4g tol=%.4g\n", what, err, tol);
        return;
    }
    if (!ok) fail_msg("%s: error %.4g beyond tolerance %.4g", what, err, tol);
}

/* |got - want| / |want| <= tol. */
static inline void rd_check_rel(const char *what, double got, double want, double tol, int mode)
{
    double e = fabs(got - want) / fabs(want);
    print_message("CHECK %s: rockdem %.6g, reference %.6g, error %.3g, tol %.3g\n", what, got, want,
                  e, tol);
    rd_verdict(what, e <= tol, e, tol, mode);
}

/* |got - want| <= tol, in the quantity's own unit. */
static inline void rd_check_abs(const char *what, double got, double want, double tol, int mode)
{
    double e = fabs(got - want);
    print_message("CHECK %s: rockdem %.6g, reference %.6g, error %.3g, tol %.3g\n", what, got, want,
                  e, tol);
    rd_verdict(what, e <= tol, e, tol, mode);
}

#endif
