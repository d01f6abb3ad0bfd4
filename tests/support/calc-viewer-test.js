// Drives the live-session viewer in headless Chromium (Debian's /usr/bin/chromium
// through playwright-core) against a running `vesselcad serve` of a deficient
// design: once the part <id> is shown, reads its material colour and the
// Calculation panel; then sends the JSON Patch <patch> (which should clear the
// deficiency) through the page and reads them again. Prints one JSON report.
//
// Usage: node calc-viewer-test.js <base-url> <stable-id> <sound-id> <patch-json>
// Exits 2 if anything fails or takes longer than the time limit.

const { chromium } = require('playwright-core');

const [base, id, soundId, patch] = process.argv.slice(2);
const LIMIT_MS = 90_000;
const STEP_MS = 30_000;
setTimeout(() => {
  console.error(`calc-viewer-test: gave up after ${LIMIT_MS} ms`);
  process.exit(2);
}, LIMIT_MS).unref();

(async () => {
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    headless: true,
    timeout: STEP_MS,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    const consoleErrors = [];
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => consoleErrors.push(String(e)));
    await page.goto(base, { timeout: STEP_MS });
    await page.waitForFunction(
      (ids) => window.vesselcad && window.vesselcad.calcRevision >= 0
        && ids.every((i) => window.vesselcad.colour(i) !== null),
      [id, soundId], { timeout: STEP_MS });
    const before = {
      colour: await page.evaluate((i) => window.vesselcad.colour(i), id),
      sound: await page.evaluate((i) => window.vesselcad.colour(i), soundId),
      deficiencies: await page.evaluate(() => window.vesselcad.deficiencies()),
      note: await page.locator('#calc-note').textContent(),
    };
    // A click on the deficiency picks its part.
    await page.locator('#deficiencies li').first().click();
    const picked = await page.locator('#pick').inputValue();
    const status = await page.evaluate(async (body) => {
      const r = await fetch('/edit', { method: 'POST', headers: { 'content-type': 'application/json' }, body });
      return r.status;
    }, patch);
    await page.waitForFunction(() => window.vesselcad.calcRevision >= 1, null, { timeout: STEP_MS });
    await page.waitForFunction((i) => window.vesselcad.colour(i) !== null, id, { timeout: STEP_MS });
    const after = {
      colour: await page.evaluate((i) => window.vesselcad.colour(i), id),
      deficiencies: await page.evaluate(() => window.vesselcad.deficiencies()),
      note: await page.locator('#calc-note').textContent(),
    };
    console.log(JSON.stringify({ before, picked, status, after, consoleErrors }));
  } finally {
    await browser.close();
  }
})().catch((e) => {
  console.error(`calc-viewer-test: ${e.stack || e}`);
  process.exit(2);
});
