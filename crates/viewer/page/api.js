// @ts-check
// godel view: the page's requests to the viewer's server (crates/viewer/src/*_routes.rs, their
// JSON typed in contract.d.ts). Every refusal is read into a message one way (errorText: the
// server's `{"error": …}`, which names the field); the fetches here throw it, with the status
// (410: an explore frame replaced meanwhile, 503: the server busy), as an HttpError.
'use strict';

// A 503 (the server busy with other tabs or scripts) is retried this many times, waiting a
// little longer each time (about 10 s in all), then shown as an error.
const BUSY_RETRIES = 20;

/** A request the server refused: its message and HTTP status. */
export class HttpError extends Error {
  /**
   * @param {string} message
   * @param {number} status
   */
  constructor(message, status) {
    super(message);
    this.status = status;
  }
}

/**
 * The message of anything thrown: an Error's, else the thing as text.
 * @param {unknown} e
 * @returns {string}
 */
export const messageOf = (e) => (e instanceof Error && e.message ? e.message : String(e));

/**
 * The message of a refused request: the server's `{"error": …}` (contract.d.ts, ApiError),
 * else the status and whatever the body says.
 * @param {Response} response
 * @returns {Promise<string>}
 */
export async function errorText(response) {
  const text = await response.text();
  try {
    const { error } = JSON.parse(text);
    if (typeof error === 'string' && error !== '') return error;
  } catch (_) { /* not JSON */ }
  return `${response.status} ${response.statusText}${text ? `: ${text}` : ''}`;
}

/**
 * `response` where it succeeded; else throws what the server said, `what` before it.
 * @param {Response} response
 * @param {string} [what]
 * @returns {Promise<Response>}
 */
export async function ok(response, what) {
  if (response.ok) return response;
  const message = await errorText(response);
  throw new HttpError(what ? `${what}: ${message}` : message, response.status);
}

/** @param {number} ms */
const sleep = (ms) => new Promise((resolve) => { setTimeout(resolve, ms); });

/**
 * `fetch(url, init)`, asked again while the server answers 503 (busy), at most BUSY_RETRIES
 * times.
 * @param {string} url
 * @param {RequestInit} [init]
 * @returns {Promise<Response>}
 */
export async function fetchPatiently(url, init) {
  let response = await fetch(url, init);
  for (let k = 1; response.status === 503 && k <= BUSY_RETRIES; k += 1) {
    await sleep(50 * k);
    response = await fetch(url, init);
  }
  return response;
}

/**
 * The JSON `url` answers (of the type contract.d.ts gives the route: the caller names it),
 * asked again while the server is busy; a refusal throws, naming the URL.
 * @param {string} url
 * @returns {Promise<unknown>}
 */
export async function getJson(url) {
  return (await ok(await fetchPatiently(url), url)).json();
}

/**
 * The text `url` answers; a refusal throws, naming the URL.
 * @param {string} url
 * @returns {Promise<string>}
 */
export async function getText(url) {
  return (await ok(await fetch(url), url)).text();
}

/**
 * POSTs `body` to `url` as JSON (a string as it is, else JSON.stringify's): the response,
 * refused or not (the caller reads it: a picture, a download, a 204 or a 410). `patient`:
 * asked again while the server is busy.
 * @param {string} url
 * @param {unknown} body
 * @param {{ patient?: boolean }} [options]
 * @returns {Promise<Response>}
 */
export function postJson(url, body, { patient = false } = {}) {
  const init = {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: typeof body === 'string' ? body : JSON.stringify(body),
  };
  return patient ? fetchPatiently(url, init) : fetch(url, init);
}

/**
 * POSTs `body` as JSON to `url` and resolves to the JSON answered (of the type contract.d.ts
 * gives the route); a refusal throws what the server said.
 * @param {string} url
 * @param {unknown} body
 * @returns {Promise<unknown>}
 */
export async function exchangeJson(url, body) {
  return (await ok(await postJson(url, body))).json();
}
