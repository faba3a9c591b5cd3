// Compares what `gltf-transform inspect` reports (the scenes, meshes with
// their primitives, attributes and instances, materials, textures and
// animations) for an asset lodbake read and files lodbake wrote from it:
// they must be the same. The report is computed in this process with the
// function the CLI prints (inspect() of npm @gltf-transform/functions),
// each row as the CLI's CSV has it, so that one node start serves every
// file (the CLI's own start was most of a second per file); files are read
// by gltf_read.mjs, which reads two shared assets the CLI cannot
// (Lantern's missing image, BoxMetaDraco's EXT_mesh_features). Exits 0
// when they are the same, 1 with the first difference of each output that
// differs, 77 when the packages are not installed, 2 on bad usage or an
// unreadable input.
//
//   node same_inventory.mjs [--modules NPM_DIR] INPUT [OUTPUT...] [--lod OUTPUT...]
//
// Columns that are the writer's choice are left out: sizes in bytes,
// image URIs (a GLB embeds what a .gltf names), index types, and the
// overview (the generator; decoded compression extensions). --lod: the
// outputs after it (also when it comes before INPUT) are simplified levels,
// so triangle and vertex counts and bounds may differ.
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openReader } from './gltf_read.mjs';

let modules = process.env.LODBAKE_NPM_DIR || path.dirname(fileURLToPath(import.meta.url));
let input = null;
const outputs = [];  // { file, level }
let level = false, unknown = false;
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--lod') level = true;
  else if (args[i].startsWith('--')) unknown = true;
  else if (input === null) input = args[i];
  else outputs.push({ file: args[i], level });
}
if (input === null || outputs.length === 0 || unknown) {
  console.error('usage: node same_inventory.mjs [--modules DIR] INPUT [OUTPUT...] [--lod OUTPUT...]');
  process.exit(2);
}
const reader = await openReader(modules);
if (reader === null) {
  console.error(`Warning: @gltf-transform/core, extensions, functions or draco3dgltf is not installed in ${modules} ` +
                `(run make npm-deps): skipped`);
  process.exit(77);
}

const ignored = new Set(['size', 'uri', 'indices', 'compression']);
const ignoredForLevel = new Set(['glPrimitives', 'vertices', 'renderVertexCount', 'uploadVertexCount',
                                 'uploadNaiveVertexCount', 'bboxMin', 'bboxMax']);
const sections = ['scenes', 'meshes', 'materials', 'textures', 'animations'];

// A property's row as the CLI's CSV writes it (its formatPropertyReport):
// arrays joined with ", ", booleans as a check mark or nothing.
function row(property, index) {
  const out = { '#': String(index) };
  for (const [key, value] of Object.entries(property)) {
    if (ignored.has(key)) continue;
    if (Array.isArray(value)) out[key] = value.join(', ');
    else if (typeof value === 'boolean') out[key] = value ? '✓' : '';
    else out[key] = String(value);
  }
  return out;
}

// FILE's report: per section, its rows.
async function inventory(file) {
  const report = reader.functions.inspect(await reader.read(file));
  const out = {};
  for (const s of sections) out[s] = report[s].properties.map(row);
  return out;
}

// A row without the columns a level may change.
function levelRow(r) {
  const out = {};
  for (const [k, v] of Object.entries(r)) if (!ignoredForLevel.has(k)) out[k] = v;
  return out;
}

// The first difference between the input's inventory and an output's, or null.
function difference(reference, output, isLevel) {
  const shown = (r) => JSON.stringify(isLevel ? levelRow(r) : r);
  for (const s of sections) {
    const a = reference[s], b = output[s];
    if (a.length !== b.length) return `${s}: ${a.length} in the input, ${b.length} here`;
    for (let i = 0; i < a.length; ++i) {
      if (shown(a[i]) !== shown(b[i])) return `${s} row ${i}: input ${shown(a[i])}\n  output ${shown(b[i])}`;
    }
  }
  return null;
}

let reference;
try {
  reference = await inventory(input);
} catch (e) {
  console.error(`Error: ${input}: ${e.message}`);
  process.exit(2);
}
const count = (s) => reference[s].length;
let same = true;
for (const { file, level: isLevel } of outputs) {
  let why;
  try {
    why = difference(reference, await inventory(file), isLevel);
  } catch (e) {
    why = `cannot be read: ${e.message}`;
  }
  if (why !== null) {
    console.log(`${file}: ${why}`);
    same = false;
  } else {
    console.log(`${file}: same inventory as ${input}${isLevel ? ' (a level)' : ''} (${count('scenes')} scenes, ` +
                `${count('meshes')} meshes, ${count('materials')} materials, ${count('textures')} textures, ` +
                `${count('animations')} animations)`);
  }
}
process.exit(same ? 0 : 1);
