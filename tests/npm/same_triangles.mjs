// Compares the geometry of two glTF files corner by corner, read with
// glTF-Transform's core (npm @gltf-transform/core, Draco decoded by
// draco3dgltf): each mesh's primitives, in order, must have the same mode,
// material, attribute names and morph target count, and the same triangles
// (points and lines: the same elements) where a corner is the values of
// every attribute and morph target at its vertex. Triangles are compared as
// a multiset, each rotated to start at its least corner (the orientation is
// kept), so vertex order, index order and vertex sharing are the writer's
// choice; values are compared exactly. Exits 0 when they are the same, 1
// with the first difference, 77 when the packages are not installed, 2 on
// bad usage or an unreadable file.
//
//   node same_triangles.mjs [--modules NPM_DIR] EXPECTED ACTUAL...
//
// Used for the full level of a progressive mesh (it must be its input), and
// for one level written twice (.glb and .gltf, or from a Draco container).
// Images are not read: a .gltf's missing image is not an error here.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

function usage(message) {
  console.error(`Error: ${message}\nusage: node same_triangles.mjs [--modules DIR] EXPECTED ACTUAL...`);
  process.exit(2);
}

let modules = process.env.LODBAKE_NPM_DIR || path.dirname(fileURLToPath(import.meta.url));
const files = [];
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i].startsWith('--')) usage(`unknown option ${args[i]}`);
  else files.push(args[i]);
}
if (files.length < 2) usage('an expected file and at least one other are needed');

let core, extensions, draco3d;
try {
  const require = createRequire(path.join(path.resolve(modules), 'package.json'));
  core = await import(require.resolve('@gltf-transform/core'));
  extensions = await import(require.resolve('@gltf-transform/extensions'));
  draco3d = require('draco3dgltf');
} catch (e) {
  console.error(`Warning: @gltf-transform/core, extensions or draco3dgltf is not installed in ${modules} ` +
                `(run make npm-deps): skipped`);
  process.exit(77);
}
// gltf-transform 4.5 cannot read EXT_mesh_features without property tables
// (BoxMetaDraco): left unregistered, it is an unknown extension and its
// feature-id attributes are read as attributes.
const metadata = new Set(['EXT_mesh_features', 'EXT_structural_metadata']);
const io = new core.NodeIO()
  .setLogger(new core.Logger(core.Logger.Verbosity.ERROR))
  .registerExtensions(extensions.ALL_EXTENSIONS.filter((e) => !metadata.has(e.EXTENSION_NAME)))
  .registerDependencies({ 'draco3d.decoder': await draco3d.createDecoderModule() });

// A GLB's JSON and BIN chunks.
function glbChunks(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 20 || view.getUint32(0, true) !== 0x46546c67) throw new Error('not a GLB');
  let json = null, bin = null;
  for (let at = 12; at + 8 <= bytes.length;) {
    const length = view.getUint32(at, true), type = view.getUint32(at + 4, true);
    const chunk = bytes.subarray(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else if (type === 0x004e4942) bin = chunk;
    at += 8 + length;
  }
  if (json === null) throw new Error('a GLB without a JSON chunk');
  return { json, bin };
}

// The JSON with its buffers (a GLB's BIN chunk, a .gltf's files); images
// are given as empty, so a missing one (Lantern's) does not stop the read.
async function read(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const { json, bin } = file.endsWith('.glb') ? glbChunks(bytes)
                                              : { json: JSON.parse(new TextDecoder().decode(bytes)), bin: null };
  const resources = {};
  if (bin !== null) resources['@glb.bin'] = bin;  // gltf-transform's name for the GLB buffer
  for (const buffer of json.buffers || []) {
    if (buffer.uri !== undefined && !buffer.uri.startsWith('data:')) {
      resources[buffer.uri] =
        new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(buffer.uri))));
    }
  }
  for (const image of json.images || []) {
    if (image.uri !== undefined && !image.uri.startsWith('data:')) resources[image.uri] = new Uint8Array(0);
  }
  return io.readJSON({ json, resources });
}

// One corner: every attribute's values, then every morph target's, in name
// order, printed exactly (a float32 read as a double prints all its bits).
function cornerKey(prim, names, targets, vertex) {
  // getElement fills its target without shortening it: a new one each time.
  const parts = [];
  for (const name of names) parts.push(`${name}=${prim.getAttribute(name).getElement(vertex, []).join(' ')}`);
  targets.forEach((target, t) => {
    for (const name of target.listSemantics().sort()) {
      parts.push(`t${t}.${name}=${target.getAttribute(name).getElement(vertex, []).join(' ')}`);
    }
  });
  return parts.join(';');
}

const modeNames = ['POINTS', 'LINES', 'LINE_LOOP', 'LINE_STRIP', 'TRIANGLES', 'TRIANGLE_STRIP', 'TRIANGLE_FAN'];

// Corner keys as small integers, the same for every file read, so that a
// triangle is three numbers.
const cornerIds = new Map();
const cornerKeys = [];
function cornerId(key) {
  let id = cornerIds.get(key);
  if (id === undefined) {
    cornerIds.set(key, (id = cornerKeys.length));
    cornerKeys.push(key);
  }
  return id;
}
const spelled = (element) => element.split(' ').map((id) => `(${cornerKeys[Number(id)]})`).join(' ');

// A primitive as { header, elements }: elements are corner ids, one string
// per triangle (rotated to its least corner; sorted), or per line or point
// vertex (in order).
function primitiveOf(prim, materials) {
  const names = prim.listSemantics().sort();
  const targets = prim.listTargets();
  const mode = prim.getMode();
  const material = prim.getMaterial() === null ? -1 : materials.indexOf(prim.getMaterial());
  const header = `${modeNames[mode]} material ${material} attributes ${names.join(',')} targets ${targets.length}`;
  const count = prim.getAttribute('POSITION').getCount();
  const indices = prim.getIndices();
  const order = indices === null ? [...Array(count).keys()] : Array.from(indices.getArray());
  const keys = new Map();
  const key = (v) => {
    if (!keys.has(v)) keys.set(v, cornerId(cornerKey(prim, names, targets, v)));
    return keys.get(v);
  };
  const elements = [];
  if (mode === core.Primitive.Mode.TRIANGLES) {
    for (let i = 0; i + 2 < order.length; i += 3) {
      const c = [key(order[i]), key(order[i + 1]), key(order[i + 2])];
      let first = 0;
      for (let k = 1; k < 3; ++k) if (c[k] < c[first]) first = k;
      elements.push(`${c[first]} ${c[(first + 1) % 3]} ${c[(first + 2) % 3]}`);
    }
    elements.sort();
  } else {
    // Points, lines and strips: kept as the writer has them, in order.
    for (const v of order) elements.push(String(key(v)));
  }
  return { header, elements };
}

function meshesOf(doc) {
  const root = doc.getRoot();
  const materials = root.listMaterials();
  return root.listMeshes().map((mesh) => mesh.listPrimitives().map((p) => primitiveOf(p, materials)));
}

// The first difference, or null.
function difference(expected, actual) {
  if (expected.length !== actual.length) return `${expected.length} meshes expected, ${actual.length} found`;
  for (let m = 0; m < expected.length; ++m) {
    if (expected[m].length !== actual[m].length) {
      return `mesh ${m}: ${expected[m].length} primitives expected, ${actual[m].length} found`;
    }
    for (let p = 0; p < expected[m].length; ++p) {
      const a = expected[m][p], b = actual[m][p];
      const where = `mesh ${m} primitive ${p}`;
      if (a.header !== b.header) return `${where}: expected ${a.header}, found ${b.header}`;
      if (a.elements.length !== b.elements.length) {
        return `${where}: ${a.elements.length} elements expected, ${b.elements.length} found`;
      }
      for (let i = 0; i < a.elements.length; ++i) {
        if (a.elements[i] !== b.elements[i]) {
          return `${where}: element ${i} (sorted) differs:\n  expected ${spelled(a.elements[i])}\n` +
                 `  found    ${spelled(b.elements[i])}`;
        }
      }
    }
  }
  return null;
}

async function load(file) {
  try {
    return meshesOf(await read(file));
  } catch (e) {
    console.error(`Error: ${file}: ${e.message}`);
    process.exit(2);
  }
}

const expected = await load(files[0]);
let failed = false;
for (const file of files.slice(1)) {
  const why = difference(expected, await load(file));
  if (why !== null) {
    console.log(`${file}: not the triangles of ${files[0]}: ${why}`);
    failed = true;
  } else {
    const elements = expected.flat().reduce((n, p) => n + p.elements.length, 0);
    console.log(`${file}: the same ${elements} triangles, lines and points as ${files[0]}, every corner's values`);
  }
}
process.exit(failed ? 1 : 0);
