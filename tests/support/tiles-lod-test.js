// Shows a 3D Tiles tileset written by `vesselcad build --tiles` with the
// viewer's tiles.js (src/server/assets/tiles.js) and the bundled three.js in
// headless Chromium (Debian's /usr/bin/chromium through playwright-core), from
// given camera positions, and reports which level of each vessel is drawn.
// Nothing is served over a network: the page, the modules and the tileset's
// files are answered from disk by request interception.
//
// Usage: node tiles-lod-test.js <three-bundle.js> <tiles.js> <dir> <cameras.json>
// cameras.json: [{"eye": [x, y, z], "target": [x, y, z]}, ...] in the
// tileset's frame (Z-up, metres); the viewport is 1000 px high, fov 50°.
// Prints one JSON array: per camera, the tiles drawn (tag, tolerance, uri),
// with the triangles three.js draws for each, and the files fetched so far;
// or the error. Exits 2 on any failure.
'use strict';

const fs = require('fs');
const path = require('path');
const { chromium } = require('playwright-core');

const LIMIT_MS = 120_000;
setTimeout(() => {
  console.error(`tiles-lod-test: gave up after ${LIMIT_MS} ms`);
  process.exit(2);
}, LIMIT_MS).unref();

const ORIGIN = 'http://vesselcad.invalid';
const PAGE = `<!doctype html><html><body><script type="module">
import { PerspectiveCamera, Vector3 } from '/static/three-bundle.js';
import { Tileset } from '/static/tiles.js';
const fetched = [];
const original = window.fetch;
window.fetch = (url, ...rest) => { fetched.push(String(url).split('/').pop()); return original(url, ...rest); };
window.look = async (cameras) => {
  const tiles = await Tileset.load('/out/tileset.json');
  const out = [];
  for (const { eye, target } of cameras) {
    const camera = new PerspectiveCamera(50, 1.5, 0.01, 1e5);
    camera.position.set(eye[0], eye[2], -eye[1]);
    camera.lookAt(new Vector3(target[0], target[2], -target[1]));
    camera.updateMatrixWorld(true);
    tiles.update(camera, 1000);
    await tiles.settled();
    const shown = [];
    tiles.group.traverse((o) => {
      if (o.userData.tile && o.visible) {
        let triangles = 0;
        o.traverse((m) => {
          if (m.isMesh) {
            const g = m.geometry;
            triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
          }
        });
        shown.push({ ...o.userData.tile, triangles });
      }
    });
    out.push({ shown, fetched: [...fetched], failures: tiles.failures });
  }
  return out;
};
window.ready = true;
</script></body></html>`;

(async () => {
  const [bundle, tilesJs, dir, cameras] = process.argv.slice(2);
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  let report;
  let failed = false;
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.route('**/*', (route) => {
      const url = new URL(route.request().url());
      if (url.origin !== ORIGIN) return route.abort();
      const js = (file) => route.fulfill({ contentType: 'text/javascript', body: fs.readFileSync(file) });
      if (url.pathname === '/') return route.fulfill({ contentType: 'text/html', body: PAGE });
      if (url.pathname === '/static/three-bundle.js') return js(bundle);
      if (url.pathname === '/static/tiles.js') return js(tilesJs);
      const name = decodeURIComponent(url.pathname.replace(/^\/out\//, ''));
      const file = path.join(dir, path.basename(name));
      if (!url.pathname.startsWith('/out/') || !fs.existsSync(file)) {
        return route.fulfill({ status: 404, body: '' });
      }
      const type = name.endsWith('.json') ? 'application/json' : 'model/gltf-binary';
      return route.fulfill({ contentType: type, body: fs.readFileSync(file) });
    });
    await page.goto(ORIGIN + '/');
    await page.waitForFunction(() => window.ready === true, null, { timeout: 30_000 });
    report = await page.evaluate((c) => window.look(c), JSON.parse(fs.readFileSync(cameras, 'utf8')));
    if (errors.length || report.some((r) => r.failures.length)) {
      failed = true;
      report = { report, pageErrors: errors };
    }
  } catch (e) {
    failed = true;
    report = { error: String(e) };
  } finally {
    await browser.close();
  }
  console.log(JSON.stringify(report, null, 2));
  process.exit(failed ? 2 : 0);
})().catch((e) => {
  console.error(`tiles-lod-test failed: ${e && e.stack ? e.stack : e}`);
  process.exit(2);
});
