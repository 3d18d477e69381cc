#!/usr/bin/env bash
# The drum-column benchmark scene: N drums (0.8 m across, 0.6 m tall, 16 sides, subcontact
# spacing 0.2 m) on a fixed base under a gentle 2 Hz harmonic (every joint loaded), fixed step
# 2e-5 s so every column does the same number of steps. Used by bench/columns.sh and
# bench/kernel.sh.
#   bash bench/column_scene.sh N DURATION_S OUT.h5 > column.dat
set -eu
[ $# -eq 3 ] || { echo "usage: bash bench/column_scene.sh N DURATION_S OUT.h5" >&2; exit 2; }
case $1 in ''|*[!0-9]*) echo "column_scene: N must be a positive integer, got '$1'" >&2; exit 2 ;; esac
cat <<DAT
block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base
block create column drums $1 diameter 0.8 height 0.6 sides 16 seat-on base name c
contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing 0.2
model timestep fixed 2e-5
model settle off
ground-motion pulse harmonic amplitude 0.02g frequency 2 cycles 1
model solve time $2
output hdf5 '$3' interval 0.05
DAT
