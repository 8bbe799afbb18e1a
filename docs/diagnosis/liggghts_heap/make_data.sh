#!/bin/bash
# Slot heaps made by LIGGGHTS 3.8 and measured as a lab would, into a measured-data CSV for
# `repose diagnose`. Usage (from this folder, LIGGGHTS and a built repose on the PATH or REPOSE=):
#   ./make_data.sh K OUT.csv      K: sjkr cohesion energy density between grains, J/m^3 (0: dry)
# For each fill count (150, 200, 250) and replicate (six fills, LIGGGHTS seeds below), LIGGGHTS
# writes the bed before the lift (bed_*.dump) and the settled heap (heap_*.dump); each dump
# becomes a sphere CSV (x,y,z,radius), `repose heap-angle --measures` measures the right-hand
# slope seen from the front (the case's heap_side) and the bed, and the rows are appended with
# the case, the condition and the replicate.
set -euo pipefail
K=$1; OUT=$2
REPOSE=${REPOSE:-repose}
CASE=liggghts_slot_heap.toml   # the case column, relative to the CSV (cases/diagnosis/)
SEEDS=(10007 10009 10037 10039 10061 10067)
work=$(mktemp -d); cp in.slot_heap gate.stl "$work"/
to_csv() {  # LIGGGHTS custom dump (id x y z radius ...) -> x,y,z,radius
  awk 'BEGIN{print "x,y,z,radius"} /^ITEM: ATOMS/{on=1; next} on{print $2","$3","$4","$5}' "$1" > "$2"
}
echo "case,set:fill.0.count,measure,value,replicate" > "$OUT"
for N in 150 200 250; do
  for r in 1 2 3 4 5 6; do
    tag=n${N}_r${r}
    (cd "$work" && liggghts -var N $N -var K $K -var TR on -var SEED ${SEEDS[$((r-1))]} -var TAG $tag \
        -in in.slot_heap -log log.$tag > out.$tag)
    to_csv "$work/heap_$tag.dump" "$work/heap_$tag.csv"
    to_csv "$work/bed_$tag.dump" "$work/bed_$tag.csv"
    { "$REPOSE" heap-angle "$work/heap_$tag.csv" --view y --floor 0 --side right --measures | grep -v '^bed_height'
      "$REPOSE" heap-angle "$work/bed_$tag.csv" --view y --floor 0 --measures | grep '^bed_height'
    } | grep -v '^measure,' | sed "s|^|$CASE,$N,|; s|$|,$r|" >> "$OUT"
  done
done
rm -rf "$work"
