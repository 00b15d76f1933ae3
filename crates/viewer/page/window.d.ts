// The page's one global (viewer.js sets it): the page's state and functions, which the
// browser tests (tests/browser/*.mjs) and scripts read and call.
interface Window {
  godelViewer: import('./viewer.js').Viewer;
}
