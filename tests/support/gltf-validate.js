// Validates glTF files with the Khronos glTF validator, for tests/gltf_validator.rs.
//
// Usage: node gltf-validate.js PACKAGE_DIR FILE...
// PACKAGE_DIR is the npm package `gltf-validator`. Prints one JSON object: the
// validator's version and, per file in order, its report (`issues.numErrors`,
// `numWarnings`, `numInfos`, `numHints`, `messages`), or `rejected` with the reason
// where the validator could not read the file at all.
'use strict';
const fs = require('fs');
const path = require('path');

const [packageDir, ...files] = process.argv.slice(2);
const validator = require(path.resolve(packageDir));

async function main() {
  const reports = [];
  for (const file of files) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    try {
      const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0, // every issue
        externalResourceFunction: (uri) => Promise.reject(`no external resource: ${uri}`),
      });
      reports.push({ file: path.basename(file), report });
    } catch (error) {
      reports.push({ file: path.basename(file), rejected: String(error) });
    }
  }
  process.stdout.write(JSON.stringify({ version: validator.version(), reports }) + '\n');
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
