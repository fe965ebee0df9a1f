// Validates glTF/GLB files with the Khronos glTF-Validator (npm `gltf-validator`, pinned in
// package-lock.json; install with `npm ci --prefix tests/js`). Prints one JSON array: for each
// file, the validator's report (issues with every message, info) plus `file` and
// `validatorVersion`. Exits 2 when the validator is not installed or rejects a file outright.
"use strict";
const fs = require("fs");

let validator;
try {
    validator = require("gltf-validator");
} catch (e) {
    console.error("gltf-validator is not installed: run `npm ci --prefix tests/js`");
    process.exit(2);
}

async function main() {
    const reports = [];
    for (const file of process.argv.slice(2)) {
        const bytes = new Uint8Array(fs.readFileSync(file));
        const report = await validator.validateBytes(bytes, {
            uri: file,
            maxIssues: 0,
            writeTimestamp: false,
        });
        report.file = file;
        report.validatorVersion = validator.version();
        reports.push(report);
    }
    console.log(JSON.stringify(reports));
}

main().catch((e) => {
    console.error(`glTF-Validator failed: ${e}`);
    process.exit(2);
});
