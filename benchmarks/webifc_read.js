// A second IFC reader: web-ifc (That Open Company's engine, C++ compiled to
// WebAssembly, independent of ifcopenshell) opens a castor IFC file, and this
// script writes what it read: per element its name, class, volume and colours
// as JSON on stdout, and the triangles web-ifc made as an OBJ + MTL (+Y up,
// as web-ifc hands them) that Blender renders. Usage (from a directory where
// `npm install web-ifc` was run):
//   node webifc_read.js model.ifc out.obj > elements.json
const fs = require("fs");
const path = require("path");
const WebIFC = require(require.resolve("web-ifc", {paths: [process.cwd()]}));

async function main() {
  const [input, objPath] = process.argv.slice(2);
  const api = new WebIFC.IfcAPI();
  await api.Init();
  const model = api.OpenModel(new Uint8Array(fs.readFileSync(input)));
  const elements = {};
  const obj = [`mtllib ${path.basename(objPath, ".obj")}.mtl`];
  const mtl = [];
  const colours = {};
  let base = 1;
  api.StreamAllMeshes(model, (mesh) => {
    const line = api.GetLine(model, mesh.expressID);
    const name = line.Name ? line.Name.value : `#${mesh.expressID}`;
    const record = elements[name] || (elements[name] = {
      name, class: api.GetNameFromTypeCode(line.type), volume: 0, colours: [], triangles: 0});
    obj.push(`o ${name}_${mesh.expressID}`);
    const geometries = mesh.geometries;
    for (let g = 0; g < geometries.size(); g++) {
      const placed = geometries.get(g);
      const geometry = api.GetGeometry(model, placed.geometryExpressID);
      const vertices = api.GetVertexArray(geometry.GetVertexData(), geometry.GetVertexDataSize());
      const indices = api.GetIndexArray(geometry.GetIndexData(), geometry.GetIndexDataSize());
      const m = placed.flatTransformation;  // 4x4, column-major
      const points = [];
      for (let i = 0; i < vertices.length; i += 6) {
        const [x, y, z] = [vertices[i], vertices[i + 1], vertices[i + 2]];
        points.push([m[0] * x + m[4] * y + m[8] * z + m[12],
                     m[1] * x + m[5] * y + m[9] * z + m[13],
                     m[2] * x + m[6] * y + m[10] * z + m[14]]);
      }
      const c = placed.color;
      const rgb = [c.x, c.y, c.z].map((v) => Math.round(v * 1e6) / 1e6);
      const key = rgb.join(" ");
      if (!(key in colours)) {
        colours[key] = `colour${Object.keys(colours).length}`;
        mtl.push(`newmtl ${colours[key]}`, `Kd ${key}`, "");
      }
      if (!record.colours.some((r) => r.join(" ") === key)) record.colours.push(rgb);
      obj.push(`usemtl ${colours[key]}`);
      for (const p of points) obj.push(`v ${p[0]} ${p[1]} ${p[2]}`);
      for (let t = 0; t < indices.length; t += 3) {
        const [a, b, d] = [points[indices[t]], points[indices[t + 1]], points[indices[t + 2]]];
        // six times the signed volume of the tetrahedron from the origin
        record.volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                          + a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
        obj.push(`f ${indices[t] + base} ${indices[t + 1] + base} ${indices[t + 2] + base}`);
        record.triangles += 1;
      }
      base += points.length;
    }
  });
  api.CloseModel(model);
  if (objPath) {
    fs.writeFileSync(objPath, obj.join("\n") + "\n");
    fs.writeFileSync(objPath.replace(/\.obj$/, ".mtl"), mtl.join("\n") + "\n");
  }
  process.stdout.write(JSON.stringify(Object.values(elements)) + "\n");
}

main().catch((error) => { console.error(error); process.exit(1); });
