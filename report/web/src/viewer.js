// The 3D view of report.html (three.js): part 1 fixed and see-through, part 2 placed at a
// pose in part 1's frame, the force and torque sent to the device as arrows at part 2's
// origin, the path of that origin, and contact shown by colouring triangles.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

import { float32s } from './page_data.js';

export const COLORS = {
  part1: '#9aa3ad',
  part2: '#2f6db5',
  inside: '#e0312b',
  force: '#e4572e',
  torque: '#7b3fb0',
  path: '#444444',
};

// A triangle soup (9 floats a triangle) as geometry with one colour per corner.
function partGeometry(positions, color) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  const colors = new Float32Array(positions.length);
  const c = new THREE.Color(color);
  for (let i = 0; i < colors.length; i += 3) colors.set([c.r, c.g, c.b], i);
  geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  return geometry;
}

function arrow(color) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, new THREE.Color(color).getHex());
  a.line.material.linewidth = 2;
  a.visible = false;
  return a;
}

// container: an element with a size. parts: [{positions (base64 float32), name}] for part 1
// and part 2 in their own frames. path: float32 positions of part 2's origin (may be empty);
// turns: float32 quaternions (w, x, y, z) at the same frames (may be null).
export function createViewer(container, parts, path, turns) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(container.clientWidth, container.clientHeight);
  container.append(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color('#f4f5f7');
  const camera = new THREE.PerspectiveCamera(35, container.clientWidth / container.clientHeight, 0.01, 1e6);
  camera.up.set(0, 0, 1);
  scene.add(camera);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
  const light = new THREE.DirectionalLight(0xffffff, 1.8);
  light.position.set(0.4, 0.3, 1);
  camera.add(light);

  const meshes = parts.map((part, i) => {
    const geometry = partGeometry(float32s(part.positions), i === 0 ? COLORS.part1 : COLORS.part2);
    const material = new THREE.MeshStandardMaterial({
      vertexColors: true, flatShading: true, roughness: 0.65, metalness: 0.05, side: THREE.DoubleSide,
    });
    if (i === 0) {
      material.transparent = true;
      material.opacity = 0.42;
      material.depthWrite = false;
    }
    const mesh = new THREE.Mesh(geometry, material);
    mesh.renderOrder = i === 0 ? 1 : 0;
    mesh.matrixAutoUpdate = i !== 0;
    scene.add(mesh);
    return mesh;
  });
  const part2 = meshes[1];

  const pathPoints = path && path.length >= 6 ? path : new Float32Array(0);
  if (pathPoints.length) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pathPoints, 3));
    scene.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: COLORS.path, transparent: true, opacity: 0.6 })));
  }
  const forceArrow = arrow(COLORS.force), torqueArrow = arrow(COLORS.torque);
  scene.add(forceArrow, torqueArrow);

  // Frame everything: part 1, and part 2 wherever the run takes it (its box's corners at
  // every recorded pose), so that no moment of the playback is cut off.
  const box = new THREE.Box3().setFromObject(meshes[0]);
  const own = part2.geometry.boundingBox;
  const corner = new THREE.Vector3(), turn = new THREE.Quaternion(), at = new THREE.Vector3();
  const frames = pathPoints.length / 3;
  if (frames === 0) box.union(new THREE.Box3().setFromObject(part2));
  for (let f = 0; f < frames; f++) {
    at.set(pathPoints[3 * f], pathPoints[3 * f + 1], pathPoints[3 * f + 2]);
    if (turns && turns.length >= 4 * (f + 1)) turn.set(turns[4 * f + 1], turns[4 * f + 2], turns[4 * f + 3], turns[4 * f]);
    else turn.identity();
    for (let c = 0; c < 8; c++) {
      corner.set(c & 1 ? own.max.x : own.min.x, c & 2 ? own.max.y : own.min.y, c & 4 ? own.max.z : own.min.z);
      box.expandByPoint(corner.applyQuaternion(turn).add(at));
    }
  }
  const center = box.getCenter(new THREE.Vector3());
  const size = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-6);
  const arrowScale = 0.3 * size;  // an arrow this long shows the run's largest magnitude
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(center);
  // Far enough that the box's bounding sphere fits the narrower of the two fields of view.
  const halfFov = Math.min(THREE.MathUtils.degToRad(camera.fov) / 2,
                           Math.atan(Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2) * camera.aspect));
  const distance = (0.5 * size) / Math.sin(halfFov) * 1.05;
  camera.position.copy(center).add(new THREE.Vector3(1.0, -1.5, 0.8).normalize().multiplyScalar(distance));
  camera.near = size / 1000;
  camera.far = size * 100;
  camera.updateProjectionMatrix();
  controls.update();

  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);
  new ResizeObserver(() => {
    const w = container.clientWidth, h = container.clientHeight;
    if (w < 1 || h < 1) return;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  }).observe(container);

  const base = parts.map((_, i) => new THREE.Color(i === 0 ? COLORS.part1 : COLORS.part2));
  const inside = new THREE.Color(COLORS.inside);
  const origin = new THREE.Vector3();

  function setArrow(a, vector, largest) {
    const v = new THREE.Vector3(vector[0], vector[1], vector[2]);
    const length = largest > 0 ? (arrowScale * v.length()) / largest : 0;
    if (!(length > 1e-3 * arrowScale)) {
      a.visible = false;
      return;
    }
    a.visible = true;
    a.position.copy(origin);
    a.setDirection(v.normalize());
    a.setLength(length, Math.min(0.3 * length, 0.06 * size), Math.min(0.15 * length, 0.03 * size));
  }

  return {
    arrowScale,
    size,
    // The three.js objects, for a page that adds its own (the live page's device pose).
    three: { scene, camera, controls, canvas: renderer.domElement },
    // position [x, y, z], quaternion [w, x, y, z] of part 2 in part 1's frame.
    setPart2Pose(position, quaternion) {
      part2.position.set(position[0], position[1], position[2]);
      part2.quaternion.set(quaternion[1], quaternion[2], quaternion[3], quaternion[0]).normalize();
      origin.set(position[0], position[1], position[2]);
    },
    setArrows(force, torque, forceMax, torqueMax) {
      setArrow(forceArrow, force, forceMax);
      setArrow(torqueArrow, torque, torqueMax);
    },
    // flags[i]: bytes with one bit a triangle (bit t % 8 of byte t / 8) for part i + 1; null: none inside.
    setContact(flags) {
      meshes.forEach((mesh, i) => {
        const colors = mesh.geometry.getAttribute('color');
        const bits = flags ? flags[i] : null;
        const triangles = colors.count / 3;
        for (let t = 0; t < triangles; t++) {
          const c = bits && (bits[t >> 3] >> (t & 7)) & 1 ? inside : base[i];
          for (let k = 0; k < 3; k++) colors.setXYZ(3 * t + k, c.r, c.g, c.b);
        }
        colors.needsUpdate = true;
      });
    },
    render,
    // Part 2's bounding box projected to the canvas, in CSS pixels {left, top, right, bottom}.
    partScreenBox() {
      part2.updateMatrixWorld(true);
      const b = part2.geometry.boundingBox;
      const out = { left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
      const w = renderer.domElement.clientWidth, h = renderer.domElement.clientHeight;
      for (let c = 0; c < 8; c++) {
        const p = new THREE.Vector3(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z);
        p.applyMatrix4(part2.matrixWorld).project(camera);
        const x = ((p.x + 1) / 2) * w, y = ((1 - p.y) / 2) * h;
        out.left = Math.min(out.left, x);
        out.right = Math.max(out.right, x);
        out.top = Math.min(out.top, y);
        out.bottom = Math.max(out.bottom, y);
      }
      return out;
    },
  };
}
