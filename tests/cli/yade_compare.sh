#!/usr/bin/env bash
# rockdem vs the stored YADE runs (tests/data/yade/*.h5 at YADE's dt, tests/data/yade/half/*.h5
# at dt/2; made by tools/yade/regen.py, `make check-yade`; no YADE needed here). The cases are
# the YADE and column groups of the validation ladder (tools/validate/ladder.py, the fast depth:
# free rocking, the overturning bracket, the stack at 0.3 and 1.0 g, the slide, the column at
# 1.6 g); `make validate` runs all amplitudes. Tolerances: the change of each code's answer at
# dt/2 (both codes), plus closed-form allowances named per row; the overturning bracket is run
# with rockdem's shear stiffness matched to YADE's per-face law (docs/YADE.md, "contact law").
# A missing stored file is a failure, not a skip. Known gaps print "XFAIL: ... gap=".
set -u
exec /usr/bin/python3 tools/validate/ladder.py --depth fast --only yade,column --bin "${RD_BIN:-bin/rockdem}"
