#!/usr/bin/env bash
# Writes an ASCII STL of a hopper's cone: a frustum from an open outlet up to an open top, axis
# +z, metres, SEGMENTS sectors of two triangles each. cases/large_heap/hopper.stl was made by
# the second line below (its bin above the cone is a cylinder wall in the case).
#
#   bash scripts/make-hopper-stl.sh OUTLET_R OUTLET_Z TOP_R TOP_Z SEGMENTS > hopper.stl
#   bash scripts/make-hopper-stl.sh 0.25 0.9 0.6 1.3 16 > cases/large_heap/hopper.stl
#
# A still mesh's triangles are listed by cell (the wall grid, docs/case-format.md, mesh), so
# SEGMENTS may be large; `repose mesh hopper` writes the same cone in any unit.
set -euo pipefail
if [ $# -ne 5 ]; then
  sed -n '2,7p' "$0" >&2
  exit 2
fi
awk -v ro="$1" -v zo="$2" -v rt="$3" -v zt="$4" -v n="$5" 'BEGIN {
  if (!(ro > 0 && rt > ro && zt > zo && n >= 3)) {
    print "make-hopper-stl.sh: need 0 < OUTLET_R < TOP_R, OUTLET_Z < TOP_Z and SEGMENTS >= 3" > "/dev/stderr"
    exit 2
  }
  pi = atan2(0, -1)
  print "solid hopper"
  for (k = 0; k < n; k++) {
    a0 = 2 * pi * k / n; a1 = 2 * pi * (k + 1) / n
    # The quad between the outlet and the top circles over the sector [a0, a1].
    tri(ro * cos(a0), ro * sin(a0), zo, ro * cos(a1), ro * sin(a1), zo, rt * cos(a1), rt * sin(a1), zt)
    tri(ro * cos(a0), ro * sin(a0), zo, rt * cos(a1), rt * sin(a1), zt, rt * cos(a0), rt * sin(a0), zt)
  }
  print "endsolid hopper"
}
# The stored normal is 0: Repose (and most readers) take it from the winding.
function tri(x0, y0, z0, x1, y1, z1, x2, y2, z2) {
  print "  facet normal 0 0 0"
  print "    outer loop"
  printf "      vertex %.9g %.9g %.9g\n", x0, y0, z0
  printf "      vertex %.9g %.9g %.9g\n", x1, y1, z1
  printf "      vertex %.9g %.9g %.9g\n", x2, y2, z2
  print "    endloop"
  print "  endfacet"
}'
