#!/usr/bin/env node
// Serves the gaitlab demo with the Vite dev server and web/vite.config.ts, which sends the
// cross-origin isolation headers WASM threads need and serves the WASM build under /wasm/.
//
//   node scripts/serve.mjs            http://localhost:5173/   (PORT and HOST override)
//
// Tests import startServer() to run the same server on a free port.
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createServer } from 'vite';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
export const configFile = path.join(repoDir, 'web', 'vite.config.ts');

/**
 * Starts the dev server. `port: 0` picks a free port. Resolves to `{ url, port, server, close }`;
 * `close()` stops it.
 *
 * @param {{ port?: number, host?: string, quiet?: boolean }} [options]
 */
export async function startServer({ port = 5173, host = '127.0.0.1', quiet = false } = {}) {
  const server = await createServer({
    configFile,
    logLevel: quiet ? 'error' : 'info',
    // A test's server must not reload pages when files change under it, nor open a browser.
    server: { port, host, strictPort: port !== 0, open: false, ...(quiet ? { watch: null, hmr: false } : {}) },
    clearScreen: false,
  });
  await server.listen();
  const address = server.httpServer?.address();
  if (!address || typeof address === 'string') throw new Error('the dev server has no TCP address');
  // 127.0.0.1 and 0.0.0.0 are best shown as localhost (same machine; the name people type).
  const shownHost = host === '127.0.0.1' || host === '0.0.0.0' || host === '::' ? 'localhost' : host;
  return {
    server,
    port: address.port,
    url: `http://${shownHost}:${address.port}/`,
    close: () => server.close(),
  };
}

async function main() {
  const port = process.env.PORT ? Number(process.env.PORT) : 5173;
  if (!Number.isInteger(port) || port < 0 || port > 65535) {
    console.error(`gaitlab: PORT must be a port number, got ${JSON.stringify(process.env.PORT)}`);
    process.exit(1);
  }
  const { url, close } = await startServer({ port, host: process.env.HOST || '127.0.0.1' });
  console.log(`\n  gaitlab demo: ${url}\n`);
  const stop = () => close().finally(() => process.exit(0));
  process.once('SIGINT', stop);
  process.once('SIGTERM', stop);
}

if (process.argv[1] && import.meta.url === pathToFileURL(path.resolve(process.argv[1])).href) {
  main().catch((error) => {
    console.error(`gaitlab: cannot start the server: ${error?.message ?? error}`);
    process.exit(1);
  });
}
