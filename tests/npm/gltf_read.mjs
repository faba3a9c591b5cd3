// Reads a .gltf or .glb into a glTF-Transform Document (npm
// @gltf-transform/core and extensions, Draco decoded by draco3dgltf), for
// the checks that compare what lodbake wrote with its input
// (same_triangles.mjs, same_inventory.mjs). Two differences from
// `gltf-transform inspect`'s reader, both so that every shared asset reads:
// an image file that is missing is read as a 1x1 grey PNG (Lantern names
// one; inspect() needs an image it can size), and
// EXT_mesh_features / EXT_structural_metadata are left unregistered, so
// they are unknown extensions (gltf-transform 4.5 fails on
// EXT_mesh_features without property tables, BoxMetaDraco's) and their
// feature-id attributes are plain attributes.
//
//   const reader = await openReader(NPM_DIR);  // null: not installed
//   const doc = await reader.read(FILE);
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const metadata = new Set(['EXT_mesh_features', 'EXT_structural_metadata']);
const placeholder = Buffer.from('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAAAAAA6fptVAAAACklEQVR4nGNgAAAAAgABSK+kcQAAAABJRU5ErkJggg==',
                                'base64');

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

export async function openReader(modules) {
  let core, extensions, functions, draco3d;
  try {
    const require = createRequire(path.join(path.resolve(modules), 'package.json'));
    core = await import(require.resolve('@gltf-transform/core'));
    extensions = await import(require.resolve('@gltf-transform/extensions'));
    functions = await import(require.resolve('@gltf-transform/functions'));
    draco3d = require('draco3dgltf');
  } catch (e) {
    return null;
  }
  const io = new core.NodeIO()
    .setLogger(new core.Logger(core.Logger.Verbosity.ERROR))
    .registerExtensions(extensions.ALL_EXTENSIONS.filter((e) => !metadata.has(e.EXTENSION_NAME)))
    .registerDependencies({ 'draco3d.decoder': await draco3d.createDecoderModule() });

  // The JSON with its external files beside it (a GLB's BIN chunk too).
  async function read(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const { json, bin } = file.endsWith('.glb') ? glbChunks(bytes)
                                                : { json: JSON.parse(new TextDecoder().decode(bytes)), bin: null };
    const resources = {};
    if (bin !== null) resources['@glb.bin'] = bin;  // gltf-transform's name for the GLB buffer
    const external = (uri) => path.join(path.dirname(file), decodeURIComponent(uri));
    for (const buffer of json.buffers || []) {
      if (buffer.uri !== undefined && !buffer.uri.startsWith('data:')) {
        resources[buffer.uri] = new Uint8Array(fs.readFileSync(external(buffer.uri)));
      }
    }
    for (const image of json.images || []) {
      if (image.uri !== undefined && !image.uri.startsWith('data:')) {
        const where = external(image.uri);
        resources[image.uri] = new Uint8Array(fs.existsSync(where) ? fs.readFileSync(where) : placeholder);
      }
    }
    return io.readJSON({ json, resources });
  }
  return { core, functions, read };
}
