#!/usr/bin/env node
// SPDX-License-Identifier: MIT
// A static file server on 127.0.0.1 for the built site (and the benchmark's
// pages): `node tools/serve.mjs FOLDER [PORT]`. GET and HEAD only, no
// listings, nothing outside FOLDER.
import {createServer} from 'node:http';
import {readFile, stat} from 'node:fs/promises';
import {extname, join, normalize, resolve, sep} from 'node:path';
import {fileURLToPath} from 'node:url';

const kTypes = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.toml': 'text/plain; charset=utf-8',
  '.png': 'image/png',
  '.json': 'application/json',
};

// Serves the folders of `mounts` ({'/': folder, '/p5/': other}) and resolves
// to the running server once it listens (port 0: any free port).
export function serve(mounts, port = 0) {
  if (typeof mounts === 'string') mounts = {'/': mounts};
  const prefixes = Object.keys(mounts).sort((a, b) => b.length - a.length);
  const server = createServer(async (request, response) => {
    try {
      if (request.method !== 'GET' && request.method !== 'HEAD') {
        response.writeHead(405).end();
        return;
      }
      const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
      const prefix = prefixes.find((p) => path.startsWith(p));
      const root = resolve(mounts[prefix]);
      let file = normalize(join(root, path.slice(prefix.length)));
      if (file !== root && !file.startsWith(root + sep)) {
        response.writeHead(403).end();
        return;
      }
      if ((await stat(file)).isDirectory()) file = join(file, 'index.html');
      const body = await readFile(file);
      response.writeHead(200, {
        'Content-Type': kTypes[extname(file)] || 'application/octet-stream',
        'Cache-Control': 'no-store',
      });
      response.end(request.method === 'HEAD' ? undefined : body);
    } catch {
      response.writeHead(404, {'Content-Type': 'text/plain'}).end('not found\n');
    }
  });
  return new Promise((done, fail) => {
    server.once('error', fail);
    server.listen(port, '127.0.0.1', () => done(server));
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const folder = process.argv[2];
  if (!folder) {
    console.error('usage: node tools/serve.mjs FOLDER [PORT]');
    process.exit(2);
  }
  const server = await serve(folder, Number(process.argv[3] || 8000));
  console.log(`serving ${folder} on http://127.0.0.1:${server.address().port}/`);
}
