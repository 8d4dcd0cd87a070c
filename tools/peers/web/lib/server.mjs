// A tiny HTTP server on 127.0.0.1 for the page: module scripts and import maps do not load from file://,
// and nothing may come from a CDN. It serves only fixed places: the page folder, node_modules, three
// CommonJS files that vtk.js imports (wrapped as ES modules), and the scene's data under fixed names
// (/data/...), so that no name from the card ever appears in a URL or in page source.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';

const WEB_DIR = path.resolve(path.dirname(new URL(import.meta.url).pathname), '..');
const ROOTS = { '/page/': path.join(WEB_DIR, 'page'), '/node_modules/': path.join(WEB_DIR, 'node_modules') };

// vtk.js's ES modules import these CommonJS packages by bare name; the import map points them here.
const COMMONJS = {
  'fast-deep-equal': 'fast-deep-equal/index.js',
  seedrandom: 'seedrandom/seedrandom.js',
  'spark-md5': 'spark-md5/spark-md5.js',
};

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json' };

// A CommonJS file as an ES module: module and exports exist, require finds nothing (seedrandom's optional
// require('crypto') is in a try block), and module.exports is the default export.
function wrapCommonJS(source) {
  return 'const module = { exports: {} }; const exports = module.exports;\n' +
    'const require = (name) => { throw new Error("no require in the browser: " + name); };\n' +
    `${source}\nexport default module.exports;\n`;
}

function fileUnder(root, rest) {
  const file = path.resolve(root, '.' + path.posix.normalize('/' + rest));
  return file.startsWith(root + path.sep) ? file : null;
}

// data: { '/data/NAME': Buffer }. Returns { origin, close }.
export async function startServer(data = {}) {
  const server = http.createServer((req, res) => {
    let body = null;
    let type = 'application/octet-stream';
    const url = decodeURIComponent(new URL(req.url, 'http://127.0.0.1').pathname);
    if (url === '/') {
      body = fs.readFileSync(path.join(ROOTS['/page/'], 'index.html'));
      type = TYPES['.html'];
    } else if (Object.hasOwn(data, url)) {
      body = data[url];
    } else if (url.startsWith('/cjs/') && Object.hasOwn(COMMONJS, url.slice(5))) {
      body = wrapCommonJS(fs.readFileSync(path.join(ROOTS['/node_modules/'], COMMONJS[url.slice(5)]), 'utf8'));
      type = TYPES['.js'];
    } else {
      for (const [prefix, root] of Object.entries(ROOTS)) {
        if (!url.startsWith(prefix)) continue;
        const file = fileUnder(root, url.slice(prefix.length));
        if (file && fs.existsSync(file) && fs.statSync(file).isFile()) {
          body = fs.readFileSync(file);
          type = TYPES[path.extname(file)] ?? type;
        }
      }
    }
    if (body === null && url === '/favicon.ico') {
      res.writeHead(204).end(); // asked for by Chromium on every page: not an error of the page's
      return;
    }
    if (body === null) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'Content-Type': type, 'Cache-Control': 'no-store' }).end(body);
  });
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', resolve);
  });
  return {
    origin: `http://127.0.0.1:${server.address().port}`,
    close: () => new Promise((resolve) => {
      server.closeAllConnections();
      server.close(resolve);
    }),
  };
}
