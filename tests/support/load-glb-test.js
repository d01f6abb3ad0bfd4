// Loads GLB files with three.js in headless Chromium (Debian's /usr/bin/chromium
// through playwright-core): the bundle vesselcad serves
// (src/server/assets/three-bundle.js, three r187) with its GLTFLoader and
// MeshoptDecoder, as a viewer would. Nothing is served over a network: the page
// and its files are answered from disk by request interception.
//
// Usage: node load-glb-test.js <three-bundle.js> <file.glb>...
// Prints one JSON object: per file, the meshes three.js made (draw calls), the
// meshes they draw (an InstancedMesh counts its instances), their triangles and
// vertices (of every instance), the meshes shaded flat (no normals), the named nodes, the world bounding box (metres, Y-up) and the
// extras of the first vessel node; or the error. Exits 2 if any file fails.
'use strict';

const fs = require('fs');
const path = require('path');
const { chromium } = require('playwright-core');

const LIMIT_MS = 90_000;
setTimeout(() => {
  console.error(`load-glb-test: gave up after ${LIMIT_MS} ms`);
  process.exit(2);
}, LIMIT_MS).unref();

const ORIGIN = 'http://vesselcad.invalid';
const PAGE = `<!doctype html><html><body><script type="module">
import * as THREE from '/three-bundle.js';
window.load = async (name) => {
  const loader = new THREE.GLTFLoader();
  loader.setMeshoptDecoder(THREE.MeshoptDecoder);
  const bytes = await (await fetch('/files/' + name)).arrayBuffer();
  const gltf = await loader.parseAsync(bytes, '');
  let meshes = 0, drawn = 0, triangles = 0, vertices = 0, flat = 0;
  const names = [];
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((o) => {
    if (o.name) names.push(o.name);
    if (o.isMesh) {
      meshes += 1;
      const copies = o.isInstancedMesh ? o.count : 1;
      drawn += copies;
      const g = o.geometry;
      triangles += copies * (g.index ? g.index.count : g.attributes.position.count) / 3;
      vertices += copies * g.attributes.position.count;
      if (o.material && o.material.flatShading) flat += 1;
    }
  });
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const vessel = gltf.scene.children[0]?.children[0];
  return {
    meshes, drawn, triangles, vertices, flat, names: names.length,
    box: [...box.min.toArray(), ...box.max.toArray()],
    vessel: vessel ? vessel.userData : null,
  };
};
window.ready = true;
</script></body></html>`;

(async () => {
  const [bundle, ...files] = process.argv.slice(2);
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const report = {};
  let failed = false;
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.route('**/*', (route) => {
      const url = new URL(route.request().url());
      if (url.origin !== ORIGIN) return route.abort();
      if (url.pathname === '/') {
        return route.fulfill({ contentType: 'text/html', body: PAGE });
      }
      if (url.pathname === '/three-bundle.js') {
        return route.fulfill({ contentType: 'text/javascript', body: fs.readFileSync(bundle) });
      }
      const name = decodeURIComponent(url.pathname.replace(/^\/files\//, ''));
      const file = files.find((f) => path.basename(f) === name);
      if (!file) return route.fulfill({ status: 404, body: '' });
      return route.fulfill({ contentType: 'model/gltf-binary', body: fs.readFileSync(file) });
    });
    await page.goto(ORIGIN + '/');
    await page.waitForFunction(() => window.ready === true, null, { timeout: 30_000 });
    for (const file of files) {
      const name = path.basename(file);
      try {
        report[name] = await page.evaluate((n) => window.load(n), name);
      } catch (e) {
        failed = true;
        report[name] = { error: String(e) };
      }
    }
    if (errors.length) {
      failed = true;
      report.pageErrors = errors;
    }
  } finally {
    await browser.close();
  }
  console.log(JSON.stringify(report, null, 2));
  process.exit(failed ? 2 : 0);
})().catch((e) => {
  console.error(`load-glb-test failed: ${e && e.stack ? e.stack : e}`);
  process.exit(2);
});
