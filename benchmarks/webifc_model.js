// What a coordinator's viewer built on web-ifc (That Open Company's engine,
// independent of ifcopenshell) finds in a castor IFC file: the storeys with
// their elevations and the elements each contains, the spaces each aggregates,
// the openings (the element each voids, the door or window filling it), and
// per element the colour web-ifc draws it in and its volume from web-ifc's
// triangles. JSON on stdout. Usage, from a directory where `npm install
// web-ifc` was run:
//   node webifc_model.js model.ifc > model.json
const fs = require("fs");
const WebIFC = require(require.resolve("web-ifc", {paths: [process.cwd()]}));

function value(attribute) {
  return attribute && attribute.value !== undefined ? attribute.value : attribute;
}

function lines(api, model, type) {
  const ids = api.GetLineIDsWithType(model, type, true);
  const found = [];
  for (let i = 0; i < ids.size(); i++) found.push(api.GetLine(model, ids.get(i)));
  return found;
}

async function main() {
  const [input] = process.argv.slice(2);
  const api = new WebIFC.IfcAPI();
  await api.Init();
  const model = api.OpenModel(new Uint8Array(fs.readFileSync(input)));
  const nameOf = (id) => {
    const line = api.GetLine(model, value(id));
    return `${api.GetNameFromTypeCode(line.type)} ${value(line.Name)}`;
  };
  const storeys = {};
  for (const storey of lines(api, model, WebIFC.IFCBUILDINGSTOREY)) {
    storeys[storey.expressID] = {name: value(storey.Name), elevation: value(storey.Elevation),
                                 elements: [], spaces: []};
  }
  for (const rel of lines(api, model, WebIFC.IFCRELCONTAINEDINSPATIALSTRUCTURE)) {
    const storey = storeys[value(rel.RelatingStructure)];
    if (storey) for (const e of rel.RelatedElements) storey.elements.push(nameOf(e));
  }
  for (const rel of lines(api, model, WebIFC.IFCRELAGGREGATES)) {
    const storey = storeys[value(rel.RelatingObject)];
    if (storey) for (const e of rel.RelatedObjects) storey.spaces.push(nameOf(e));
  }
  const fills = {};
  for (const rel of lines(api, model, WebIFC.IFCRELFILLSELEMENT)) {
    fills[value(rel.RelatingOpeningElement)] = nameOf(rel.RelatedBuildingElement);
  }
  const openings = lines(api, model, WebIFC.IFCRELVOIDSELEMENT).map((rel) => ({
    voids: nameOf(rel.RelatingBuildingElement),
    filled_by: fills[value(rel.RelatedOpeningElement)] || null}));
  const colour_maps = lines(api, model, WebIFC.IFCINDEXEDCOLOURMAP).length;
  const elements = {};
  api.StreamAllMeshes(model, (mesh) => {
    const line = api.GetLine(model, mesh.expressID);
    const key = `${api.GetNameFromTypeCode(line.type)} ${value(line.Name)} #${mesh.expressID}`;
    const record = elements[key] = {colours: [], volume: 0};
    for (let g = 0; g < mesh.geometries.size(); g++) {
      const placed = mesh.geometries.get(g);
      const geometry = api.GetGeometry(model, placed.geometryExpressID);
      const v = api.GetVertexArray(geometry.GetVertexData(), geometry.GetVertexDataSize());
      const index = api.GetIndexArray(geometry.GetIndexData(), geometry.GetIndexDataSize());
      const m = placed.flatTransformation;
      const p = (i) => [m[0] * v[6 * i] + m[4] * v[6 * i + 1] + m[8] * v[6 * i + 2] + m[12],
                        m[1] * v[6 * i] + m[5] * v[6 * i + 1] + m[9] * v[6 * i + 2] + m[13],
                        m[2] * v[6 * i] + m[6] * v[6 * i + 1] + m[10] * v[6 * i + 2] + m[14]];
      for (let t = 0; t < index.length; t += 3) {
        const [a, b, d] = [p(index[t]), p(index[t + 1]), p(index[t + 2])];
        record.volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                          + a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
      }
      const c = placed.color;
      record.colours.push([c.x, c.y, c.z].map((x) => Math.round(x * 1e6) / 1e6));
    }
  });
  console.log(JSON.stringify({storeys: Object.values(storeys), openings, colour_maps, elements},
                             null, 1));
  api.CloseModel(model);
}

main().catch((error) => { console.error(error); process.exit(1); });
