// Validates a .glb with the Khronos glTF validator (npm package `gltf-validator`) and
// prints its report's summary and every message; exits 1 if there is any error or warning.
// usage: NODE_PATH=DIR/node_modules node validate.js FILE.glb
const fs = require('fs');
const validator = require('gltf-validator');

const path = process.argv[2];
validator
  .validateBytes(new Uint8Array(fs.readFileSync(path)), { maxIssues: 100 })
  .then((report) => {
    const issues = report.issues;
    console.log(
      `errors ${issues.numErrors} warnings ${issues.numWarnings} infos ${issues.numInfos} hints ${issues.numHints}`
    );
    for (const m of issues.messages) {
      console.log(`${m.severity} ${m.code} ${m.pointer || ''} ${m.message}`);
    }
    process.exit(issues.numErrors + issues.numWarnings > 0 ? 1 : 0);
  })
  .catch((e) => {
    console.log(`the validator failed: ${e}`);
    process.exit(2);
  });
