// vesselcad live-session viewer.
//
// Connects to /ws, shows the plant from the hello's full GLB, then applies each
// delta: the JSON header names the changed and removed stable ids ("tag" for a
// vessel, "tag/id" for a part or nozzle), the binary GLB that follows holds only
// the changed parts under their vessels, and each replaces exactly the node with
// its id. A "resync" (the viewer fell behind) replaces everything. Picking a part
// or nozzle (in the view or the list) shows its design parameters from
// /design.json; changing one sends a JSON Patch (a `test` of the old value and a
// `replace`) to POST /edit. The drawing panel shows /drawing.svg for the picked
// vessel. `window.vesselcad` exposes the state for tests.

import {
  Scene, PerspectiveCamera, WebGLRenderer, HemisphereLight, DirectionalLight,
  Box3, Vector3, Vector2, Raycaster, Color, GLTFLoader, OrbitControls,
} from '/static/three-bundle.js';

const $ = (id) => document.getElementById(id);
const loader = new GLTFLoader();

const state = {
  revision: -1,
  design: null,
  root: null,          // the loaded glTF scene (holds the plant node)
  plant: null,         // the plant node
  vessels: new Map(),  // tag → vessel node
  nodes: new Map(),    // "tag/id" → part or nozzle node
  selected: '',
  lastError: '',
  gaps: 0,             // deltas whose revision did not follow the last one
  resyncs: 0,
  updates: 0,
};

// ---- 3D view ---------------------------------------------------------------

const scene = new Scene();
scene.background = new Color(0xdfe6ec);
scene.add(new HemisphereLight(0xffffff, 0x8090a0, 2.0));
const sun = new DirectionalLight(0xffffff, 1.5);
sun.position.set(30, 60, 40);
scene.add(sun);
const camera = new PerspectiveCamera(45, 1, 0.05, 5000);
camera.position.set(20, 15, 20);
let renderer = null;
let controls = null;
try {
  renderer = new WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  $('view').appendChild(renderer.domElement);
  controls = new OrbitControls(camera, renderer.domElement);
} catch (e) {
  // No WebGL (e.g. a headless browser without a GPU): the model is still kept
  // up to date and can be picked from the list.
  $('view').textContent = 'No WebGL here: the 3D view is off; pick parts from the list.';
}

function resize() {
  if (!renderer) return;
  const el = $('view');
  const w = Math.max(el.clientWidth, 1), h = Math.max(el.clientHeight, 1);
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

function frame() {
  if (!renderer) return;
  controls.update();
  renderer.render(scene, camera);
  requestAnimationFrame(frame);
}

function fitCamera() {
  if (!state.plant) return;
  const box = new Box3().setFromObject(state.plant);
  if (box.isEmpty()) return;
  const center = box.getCenter(new Vector3());
  const size = box.getSize(new Vector3()).length() || 1;
  camera.position.copy(center).add(new Vector3(0.45, 0.35, 0.6).multiplyScalar(size));
  camera.near = size / 1000;
  camera.far = size * 20;
  camera.updateProjectionMatrix();
  if (controls) controls.target.copy(center);
}

// ---- model: full loads and deltas ------------------------------------------

function parseGlb(buffer) {
  return new Promise((resolve, reject) => loader.parse(buffer, '', resolve, reject));
}

function plantOf(gltf) {
  return gltf.scene.children.find((c) => c.userData.name === 'plant') || gltf.scene;
}

function dispose(object) {
  object.traverse((o) => {
    if (o.isMesh) {
      o.geometry.dispose();
      if (o.userData.highlight) o.material.dispose();
    }
  });
}

function indexVessel(vessel) {
  const tag = vessel.userData.name;
  state.vessels.set(tag, vessel);
  for (const part of vessel.children) indexPart(tag, part);
}

function indexPart(tag, part) {
  const id = `${tag}/${part.userData.name}`;
  part.userData.stableId = id;
  state.nodes.set(id, part);
}

async function applyFull(header, buffer) {
  const gltf = await parseGlb(buffer);
  const first = state.root === null;
  if (state.root) {
    scene.remove(state.root);
    dispose(state.root);
  }
  state.root = gltf.scene;
  state.plant = plantOf(gltf);
  state.vessels.clear();
  state.nodes.clear();
  for (const vessel of [...state.plant.children]) indexVessel(vessel);
  scene.add(state.root);
  if (header.type === 'resync') state.resyncs += 1;
  if (first) fitCamera();
}

async function applyDelta(header, buffer) {
  if (header.revision !== state.revision + 1) state.gaps += 1;
  const gltf = await parseGlb(buffer);
  const changed = new Set(header.changed);
  for (const id of header.removed) {
    const node = state.nodes.get(id) || state.vessels.get(id);
    if (node && node.parent) node.parent.remove(node);
    if (node) dispose(node);
    state.nodes.delete(id);
    state.vessels.delete(id);
  }
  for (const incoming of [...plantOf(gltf).children]) {
    const tag = incoming.userData.name;
    const vessel = state.vessels.get(tag);
    if (!vessel) {
      state.plant.add(incoming);
      indexVessel(incoming);
      continue;
    }
    if (changed.has(tag)) {
      vessel.position.copy(incoming.position);
      vessel.quaternion.copy(incoming.quaternion);
      vessel.scale.copy(incoming.scale);
      vessel.userData = { ...incoming.userData };
    }
    for (const part of [...incoming.children]) {
      const id = `${tag}/${part.userData.name}`;
      const old = state.nodes.get(id);
      if (old) {
        vessel.remove(old);
        dispose(old);
      }
      vessel.add(part);
      indexPart(tag, part);
    }
  }
}

async function handle(header, buffer) {
  if (header.type === 'delta') await applyDelta(header, buffer);
  else await applyFull(header, buffer);
  state.revision = header.revision;
  state.updates += 1;
  $('status').textContent = `revision ${state.revision} · ${state.nodes.size} parts and nozzles`;
  $('status').dataset.revision = String(state.revision);
  refreshPickList();
  await loadDesign();
  highlight();
  renderParams();
  refreshDrawing();
}

// ---- token --------------------------------------------------------------------
// A server started with --token needs it on every route but this page: from
// the address (#token=...), the field, or asked for once; kept for the tab.

function currentToken() {
  const fromHash = new URLSearchParams(location.hash.slice(1)).get('token');
  if (fromHash) sessionStorage.setItem('vesselcad-token', fromHash);
  return $('token').value || sessionStorage.getItem('vesselcad-token') || '';
}

function authHeaders() {
  const token = currentToken();
  return token ? { Authorization: `Bearer ${token}` } : {};
}

// A GET URL carrying the token, for what cannot send headers (socket, image).
function withToken(url) {
  const token = currentToken();
  if (!token) return url;
  return `${url}${url.includes('?') ? '&' : '?'}token=${encodeURIComponent(token)}`;
}

let asked = false;
function askToken() {
  if (asked) return;
  asked = true;
  const token = window.prompt('This vesselcad session needs its token (serve --token):');
  if (token) {
    sessionStorage.setItem('vesselcad-token', token);
    location.reload();
  }
}

$('token').addEventListener('change', (e) => sessionStorage.setItem('vesselcad-token', e.target.value));
$('token').value = currentToken();

// Messages come in pairs (JSON header, GLB); they are handled one at a time.
let pendingHeader = null;
let queue = Promise.resolve();
function connect() {
  const ws = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${withToken('/ws')}`);
  ws.binaryType = 'arraybuffer';
  ws.onmessage = (event) => {
    if (typeof event.data === 'string') {
      pendingHeader = JSON.parse(event.data);
      return;
    }
    const header = pendingHeader;
    pendingHeader = null;
    if (!header) return;
    queue = queue.then(() => handle(header, event.data)).catch((e) => showError(`viewer: ${e}`));
  };
  ws.onclose = async () => {
    $('status').textContent = `disconnected at revision ${state.revision}; reconnecting…`;
    // A refused upgrade says nothing to the page: ask the server why.
    const probe = await fetch('/design.json', { cache: 'no-store', headers: authHeaders() }).catch(() => null);
    if (probe && probe.status === 401) askToken();
    setTimeout(connect, 1000);
  };
}

// ---- picking and parameters -------------------------------------------------

function refreshPickList() {
  const pick = $('pick');
  const ids = [...state.nodes.keys()].sort();
  const have = [...pick.options].slice(1).map((o) => o.value);
  if (have.join('\n') !== ids.join('\n')) {
    pick.length = 1;
    for (const id of ids) pick.add(new Option(id, id));
  }
  pick.value = state.nodes.has(state.selected) ? state.selected : '';
}

function select(id) {
  state.selected = state.nodes.has(id) ? id : '';
  $('pick').value = state.selected;
  $('error').textContent = '';
  highlight();
  renderParams();
  refreshDrawing();
}

function highlight() {
  for (const [id, node] of state.nodes) {
    node.traverse((o) => {
      if (!o.isMesh) return;
      if (id === state.selected && !o.userData.highlight) {
        o.userData.base = o.material;
        o.material = o.material.clone();
        o.material.emissive = new Color(0x3366ff);
        o.material.emissiveIntensity = 0.6;
        o.userData.highlight = true;
      } else if (id !== state.selected && o.userData.highlight) {
        o.material.dispose();
        o.material = o.userData.base;
        o.userData.highlight = false;
      }
    });
  }
}

async function loadDesign() {
  const response = await fetch('/design.json', { cache: 'no-store', headers: authHeaders() });
  if (response.status === 401) return askToken();
  if (response.ok) state.design = await response.json();
}

// The design object of a stable id and its JSON Pointer, or null.
function designEntry(id) {
  if (!state.design) return null;
  const slash = id.lastIndexOf('/');
  const tag = id.slice(0, slash), key = id.slice(slash + 1);
  const v = state.design.vessels.findIndex((x) => x.tag === tag);
  if (v < 0) return null;
  const vessel = state.design.vessels[v];
  const p = (vessel.parts || []).findIndex((x) => Object.values(x)[0].id === key);
  if (p >= 0) {
    const kind = Object.keys(vessel.parts[p])[0];
    return { kind, object: vessel.parts[p][kind], pointer: `/vessels/${v}/parts/${p}/${kind}` };
  }
  const n = (vessel.nozzles || []).findIndex((x) => x.mark === key);
  if (n >= 0) return { kind: 'nozzle', object: vessel.nozzles[n], pointer: `/vessels/${v}/nozzles/${n}` };
  return null;
}

const escapePointer = (s) => s.replace(/~/g, '~0').replace(/\//g, '~1');

function fieldRows(object, pointer, prefix, rows) {
  for (const [key, value] of Object.entries(object)) {
    const path = `${pointer}/${escapePointer(key)}`;
    const name = prefix ? `${prefix}.${key}` : key;
    if (value !== null && typeof value === 'object' && !Array.isArray(value)) {
      fieldRows(value, path, name, rows);
    } else {
      rows.push({ name, path, value, readOnly: key === 'id' || key === 'mark' });
    }
  }
}

function renderParams() {
  const panel = $('params');
  panel.textContent = '';
  const entry = state.selected && designEntry(state.selected);
  if (!entry) {
    panel.innerHTML = '<p class="hint">Click a part or nozzle to see and edit its parameters.</p>';
    return;
  }
  const title = document.createElement('h2');
  title.textContent = `${state.selected} (${entry.kind})`;
  panel.appendChild(title);
  const table = document.createElement('table');
  const rows = [];
  fieldRows(entry.object, entry.pointer, '', rows);
  for (const row of rows) {
    const tr = table.insertRow();
    tr.insertCell().textContent = row.name;
    const input = document.createElement('input');
    input.name = row.name;
    input.dataset.path = row.path;
    if (typeof row.value === 'number') {
      input.type = 'number';
      input.step = 'any';
      input.value = String(row.value);
    } else {
      input.type = 'text';
      input.value = typeof row.value === 'string' ? row.value : JSON.stringify(row.value);
    }
    input.readOnly = row.readOnly;
    input.addEventListener('change', () => {
      let value;
      if (typeof row.value === 'number') value = Number(input.value);
      else if (typeof row.value === 'string') value = input.value;
      else {
        try { value = JSON.parse(input.value); } catch (e) { showError(`${row.name}: not JSON: ${e.message}`); return; }
      }
      sendEdit([
        { op: 'test', path: row.path, value: row.value },
        { op: 'replace', path: row.path, value },
      ]);
    });
    tr.insertCell().appendChild(input);
  }
  const node = state.nodes.get(state.selected);
  const resolved = node && node.userData.resolved;
  if (resolved) {
    for (const [key, value] of Object.entries(resolved)) {
      const tr = table.insertRow();
      tr.className = 'resolved';
      tr.insertCell().textContent = `${key} (resolved)`;
      tr.insertCell().textContent = typeof value === 'number' ? String(+value.toFixed(3)) : JSON.stringify(value);
    }
  }
  panel.appendChild(table);
}

function showError(message) {
  state.lastError = message;
  $('error').textContent = message;
}

async function sendEdit(patch) {
  const headers = { 'Content-Type': 'application/json-patch+json', ...authHeaders() };
  try {
    const response = await fetch('/edit', { method: 'POST', headers, body: JSON.stringify(patch) });
    const body = await response.json();
    if (!response.ok) {
      const rules = (body.violations || []).map((v) => `• ${v.entity} ${v.field} = ${v.value}: ${v.rule}`);
      showError([`${response.status}: ${body.error}`, ...rules].join('\n'));
      renderParams();
      return;
    }
    state.lastError = '';
    $('error').textContent = `accepted as revision ${body.revision}`;
  } catch (e) {
    showError(`edit failed: ${e}`);
  }
}

// ---- drawing -----------------------------------------------------------------

function refreshDrawing() {
  const tag = state.selected ? state.selected.slice(0, state.selected.lastIndexOf('/')) : (state.vessels.keys().next().value || '');
  $('drawing-vessel').textContent = tag;
  const url = `/drawing.svg?vessel=${encodeURIComponent(tag)}`;
  const img = $('drawing');
  if (!tag || img.dataset.key === `${url}#${state.revision}`) return;
  img.dataset.key = `${url}#${state.revision}`;
  $('drawing-error').textContent = '';
  img.src = withToken(`${url}&revision=${state.revision}`);
}

$('drawing').addEventListener('error', async () => {
  const response = await fetch($('drawing').src, { headers: authHeaders() });
  let text = `${response.status}`;
  try { text = (await response.json()).error; } catch (e) { /* not JSON */ }
  $('drawing-error').textContent = text;
});

// ---- events and test hooks -----------------------------------------------------

$('pick').addEventListener('change', (e) => select(e.target.value));

if (renderer) {
  const raycaster = new Raycaster();
  let down = null;
  renderer.domElement.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4 || !state.root) return;
    const rect = renderer.domElement.getBoundingClientRect();
    const ndc = new Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObject(state.root, true)[0];
    let o = hit && hit.object;
    while (o && !o.userData.stableId) o = o.parent;
    select(o ? o.userData.stableId : '');
  });
}

window.vesselcad = {
  get revision() { return state.revision; },
  get lastError() { return state.lastError; },
  get gaps() { return state.gaps; },
  get resyncs() { return state.resyncs; },
  ids: () => [...state.nodes.keys()],
  // World-space bounding box [minX, minY, minZ, maxX, maxY, maxZ] (glTF metres).
  box(id) {
    const node = state.nodes.get(id) || state.vessels.get(id);
    if (!node) return null;
    node.updateWorldMatrix(true, true);
    const b = new Box3().setFromObject(node);
    return [...b.min.toArray(), ...b.max.toArray()];
  },
  select,
};

resize();
connect();
requestAnimationFrame(frame);
