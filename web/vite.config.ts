// Vite configuration of the gaitlab front end (root: web/).
//
// The WASM module uses pthreads, i.e. a SharedArrayBuffer, which browsers only hand out to
// cross-origin isolated pages. So every response — page, scripts, the sim worker, the WASM
// module and its pthread worker script — carries COOP/COEP (and CORP, which require-corp asks of
// every subresource). Without them `crossOriginIsolated` is false and the simulation cannot start.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import type { Connect, Plugin } from 'vite';
import { defineConfig } from 'vite';

const webDir = path.dirname(fileURLToPath(import.meta.url));
const repoDir = path.resolve(webDir, '..');

/** Where the lead's build puts the browser WASM module (gaitlab.mjs, .wasm, .worker.js). */
export const wasmDir = process.env.GAITLAB_WASM_DIR
  ? path.resolve(process.env.GAITLAB_WASM_DIR)
  : path.join(repoDir, 'build', 'wasm');

/** The browser build's files. The Node build (gaitlab-node.*) is not served. */
const wasmFiles = ['gaitlab.mjs', 'gaitlab.wasm', 'gaitlab.worker.js'];

/**
 * The jolt-physics package's two builds that the performance page's peer section compares with
 * (web/src/bench/peers.ts): the SIMD multithreaded one and the default one. Served as they are
 * under /jolt, like gaitlab's module: each finds its .wasm (and the multithreaded one its pthread
 * workers, itself) relative to its own URL, which bundling would break.
 */
const joltDir = path.join(repoDir, 'node_modules', 'jolt-physics', 'dist');
const joltFiles = ['jolt-physics.multithread.wasm.js', 'jolt-physics.multithread.wasm.wasm', 'jolt-physics.wasm.js', 'jolt-physics.wasm.wasm'];

export const isolationHeaders: Record<string, string> = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
  'Cross-Origin-Resource-Policy': 'same-origin',
};

const mimeTypes: Record<string, string> = {
  '.mjs': 'text/javascript; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
};

/**
 * Serves `/wasm/*` from build/wasm in dev, and copies those files to `<outDir>/wasm/` in a build;
 * the same for `/jolt/*` (joltFiles). The module is loaded at run time by the sim worker (a
 * dynamic import Vite must not touch), so it is not part of the module graph; this plugin is what
 * makes it reachable.
 */
function gaitlabWasm(): Plugin {
  const serveFrom = (dir: string): Connect.NextHandleFunction => (req, res, next) => {
    // Mounted at /wasm (or /jolt), so req.url is "/gaitlab.mjs" (plus maybe a query string).
    const name = decodeURIComponent((req.url ?? '').split('?')[0]).replace(/^\/+/, '');
    const type = mimeTypes[path.extname(name)];
    if (!type || name.includes('/') || name.includes('\\')) return next();
    const file = path.join(dir, name);
    fs.stat(file, (statError, stat) => {
      if (statError || !stat.isFile()) {
        // A plain 404 with the reason, rather than falling through to an HTML page that the
        // browser would then fail to parse as JavaScript.
        res.writeHead(404, { 'Content-Type': 'text/plain; charset=utf-8', ...isolationHeaders });
        res.end(`gaitlab: ${file} does not exist; build the WASM module first (npm run build)\n`);
        return;
      }
      res.writeHead(200, {
        'Content-Type': type,
        'Content-Length': String(stat.size),
        // The module is rebuilt under the same name: never let the browser keep an old copy.
        'Cache-Control': 'no-cache',
        ...isolationHeaders,
      });
      if (req.method === 'HEAD') return void res.end();
      fs.createReadStream(file).pipe(res);
    });
  };

  return {
    name: 'gaitlab-wasm',
    configureServer(server) {
      server.middlewares.use('/wasm', serveFrom(wasmDir));
      server.middlewares.use('/jolt', serveFrom(joltDir));
    },
    generateBundle() {
      for (const [dir, files, folder] of [[wasmDir, wasmFiles, 'wasm'], [joltDir, joltFiles, 'jolt']] as const) {
        for (const name of files) {
          const file = path.join(dir, name);
          if (!fs.existsSync(file)) {
            this.error(`gaitlab: ${file} does not exist; build the WASM module (and install the packages) before the web page`);
          }
          this.emitFile({ type: 'asset', fileName: `${folder}/${name}`, source: fs.readFileSync(file) });
        }
      }
    },
  };
}

/**
 * coi-serviceworker (from node_modules) at the site root, for static hosts that cannot send
 * COOP/COEP: the page loads it first (index.html); when the page is not cross-origin isolated it
 * installs itself as a service worker that adds the headers to every response, and reloads once.
 * With the headers already present (npm start) it does nothing.
 */
function coiServiceWorker(): Plugin {
  const file = path.join(repoDir, 'node_modules', 'coi-serviceworker', 'coi-serviceworker.min.js');
  const name = 'coi-serviceworker.js';
  return {
    name: 'gaitlab-coi-serviceworker',
    configureServer(server) {
      server.middlewares.use(`/${name}`, (_req, res) => {
        res.writeHead(200, { 'Content-Type': 'text/javascript; charset=utf-8', 'Cache-Control': 'no-cache', ...isolationHeaders });
        fs.createReadStream(file).pipe(res);
      });
    },
    generateBundle() {
      this.emitFile({ type: 'asset', fileName: name, source: fs.readFileSync(file) });
    },
    // A classic script, first in <head>, before anything else loads: on a host without COOP/COEP
    // it installs the service worker and reloads; with the headers it does nothing. (Injected
    // here rather than written in index.html, where Vite would try to bundle it.)
    transformIndexHtml() {
      return [{ tag: 'script', attrs: { src: name }, injectTo: 'head-prepend' }];
    },
  };
}

export default defineConfig({
  root: webDir,
  // Relative URLs in the built page, so it works from any folder of a static host.
  base: './',
  publicDir: path.join(repoDir, 'public'),
  // Several HTML entry points (the demo, index.html, and the performance page, bench.html); no
  // SPA fallback, so a missing file is a 404 instead of the demo page.
  appType: 'mpa',
  plugins: [gaitlabWasm(), coiServiceWorker()],
  server: { headers: isolationHeaders },
  preview: { headers: isolationHeaders },
  worker: {
    // The sim worker is a module worker: it imports the ES6 WASM glue dynamically.
    format: 'es',
  },
  optimizeDeps: {
    // Pre-bundle three (and uPlot: the optimize panel, the performance page) up front so the dev
    // server never reloads the page mid-run to add it.
    include: ['three', 'three/examples/jsm/controls/OrbitControls.js', 'uplot'],
  },
  build: {
    outDir: path.join(repoDir, 'build', 'web'),
    emptyOutDir: true,
    target: 'es2022',
    // three.js alone is about 550 kB minified; one chunk is fine for this page.
    chunkSizeWarningLimit: 800,
    rolldownOptions: {
      input: {
        index: path.join(webDir, 'index.html'),
        bench: path.join(webDir, 'bench.html'),
      },
    },
  },
});
