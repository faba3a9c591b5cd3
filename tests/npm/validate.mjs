// Validates .gltf and .glb files with Khronos's glTF validator (npm
// gltf-validator), external buffers and images read from each file's
// folder. Prints each file's error count and each error; exits 1 when a
// file has an error, 77 (CTest's skip code here) when the validator is not
// installed, 2 on bad usage or an unreadable file. Several files share one
// node start and one validation of the baseline.
//
//   node validate.mjs [--modules NPM_DIR] [--allow-missing URI]... [--baseline INPUT] FILE...
//
// --modules: the folder `make npm-deps` installed the packages into
// (default: $LODBAKE_NPM_DIR, else this script's folder).
// --allow-missing URI: the one error accepted, the validator's IO_ERROR for
// an image or buffer whose file is absent, for this URI only (an input that
// named a missing image: the writer keeps the reference; see docs/export.md).
// --baseline INPUT: the file lodbake read to write FILE; errors of a kind
// (code) INPUT already has are inherited, not lodbake's, and accepted
// (CesiumMan's input has weights that do not sum to 1: lodbake keeps every
// value as it is).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

function usage(message) {
  console.error(`Error: ${message}\n` +
                'usage: node validate.mjs [--modules DIR] [--allow-missing URI]... [--baseline INPUT] FILE...');
  process.exit(2);
}

let modules = process.env.LODBAKE_NPM_DIR || path.dirname(fileURLToPath(import.meta.url));
const allowMissing = new Set();
let baseline = null;
const files = [];
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--modules' && i + 1 < args.length) modules = args[++i];
  else if (args[i] === '--allow-missing' && i + 1 < args.length) allowMissing.add(args[++i]);
  else if (args[i] === '--baseline' && i + 1 < args.length) baseline = args[++i];
  else if (args[i].startsWith('--')) usage(`unknown option ${args[i]}`);
  else files.push(args[i]);
}
if (files.length === 0) usage('no file given');

let validator;
try {
  validator = createRequire(path.join(path.resolve(modules), 'package.json'))('gltf-validator');
} catch (e) {
  console.error(`Warning: gltf-validator is not installed in ${modules} (run make npm-deps): skipped`);
  process.exit(77);
}

async function validate(name) {
  let bytes;
  try {
    bytes = new Uint8Array(fs.readFileSync(name));
  } catch (e) {
    console.error(`Error: ${name}: ${e.message}`);
    process.exit(2);
  }
  const folder = path.dirname(path.resolve(name));
  return validator.validateBytes(bytes, {
    uri: path.basename(name),
    maxIssues: 0,  // no limit
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(folder, decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
}

const inherited = new Set();
if (baseline !== null) {
  for (const m of (await validate(baseline)).issues.messages)
    if (m.severity === 0) inherited.add(m.code);
}

// Prints FILE's report; true when it has no error but accepted ones.
async function check(file) {
  const report = await validate(file);
  // The resource each pointer names ("/images/0" -> "Lantern_baseColor.png"),
  // to tell the accepted missing-file errors from any other.
  const uriOf = new Map();
  for (const resource of (report.info && report.info.resources) || []) {
    if (resource.uri !== undefined) uriOf.set(resource.pointer, resource.uri);
  }
  const accepted = (m) => inherited.has(m.code) ||
    m.code === 'IO_ERROR' && m.pointer !== undefined && m.pointer.endsWith('/uri') &&
    allowMissing.has(decodeURIComponent(uriOf.get(m.pointer.slice(0, -4)) || ''));

  const errors = report.issues.messages.filter((m) => m.severity === 0);
  const failing = errors.filter((m) => !accepted(m));
  console.log(`${file}: ${failing.length} errors (${errors.length - failing.length} accepted), ` +
              `${report.issues.numWarnings} warnings, validator ${report.validatorVersion}`);
  for (const m of errors) {
    console.log(`  ${accepted(m) ? 'accepted' : 'error'} ${m.code} at ${m.pointer || '/'}: ${m.message}`);
  }
  for (const m of report.issues.messages.filter((w) => w.severity === 1)) {
    console.log(`  warning ${m.code} at ${m.pointer || '/'}: ${m.message}`);
  }
  return failing.length === 0;
}

let clean = true;
for (const file of files) clean = (await check(file)) && clean;
process.exit(clean ? 0 : 1);
