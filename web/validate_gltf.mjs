// Validates glTF files with the Khronos glTF-Validator (npm gltf-validator):
//   node web/validate_gltf.mjs FILE.glb|FILE.gltf...
// Prints one line per file (its error, warning, info and hint counts, then each error) and
// exits 1 when any file has an error. The meshsal tests run it on every glTF they write.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) => readFile(path.join(path.dirname(file), decodeURIComponent(uri))),
  });
  const n = report.issues;
  console.log(`${file}: ${n.numErrors} errors, ${n.numWarnings} warnings, ${n.numInfos} infos, ${n.numHints} hints`);
  for (const m of n.messages) {
    if (m.severity === 0) console.log(`  error ${m.code} at ${m.pointer ?? ''}: ${m.message}`);
    else if (m.severity === 1) console.log(`  warning ${m.code} at ${m.pointer ?? ''}: ${m.message}`);
  }
  if (n.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
