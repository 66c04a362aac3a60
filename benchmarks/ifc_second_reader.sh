#!/bin/sh
# The house, the two-storey pavilion and the bus shelter (as seven '>'
# objects) written as IFC by castor, read by web-ifc (a second IFC reader,
# nothing shared with ifcopenshell) and drawn by Blender from what web-ifc
# read; prints, per element name, what web-ifc found (class, volume, colours)
# beside castor's volume of the elements of that name, and what
# webifc_model.js finds of the pavilion's storeys and openings.
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
castor -o "$out/house.ifc" "$root/examples/house.cas"
castor -o "$out/pavilion.ifc" "$root/examples/pavilion.cas"
castor -I "$root/examples" --title "Arrêt de bus" --ifc-class facade=IfcWall \
    --ifc-class rue=IfcCivilElement --ifc-class mobilier=IfcFurniture \
    --ifc-class mobilier_plus=IfcFurniture -o "$out/shelter.ifc" "$out/shelter_elements.cas"
for name in house pavilion shelter; do
    (cd "$WEB_IFC" && node "$here/webifc_read.js" "$out/$name.ifc" "$out/$name-web-ifc.obj") \
        | grep -v '^\[WEB-IFC\]' > "$out/$name-web-ifc.json"
    "${PYTHON:-python3}" - "$out/$name.ifc" "$out/$name-web-ifc.json" <<'PY'
import json, sys
import ifcopenshell, ifcopenshell.geom, ifcopenshell.util.shape
model = ifcopenshell.open(sys.argv[1])
settings = ifcopenshell.geom.settings()
settings.set("use-world-coords", True)
volumes = {}
for e in model.by_type("IfcElement"):
    if not e.is_a("IfcOpeningElement"):
        shape = ifcopenshell.geom.create_shape(settings, e).geometry
        volumes[e.Name] = volumes.get(e.Name, 0) + ifcopenshell.util.shape.get_volume(shape)
for e in json.load(open(sys.argv[2])):
    print(f"{e['name']:16} {e['class']:24} volume {volumes[e['name']]:.6f} (ifcopenshell) "
          f"{e['volume']:.6f} (web-ifc), colours {e['colours']}")
PY
    blender -b -P "$here/render_obj.py" -- "$out/$name-web-ifc.obj" "$out/$name-web-ifc.png" \
        > /dev/null 2>&1
done
(cd "$WEB_IFC" && node "$here/webifc_model.js" "$out/pavilion.ifc") > "$out/pavilion-model.json"
echo "pictures: $out/house-web-ifc.png $out/pavilion-web-ifc.png $out/shelter-web-ifc.png"
