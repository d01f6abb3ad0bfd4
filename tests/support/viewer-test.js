// Drives the live-session viewer page in headless Chromium (Debian's
// /usr/bin/chromium through playwright-core) against a running `vesselcad serve`:
// two pages open the viewer; page A picks a part from its list, changes one of its
// parameters in the parameter panel (which sends a JSON Patch), and page B must
// see that part's geometry change (and its pixels). A bad value typed in page A
// must show the server's error and change nothing in page B. Then Ctrl+Z in
// page A (the server's undo, or its error), a nozzle added to the vessel through
// page A's button (page B gets it and its pixels change), and the vessel's typed
// editors; the delta page B drew (its GLB's bytes and extensions). Prints one
// JSON report on stdout.
//
// Usage: node viewer-test.js <base-url> <stable-id> <field> <new-value> <bad-value>
// Exits 2 if anything fails or takes longer than the global time limit.

const { chromium } = require('playwright-core');

const [base, id, field, value, bad] = process.argv.slice(2);
const LIMIT_MS = 90_000;
const STEP_MS = 30_000;
setTimeout(() => {
  console.error(`viewer-test: gave up after ${LIMIT_MS} ms`);
  process.exit(2);
}, LIMIT_MS).unref();

async function open(browser, log) {
  const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  page.on('console', (m) => { if (m.type() === 'error') log.push(m.text()); });
  page.on('pageerror', (e) => log.push(String(e)));
  await page.goto(base, { timeout: STEP_MS });
  await page.waitForFunction(
    (id) => window.vesselcad && window.vesselcad.revision >= 0 && window.vesselcad.box(id),
    id, { timeout: STEP_MS });
  return page;
}

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
    const a = await open(browser, consoleErrors);
    const b = await open(browser, consoleErrors);
    const revision0 = await b.evaluate(() => window.vesselcad.revision);
    const before = await b.evaluate((id) => window.vesselcad.box(id), id);
    const pixels0 = await b.evaluate(() => window.vesselcad.pixels());

    // Page A: pick the part in the list, edit the field in the panel.
    await a.selectOption('#pick', id, { timeout: STEP_MS });
    const input = a.locator(`#params input[name="${field}"]`);
    await input.waitFor({ timeout: STEP_MS });
    const shown = await input.inputValue();
    await input.fill(value);
    await input.press('Tab'); // leaving the field fires `change`: the edit is sent
    await b.waitForFunction((r) => window.vesselcad.revision > r, revision0, { timeout: STEP_MS });
    const after = await b.evaluate((id) => window.vesselcad.box(id), id);
    const revision1 = await b.evaluate(() => window.vesselcad.revision);
    await a.waitForFunction((r) => window.vesselcad.revision >= r, revision1, { timeout: STEP_MS });
    const statusA = await a.locator('#message').textContent();
    const statusAError = await a.locator('#error').textContent();
    const pixels1 = await b.evaluate(() => window.vesselcad.pixels());
    const editToView = await b.evaluate(() => window.vesselcad.lastApplied);
    // The delta page B drew: its GLB's size and extensions (the page asks
    // for meshopt-compressed deltas).
    const delta = await b.evaluate(() => window.vesselcad.lastDelta);

    // A bad value: the page shows the server's error; page B sees no change.
    const again = a.locator(`#params input[name="${field}"]`);
    await again.fill(bad);
    await again.press('Tab');
    await a.waitForFunction(() => window.vesselcad.lastError !== '', null, { timeout: STEP_MS });
    const errorText = await a.locator('#error').textContent();
    await b.waitForTimeout(500);
    const revision2 = await b.evaluate(() => window.vesselcad.revision);
    const afterBad = await b.evaluate((id) => window.vesselcad.box(id), id);

    // Undo (Ctrl+Z): the server's answer, an error in red if it has no /undo.
    const revisionBeforeUndo = await a.evaluate(() => window.vesselcad.revision);
    await a.locator('#status').click();
    await a.keyboard.press('Control+z');
    await a.waitForFunction(
      (r) => window.vesselcad.lastError !== '' || window.vesselcad.revision > r,
      revisionBeforeUndo, { timeout: STEP_MS });
    const undo = {
      error: await a.locator('#error').textContent(),
      message: await a.locator('#message').textContent(),
      revision: await a.evaluate(() => window.vesselcad.revision),
    };
    // Add a nozzle to the picked part's vessel: page B gets it.
    const vessel = id.slice(0, id.lastIndexOf('/'));
    await a.selectOption('#pick', vessel, { timeout: STEP_MS });
    const idsBefore = await b.evaluate(() => window.vesselcad.ids());
    const revisionBeforeAdd = await b.evaluate(() => window.vesselcad.revision);
    await a.click('#add-nozzle');
    await b.waitForFunction((r) => window.vesselcad.revision > r, revisionBeforeAdd, { timeout: STEP_MS });
    const idsAfter = await b.evaluate(() => window.vesselcad.ids());
    const added = idsAfter.filter((x) => !idsBefore.includes(x));
    const addError = await a.evaluate(() => window.vesselcad.lastError);
    const pixels2 = await b.evaluate(() => window.vesselcad.pixels());
    // The vessel's fields: typed editors from the schema.
    await a.selectOption('#pick', vessel, { timeout: STEP_MS });
    const kindEditor = await a.locator('#params select[name="kind"]').count();
    const levelLabel = await a.locator('#params tr', { hasText: 'operating.liquid_level' }).textContent();

    const drawingSrc = await a.locator('#drawing').getAttribute('src');
    const webgl = await a.evaluate(() => !!document.querySelector('#view canvas'));
    const gaps = await b.evaluate(() => window.vesselcad.gaps);
    // With WebGL, picking in the view: a click on the middle of page A's view
    // selects whatever part is drawn there.
    let picked = null;
    if (webgl) {
      await a.selectOption('#pick', '');
      const box = await a.locator('#view canvas').boundingBox();
      await a.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
      picked = await a.locator('#pick').inputValue();
    }
    console.log(JSON.stringify({
      shown, before, after, revision0, revision1, revision2, afterBad,
      statusA, statusAError, errorText, drawingSrc, webgl, picked, gaps, consoleErrors,
      pixelsChangedByEdit: pixels0 !== pixels1, pixelsChangedByAdd: pixels1 !== pixels2,
      undo, added, addError, kindEditor, levelLabel, editToView: editToView > 0, delta,
    }));
  } finally {
    await browser.close();
  }
})().catch((e) => {
  console.error(`viewer-test: ${e.stack || e}`);
  process.exit(2);
});
