// The parts of three.js the live-session viewer uses, bundled into one ES module
// (src/server/assets/three-bundle.js) that `vesselcad serve` embeds and serves.
export * from 'three';
export { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
export { OrbitControls } from 'three/addons/controls/OrbitControls.js';
export { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
