import type { Page } from 'puppeteer-core';

/** Records the page's console errors and uncaught exceptions, from now on, into the returned list. */
export function recordPageErrors(page: Page): string[] {
  const errors: string[] = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push((e as Error).message));
  return errors;
}
