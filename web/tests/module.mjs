// SPDX-License-Identifier: MIT
// Where the tests find the built site and the native command, and the
// WebAssembly module loaded under node.
import {readFileSync} from 'node:fs';
import {createRequire} from 'node:module';
import {dirname, resolve} from 'node:path';
import {fileURLToPath} from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
export const kRoot = resolve(here, '../..');
export const kSite = resolve(process.env.CALDER_WEB_SITE || resolve(kRoot, 'build-web/web/site'));
export const kNative = resolve(process.env.CALDER_NATIVE || resolve(kRoot, 'build/apps/calder'));

// The module with its .wasm handed over directly (no fetch under node).
export async function loadCore() {
  const require = createRequire(import.meta.url);
  const create = require(resolve(kSite, 'calder-core.js'));
  const core = await create({wasmBinary: readFileSync(resolve(kSite, 'calder-core.wasm'))});
  // Emscripten's node glue rethrows every uncaught error from inside its own
  // source (printing all of it): let node report them itself.
  process.removeAllListeners('uncaughtException');
  process.removeAllListeners('unhandledRejection');
  return core;
}

let failures = 0;
export function check(ok, what) {
  if (ok) {
    console.log(`ok    ${what}`);
  } else {
    failures += 1;
    console.log(`FAIL  ${what}`);
  }
}
export function done() {
  if (failures > 0) {
    console.log(`${failures} failed`);
    process.exit(1);
  }
  console.log('all passed');
}
