#!/usr/bin/env node
// A static file server on 127.0.0.1 for the example page (module workers and fetch need http:):
//   node serve.mjs [--port 8080] [--mount /PREFIX=FOLDER ...]
// serves this folder at / (the example at /example/) and each FOLDER under its /PREFIX; a file
// asked for with ?chunk=N&ms=M comes N bytes every M milliseconds (a slow network).
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8', '.mjs': 'text/javascript', '.js': 'text/javascript', '.json': 'application/json',
  '.wasm': 'application/wasm', '.glb': 'model/gltf-binary', '.png': 'image/png', '.jpg': 'image/jpeg', '.css': 'text/css',
};

function trickle(bytes, chunk, ms, response) {
  const send = (at) => {
    if (at >= bytes.length || response.destroyed) return response.end();
    response.write(bytes.subarray(at, at + chunk));
    setTimeout(send, ms, at + chunk);
  };
  send(0);
}

// mounts: { '/': folder, '/data': folder, ... }. Resolves to { server, url } once listening.
export function startServer({ mounts, port = 0 }) {
  const prefixes = Object.keys(mounts).sort((a, b) => b.length - a.length);
  const server = http.createServer((request, response) => {
    const pathname = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const prefix = prefixes.find((p) => pathname === p || pathname.startsWith(p.endsWith('/') ? p : `${p}/`));
    let file = null;
    if (prefix !== undefined) {
      const root = path.resolve(mounts[prefix]);
      file = path.resolve(root, `.${pathname.slice(prefix.length).replace(/^\/*/, '/')}`);
      if (file !== root && !file.startsWith(`${root}${path.sep}`)) file = null;
      else if (fs.statSync(file, { throwIfNoEntry: false })?.isDirectory()) file = path.join(file, 'index.html');
    }
    const stat = file && fs.statSync(file, { throwIfNoEntry: false });
    if (!stat?.isFile()) {
      response.writeHead(404, { 'content-type': 'text/plain' }).end('not found\n');
      return;
    }
    response.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream',
                              'content-length': stat.size, 'cache-control': 'no-store' });
    // ?chunk=N&ms=M: N bytes every M milliseconds, as a slow network delivers them.
    const query = new URL(request.url, 'http://localhost').searchParams;
    const chunk = Number(query.get('chunk')), ms = Number(query.get('ms'));
    if (chunk > 0 && ms > 0) trickle(fs.readFileSync(file), chunk, ms, response);
    else fs.createReadStream(file).pipe(response);
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', () => resolve({ server, url: `http://127.0.0.1:${server.address().port}` }));
  });
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const mounts = { '/': path.dirname(fileURLToPath(import.meta.url)) };
  let port = 8080;
  for (let k = 0; k < args.length; ++k) {
    if (args[k] === '--port') port = Number(args[++k]);
    else if (args[k] === '--mount' && /^\/[^=]*=.+/.test(args[k + 1] ?? '')) {
      const [prefix, folder] = args[++k].split(/=(.*)/s);
      mounts[prefix] = folder;
    } else {
      process.stderr.write(`serve.mjs: unknown argument ${args[k]} (usage: node serve.mjs [--port N] [--mount /PREFIX=FOLDER])\n`);
      process.exit(1);
    }
  }
  const { url } = await startServer({ mounts, port });
  process.stdout.write(`${url}/example/\n`);
}
