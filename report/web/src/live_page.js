// The page of `snapfit serve` (report/live_page.h writes the data block):
//   {kind: "live", title, parts, start_pose, units, bridge_port, state_hz}
// The mouse is the haptic device: drag to move it in the view plane, the wheel for depth,
// the right button (or shift and drag) to turn it; the middle button orbits the camera.
// The device's pose goes to the session (POST /device); the loop's latest frame comes
// back from GET /state (part 2's pose, the force and torque sent, energy, contact, m',
// frame time). Reset and Record talk to the session too.
// Sets window.snapfitLive (ready, updates, draws, state, setDevicePose, lastRecording) for tests.
import './style.css';

import * as THREE from 'three';

import { element, float32s, formatNumber, readPageData } from './page_data.js';
import { COLORS, createViewer } from './viewer.js';

const DEG = Math.PI / 180;

async function post(path, body) {
  const response = await fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body || {}),
  });
  const reply = await response.json();
  if (!response.ok) throw new Error(reply.error || `${path}: HTTP ${response.status}`);
  return reply;
}

// The device's pose as the mouse sets it: position and quaternion in part 1's frame.
class MouseDevice {
  constructor(startPose, send) {
    this.position = new THREE.Vector3(...startPose.position);
    const q = startPose.rotation.quaternion;
    this.turn = new THREE.Quaternion(q[1], q[2], q[3], q[0]);
    this.send = send;
    this.pending = false;
  }
  pose() {
    return {
      position: [this.position.x, this.position.y, this.position.z],
      quaternion: [this.turn.w, this.turn.x, this.turn.y, this.turn.z],
    };
  }
  set(position, quaternion) {
    this.position.set(...position);
    this.turn.set(quaternion[1], quaternion[2], quaternion[3], quaternion[0]).normalize();
    this.changed();
  }
  // At most one pose a display frame goes out; the last one always does.
  changed() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.send(this.pose());
    });
  }
}

// Mouse gestures on the canvas move the device relative to the camera.
function attachMouse(canvas, camera, device, worldPerPixel, depthStep) {
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('pointerdown', (e) => {
    if (e.button === 1) return;  // the middle button orbits
    drag = { x: e.clientX, y: e.clientY, turn: e.button === 2 || e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
    if (drag.turn) {  // about the view's up axis for dx, its right axis for dy, 0.5 degree a pixel
      const q = new THREE.Quaternion().setFromAxisAngle(up, dx * 0.5 * DEG)
        .multiply(new THREE.Quaternion().setFromAxisAngle(right, dy * 0.5 * DEG));
      device.turn.premultiply(q).normalize();
    } else {
      const scale = worldPerPixel();
      device.position.addScaledVector(right, dx * scale).addScaledVector(up, -dy * scale);
    }
    device.changed();
  });
  const end = (e) => {
    drag = null;
    if (canvas.hasPointerCapture(e.pointerId)) canvas.releasePointerCapture(e.pointerId);
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const forward = new THREE.Vector3();
    camera.getWorldDirection(forward);
    device.position.addScaledVector(forward, (e.deltaY < 0 ? 1 : -1) * depthStep);
    device.changed();
  }, { passive: false });
}

function statusItem(id, label) {
  return element('div', {}, element('dt', { text: label }), element('dd', { id, text: '-' }));
}

function main() {
  const data = readPageData();
  const root = document.getElementById('app');
  root.append(element('h1', { text: data.title }));
  const status = element('dl', { class: 'summary', id: 'status' },
    statusItem('energy', 'energy'), statusItem('force', 'force sent (N)'), statusItem('torque', 'torque sent (N m)'),
    statusItem('contact', `contact depth (${data.units})`), statusItem('modes', "m'"),
    statusItem('frame', 'frame time (ms)'), statusItem('frames', 'frames, misses'),
    statusItem('verdict', 'assembled'), statusItem('source', 'device'));
  root.append(status);
  const reset = element('button', { id: 'reset', type: 'button', text: 'Reset' });
  const record = element('button', { id: 'record', type: 'button', text: 'Record' });
  const message = element('span', { id: 'message', class: 'clock' });
  root.append(element('div', { class: 'controls' }, reset, record, message));
  const view = element('div', { id: 'view' });
  root.append(view);
  root.append(element('p', { class: 'note', text:
    'Drag to move the device in the view plane, the wheel for depth, the right button (or shift and drag) to ' +
    'turn it; the middle button orbits the camera. The outline is the device; part 2 follows it through the ' +
    `virtual coupling. A device program can drive the session instead over the bridge (UDP 127.0.0.1:${data.bridge_port}, ` +
    'docs/haptics.md).' }));

  const viewer = createViewer(view, data.parts, new Float32Array(0), null);
  const { scene, camera, controls, canvas } = viewer.three;
  controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.ROTATE, RIGHT: null };
  controls.enableZoom = false;
  const ghost = new THREE.Mesh(
    new THREE.BufferGeometry().setAttribute('position',
      new THREE.BufferAttribute(float32s(data.parts[1].positions), 3)),
    new THREE.MeshBasicMaterial({ color: COLORS.part2, wireframe: true, transparent: true, opacity: 0.25 }));
  scene.add(ghost);

  let state = null, updates = 0, draws = 0, sent = 0;
  const device = new MouseDevice(data.start_pose, (pose) => {
    sent++;
    post('/device', pose).catch((e) => { message.textContent = e.message; });
  });
  const worldPerPixel = () => {
    const distance = camera.position.distanceTo(device.position);
    return (2 * distance * Math.tan((camera.fov * DEG) / 2)) / Math.max(1, canvas.clientHeight);
  };
  attachMouse(canvas, camera, device, worldPerPixel, viewer.size / 200);

  let forceMax = 1e-9, torqueMax = 1e-9;
  const norm = (v) => Math.hypot(v[0], v[1], v[2]);
  // The latest state's numbers at once; the 3D view at the display's pace.
  let drawn = null;
  function show(s) {
    state = s;
    updates++;
    const f = s.frame;
    document.getElementById('energy').textContent = formatNumber(f.energy, 5);
    document.getElementById('force').textContent = formatNumber(norm(f.sent.force), 3);
    document.getElementById('torque').textContent = formatNumber(norm(f.sent.torque), 3);
    document.getElementById('contact').textContent = formatNumber(f.contact_depth, 3);
    document.getElementById('modes').textContent = String(f.modes);
    document.getElementById('frame').textContent = formatNumber(f.frame_ms, 3);
    document.getElementById('frames').textContent = `${f.frame}, ${s.status.misses}`;
    const verdict = document.getElementById('verdict');
    verdict.textContent = !s.status.evaluated ? 'no assembled pose' :
      `${s.status.assembled ? 'yes' : 'no'} (${formatNumber(s.status.position_error, 3)} ${data.units}, ` +
      `${formatNumber(s.status.angle_error_deg, 3)} deg, surface ${formatNumber(s.status.surface_deviation, 3)} ` +
      `${data.units})`;
    verdict.className = s.status.assembled ? 'good' : '';
    document.getElementById('source').textContent = f.late ? `silent (fade ${formatNumber(f.fade, 2)})` : 'live';
    record.textContent = s.status.recording ? 'Stop recording' : 'Record';
  }
  // A slow renderer (software GL) keeps to about a quarter of the page's time, so the
  // numbers above still follow the loop.
  let nextDraw = 0;
  function draw(now) {
    if (state && state !== drawn && now >= nextDraw) {
      const begin = performance.now();
      drawn = state;
      const f = state.frame;
      viewer.setPart2Pose(f.part.position, f.part.rotation.quaternion);
      ghost.position.set(...f.device.position);
      const dq = f.device.rotation.quaternion;
      ghost.quaternion.set(dq[1], dq[2], dq[3], dq[0]);
      forceMax = Math.max(0.98 * forceMax, norm(f.sent.force));
      torqueMax = Math.max(0.98 * torqueMax, norm(f.sent.torque));
      viewer.setArrows(f.sent.force, f.sent.torque, forceMax, torqueMax);
      viewer.render();
      draws++;
      const cost = performance.now() - begin;
      nextDraw = now + Math.max(0, 4 * cost - 16);
    }
    requestAnimationFrame(draw);
  }
  requestAnimationFrame(draw);

  // The loop's latest frame, state_hz times a second (sooner after a slow reply).
  async function poll() {
    const period = 1000 / data.state_hz;
    for (let due = performance.now(); ; due += period) {
      try {
        const response = await fetch('/state');
        show(await response.json());
      } catch (e) {
        message.textContent = `the session is gone (${e.message})`;
        return;
      }
      due = Math.max(due, performance.now() - period);  // behind: no burst to catch up
      await new Promise((done) => setTimeout(done, Math.max(0, due + period - performance.now())));
    }
  }

  reset.addEventListener('click', async () => {
    await post('/reset');
    device.set(data.start_pose.position, data.start_pose.rotation.quaternion);
    message.textContent = 'reset';
  });
  record.addEventListener('click', async () => {
    try {
      const reply = await post(state && state.status.recording ? '/record/stop' : '/record/start');
      message.textContent = reply.folder ? `recorded: ${reply.folder} (${reply.files.join(', ')})` : 'recording';
      window.snapfitLive.lastRecording = reply;
    } catch (e) {
      message.textContent = e.message;
    }
  });

  window.snapfitLive = {
    ready: false,
    get updates() { return updates; },
    get draws() { return draws; },
    get sent() { return sent; },
    get state() { return state; },
    setDevicePose(position, quaternion) { device.set(position, quaternion); },
    lastRecording: null,
  };
  poll();
  const waitFirst = () => (updates > 0 ? (window.snapfitLive.ready = true) : setTimeout(waitFirst, 20));
  waitFirst();
}

main();
