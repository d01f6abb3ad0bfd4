#!/usr/bin/env node
// Validates a glTF or GLB file with the Khronos glTF validator (the npm package
// `gltf-validator`, pinned in package.json beside this script; install it with
// `npm ci --prefix tests/support`).
//
// Usage: node tests/support/validate-gltf.js <file.glb>
//
// Prints one JSON object: the validator version, numErrors, numWarnings, numInfos,
// numHints, and every message (code, severity, message, pointer). Exits 1 when the
// file has errors, 2 when it cannot be read or validated, 0 otherwise.
'use strict';

const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const SEVERITY = ['error', 'warning', 'info', 'hint'];

async function main() {
  const file = process.argv[2];
  if (!file) {
    console.error('usage: node validate-gltf.js <file.glb>');
    return 2;
  }
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) =>
      Promise.reject(new Error(`external resource not allowed: ${uri}`)),
  });
  const issues = report.issues;
  const summary = {
    validator: report.validatorVersion,
    numErrors: issues.numErrors,
    numWarnings: issues.numWarnings,
    numInfos: issues.numInfos,
    numHints: issues.numHints,
    messages: issues.messages.map((m) => ({
      code: m.code,
      severity: SEVERITY[m.severity] ?? m.severity,
      message: m.message,
      pointer: m.pointer ?? m.offset,
    })),
  };
  console.log(JSON.stringify(summary, null, 2));
  return issues.numErrors > 0 ? 1 : 0;
}

main().then(
  (code) => process.exit(code),
  (error) => {
    console.error(`validation failed: ${error && error.stack ? error.stack : error}`);
    process.exit(2);
  },
);
