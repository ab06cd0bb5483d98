// A static HTTP server on 127.0.0.1 for the page: `/web/...` serves examples/web (the pages and
// node_modules), `/scene/...` the export folder. Pages from http:// avoid file://'s rules for
// module scripts and fetches (docs/external.md, notes in examples/web/README.md).
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';

const kTypes = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
  '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.wasm': 'application/wasm', '.png': 'image/png',
  '.bin': 'application/octet-stream', '.ktx': 'application/octet-stream',
};

function resolveUnder(root, relative) {
  const full = path.resolve(root, '.' + path.posix.normalize('/' + relative));
  return full === root || full.startsWith(root + path.sep) ? full : null;
}

/** Starts the server; resolves to {url, close()}. `mounts` maps a first path segment to a folder. */
export function serve(mounts) {
  const roots = Object.fromEntries(Object.entries(mounts).map(([k, v]) => [k, path.resolve(v)]));
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://127.0.0.1');
    const [, mount, ...rest] = decodeURIComponent(url.pathname).split('/');
    const file = roots[mount] ? resolveUnder(roots[mount], rest.join('/')) : null;
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404, { 'Content-Type': 'text/plain' });
      res.end(`not found: ${url.pathname}`);
      return;
    }
    res.writeHead(200, { 'Content-Type': kTypes[path.extname(file)] || 'application/octet-stream', 'Cache-Control': 'no-store' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      // close() alone waits for the browser's keep-alive connections, which a browser kept open
      // for the next render (a sweep's) never ends.
      const close = () => new Promise((r) => { server.close(r); server.closeAllConnections(); });
      resolve({ url: `http://127.0.0.1:${port}`, close });
    });
  });
}
