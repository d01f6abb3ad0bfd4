// vesselcad live-session viewer.
//
// Connects to /ws?progressive=1: the hello names every stable id and gives each
// vessel's bounding box, drawn at once as a grey box (the coarse whole, framed
// by the first view); each vessel's GLB is then fetched from
// /vessel.glb?tag=T, nearest to the camera first, and replaces its box. Deltas:
// the JSON header names the changed and removed stable ids ("tag" for a vessel,
// "tag/id" for a part or nozzle), the binary GLB that follows holds only the
// changed parts under their vessels, and each replaces exactly the node with its
// id; a vessel still shown as a box is fetched again if its GLB is older than
// the delta. A "resync" (the viewer fell behind) replaces everything.
//
// Picking a part, nozzle or vessel (in the view or the list; the list frames
// it) shows its design fields with editors typed from the format's JSON Schema
// (/static/schema.json: enums as drop-downs, numbers with their unit and range);
// a change sends a JSON Patch (a `test` of the old value and a `replace`) to
// POST /edit. Nozzles can be added to and parts or nozzles removed from the
// picked vessel; the Undo and Redo buttons (Ctrl+Z / Ctrl+Shift+Z) call POST
// /undo and /redo. The History panel lists the store's revisions (GET
// /revisions; newest first, each with its design as JSON) while it is open.
// Errors show in red, success does not. The view is drawn on demand (after a
// camera move, an update, a highlight or a resize), not every frame. The drawing panel shows /drawing.svg of the picked
// vessel; a click opens it full size with SVG and DXF downloads. After each
// revision the Calculation panel fetches /calc.json: a part or nozzle the code
// calculation finds deficient is drawn red and its figures are listed.
// `window.vesselcad` exposes the state for tests.

import {
  Scene, PerspectiveCamera, WebGLRenderer, HemisphereLight, DirectionalLight,
  Box3, Vector3, Vector2, Raycaster, Color, GLTFLoader, OrbitControls,
  Group, Mesh, BoxGeometry, MeshStandardMaterial, MeshoptDecoder,
} from '/static/three-bundle.js';

const $ = (id) => document.getElementById(id);
// Deltas come meshopt-compressed (the socket asks for `compress=meshopt`).
const loader = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder);

const state = {
  revision: -1,
  design: null,
  schema: null,
  root: null,          // the plant's root object in the three.js scene
  plant: null,         // the plant node
  vessels: new Map(),  // tag → vessel node (a box group until its GLB arrives)
  loaded: new Set(),   // tags whose GLB is shown
  touched: new Map(),  // tag → revision of the last delta that touched it
  nodes: new Map(),    // "tag/id" → part or nozzle node
  selected: '',
  lastError: '',
  historyAt: null,     // the revision the History panel shows
  frames: 0,           // frames drawn (on demand)
  gaps: 0,             // deltas whose revision did not follow the last one
  resyncs: 0,
  updates: 0,
  lastApplied: 0,      // performance.now() when the last delta was on screen
  generation: 0,       // bumped by each hello/resync: stale fetches are dropped
  deficient: new Map(), // stable id → the sentences of its deficiencies
  calcRevision: -1,    // the revision /calc.json last answered for
  lastDelta: null,     // {revision, bytes, extensions} of the last delta's GLB
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
const boxMaterial = new MeshStandardMaterial({ color: 0x9aa4ad, transparent: true, opacity: 0.55 });
let renderer = null;
let controls = null;
try {
  renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  $('view').appendChild(renderer.domElement);
  controls = new OrbitControls(camera, renderer.domElement);
  controls.addEventListener('change', () => invalidate());
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
  invalidate();
}
window.addEventListener('resize', resize);

// Drawing on demand: a frame is drawn after something changed (the camera,
// the model, the highlight, the size), not 60 times a second while idle.
let frameQueued = false;
function invalidate() {
  if (!renderer || frameQueued) return;
  frameQueued = true;
  requestAnimationFrame(frame);
}

function frame() {
  frameQueued = false;
  controls.update();
  renderer.render(scene, camera);
  state.frames += 1;
}

// Points the camera at `object` (the plant by default) so that all of it shows.
function frameObject(object) {
  if (!object) return;
  object.updateWorldMatrix(true, true);
  const box = new Box3().setFromObject(object);
  if (box.isEmpty()) return;
  const center = box.getCenter(new Vector3());
  const size = box.getSize(new Vector3()).length() || 1;
  const direction = camera.position.clone().sub(controls ? controls.target : new Vector3());
  if (direction.lengthSq() === 0) direction.set(0.45, 0.35, 0.6);
  const fov = (camera.fov * Math.PI) / 180;
  const distance = (0.6 * size) / Math.tan(fov / 2);
  camera.position.copy(center).add(direction.normalize().multiplyScalar(distance));
  camera.near = Math.max(size / 1000, distance / 1000);
  camera.far = distance + size * 20;
  camera.updateProjectionMatrix();
  if (controls) controls.target.copy(center);
  invalidate();
}

// ---- model: outline, vessels, deltas -----------------------------------------

function parseGlb(buffer) {
  return new Promise((resolve, reject) => loader.parse(buffer, '', resolve, reject));
}

function plantOf(gltf) {
  return gltf.scene.children.find((c) => c.userData.name === 'plant') || gltf.scene;
}

function dispose(object) {
  object.traverse((o) => {
    if (o.isMesh) {
      if (!o.userData.placeholder) o.geometry.dispose();
      if (o.userData.highlight || o.userData.deficient) o.material.dispose();
    }
  });
}

function indexVessel(vessel) {
  const tag = vessel.userData.name;
  vessel.userData.stableId = tag;
  state.vessels.set(tag, vessel);
  for (const part of vessel.children) if (!part.userData.placeholder) indexPart(tag, part);
}

function indexPart(tag, part) {
  const id = `${tag}/${part.userData.name}`;
  part.userData.stableId = id;
  state.nodes.set(id, part);
  paintNode(id, part);
}

function clearModel() {
  if (state.root) {
    scene.remove(state.root);
    dispose(state.root);
  }
  state.vessels.clear();
  state.nodes.clear();
  state.loaded.clear();
  state.touched.clear();
}

// A vessel drawn as its bounding box until its GLB arrives.
const unitBox = new BoxGeometry(1, 1, 1);
function boxVessel(entry) {
  const group = new Group();
  group.userData = { name: entry.tag, stableId: entry.tag, outline: true };
  const mesh = new Mesh(unitBox, boxMaterial);
  mesh.userData.placeholder = true;
  const [a, b] = [entry.min, entry.max];
  mesh.position.set((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
  mesh.scale.set(Math.max(b[0] - a[0], 1e-3), Math.max(b[1] - a[1], 1e-3), Math.max(b[2] - a[2], 1e-3));
  group.add(mesh);
  return group;
}

async function applyOutline(header) {
  const first = state.root === null;
  clearModel();
  state.generation += 1;
  const root = new Group();
  const plant = new Group();
  plant.userData.name = 'plant';
  root.add(plant);
  state.root = root;
  state.plant = plant;
  state.outline = header.vessels;
  for (const entry of header.vessels) {
    const group = boxVessel(entry);
    plant.add(group);
    state.vessels.set(entry.tag, group);
  }
  state.ids = header.ids;
  scene.add(root);
  if (header.type === 'resync') state.resyncs += 1;
  if (first) frameObject(state.plant);
  loadVessels(state.generation);
}

// Fetches every vessel's GLB, nearest to the camera first, a few at a time.
async function loadVessels(generation) {
  const eye = camera.position;
  const order = state.outline
    .map((e) => ({
      tag: e.tag,
      d: Math.hypot(...[0, 1, 2].map((k) => (e.min[k] + e.max[k]) / 2 - eye.getComponent(k))),
    }))
    .sort((x, y) => x.d - y.d)
    .map((x) => x.tag);
  const total = order.length;
  let done = 0;
  const progress = () => {
    $('progress').value = total ? done / total : 1;
    $('progress').hidden = done >= total;
    $('loading').textContent = done >= total ? '' : `loading ${done}/${total} vessels`;
  };
  progress();
  let next = 0;
  const worker = async () => {
    while (next < order.length && generation === state.generation) {
      const tag = order[next++];
      try {
        await loadVessel(tag, generation);
      } catch (e) {
        showError(`viewer: vessel ${tag}: ${e}`);
      }
      done += 1;
      progress();
    }
  };
  await Promise.all([0, 1, 2, 3, 4, 5].map(worker));
  if (generation === state.generation) {
    refreshPickList();
    highlight();
  }
}

async function loadVessel(tag, generation) {
  for (;;) {
    const response = await fetch(withToken(`/vessel.glb?tag=${encodeURIComponent(tag)}`), { headers: authHeaders() });
    if (response.status === 404) return; // removed meanwhile
    if (!response.ok) throw new Error(`${response.status}`);
    const vesselRevision = Number(response.headers.get('x-vesselcad-vessel-revision'));
    const gltf = await parseGlb(await response.arrayBuffer());
    if (generation !== state.generation) return;
    // A delta touched it after this GLB was written: fetch again.
    if ((state.touched.get(tag) || 0) > vesselRevision) continue;
    const incoming = plantOf(gltf).children.find((c) => c.userData.name === tag);
    if (!incoming) return;
    const old = state.vessels.get(tag);
    if (old && old.parent) old.parent.remove(old);
    if (old) dispose(old);
    for (const id of [...state.nodes.keys()]) if (id.startsWith(`${tag}/`)) state.nodes.delete(id);
    state.plant.add(incoming);
    indexVessel(incoming);
    state.loaded.add(tag);
    invalidate();
    if (state.selected.startsWith(`${tag}/`) || state.selected === tag) highlight();
    return;
  }
}

async function applyFull(header, buffer) {
  const gltf = await parseGlb(buffer);
  const first = state.root === null;
  clearModel();
  state.generation += 1;
  state.root = gltf.scene;
  state.plant = plantOf(gltf);
  for (const vessel of [...state.plant.children]) {
    indexVessel(vessel);
    state.loaded.add(vessel.userData.name);
  }
  scene.add(state.root);
  if (header.type === 'resync') state.resyncs += 1;
  if (first) frameObject(state.plant);
}

async function applyDelta(header, buffer) {
  if (header.revision !== state.revision + 1) state.gaps += 1;
  const gltf = await parseGlb(buffer);
  state.lastDelta = {
    revision: header.revision,
    bytes: buffer.byteLength,
    extensions: gltf.parser.json.extensionsUsed || [],
  };
  const changed = new Set(header.changed);
  for (const id of header.removed) {
    const node = state.nodes.get(id) || state.vessels.get(id);
    if (node && node.parent) node.parent.remove(node);
    if (node) dispose(node);
    state.nodes.delete(id);
    state.vessels.delete(id);
    state.loaded.delete(id);
  }
  for (const incoming of [...plantOf(gltf).children]) {
    const tag = incoming.userData.name;
    state.touched.set(tag, header.revision);
    const vessel = state.vessels.get(tag);
    if (!vessel) {
      state.plant.add(incoming);
      indexVessel(incoming);
      state.loaded.add(tag);
      continue;
    }
    // Still a box: its GLB, fetched or being fetched, brings this change.
    if (!state.loaded.has(tag)) continue;
    if (changed.has(tag)) {
      vessel.position.copy(incoming.position);
      vessel.quaternion.copy(incoming.quaternion);
      vessel.scale.copy(incoming.scale);
      vessel.userData = { ...incoming.userData, stableId: tag };
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
  return new Set([...plantOf(gltf).children].map((v) => v.userData.name).concat(header.removed.map((id) => id.split('/')[0])));
}

async function handle(header, buffer) {
  let touched = null;
  if (header.type === 'delta') touched = await applyDelta(header, buffer);
  else if (header.progressive) await applyOutline(header);
  else await applyFull(header, buffer);
  state.revision = header.revision;
  state.updates += 1;
  state.lastApplied = performance.now();
  $('status').textContent = `revision ${state.revision} · ${state.vessels.size} vessels`;
  $('status').dataset.revision = String(state.revision);
  invalidate();
  refreshPickList();
  highlight();
  // The design: whole on a hello, resync or a vessel added or removed; else
  // only the vessels the delta touched.
  const whole = !touched || !state.design
    || [...touched].some((tag) => !state.design.vessels.some((v) => v.tag === tag))
    || header.removed.some((id) => !id.includes('/'));
  if (whole) await loadDesign();
  else await Promise.all([...touched].map(loadVesselDesign));
  // After an added nozzle's delta, pick it.
  if (state.selectAfter && known(state.selectAfter)) {
    state.selected = state.selectAfter;
    state.selectAfter = null;
    $('pick').value = state.selected;
    highlight();
  }
  renderParams();
  if (!touched || touched.has(drawingTag())) refreshDrawing();
  refreshHistory();
  refreshCalc();
}

// ---- calculation -----------------------------------------------------------
// GET /calc.json after each revision: the live calculation's deficiencies by
// stable id. A deficient part or nozzle is drawn red (its meshes get their own
// copies of their materials) and its figures are listed; a line picks its part.

const DEFICIENT = new Color(0xd01010);

function paintNode(id, node) {
  const bad = state.deficient.has(id);
  node.traverse((o) => {
    if (!o.isMesh || o.userData.placeholder || Boolean(o.userData.deficient) === bad) return;
    if (o.userData.highlight) {
      o.material.dispose();
      o.material = o.userData.base;
      o.userData.highlight = false;
    }
    if (bad) {
      o.userData.sound = o.material;
      o.material = o.material.clone();
      o.material.color = DEFICIENT.clone();
    } else {
      o.material.dispose();
      o.material = o.userData.sound;
    }
    o.userData.deficient = bad;
  });
}

async function refreshCalc() {
  const response = await fetch('/calc.json', { cache: 'no-store', headers: authHeaders() }).catch(() => null);
  if (!response || !response.ok) return;
  const calc = await response.json();
  if (calc.revision < state.calcRevision) return;
  state.calcRevision = calc.revision;
  state.deficient = new Map();
  for (const d of calc.deficiencies) {
    if (!state.deficient.has(d.id)) state.deficient.set(d.id, []);
    state.deficient.get(d.id).push(d.text);
  }
  for (const [id, node] of state.nodes) paintNode(id, node);
  $('deficiencies').replaceChildren(...calc.deficiencies.map((d) => {
    const li = document.createElement('li');
    li.dataset.id = d.id;
    li.textContent = d.id.includes('/') ? `${d.id.split('/')[0]}/${d.text}` : `${d.id}: ${d.text}`;
    li.addEventListener('click', () => select(d.id, true));
    return li;
  }));
  $('calc-note').textContent = calc.deficiencies.length
    ? `${calc.deficiencies.length} deficiencies (red in the view):`
    : 'No deficiency: every wall, nozzle and support holds.';
  highlight();
}

// ---- history -------------------------------------------------------------------
// The store's revisions, fetched when the panel is opened and after each
// revision while it is open. A session without a store keeps no history (404).

const HISTORY_ROWS = 50;

async function refreshHistory() {
  if (!$('history-panel').open || state.historyAt === state.revision) return;
  state.historyAt = state.revision;
  const list = $('history');
  try {
    const response = await fetch('/revisions', { headers: authHeaders() });
    if (response.status === 404) {
      list.textContent = '';
      $('history-note').textContent = 'This session keeps no history: start `vesselcad serve` with --store.';
      return;
    }
    const body = await response.json();
    if (!response.ok) throw new Error(body.error || response.statusText);
    const revisions = body.revisions.slice(-HISTORY_ROWS).reverse();
    const shown = body.revisions.length - revisions.length;
    $('history-note').textContent = shown > 0 ? `the newest ${HISTORY_ROWS} of ${body.revisions.length} revisions` : '';
    list.textContent = '';
    for (const r of revisions) {
      const item = document.createElement('li');
      item.value = r.rev;
      item.dataset.rev = String(r.rev);
      if (r.rev === state.revision) item.className = 'current';
      const when = r.at.replace('T', ' ').replace(/\.\d+/, '').replace(/Z$/, ' UTC');
      const tags = r.tags.length ? ` [${r.tags.join(', ')}]` : '';
      const text = document.createElement('span');
      text.textContent = `${r.message}${tags} · ${r.author} · ${when} `;
      const link = document.createElement('a');
      link.href = withToken(`/design.json?rev=${r.rev}`);
      link.textContent = 'JSON';
      link.target = '_blank';
      item.append(text, link);
      list.append(item);
    }
  } catch (e) {
    state.historyAt = null;
    $('history-note').textContent = `history not available: ${e.message || e}`;
  }
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

// Messages are a JSON header, followed by a GLB except for a progressive hello
// or resync; they are handled one at a time.
let pendingHeader = null;
let queue = Promise.resolve();
function connect() {
  const ws = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${withToken('/ws?progressive=1&compress=meshopt')}`);
  ws.binaryType = 'arraybuffer';
  ws.onmessage = (event) => {
    if (typeof event.data === 'string') {
      const header = JSON.parse(event.data);
      if (header.progressive) {
        queue = queue.then(() => handle(header, null)).catch((e) => showError(`viewer: ${e}`));
      } else {
        pendingHeader = header;
      }
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
  const ids = [...state.vessels.keys(), ...state.nodes.keys()].sort();
  const have = [...pick.options].slice(1).map((o) => o.value);
  if (have.join('\n') !== ids.join('\n')) {
    pick.length = 1;
    for (const id of ids) pick.add(new Option(id, id));
  }
  pick.value = known(state.selected) ? state.selected : '';
}

const known = (id) => state.nodes.has(id) || state.vessels.has(id);

function select(id, frameIt = false) {
  state.selected = known(id) ? id : '';
  $('pick').value = state.selected;
  clearMessages();
  highlight();
  renderParams();
  refreshDrawing();
  if (frameIt && state.selected) frameObject(state.nodes.get(id) || state.vessels.get(id));
}

function highlight() {
  const paint = (id, node) => node.traverse((o) => {
    if (!o.isMesh || o.userData.placeholder) return;
    const on = id === state.selected || (state.selected && !state.selected.includes('/') && id.startsWith(`${state.selected}/`));
    if (on && !o.userData.highlight) {
      o.userData.base = o.material;
      o.material = o.material.clone();
      o.material.emissive = new Color(0x3366ff);
      o.material.emissiveIntensity = 0.6;
      o.userData.highlight = true;
    } else if (!on && o.userData.highlight) {
      o.material.dispose();
      o.material = o.userData.base;
      o.userData.highlight = false;
    }
  });
  for (const [id, node] of state.nodes) paint(id, node);
  invalidate();
}

async function loadDesign() {
  const response = await fetch('/design.json', { cache: 'no-store', headers: authHeaders() });
  if (response.status === 401) return askToken();
  if (response.ok) state.design = await response.json();
}

async function loadVesselDesign(tag) {
  const response = await fetch(withToken(`/vessel.json?vessel=${encodeURIComponent(tag)}`), { cache: 'no-store', headers: authHeaders() });
  if (!response.ok) return loadDesign();
  const { index, vessel } = await response.json();
  if (state.design && state.design.vessels[index] && state.design.vessels[index].tag === tag) {
    state.design.vessels[index] = vessel;
  } else {
    await loadDesign();
  }
}

async function loadSchema() {
  const response = await fetch('/static/schema.json');
  if (response.ok) state.schema = await response.json();
}

// The design object of a stable id and its JSON Pointer, or null.
function designEntry(id) {
  if (!state.design || !id) return null;
  const slash = id.lastIndexOf('/');
  const tag = slash < 0 ? id : id.slice(0, slash), key = id.slice(slash + 1);
  const v = state.design.vessels.findIndex((x) => x.tag === tag);
  if (v < 0) return null;
  const vessel = state.design.vessels[v];
  if (slash < 0) {
    const object = {};
    for (const k of ['tag', 'kind', 'placement', 'design', 'operating']) if (k in vessel) object[k] = vessel[k];
    if (!('operating' in object) || object.operating === null) object.operating = { liquid_level: 0 };
    return { kind: 'vessel', object, pointer: `/vessels/${v}`, schema: ['VesselDesign'], vessel: v };
  }
  const p = (vessel.parts || []).findIndex((x) => Object.values(x)[0].id === key);
  if (p >= 0) {
    const kind = Object.keys(vessel.parts[p])[0];
    return { kind, object: vessel.parts[p][kind], pointer: `/vessels/${v}/parts/${p}/${kind}`, schema: ['PartDesign', kind], vessel: v };
  }
  const n = (vessel.nozzles || []).findIndex((x) => x.mark === key);
  if (n >= 0) return { kind: 'nozzle', object: vessel.nozzles[n], pointer: `/vessels/${v}/nozzles/${n}`, schema: ['NozzleDesign'], vessel: v };
  return null;
}

const escapePointer = (s) => s.replace(/~/g, '~0').replace(/\//g, '~1');

// ---- schema: the type, range and unit of a field -------------------------------

function deref(node) {
  let n = node;
  for (let i = 0; n && n.$ref && i < 10; i += 1) n = state.schema.$defs[n.$ref.split('/').pop()];
  return n;
}

// The schema of property `key` below `node`, through $ref, anyOf and oneOf.
function propertyOf(node, key) {
  const n = deref(node);
  if (!n) return null;
  if (n.properties && key in n.properties) return n.properties[key];
  for (const branch of [...(n.anyOf || []), ...(n.oneOf || [])]) {
    const found = propertyOf(branch, key);
    if (found) return found;
  }
  if (n.items && /^\d+$/.test(key)) return n.items;
  return null;
}

// The leaf's editor: {kind: 'enum', options} | {kind: 'number', min, max, unit} | {kind: 'text'}.
function fieldType(schemaPath, keys) {
  if (!state.schema) return { kind: 'text' };
  let node = { $ref: `#/$defs/${schemaPath[0]}` };
  for (const key of [...schemaPath.slice(1), ...keys]) {
    node = propertyOf(node, key);
    if (!node) return { kind: 'text' };
  }
  const description = node.description || '';
  const n = deref(node) || {};
  const branches = [n, ...(n.anyOf || []).map(deref), ...(n.oneOf || []).map(deref)];
  const consts = (n.oneOf || []).map(deref).filter((b) => b && 'const' in b).map((b) => b.const);
  const enums = n.enum || branches.find((b) => b && b.enum)?.enum;
  if (consts.length || enums) return { kind: 'enum', options: consts.length ? consts : enums };
  const numeric = branches.find((b) => b && (b.type === 'number' || (Array.isArray(b.type) && b.type.includes('number'))));
  if (numeric) {
    const unit = (description.match(/\b(mm|MPa|kPa|°C|kg\/m³|kg|degrees)\b/) || [])[1] || '';
    return {
      kind: 'number',
      min: numeric.minimum ?? numeric.exclusiveMinimum,
      max: numeric.maximum ?? numeric.exclusiveMaximum,
      unit: unit === 'degrees' ? '°' : unit,
      description,
    };
  }
  return { kind: 'text', description };
}

function fieldRows(object, pointer, prefix, keys, rows) {
  for (const [key, value] of Object.entries(object)) {
    const path = `${pointer}/${escapePointer(key)}`;
    const name = prefix ? `${prefix}.${key}` : key;
    if (value !== null && typeof value === 'object' && !Array.isArray(value)) {
      fieldRows(value, path, name, [...keys, key], rows);
    } else {
      rows.push({ name, path, value, keys: [...keys, key], readOnly: key === 'id' || key === 'mark' || key === 'tag' });
    }
  }
}

function renderParams() {
  const panel = $('params');
  panel.textContent = '';
  const entry = state.selected && designEntry(state.selected);
  if (!entry) {
    panel.innerHTML = '<p class="hint">Click a part or nozzle to see and edit its parameters; pick a vessel for its placement, conditions and liquid level.</p>';
    return;
  }
  const title = document.createElement('h2');
  title.textContent = `${state.selected} (${entry.kind})`;
  panel.appendChild(title);
  const table = document.createElement('table');
  const rows = [];
  fieldRows(entry.object, entry.pointer, '', [], rows);
  for (const row of rows) {
    const tr = table.insertRow();
    const type = typeof row.value === 'number' || typeof row.value === 'string' ? fieldType(entry.schema, row.keys) : { kind: 'text' };
    const label = tr.insertCell();
    label.textContent = type.unit ? `${row.name} (${type.unit})` : row.name;
    if (type.description) label.title = type.description;
    let input;
    if (type.kind === 'enum' && typeof row.value === 'string') {
      input = document.createElement('select');
      for (const option of type.options) input.add(new Option(option, option));
      input.value = row.value;
    } else {
      input = document.createElement('input');
      if (typeof row.value === 'number') {
        input.type = 'number';
        input.step = 'any';
        if (type.min !== undefined) input.min = String(type.min);
        if (type.max !== undefined) input.max = String(type.max);
        input.value = String(row.value);
      } else {
        input.type = 'text';
        input.value = typeof row.value === 'string' ? row.value : JSON.stringify(row.value);
      }
      input.readOnly = row.readOnly;
    }
    input.name = row.name;
    input.dataset.path = row.path;
    input.addEventListener('change', () => {
      let value;
      if (typeof row.value === 'number') value = Number(input.value);
      else if (typeof row.value === 'string') value = input.value;
      else {
        try { value = JSON.parse(input.value); } catch (e) { showError(`${row.name}: not JSON: ${e.message}`); return; }
      }
      // The operating state may be absent from the design: set it whole.
      const operating = state.design.vessels[entry.vessel].operating;
      if (row.path.endsWith('/operating/liquid_level') && (operating === undefined || operating === null)) {
        sendEdit([{ op: 'add', path: `/vessels/${entry.vessel}/operating`, value: { liquid_level: value } }]);
        return;
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

function clearMessages() {
  state.lastError = '';
  $('error').textContent = '';
  $('message').textContent = '';
}

function showError(message) {
  state.lastError = message;
  $('message').textContent = '';
  $('error').textContent = message;
}

function showMessage(message) {
  state.lastError = '';
  $('error').textContent = '';
  $('message').textContent = message;
}

// Sends a request whose answer is an accepted edit or an error.
async function post(url, patch) {
  // The guard wants a JSON content type on every POST: undo and redo send `{}`.
  const headers = { ...authHeaders(), 'Content-Type': patch ? 'application/json-patch+json' : 'application/json' };
  // A new request: the last one's error or success no longer stands.
  clearMessages();
  state.sentAt = performance.now();
  try {
    const response = await fetch(url, { method: 'POST', headers, body: patch ? JSON.stringify(patch) : '{}' });
    let body = {};
    try { body = await response.json(); } catch (e) { body = { error: `${response.statusText || 'no JSON answer'}` }; }
    if (!response.ok) {
      const rules = (body.violations || []).map((v) => `• ${v.entity} ${v.field} = ${v.value}: ${v.rule}`);
      showError([`${response.status}: ${body.error || body.message || url}`, ...rules].join('\n'));
      renderParams();
      return null;
    }
    showMessage(`accepted as revision ${body.revision}`);
    return body;
  } catch (e) {
    showError(`${url} failed: ${e}`);
    return null;
  }
}

const sendEdit = (patch) => post('/edit', patch);

// ---- adding and removing ---------------------------------------------------------

function selectedVessel() {
  if (!state.selected || !state.design) return null;
  const tag = state.selected.includes('/') ? state.selected.slice(0, state.selected.lastIndexOf('/')) : state.selected;
  const index = state.design.vessels.findIndex((v) => v.tag === tag);
  return index < 0 ? null : { tag, index, vessel: state.design.vessels[index] };
}

// A new 2" nozzle on the picked vessel's first shell course, with the next
// free mark, where no nozzle of that course is near (the server checks the
// rest and says why if it refuses).
function addNozzle() {
  const picked = selectedVessel();
  if (!picked) return showError('pick a vessel, part or nozzle first');
  const { index, vessel } = picked;
  const nozzles = vessel.nozzles || [];
  const shell = (vessel.parts || []).map((p) => p.shell).find(Boolean);
  if (!shell) return showError(`${picked.tag} has no shell course to put a nozzle on`);
  const marks = new Set(nozzles.map((n) => n.mark));
  let k = nozzles.length + 1;
  while (marks.has(`N${k}`)) k += 1;
  const onShell = nozzles.filter((n) => n.host === shell.id);
  const length = shell.length || 1000;
  let best = null;
  for (const f of [0.5, 0.3, 0.7, 0.15, 0.85]) {
    for (const orientation of [270, 90, 180, 0, 45, 135, 225, 315]) {
      const elevation = Math.round(length * f);
      const clear = onShell.every((n) => {
        const turn = Math.abs((((n.orientation || 0) - orientation) % 360 + 540) % 360 - 180);
        return turn >= 40 || Math.abs((n.elevation || 0) - elevation) >= 500;
      });
      if (clear && !best) best = { orientation, elevation };
    }
  }
  if (!best) return showError(`no free place for a nozzle on ${picked.tag}/${shell.id}`);
  const like = onShell.find((n) => n.projection) || nozzles.find((n) => n.projection);
  const nozzle = {
    mark: `N${k}`,
    service: 'added',
    size: 2,
    rating: 150,
    host: shell.id,
    orientation: best.orientation,
    elevation: best.elevation,
    projection: like ? like.projection : Math.round((shell.od || 1000) / 2 + 300),
  };
  state.selectAfter = `${picked.tag}/N${k}`;
  post('/edit', [{ op: 'add', path: `/vessels/${index}/nozzles/-`, value: nozzle }]).then((ok) => {
    if (!ok) state.selectAfter = null;
  });
}

function removeSelected() {
  const entry = designEntry(state.selected);
  if (!entry || entry.kind === 'vessel') return showError('pick a part or nozzle to remove');
  const pointer = entry.kind === 'nozzle' ? entry.pointer : entry.pointer.slice(0, entry.pointer.lastIndexOf('/'));
  sendEdit([{ op: 'remove', path: pointer }]);
}

// ---- drawing -----------------------------------------------------------------

function drawingTag() {
  if (state.selected) return state.selected.includes('/') ? state.selected.slice(0, state.selected.lastIndexOf('/')) : state.selected;
  return state.vessels.keys().next().value || '';
}

function refreshDrawing() {
  const tag = drawingTag();
  $('drawing-vessel').textContent = tag;
  const url = `/drawing.svg?vessel=${encodeURIComponent(tag)}`;
  const img = $('drawing');
  if (!tag || img.dataset.key === `${url}#${state.revision}`) return;
  img.dataset.key = `${url}#${state.revision}`;
  $('drawing-error').textContent = '';
  img.src = withToken(`${url}&revision=${state.revision}`);
  $('svg-link').href = withToken(url);
  $('svg-link').download = `${tag}.svg`;
  $('dxf-link').href = withToken(`/drawing.dxf?vessel=${encodeURIComponent(tag)}`);
}

$('drawing').addEventListener('error', async () => {
  const response = await fetch($('drawing').src, { headers: authHeaders() });
  let text = `${response.status}`;
  try { text = (await response.json()).error; } catch (e) { /* not JSON */ }
  $('drawing-error').textContent = text;
});

$('drawing').addEventListener('click', () => {
  $('sheet-full').src = $('drawing').src;
  $('sheet').hidden = false;
});
$('sheet-close').addEventListener('click', () => { $('sheet').hidden = true; });

// ---- events and test hooks -----------------------------------------------------

$('pick').addEventListener('change', (e) => select(e.target.value, true));
$('add-nozzle').addEventListener('click', addNozzle);
$('remove').addEventListener('click', removeSelected);
$('frame-all').addEventListener('click', () => frameObject(state.plant));
$('undo').addEventListener('click', () => post('/undo', null));
$('redo').addEventListener('click', () => post('/redo', null));
$('history-panel').addEventListener('toggle', () => { state.historyAt = null; refreshHistory(); });

window.addEventListener('keydown', (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.key.toLowerCase() !== 'z') return;
  if (e.target && (e.target.tagName === 'INPUT' || e.target.tagName === 'SELECT')) return;
  e.preventDefault();
  post(e.shiftKey ? '/redo' : '/undo', null);
});

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
  get loaded() { return state.loaded.size; },
  get vessels() { return state.vessels.size; },
  get lastApplied() { return state.lastApplied; },
  get lastDelta() { return state.lastDelta; },
  get frames() { return state.frames; },
  ids: () => [...state.nodes.keys()],
  get calcRevision() { return state.calcRevision; },
  // The Calculation panel's deficiencies: [stable id, text].
  deficiencies: () => [...$('deficiencies').children].map((li) => [li.dataset.id, li.textContent]),
  // The colour of the first mesh of a part or nozzle, as hex, without the
  // selection highlight (null if not shown).
  colour(id) {
    let found = null;
    const node = state.nodes.get(id);
    if (node) node.traverse((o) => {
      if (found || !o.isMesh || o.userData.placeholder) return;
      const m = o.userData.highlight ? o.userData.base : o.material;
      found = m.color.getHexString();
    });
    return found;
  },
  // The History panel's rows, newest first: [revision, text].
  history: () => [...$('history').children].map((li) => [Number(li.dataset.rev), li.textContent]),
  // World-space bounding box [minX, minY, minZ, maxX, maxY, maxZ] (glTF metres).
  box(id) {
    const node = state.nodes.get(id) || (state.loaded.has(id) ? state.vessels.get(id) : null);
    if (!node) return null;
    node.updateWorldMatrix(true, true);
    const b = new Box3().setFromObject(node);
    return [...b.min.toArray(), ...b.max.toArray()];
  },
  // Pixels of the view, as a data URL (the renderer keeps its drawing buffer).
  pixels() {
    if (!renderer) return null;
    renderer.render(scene, camera);
    return renderer.domElement.toDataURL('image/png');
  },
  select,
  addNozzle,
  removeSelected,
};

resize();
loadSchema().then(connect);
invalidate();
