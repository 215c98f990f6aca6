#!/usr/bin/env bash
# README command (1): install, build, and run the main job; results go to out/.
# Forward and inverse kinematics of the Stewart-Gough robot (models/stewart_gough.urdf):
#  - FK at the default inputs (six rods of 0.45 m): out/fk.json, out/fk.png;
#  - IK to scene R5a of the shared scenes (platform at (0, 0, 0.4) m, rotated by R_y(10 deg), i.e.
#    quaternion (cos 5 deg, 0, sin 5 deg, 0)): out/ik.json, out/ik.png.
# The two short tables are printed; the spline demo (pcr demo) is kept as out/basis.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$root/build" "$root/out"
bash "$root/scripts/build.sh" "$root/build/release"
pcr="$root/build/release/robots/pcr"
model="$root/models/stewart_gough.urdf"
out="$root/out"
echo "== Forward kinematics: $model at the default inputs"
"$pcr" fk "$model" --png "$out/fk.png" --json-file "$out/fk.json"

echo
echo "== Inverse kinematics: scene R5a, platform at (0, 0, 0.4) m, orientation R_y(10 deg)"
"$pcr" ik "$model" --target platform=0,0,0.4,0.99619469809174555,0,0.087155742747658166,0 \
  --png "$out/ik.png" --json-file "$out/ik.json"

echo
echo "wrote $out/fk.json $out/fk.png $out/ik.json $out/ik.png"
"$pcr" demo --out "$out" > "$out/demo.txt"
echo "spline demo: $out/demo.txt, $out/basis.csv"
