#!/usr/bin/env node
// Validates glTF/GLB files with the Khronos glTF-Validator (npm package `gltf-validator`).
//
//   node tools/validate_gltf.js FILE...   one line per file:
//                                         "FILE: errors E warnings W infos I hints H",
//                                         then one line per error and warning
//   node tools/validate_gltf.js --check   exits 0 if the validator package can be loaded
//
// The package is looked up from this folder (tools/node_modules, installed by tools/setup.sh or
// `cd tools && npm install --no-save gltf-validator`).
// Exit status: 0 when no file has errors, 1 when some file has errors or cannot be read,
// 2 on bad usage, 3 when the gltf-validator package is not installed.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate_gltf: the npm package gltf-validator is not installed (' +
                'cd tools && npm install --no-save gltf-validator)');
  process.exit(3);
}

const args = process.argv.slice(2);
if (args.length === 1 && args[0] === '--check') {
  console.log('gltf-validator ' + validator.version());
  process.exit(0);
}
if (args.length === 0) {
  console.error('usage: node tools/validate_gltf.js FILE... | --check');
  process.exit(2);
}

async function validate(file) {
  const bytes = fs.readFileSync(file);
  const report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)),
                  (err, data) => err ? reject(err.toString()) : resolve(new Uint8Array(data)));
    }),
  });
  const issues = report.issues;
  console.log(`${file}: errors ${issues.numErrors} warnings ${issues.numWarnings} ` +
              `infos ${issues.numInfos} hints ${issues.numHints}`);
  for (const m of issues.messages) {
    if (m.severity <= 1) {
      console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ` +
                  m.message);
    }
  }
  return issues.numErrors;
}

(async () => {
  let failed = 0;
  for (const file of args) {
    try {
      if (await validate(file) > 0) failed++;
    } catch (e) {
      console.log(`${file}: cannot validate: ${e}`);
      failed++;
    }
  }
  process.exit(failed > 0 ? 1 : 0);
})();
