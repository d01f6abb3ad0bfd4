// 3D Tiles 1.1 for three.js: shows the tileset `vesselcad build --tiles DIR
// [--lod 5,1,0.2]` writes, each vessel at the coarsest level of detail whose
// error stays under a screen-space bound, loading finer levels only when the
// camera comes near.
//
// The tileset's frame is Z-up, metres; the GLB contents are Y-up (three.js's
// frame), so contents are added as loaded and the tile boxes are turned into
// Y-up ((x, y, z) → (x, z, −y)). A tile's screen-space error is its geometric
// error × (viewport height in px) / (2 · tan(fov / 2) · distance from the
// camera to its box), the rule of 3D Tiles viewers. A tile is refined (its
// children drawn instead, `REPLACE`, or as well, `ADD`) when that error exceeds
// `maxScreenSpaceError`; until a finer level has loaded, the coarser one stays
// (no hole). Loaded levels are kept (a plant's fine levels of the few vessels
// near the camera are small).
//
// Choice: 1 px by default, not the 16 px CesiumJS uses for terrain: a CAD user
// expects silhouettes within a pixel of the exact surface.
//
// Usage:
//   const tiles = await Tileset.load('/out/tileset.json');
//   scene.add(tiles.group);
//   // each frame: tiles.update(camera, renderer.domElement.clientHeight);
//   await tiles.settled();   // every level the last update asked for is shown

import { Group, Vector3, GLTFLoader, MeshoptDecoder } from './three-bundle.js';

export const MAX_SCREEN_SPACE_ERROR = 1;

// A tile of the tileset as this module keeps it.
class Tile {
  constructor(json, base, parentRefine) {
    this.geometricError = json.geometricError;
    this.refine = (json.refine || parentRefine || 'REPLACE').toUpperCase();
    this.uri = json.content ? new URL(json.content.uri, base).href : null;
    this.extras = json.extras || {};
    const b = json.boundingVolume && json.boundingVolume.box;
    if (!b) throw new Error(`tiles.js: a tile without a box (${this.uri || 'no content'})`);
    // Z-up → Y-up.
    const yUp = (x, y, z) => new Vector3(x, z, -y);
    this.centre = yUp(b[0], b[1], b[2]);
    this.axes = [yUp(b[3], b[4], b[5]), yUp(b[6], b[7], b[8]), yUp(b[9], b[10], b[11])];
    this.children = (json.children || []).map((c) => new Tile(c, base, this.refine));
    this.object = null;   // the loaded content
    this.loading = null;  // its pending load
  }

  // Distance from `p` to the tile's box, 0 inside.
  distanceTo(p) {
    const d = p.clone().sub(this.centre);
    let sum = 0;
    for (const axis of this.axes) {
      const h = axis.length();
      if (h === 0) continue;
      const excess = Math.max(Math.abs(d.dot(axis) / h) - h, 0);
      sum += excess * excess;
    }
    return Math.sqrt(sum);
  }
}

export class Tileset {
  // Fetches `url` (a tileset.json) and returns the tileset, nothing loaded yet.
  static async load(url, options = {}) {
    const absolute = new URL(url, location.href).href;
    const response = await fetch(absolute);
    if (!response.ok) throw new Error(`tiles.js: ${absolute}: HTTP ${response.status}`);
    return new Tileset(await response.json(), absolute, options);
  }

  constructor(json, url, { maxScreenSpaceError = MAX_SCREEN_SPACE_ERROR, onLoad = null } = {}) {
    this.root = new Tile(json.root, url, null);
    this.group = new Group();
    this.maxScreenSpaceError = maxScreenSpaceError;
    this.onLoad = onLoad;
    this.loader = new GLTFLoader();
    this.loader.setMeshoptDecoder(MeshoptDecoder);
    this.pending = new Set();
    this.shownTiles = new Set();
    this.failures = [];
  }

  // Chooses the tiles to draw for `camera` (a PerspectiveCamera with its
  // matrices up to date) on a viewport `height` px high, requests the ones
  // not loaded, and shows the chosen ones that are.
  update(camera, height) {
    const k = height / (2 * Math.tan((camera.fov * Math.PI) / 360));
    const eye = new Vector3().setFromMatrixPosition(camera.matrixWorld);
    const shown = new Set();
    const visit = (tile, fallback) => {
      const error = (tile.geometricError * k) / Math.max(tile.distanceTo(eye), 1e-9);
      const refine = tile.children.length > 0 && (!tile.uri || error > this.maxScreenSpaceError);
      if (!refine) {
        if (tile.uri && this.request(tile)) shown.add(tile);
        else if (fallback) shown.add(fallback);
        return;
      }
      if (tile.refine === 'ADD') {
        if (tile.uri && this.request(tile)) shown.add(tile);
        for (const c of tile.children) visit(c, null);
      } else {
        // The coarse level is loaded too: it is what shows until the finer one is in.
        const ready = tile.uri && this.request(tile) ? tile : fallback;
        for (const c of tile.children) visit(c, ready);
      }
    };
    visit(this.root, null);
    for (const tile of this.shownTiles) if (!shown.has(tile)) tile.object.visible = false;
    for (const tile of shown) tile.object.visible = true;
    this.shownTiles = shown;
    this.lastCamera = { camera, height };
  }

  // True when `tile`'s content is loaded; else starts loading it.
  request(tile) {
    if (tile.object) return true;
    if (!tile.loading) {
      tile.loading = (async () => {
        const response = await fetch(tile.uri);
        if (!response.ok) throw new Error(`${tile.uri}: HTTP ${response.status}`);
        const gltf = await this.loader.parseAsync(await response.arrayBuffer(), '');
        tile.object = gltf.scene;
        tile.object.visible = false;
        tile.object.userData.tile = { ...tile.extras, uri: tile.uri };
        this.group.add(tile.object);
      })().catch((e) => this.failures.push(String(e)))
        .finally(() => {
          this.pending.delete(tile.loading);
          if (this.lastCamera) this.update(this.lastCamera.camera, this.lastCamera.height);
          if (this.onLoad) this.onLoad(tile);
        });
      this.pending.add(tile.loading);
    }
    return false;
  }

  // Resolves when no load is pending (each finished load updates the choice,
  // which may request finer levels: those are waited for too).
  async settled() {
    while (this.pending.size) await Promise.all([...this.pending]);
  }

  // The tiles drawn now: their extras (tag, tolerance) and content URI.
  shown() {
    return [...this.shownTiles].map((t) => ({ ...t.extras, uri: t.uri }));
  }
}
