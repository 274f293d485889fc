#!/usr/bin/env node
// Runs the Khronos glTF validator (npm package gltf-validator, pinned in package.json) on one
// .gltf or .glb file and prints a summary and every message.
//
//   node tools/gltf-validate/validate.js FILE
//
// Exit status: 0 when the report has no errors and no warnings (infos and hints are printed but
// allowed), 1 when it has any, 2 when the file cannot be read or the validator cannot run.
'use strict';

const fs = require('fs');
const path = require('path');

const severities = ['error', 'warning', 'info', 'hint'];

async function main(argv) {
  if (argv.length !== 1) {
    console.error('usage: validate.js FILE.gltf|FILE.glb');
    return 2;
  }
  const file = argv[0];
  let validator;
  try {
    validator = require('gltf-validator');
  } catch (error) {
    console.error(`validate.js: gltf-validator is not installed (run npm ci in ${__dirname}): ${error.message}`);
    return 2;
  }
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (error) {
    console.error(`${file}: ${error.message}`);
    return 2;
  }
  let report;
  try {
    report = await validator.validateBytes(new Uint8Array(bytes), {
      uri: path.basename(file),
      maxIssues: 0,
      writeTimestamp: false,
      // Buffers and images in other files, resolved beside the asset.
      externalResourceFunction: (uri) =>
        fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((data) => new Uint8Array(data)),
    });
  } catch (error) {
    console.error(`${file}: the validator could not run: ${error}`);
    return 2;
  }
  const issues = report.issues;
  console.log(`${file}: glTF validator ${report.validatorVersion}: ${issues.numErrors} errors, ` +
              `${issues.numWarnings} warnings, ${issues.numInfos} infos, ${issues.numHints} hints`);
  for (const message of issues.messages) {
    const where = message.pointer !== undefined ? message.pointer : `byte ${message.offset}`;
    console.log(`  ${severities[message.severity] || message.severity} ${message.code} at ${where}: ${message.message}`);
  }
  return issues.numErrors > 0 || issues.numWarnings > 0 ? 1 : 0;
}

main(process.argv.slice(2)).then((code) => { process.exitCode = code; });
