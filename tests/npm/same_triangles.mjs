// Compares the geometry of glTF files with an expected one, corner by
// corner, read with glTF-Transform's core (gltf_read.mjs): each mesh's
// primitives, in order, must have the same mode, material, attribute names and morph target count, and the same triangles
// (points and lines: the same elements) where a corner is the values of
// every attribute and morph target at its vertex. Triangles are compared as
// a multiset, each rotated to start at its least corner (the orientation is
// kept), so vertex order, index order and vertex sharing are the writer's
// choice; values are compared exactly. Exits 0 when they are the same, 1
// with the first difference, 77 when the packages are not installed, 2 on
// bad usage or an unreadable file.
//
//   node same_triangles.mjs [--modules NPM_DIR] EXPECTED ACTUAL... [-- EXPECTED ACTUAL...]...
//
// Used for the full level of a progressive mesh (it must be its input), and
// for one level written twice (.glb and .gltf, or from a Draco container).
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openReader } from './gltf_read.mjs';

function usage(message) {
  console.error(`Error: ${message}\n` +
                'usage: node same_triangles.mjs [--modules DIR] EXPECTED ACTUAL... [-- EXPECTED ACTUAL...]...');
  process.exit(2);
}

let modules = process.env.LODBAKE_NPM_DIR || path.dirname(fileURLToPath(import.meta.url));
const groups = [[]];  // each: an expected file and the files compared with it
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--') groups.push([]);
  else if (args[i].startsWith('--')) usage(`unknown option ${args[i]}`);
  else groups[groups.length - 1].push(args[i]);
}
if (groups.some((g) => g.length < 2)) usage('each group needs an expected file and at least one other');

const reader = await openReader(modules);
if (reader === null) {
  console.error(`Warning: @gltf-transform/core, extensions, functions or draco3dgltf is not installed in ${modules} ` +
                `(run make npm-deps): skipped`);
  process.exit(77);
}
const { core } = reader;

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
    return meshesOf(await reader.read(file));
  } catch (e) {
    console.error(`Error: ${file}: ${e.message}`);
    process.exit(2);
  }
}

let failed = false;
for (const [first, ...others] of groups) {
  const expected = await load(first);
  for (const file of others) {
    const why = difference(expected, await load(file));
    if (why !== null) {
      console.log(`${file}: not the triangles of ${first}: ${why}`);
      failed = true;
    } else {
      const elements = expected.flat().reduce((n, p) => n + p.elements.length, 0);
      console.log(`${file}: the same ${elements} triangles, lines and points as ${first}, every corner's values`);
    }
  }
}
process.exit(failed ? 1 : 0);
