// Cross-origin isolation: how a page of gaitlab gets it, and the one reload that completes it on
// a static host.
//
// WASM threads and the shared render buffer need SharedArrayBuffer, which browsers allow only in
// a cross-origin isolated page: one sent with "Cross-Origin-Opener-Policy: same-origin" and
// "Cross-Origin-Embedder-Policy: require-corp". `npm start` sends those headers. A static host
// that cannot is served by coi-serviceworker (vite.config.ts puts its script first in <head>): it
// installs a service worker that adds the headers to every response, then reloads the page once.
//
// That reload can be missed. On a first visit coi-serviceworker reloads as soon as its worker
// *starts* installing (its 'updatefound' listener). If installing takes longer than the reload
// (a busy machine), the reloaded page loads without the worker, registers again, finds it still
// installing, and gets no second 'updatefound': nothing reloads it. The worker then takes the page
// over (clients.claim()) while it stays unisolated, and waits forever. reloadWhenControlled()
// closes that gap: an unisolated page reloads when a worker takes it over.

/** How the page got isolation: the server's headers, coi-serviceworker, or not at all. */
export type IsolationMode = 'headers' | 'service worker' | 'none';

export function isolationMode(): IsolationMode {
  if (!window.crossOriginIsolated) return 'none';
  return navigator.serviceWorker?.controller?.scriptURL.includes('coi-serviceworker') ? 'service worker' : 'headers';
}

/**
 * Marks a reload made here because the page was already controlled yet unisolated, for the rest
 * of the tab's session: if the page is still unisolated after it, the worker does not add the
 * headers, and reloading again would loop for ever. Cleared once the page is isolated.
 */
const RELOADED_KEY = 'gaitlab.isolation-reload';

/**
 * On a page that is not isolated, in a browser that may install the service worker: reloads when
 * a service worker takes the page over ('controllerchange', which comes once per new worker, so
 * cannot loop), or at once if one already controls it (once per session, see RELOADED_KEY).
 */
export function reloadWhenControlled(): void {
  const workers = navigator.serviceWorker;
  try {
    if (window.crossOriginIsolated) {
      sessionStorage.removeItem(RELOADED_KEY);
      return;
    }
    if (!workers || !window.isSecureContext) return;
    if (!workers.controller) {
      workers.addEventListener('controllerchange', () => location.reload(), { once: true });
      return;
    }
    if (sessionStorage.getItem(RELOADED_KEY)) return;
    sessionStorage.setItem(RELOADED_KEY, '1');
    location.reload();
  } catch {
    // sessionStorage refused (some private modes): without the guard, no reload of a controlled
    // page; the page explains itself instead (main.ts).
  }
}
