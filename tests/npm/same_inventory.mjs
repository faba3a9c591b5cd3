// Compares what `gltf-transform inspect` (npm @gltf-transform/cli) reports
// for an asset lodbake read and files lodbake wrote from it: the scenes,
// meshes (primitives, attributes, instances), materials, textures and
// animations must be the same. Exits 0 when they are, 1 with the first
// difference of each output that differs, 77 when the CLI is not
// installed, 2 on bad usage. The input is inspected once for all outputs.
//
//   node same_inventory.mjs [--modules NPM_DIR] [--lod] INPUT OUTPUT...
//
// Columns that are the writer's choice are left out: sizes in bytes,
// image URIs (a GLB embeds what a .gltf names), index types, and the
// overview (the generator; decoded compression extensions). --lod: each
// OUTPUT is a simplified level, so triangle and vertex counts and bounds may differ.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

let modules = process.env.LODBAKE_NPM_DIR || path.dirname(fileURLToPath(import.meta.url));
let lod = false;
const files = [];
let unknown = false;
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--lod') lod = true;
  else if (args[i].startsWith('--')) unknown = true;
  else files.push(args[i]);
}
if (files.length < 2 || unknown) {
  console.error('usage: node same_inventory.mjs [--modules DIR] [--lod] INPUT OUTPUT...');
  process.exit(2);
}
const cli = path.join(path.resolve(modules), 'node_modules', '.bin', 'gltf-transform');
if (!fs.existsSync(cli)) {
  console.error(`Warning: @gltf-transform/cli is not installed in ${modules} (run make npm-deps): skipped`);
  process.exit(77);
}

const ignored = new Set(['size', 'uri', 'indices', 'compression']);
const ignoredForLod = new Set(['glPrimitives', 'vertices', 'renderVertexCount', 'uploadVertexCount',
                               'uploadNaiveVertexCount', 'bboxMin', 'bboxMax']);

// Splits a CSV line, honouring double quotes.
function cells(line) {
  const out = [];
  let cur = '', quoted = false;
  for (const ch of line) {
    if (ch === '"') quoted = !quoted;
    else if (ch === ',' && !quoted) { out.push(cur); cur = ''; }
    else cur += ch;
  }
  out.push(cur);
  return out;
}

function inventory(file) {
  let text;
  try {
    text = execFileSync(cli, ['inspect', file, '--format', 'csv'], { encoding: 'utf8' });
  } catch (e) {
    const why = String(e.stdout || e.message).split('\n').filter((l) => l.startsWith('error:'))[0];
    return { failed: why || 'it failed' };
  }
  const sections = {};
  let name = null, header = null;
  for (const raw of text.split('\n')) {
    const line = raw.trim();
    if (line === '' || line.startsWith('─')) continue;
    if (/^[A-Z ]+$/.test(line)) { name = line; header = null; sections[name] = []; continue; }
    if (name === null || name === 'OVERVIEW') continue;
    if (header === null) { header = cells(line); continue; }
    const row = {};
    cells(line).forEach((v, i) => {
      const column = header[i];
      if (!ignored.has(column) && !(lod && ignoredForLod.has(column))) row[column] = v;
    });
    sections[name].push(row);
  }
  return sections;
}

const input = inventory(files[0]);
// gltf-transform 4.5 cannot read some valid inputs (EXT_mesh_features
// without property tables; an image file that is missing): then there is
// nothing to compare against, which is said, not failed. An output it
// cannot read while it read the input is a failure.
if (input.failed) {
  console.log(`${files[0]}: gltf-transform cannot read it (${input.failed}); inventory not compared`);
  process.exit(0);
}

// The first difference between the input's inventory and OUTPUT's, or null.
function difference(file) {
  const output = inventory(file);
  if (output.failed) return `gltf-transform cannot read it: ${output.failed}`;
  for (const section of new Set([...Object.keys(input), ...Object.keys(output)])) {
    const a = input[section] || [], b = output[section] || [];
    if (a.length !== b.length) return `${section}: ${a.length} rows in the input, ${b.length} in ${file}`;
    for (let i = 0; i < a.length; ++i) {
      if (JSON.stringify(a[i]) !== JSON.stringify(b[i])) {
        return `${section} row ${i}: input ${JSON.stringify(a[i])}\n  output ${JSON.stringify(b[i])}`;
      }
    }
  }
  return null;
}

const count = (s) => (input[s] || []).length;
let same = true;
for (const file of files.slice(1)) {
  const why = difference(file);
  if (why !== null) {
    console.log(`${file}: ${why}`);
    same = false;
  } else {
    console.log(`${file}: same inventory as ${files[0]} (${count('SCENES')} scenes, ${count('MESHES')} meshes, ` +
                `${count('MATERIALS')} materials, ${count('TEXTURES')} textures, ${count('ANIMATIONS')} animations)`);
  }
}
process.exit(same ? 0 : 1);
