// Times an edit typed into the live-session viewer page (headless Chromium
// through playwright-core) against a running `vesselcad serve`: the page picks
// a part, then types values into one of its parameters, alternating two, and
// for each edit measures from the Enter key to the first animation frame in
// which the page holds the revision the edit made (the frame that draws it).
// Prints one JSON report on stdout: every latency in ms, and p50/p99/max.
//
// Usage: node edit-to-view.js <base-url> <stable-id> <field> <value-a> <value-b> <edits>
// Exits 2 if anything fails or takes longer than the global time limit.

const { chromium } = require('playwright-core');

const [base, id, field, valueA, valueB, count] = process.argv.slice(2);
const edits = Number(count);
const STEP_MS = 30_000;
const LIMIT_MS = 60_000 + edits * 2_000;
setTimeout(() => {
  console.error(`edit-to-view: gave up after ${LIMIT_MS} ms`);
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
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    await page.goto(base, { timeout: STEP_MS });
    await page.waitForFunction(
      (id) => window.vesselcad && window.vesselcad.revision >= 0 && window.vesselcad.box(id),
      id, { timeout: STEP_MS });
    await page.selectOption('#pick', id, { timeout: STEP_MS });
    const latencies = [];
    for (let k = 0; k < edits; k += 1) {
      const input = page.locator(`#params input[name="${field}"]`);
      await input.waitFor({ timeout: STEP_MS });
      await input.fill(k % 2 === 0 ? valueA : valueB);
      const revision = await page.evaluate(() => window.vesselcad.revision);
      // In the page: the time of the Enter key, and of the first frame with
      // a later revision.
      await input.evaluate((el) => {
        window.__enter = null;
        el.addEventListener('keydown', (e) => {
          if (e.key === 'Enter') window.__enter = performance.now();
        }, { once: true });
      });
      const shown = page.evaluate((r) => new Promise((resolve) => {
        const tick = () => {
          if (window.vesselcad.revision > r) resolve(performance.now());
          else requestAnimationFrame(tick);
        };
        requestAnimationFrame(tick);
      }), revision);
      await input.press('Enter');
      const frame = await shown;
      const enter = await page.evaluate(() => window.__enter);
      const error = await page.locator('#error').textContent();
      if (enter === null || (error && error.trim() !== '')) {
        throw new Error(`edit ${k}: enter ${enter}, error ${JSON.stringify(error)}`);
      }
      latencies.push(frame - enter);
    }
    const sorted = [...latencies].sort((a, b) => a - b);
    const at = (q) => sorted[Math.min(sorted.length - 1, Math.ceil(q * sorted.length) - 1)];
    console.log(JSON.stringify({
      edits, p50: at(0.5), p99: at(0.99), max: sorted[sorted.length - 1], latencies,
    }));
  } catch (e) {
    console.error(String(e && e.stack ? e.stack : e));
    process.exitCode = 2;
  } finally {
    await browser.close();
  }
})();
