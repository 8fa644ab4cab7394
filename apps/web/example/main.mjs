// The example page: an asset.subd through SubdLoader (or, with ?loader=gltf, a .glb through
// three's GLTFLoader), framed from a fixed direction and rendered once; window.subdExample.ready
// resolves with the figures of that first frame.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { SubdLoader } from '../subd_loader.mjs';

const params = new URLSearchParams(location.search);
const useGltf = params.get('loader') === 'gltf';
const src = params.get('src') ?? (useGltf ? 'decoded.glb' : 'asset.subd');
const size = Number(params.get('size') ?? 0);
const status = document.getElementById('status');
if (size) status.classList.add('below');  // a fixed-size canvas shows nothing but the asset

const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(size ? 1 : window.devicePixelRatio);
renderer.setSize(size || window.innerWidth, size || window.innerHeight);
document.body.prepend(renderer.domElement);

const scene = new THREE.Scene();
scene.background = new THREE.Color(0x202428);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.5));
const sun = new THREE.DirectionalLight(0xffffff, 2.5);
sun.position.set(1, 2, 1.5);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(35, renderer.domElement.width / renderer.domElement.height, 0.01, 100);

// A surface without an appearance comes in glTF's default material, fully metallic, which shows
// dark with no environment to reflect: the page draws it in a neutral grey instead, either loader.
const grey = new THREE.MeshStandardMaterial({ color: 0xcccccc, metalness: 0, roughness: 0.5 });
let triangles = 0;
const updates = [];  // with ?stream: { bytes, total, complete, triangles, ms } of each refinement drawn

function load() {
  // `subdfit decode` writes KHR_mesh_quantization, which GLTFLoader reads as it is; with
  // --meshopt, EXT_meshopt_compression besides, which needs meshoptimizer's decoder.
  if (useGltf) return new GLTFLoader().setMeshoptDecoder(MeshoptDecoder).loadAsync(src).then((gltf) => gltf.scene);
  const loader = new SubdLoader();
  if (params.has('triangles')) loader.setTriangles(Number(params.get('triangles')));
  if (!params.has('stream')) return loader.loadAsync(src);
  // ?stream: drawn from the file's first bytes on, each refinement as it comes.
  return loader.loadStreaming(src, (mesh, progress) => {
    updates.push({ ...progress, triangles: mesh.userData.subd.triangles, ms: performance.now() });
    if (!mesh.material.map && !mesh.material.normalMap) mesh.material = grey;
    if (!mesh.parent) {
      scene.add(mesh);
      frame(mesh);
    }
    renderer.render(scene, camera);
    status.textContent = `${src}: ${progress.bytes} of ${progress.total} bytes, ${mesh.userData.subd.triangles} triangles`;
  });
}

function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05;
  camera.position.copy(sphere.center).add(new THREE.Vector3(0.6, 0.45, 1).normalize().multiplyScalar(distance));
  camera.near = distance / 100;
  camera.far = distance * 4;
  camera.updateProjectionMatrix();
  camera.lookAt(sphere.center);
  sun.position.copy(sphere.center).add(new THREE.Vector3(1, 2, 1.5).multiplyScalar(sphere.radius));
  sun.target.position.copy(sphere.center);
  scene.add(sun.target);
  return sphere;
}


const ready = load().then((object) => {
  object.traverse((o) => {
    if (o.isMesh && !o.material.map && !o.material.normalMap) o.material = grey;
  });
  scene.add(object);
  object.traverse((o) => { if (o.isMesh) triangles += o.geometry.index ? o.geometry.index.count / 3 : 0; });
  const sphere = frame(object);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(sphere.center);
  controls.update();
  controls.addEventListener('change', () => renderer.render(scene, camera));
  renderer.render(scene, camera);
  return new Promise((resolve) => requestAnimationFrame(() => {
    const firstFrameMs = performance.now();
    status.textContent = `${src}: ${triangles} triangles, first frame ${firstFrameMs.toFixed(0)} ms after the request`;
    resolve({ firstFrameMs, triangles, updates });
  }));
}).catch((error) => {
  status.textContent = String(error?.message ?? error);
  console.error(error);
  throw error;
});
ready.catch(() => {});
window.subdExample = { ready };
