# Runs SCENE (small: a coarse glass wall) on 2 ranks and on one into OUT, then reads both runs'
# frames with VTK (pvtu_in_vtk.py). usage: pvtu_in_vtk.sh MPIEXEC FISSURE SCENE OUT
set -eu
mpiexec=$1 fissure=$2 scene=$3 out=$4
keys="--set bodies.0.resolution=0.1 --set output.surface=false --set time.end=0.001 --set output.every=0.0002"
rm -rf "$out"
"$mpiexec" -np 2 --oversubscribe "$fissure" run "$scene" --out "$out/spread" $keys >/dev/null
"$fissure" run "$scene" --out "$out/one" $keys >/dev/null
/usr/bin/python3 "$(dirname "$0")/pvtu_in_vtk.py" "$out/spread" "$out/one"
