// gltfpack's plain copy (`gltfpack -i A -o B.glb -noq`) timed inside one node
// process: the library (npm gltfpack's library.js) compiles its wasm once,
// then each asset is packed --runs times and the best time kept, so neither
// node's start-up nor the wasm compilation is in the figure. Each pack reads
// its input and writes its output through the file system, as the CLI does,
// each run to a new file (replacing a file just written costs more on ext4;
// bench_assets's lodbake runs are set up alike).
//
//   node gltfpack_copy.mjs --modules NPM_DIR --out DIR [--runs N] [--arg A]... FILE...
//
// Each --arg is appended to the pack's arguments (bench_attributes times a
// simplifying pack, e.g. --arg -si --arg 0.5, the same way).
//
// Prints tab-separated lines for bench_assets to read:
//   init   <ms to load and compile the wasm>
//   ok     <file> <best ms> <output bytes> <bytes read>
//   failed <file> <gltfpack's message, first line>
// Exits 77 when gltfpack is not installed in NPM_DIR, 2 on bad usage.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

function usage(message) {
  console.error(`Error: ${message}\nusage: node gltfpack_copy.mjs --modules DIR --out DIR [--runs N] [--arg A]... FILE...`);
  process.exit(2);
}

let modules = null;
let out = null;
let runs = 5;
const extra = [];
const files = [];
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--out' && i + 1 < args.length) out = args[++i];
  else if (args[i] === '--runs' && i + 1 < args.length) runs = Math.max(1, parseInt(args[++i], 10) || 1);
  else if (args[i] === '--arg' && i + 1 < args.length) extra.push(args[++i]);
  else if (args[i].startsWith('--')) usage(`unknown option ${args[i]}`);
  else files.push(args[i]);
}
if (modules === null || out === null || files.length === 0) usage('--modules, --out and a file are needed');

const library = path.join(modules, 'node_modules', 'gltfpack', 'library.js');
if (!fs.existsSync(library)) {
  console.error(`gltfpack is not installed in ${modules} (make npm-deps)`);
  process.exit(77);
}

// The library starts compiling its wasm when imported; the first pack()
// waits for it, so an empty call isolates that cost.
let start = performance.now();
const { pack } = await import(pathToFileURL(library).href);
await pack(['-v'], { read: () => null, write: () => {} }).catch(() => {});
console.log(`init\t${(performance.now() - start).toFixed(3)}`);

for (const [index, file] of files.entries()) {
  const input = path.resolve(file);
  const stem = `${index}-${path.basename(file).replace(/\.[^.]*$/, '')}`;
  const outputOf = (run) => path.join(path.resolve(out), `${stem}.gltfpack.r${run}.glb`);
  let bytesRead = 0;
  const iface = {
    read: (name) => {
      const data = fs.readFileSync(name);
      bytesRead += data.length;
      return data;
    },
    write: (name, data) => fs.writeFileSync(name, data),
  };
  let best = Infinity;
  let failure = null;
  let first = null;
  for (let r = 0; r < runs && failure === null; ++r) {
    bytesRead = 0;
    start = performance.now();
    try {
      await pack(['-i', input, '-o', outputOf(r), '-noq', ...extra], iface);
    } catch (err) {
      // "Error loading <input>: why" names the file; the caller prints it.
      failure = String(err.message).trim().split('\n')[0].replace(`Error loading ${input}: `, '');
      break;
    }
    best = Math.min(best, performance.now() - start);
    // One wasm instance serves every call; a copy that changed between runs
    // would mean state leaking from one pack to the next.
    const written = fs.readFileSync(outputOf(r));
    if (first === null) first = written;
    else if (!first.equals(written)) failure = 'output differs between runs';
    if (r > 0) fs.unlinkSync(outputOf(r));
  }
  if (failure !== null) console.log(`failed\t${file}\t${failure}`);
  else console.log(`ok\t${file}\t${best.toFixed(3)}\t${first.length}\t${bytesRead}`);
}
