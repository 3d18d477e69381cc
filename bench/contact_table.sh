#!/usr/bin/env bash
# How the contact's layout, KS/KN and impact restitution change free rocking (docs/CONTACT.md):
# the 0.5 x 0.5 x 1.0 m block released from half its tipping angle about its +x edge, KN 1e10
# Pa/m, friction 40 deg. For each setting: the block restitution r by amplitude decay (rockdem
# restitution), the largest hop of the whole base (lowest vertex above the ground) and the slide
# of its footprint from its upright place once at rest (tools/rocking_hop.py).
# Usage: bash bench/contact_table.sh [bin/rockdem]   (about a minute; docs/CONTACT.md's table is
# this output, written by tools/docgen.py). LAYOUTS, RATIOS, ES: the rows to run (default all).
set -eu
BIN=$(realpath "${1:-bin/rockdem}")
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
cat > "$T/free.dat" <<'DAT'
block create brick size 2 2 0.4 position 0 0 -0.2 fixed name floor
block create brick size 0.5 0.5 1.0 position 0 0 0.5 name block
block initial name block tilt 13.2825 direction 0
contact property stiffness-normal 1e10 friction 40
model solve time 5
output hdf5 'free.h5' interval 0.001
DAT
echo "| layout | KS/KN | restitution e | r (Housner 0.700) | hop (mm) | slide (mm) |"
echo "|---|---|---|---|---|---|"
for layout in ${LAYOUTS:-vertices auto}; do
  for ratio in ${RATIOS:-0.1 1 10}; do
    for e in ${ES:-0 1}; do
      ks=$(/usr/bin/python3 -c "print(1e10 * $ratio)")
      set=(--set contact.spacing=$layout --set contact.stiffness-shear=$ks --set contact.restitution=$e)
      r=$("$BIN" restitution "$T/free.dat" "${set[@]}" --target 0.7 2>/dev/null | awk '/^1e\+10/ {print $'$([ "$e" = 0 ] && echo 2 || echo 10)'}')
      (cd "$T" && "$BIN" run free.dat "${set[@]}" -q > /dev/null 2>&1) || true
      hs=$(/usr/bin/python3 tools/rocking_hop.py "$T/free.h5")
      echo "| $([ $layout = vertices ] && echo corners || echo '11x11 bed') | $ratio | $e | $r | $hs |"
    done
  done
done
