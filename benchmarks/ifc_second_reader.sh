#!/bin/sh
# The house and the bus shelter (as seven elements) written as IFC by castor,
# read by web-ifc (a second IFC reader, nothing shared with ifcopenshell) and
# drawn by Blender from what web-ifc read; prints, per element, what web-ifc
# found (class, volume, colours) beside --summary's volume.
#   WEB_IFC=/dir/where/npm/install/web-ifc/ran benchmarks/ifc_second_reader.sh OUT_DIR
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
out=${1:-ifc-second-reader}
: "${WEB_IFC:?set WEB_IFC to a directory where 'npm install web-ifc' was run}"
mkdir -p "$out"
out=$(cd "$out" && pwd)
cat > "$out/shelter_elements.cas" <<'SCENE'
/* the bus shelter as a BIM coordinator wants it: one element per part */
#include "bus_shelter/colours.cas"
#include "bus_shelter/street.cas"
#include "bus_shelter/shelter.cas"
#include "bus_shelter/furniture.cas"
#include "bus_shelter/traffic_light.cas"
#include "bus_shelter/bus.cas"
#include "bus_shelter/facade.cas"
PHASE = 0;
bus_place = PLACE_BUS bus;
> rue, abri, mobilier, mobilier_plus, facade, bus_place, feu;
SCENE
castor --summary "$out/house.json" -o "$out/house.ifc" "$root/examples/house.cas"
castor -I "$root/examples" --title "Arrêt de bus" --ifc-class facade=IfcWall \
    --ifc-class rue=IfcCivilElement --ifc-class mobilier=IfcFurniture \
    --ifc-class mobilier_plus=IfcFurniture --summary "$out/shelter.json" \
    -o "$out/shelter.ifc" "$out/shelter_elements.cas"
for name in house shelter; do
    (cd "$WEB_IFC" && node "$here/webifc_read.js" "$out/$name.ifc" "$out/$name-web-ifc.obj") \
        | grep -v '^\[WEB-IFC\]' > "$out/$name-web-ifc.json"
    python3 - "$out/$name.json" "$out/$name-web-ifc.json" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))["frames"][0]["objects"]
read = {e["name"]: e for e in json.load(open(sys.argv[2]))}
for obj in summary:
    e = read[obj["name"]]
    same = {tuple(c["rgb"]) for c in obj["colours"]} == {tuple(c) for c in e["colours"]}
    print(f"{obj['name']:14} {e['class']:24} volume {obj['volume']:.6f} (castor) "
          f"{e['volume']:.6f} (web-ifc), colours {'equal' if same else 'DIFFER'}")
PY
    blender -b -P "$here/render_obj.py" -- "$out/$name-web-ifc.obj" "$out/$name-web-ifc.png" \
        > /dev/null 2>&1
done
echo "pictures: $out/house-web-ifc.png $out/shelter-web-ifc.png"
