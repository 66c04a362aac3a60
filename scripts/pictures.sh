#!/usr/bin/env sh
# Draw the README's pictures from the examples, so that they stay true: the
# exact solids ray traced by castor with the default sun (20 degrees beside the
# camera's azimuth, 45 high: every face seen is lit and casts its shadow), and
# castor-view's wireframe of the polygons.
# Usage: scripts/pictures.sh   (from the repository, with castor installed)
set -eu
cd "$(dirname "$0")/.."
out=docs/pictures
mkdir -p "$out"
castor --edges -o "$out/car.png" examples/car.cas
castor examples/car.cas | castor-view --wire -o "$out/car-wire.png"
castor --edges -o "$out/house.png" examples/house.cas
castor --view -30,20 --edges -o "$out/staircase.png" examples/staircase.cas
castor --view -70,20 --size 480x360 -o "$out/door.gif" examples/door.cas
castor -D ONE_FRAME --set PHASE=2 --view -60,30 --size 1000x700 \
    -o "$out/bus-shelter.png" examples/bus_shelter.cas
castor --view -35,25 -o "$out/bench.png" examples/bench.cas
# the house's drawings, as SVG rendered by rsvg-convert (a fixed date in the title block)
tmp=$(mktemp -d)
for drawing in "plan --section z=1.2" "section --section x=3" "front --view front"; do
    set -- $drawing
    name=$1; shift
    SOURCE_DATE_EPOCH=1767225600 castor "$@" -o "$tmp/$name.svg" examples/house.cas
    rsvg-convert -w 1000 -b white "$tmp/$name.svg" -o "$out/house-$name.png"
done
# the pavilion's set (its register examples/pavilion-sheets.toml): the plan and the section pages
SOURCE_DATE_EPOCH=1767225600 castor examples/pavilion.cas --sheets examples/pavilion-sheets.toml \
    -o "$tmp/pavilion.pdf"
pdftoppm -png -r 90 -f 2 -l 2 -singlefile "$tmp/pavilion.pdf" "$out/pavilion-plan"
pdftoppm -png -r 90 -f 4 -l 4 -singlefile "$tmp/pavilion.pdf" "$out/pavilion-section"
rm -r "$tmp"
echo "pictures written to $out"
