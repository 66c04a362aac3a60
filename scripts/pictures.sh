#!/usr/bin/env sh
# Draw the README's pictures from the examples, so that they stay true.
# Usage: scripts/pictures.sh   (from the repository, with castor installed)
set -eu
cd "$(dirname "$0")/.."
out=docs/pictures
mkdir -p "$out"
castor examples/car.cas | castor-view --edges -o "$out/car.png"
castor examples/car.cas | castor-view --wire -o "$out/car-wire.png"
castor examples/house.cas | castor-view --edges -o "$out/house.png"
castor examples/staircase.cas | castor-view --view -30,20 --edges -o "$out/staircase.png"
castor examples/door.cas | castor-view --view -70,20 --size 480x360 -o "$out/door.gif"
castor -D ONE_FRAME --set PHASE=2 examples/bus_shelter.cas \
    | castor-view --view -60,30 --size 1000x700 -o "$out/bus-shelter.png"
echo "pictures written to $out"
