// Drives the viewer's History panel in headless Chromium (Debian's
// /usr/bin/chromium through playwright-core) against a running `vesselcad serve`:
// opens the page, opens the panel, presses the Undo button, and reports the
// panel's rows (newest first) before and after, and its note; then counts the
// frames drawn over 1.5 s of idle (the view draws on demand). Prints one JSON
// report on stdout.
//
// Usage: node history-test.js <base-url>
// Exits 2 if anything fails or takes longer than the global time limit.

const { chromium } = require('playwright-core');

const [base] = process.argv.slice(2);
const LIMIT_MS = 60_000;
const STEP_MS = 20_000;
setTimeout(() => {
  console.error(`history-test: gave up after ${LIMIT_MS} ms`);
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
    await page.waitForFunction(() => window.vesselcad && window.vesselcad.revision >= 0, null, { timeout: STEP_MS });
    const revision = await page.evaluate(() => window.vesselcad.revision);
    await page.click('#history-panel summary');
    await page.waitForFunction(
      () => window.vesselcad.history().length > 0 || document.getElementById('history-note').textContent !== '',
      null, { timeout: STEP_MS });
    const before = await page.evaluate(() => window.vesselcad.history());
    await page.click('#undo');
    await page.waitForFunction(
      (r) => window.vesselcad.lastError !== '' || window.vesselcad.revision > r,
      revision, { timeout: STEP_MS });
    const undoError = await page.evaluate(() => window.vesselcad.lastError);
    if (!undoError) {
      await page.waitForFunction(
        () => window.vesselcad.history().some(([rev]) => rev === window.vesselcad.revision)
          || document.getElementById('history-note').textContent !== '',
        null, { timeout: STEP_MS });
    }
    const after = await page.evaluate(() => window.vesselcad.history());
    const current = await page.locator('#history li.current').getAttribute('data-rev').catch(() => null);
    const note = await page.locator('#history-note').textContent();
    const revisionAfter = await page.evaluate(() => window.vesselcad.revision);
    // Drawing on demand: with nothing changing, (almost) no frame is drawn.
    const webgl = await page.evaluate(() => !!document.querySelector('#view canvas'));
    await page.waitForTimeout(300);
    const framesBefore = await page.evaluate(() => window.vesselcad.frames);
    await page.waitForTimeout(1500);
    const framesIdle = (await page.evaluate(() => window.vesselcad.frames)) - framesBefore;
    console.log(JSON.stringify({
      revision, revisionAfter, before, after, current, note, undoError, consoleErrors,
      webgl, framesBefore, framesIdle,
    }));
  } finally {
    await browser.close();
  }
})().catch((e) => {
  console.error(`history-test: ${e.stack || e}`);
  process.exit(2);
});
