// meshoptimizer's attribute-aware simplifier (npm meshoptimizer,
// MeshoptSimplifier.simplifyWithAttributes) on every triangle primitive of a
// glTF asset, for bench_attributes: the library a user would call, set up
// the way gltfpack sets it up when it simplifies (gltf/mesh.cpp):
// - vertices welded on all their attributes first (gltfpack's reindexMesh);
// - target index count = floor(triangles * ratio) * 3, target error 1e-2
//   relative to the mesh's extent (gltfpack's -se default);
// - flag Prune, no LockBorder (gltfpack without -slb);
// - attributes: NORMAL with weight 0.5 per component (gltfpack's weight),
//   COLOR_0 (rgb times alpha) with 1.0 (gltfpack's), and TEXCOORD_0 with
//   --uv-weight (default 1.0, meshoptimizer's advice for attributes in
//   [0, 1]; gltfpack passes no UV and relies on the seams alone).
// Each mesh is simplified once, however many nodes use it; every attribute
// stream (skin weights included) follows the kept vertices, which are
// compacted. Morph targets are left out of the output primitive.
//
//   node meshopt_simplify.mjs --modules NPM_DIR --ratio R [--error E] [--uv-weight W] IN OUT.glb
//
// Prints one tab-separated line for bench_attributes to read:
//   ok <ms in simplifyWithAttributes> <ms from read to written> <triangles in> <triangles out>
// Exits 77 when the npm packages are not installed in NPM_DIR, 2 on bad
// usage, 1 when the asset cannot be read or written.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

function usage(message) {
  console.error(`Error: ${message}\nusage: node meshopt_simplify.mjs --modules DIR --ratio R [--error E] [--uv-weight W] IN OUT.glb`);
  process.exit(2);
}

let modules = null;
let ratio = null;
let targetError = 1e-2;
let uvWeight = 1.0;
const files = [];
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--ratio' && i + 1 < args.length) ratio = parseFloat(args[++i]);
  else if (args[i] === '--error' && i + 1 < args.length) targetError = parseFloat(args[++i]);
  else if (args[i] === '--uv-weight' && i + 1 < args.length) uvWeight = parseFloat(args[++i]);
  else if (args[i].startsWith('--')) usage(`unknown option ${args[i]}`);
  else files.push(args[i]);
}
if (modules === null || files.length !== 2) usage('--modules, an input and an output are needed');
if (!(ratio > 0 && ratio <= 1)) usage('--ratio must be in (0, 1]');

const coreEntry = path.join(modules, 'node_modules', '@gltf-transform', 'core', 'dist', 'index.js');
const extensionsEntry = path.join(modules, 'node_modules', '@gltf-transform', 'extensions', 'dist', 'index.js');
const simplifierEntry = path.join(modules, 'node_modules', 'meshoptimizer', 'meshopt_simplifier.js');
for (const entry of [coreEntry, extensionsEntry, simplifierEntry]) {
  if (!fs.existsSync(entry)) {
    console.error(`${entry} is not installed (make npm-deps)`);
    process.exit(77);
  }
}
const { NodeIO, Primitive } = await import(pathToFileURL(coreEntry).href);
const { ALL_EXTENSIONS } = await import(pathToFileURL(extensionsEntry).href);
const { MeshoptSimplifier } = await import(pathToFileURL(simplifierEntry).href);
await MeshoptSimplifier.ready;

const NORMAL_WEIGHT = 0.5;
const COLOR_WEIGHT = 1.0;

// The vertex indices of the primitive (0, 1, 2, ... when it has none).
function indexArray(primitive, vertexCount) {
  const indices = primitive.getIndices();
  if (indices) return Uint32Array.from(indices.getArray());
  return Uint32Array.from({ length: vertexCount }, (_, i) => i);
}

// gltfpack's reindexMesh: vertices equal in every attribute become one, so
// that the simplifier sees the real topology. Returns the welded indices and
// the first vertex of each class (the new vertex order).
function weld(primitive, indices) {
  const accessors = primitive.listAttributes();
  const count = accessors[0].getCount();
  const arrays = accessors.map((a) => [a.getArray(), a.getElementSize()]);
  const classOf = new Map();
  const remap = new Uint32Array(count);
  const firsts = [];
  for (let v = 0; v < count; ++v) {
    let key = '';
    for (const [array, size] of arrays) {
      for (let k = 0; k < size; ++k) key += array[v * size + k] + ',';
    }
    let id = classOf.get(key);
    if (id === undefined) {
      id = firsts.length;
      classOf.set(key, id);
      firsts.push(v);
    }
    remap[v] = id;
  }
  return [indices.map((i) => remap[i]), firsts];
}

// Float32Array of `vertices`' values of `accessor` (normalized integers as floats).
function floats(accessor, vertices, size) {
  const out = new Float32Array(vertices.length * size);
  const element = [];
  vertices.forEach((v, i) => {
    accessor.getElement(v, element);
    for (let k = 0; k < size; ++k) out[i * size + k] = element[k] ?? 0;
  });
  return out;
}

const start = performance.now();
let simplifyMs = 0;
let trianglesIn = 0;
let trianglesOut = 0;
// The Khronos extensions registered, so that a required one (SheenCloth's
// KHR_texture_transform) is read and written back rather than refused; but
// not the feature-metadata pair, which gltf-transform 4.5.1 fails to read on
// BoxMetaDraco (it then drops them; they do not touch the geometry).
const io = new NodeIO().registerExtensions(
  ALL_EXTENSIONS.filter((e) => !['EXT_structural_metadata', 'EXT_mesh_features'].includes(e.EXTENSION_NAME)));
let document;
try {
  document = await io.read(files[0]);
} catch (err) {
  console.error(`Error: cannot read ${files[0]}: ${err.message}`);
  process.exit(1);
}
const buffer = document.getRoot().listBuffers()[0] ?? document.createBuffer();

for (const mesh of document.getRoot().listMeshes()) {
  for (const primitive of mesh.listPrimitives()) {
    if (primitive.getMode() !== Primitive.Mode.TRIANGLES) continue;
    const position = primitive.getAttribute('POSITION');
    if (!position) continue;
    const [welded, firsts] = weld(primitive, indexArray(primitive, position.getCount()));
    trianglesIn += welded.length / 3;

    const positions = floats(position, firsts, 3);
    const streams = [];
    const normal = primitive.getAttribute('NORMAL');
    if (normal) streams.push([floats(normal, firsts, 3), 3, NORMAL_WEIGHT]);
    const color = primitive.getAttribute('COLOR_0');
    if (color) {
      const size = color.getElementSize();
      const rgba = floats(color, firsts, size);
      const rgb = new Float32Array(firsts.length * 3);
      for (let v = 0; v < firsts.length; ++v) {
        const alpha = size === 4 ? rgba[v * 4 + 3] : 1;
        for (let k = 0; k < 3; ++k) rgb[v * 3 + k] = rgba[v * size + k] * alpha;
      }
      streams.push([rgb, 3, COLOR_WEIGHT]);
    }
    const uv = primitive.getAttribute('TEXCOORD_0');
    if (uv && uvWeight > 0) streams.push([floats(uv, firsts, 2), 2, uvWeight]);
    const stride = streams.reduce((sum, [, size]) => sum + size, 0);
    const attributes = new Float32Array(firsts.length * stride);
    const weights = [];
    let offset = 0;
    for (const [values, size, weight] of streams) {
      for (let v = 0; v < firsts.length; ++v)
        for (let k = 0; k < size; ++k) attributes[v * stride + offset + k] = values[v * size + k];
      for (let k = 0; k < size; ++k) weights.push(weight);
      offset += size;
    }

    const target = Math.floor(welded.length / 3 * ratio) * 3;
    const simplifyStart = performance.now();
    const [simplified] = stride > 0
      ? MeshoptSimplifier.simplifyWithAttributes(welded, positions, 3, attributes, stride, weights, null,
                                                 target, targetError, ['Prune'])
      : MeshoptSimplifier.simplify(welded, positions, 3, target, targetError, ['Prune']);
    simplifyMs += performance.now() - simplifyStart;
    trianglesOut += simplified.length / 3;

    // Compact: the kept vertices only, every stream following them.
    const [remap, kept] = MeshoptSimplifier.compactMesh(simplified);
    const source = new Uint32Array(kept);
    remap.forEach((to, welded_vertex) => {
      if (to !== 0xffffffff) source[to] = firsts[welded_vertex];
    });
    for (const semantic of primitive.listSemantics()) {
      const accessor = primitive.getAttribute(semantic);
      const size = accessor.getElementSize();
      const array = accessor.getArray();
      const out = new array.constructor(kept * size);
      source.forEach((v, i) => out.set(array.subarray(v * size, v * size + size), i * size));
      const copy = document.createAccessor()
        .setType(accessor.getType())
        .setNormalized(accessor.getNormalized())
        .setArray(out)
        .setBuffer(buffer);
      primitive.setAttribute(semantic, copy);
    }
    primitive.setIndices(document.createAccessor().setType('SCALAR').setArray(simplified).setBuffer(buffer));
    for (const target of primitive.listTargets()) primitive.removeTarget(target);
  }
}
// The input's accessors nothing refers to any more.
for (const accessor of document.getRoot().listAccessors()) {
  if (accessor.listParents().every((parent) => parent === document.getRoot())) accessor.dispose();
}

try {
  await io.write(files[1], document);
} catch (err) {
  console.error(`Error: cannot write ${files[1]}: ${err.message}`);
  process.exit(1);
}
const totalMs = performance.now() - start;
console.log(`ok\t${simplifyMs.toFixed(3)}\t${totalMs.toFixed(3)}\t${trianglesIn}\t${trianglesOut}`);
