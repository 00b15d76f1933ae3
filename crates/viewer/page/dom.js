// @ts-check
// godel view: the page's elements (index.html), looked up by id or selector with the type the
// page uses them as. One helper for every module, so that an element missing, renamed or of
// another kind fails where it is looked up, saying which, instead of as a null later.
'use strict';

/**
 * @overload
 * @param {string} id
 * @returns {HTMLElement}
 */
/**
 * @template {Element} T
 * @overload
 * @param {string} id
 * @param {{ new (): T, prototype: T }} type
 * @returns {T}
 */
/**
 * The element with id `id`, of class `type` (HTMLElement unless said).
 * @param {string} id
 * @param {{ new (): Element, prototype: Element }} [type]
 * @returns {Element}
 */
export function $(id, type = HTMLElement) {
  const element = document.getElementById(id);
  if (!(element instanceof type)) throw new Error(`the page has no ${type.name} #${id}`);
  return element;
}

/**
 * @overload
 * @param {string} selector
 * @returns {HTMLElement}
 */
/**
 * @template {Element} T
 * @overload
 * @param {string} selector
 * @param {{ new (): T, prototype: T }} type
 * @returns {T}
 */
/**
 * The first element `selector` finds, of class `type` (HTMLElement unless said).
 * @param {string} selector
 * @param {{ new (): Element, prototype: Element }} [type]
 * @returns {Element}
 */
export function query(selector, type = HTMLElement) {
  const element = document.querySelector(selector);
  if (!(element instanceof type)) throw new Error(`the page has no ${type.name} ${selector}`);
  return element;
}
