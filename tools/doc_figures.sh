#!/usr/bin/env bash
# Remake the figures of docs/ (TOOLS.md, FRAGILITY.md, ASSESS.md, the README's gallery) from real
# rockdem runs and the stored tables (docs/pbr_sweep.h5 for the PBR fragility, docs/study.md for
# the study). `make docs` runs it; tests/cli/docs_current.sh runs it into a scratch folder and
# compares each figure with the committed one.
#   bash tools/doc_figures.sh [path/to/rockdem] [workdir]
# Environment: FIGS (the figures to draw, default all: rdplot fragility pbr gallery study
# assess), FIG_OUT (where they go, default docs).
set -eu
BIN=${1:-bin/rockdem}; W=${2:-$(mktemp -d)}
PY=/usr/bin/python3
FIGS=${FIGS:-rdplot fragility pbr gallery study assess}
O=${FIG_OUT:-docs}
want() { case " $FIGS " in *" $1 "*) return 0 ;; esac; return 1; }
mkdir -p "$W/sweep" "$O"
# 1. one run that overturns: the default cask, 1.1 g one-sine at 0.7 Hz
if want rdplot; then
    "$BIN" run scenarios/default.dat --set motion.amplitude=1.1g --set motion.frequency=0.7 -q -o "$W/over.h5"
    $PY tools/rdplot.py "$W/over.h5" -o "$O/rdplot_example.png"
fi
# 2. an 8 x 8 sweep of one-sine pulses (amplitude x frequency, PGV/PGA = 1/(pi f)); the
#    runs go on after overturning ('stop off') so every run sees the whole pulse
if want fragility; then
    sed 's/^model overturn tilt-ratio 1.0$/model overturn tilt-ratio 1.0 stop off/' scenarios/default.dat > "$W/sweep.dat"
    for a in 0.5 0.8 1.1 1.4 1.7 2.0 2.5 3.0; do for f in 0.25 0.35 0.5 0.7 1.0 1.4 2.0 2.8; do
        echo "$a $f"; done; done |
        xargs -P "$(nproc)" -n 2 sh -c '"$0" run "$1" --set motion.amplitude=${3}g --set motion.frequency=$4 \
            --set model.duration=8 -q -o "$2/a${3}_f$4.h5" >/dev/null' "$BIN" "$W/sweep.dat" "$W/sweep"
    $PY tools/rdtable.py "$W"/sweep/*.h5 --csv "$W/sweep.csv" -q
    $PY tools/rdfragility.py "$W/sweep.csv" --outcome ever_overturned -o "$O/rdfragility_example.png"
fi
# 3. the PBR fragility from its stored sweep table (docs/FRAGILITY.md: "Worked example"; the
#    table itself is rerun by tools/docgen.py, block fragility-pbr)
if want pbr; then
    $PY tools/rdfragility.py docs/pbr_sweep.h5 --where direction=0 --bins 2 -o "$O/pbr_fragility.png"
fi
# 4. the README's gallery: each shipped scene family at rest (settled, first sample)
if want gallery; then
    mkdir -p "$O/gallery"
    for sc in default pbr column statue seed001_cask seed000_topple; do
        "$BIN" run "scenarios/$sc.dat" --set model.duration=0.01 -q -o "$W/$sc.h5" >/dev/null
        $PY tools/rdscene.py "$W/$sc.h5" -o "$O/gallery/$sc.png" >/dev/null
    done
fi
# 5. the study figure from its table (make study reruns the 72 DEM runs)
if want study; then
    $PY tools/study.py --replot docs/study.md --png "$O/study.png"
fi
# 6. docs/ASSESS.md: the shipped cask assessed under EN 1998 type 1, ground A, a_g = 0.6 g
if want assess; then
    "$BIN" assess scenarios/cask.dat --ag 0.6g --out "$W/assess" -q > "$W/assess.txt"
    $PY tools/rdassess.py "$W/assess"
    for f in spectrum histories margins; do cp "$W/assess/fig_$f.png" "$O/assess_$f.png"; done
fi
