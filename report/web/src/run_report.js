// report.html of `snapfit run` (report/run_page.h writes the data block):
//   {kind: "run", title, summary, parts, start_pose, playback, timeline, tuning_chart, strategy_chart, slices,
//    notes}
// The 3D view plays part 2's recorded poses with the force and torque sent to the device;
// the time charts share a cursor and show the playback time; a click on one seeks there.
// Sets window.snapfitReport (ready, range, setTime, time, partScreenBox) for tests.
import './style.css';

import { createChart, fitChartsToWidth } from './charts.js';
import { element, float32s, formatNumber, readPageData, uint8s } from './page_data.js';
import { COLORS, createViewer } from './viewer.js';

function summaryItem(key, label, value, text, tone) {
  const dd = element('dd', { 'data-key': key, 'data-value': JSON.stringify(value), text });
  if (tone) dd.className = tone;
  return element('div', {}, element('dt', { text: label }), dd);
}

// What the user feels at the fit (scheduler/rendered_wrench.h): the rendered stiffness
// over the six directions of part 1's axes, beside the coupling's (the hand's spring).
function stiffnessItem(k) {
  const range = (six) => {
    const v = Object.values(six);
    return `${formatNumber(Math.min(...v), 3)} to ${formatNumber(Math.max(...v), 3)}`;
  };
  const text = `${range(k.force_n_per_mm)} N/mm, ${range(k.torque_nm_per_deg)} N m/deg ` +
               `(coupling ${formatNumber(k.coupling_n_per_mm, 3)} N/mm, ${formatNumber(k.coupling_nm_per_deg, 3)} N m/deg)`;
  return summaryItem('stiffness_at_fit', `stiffness at the fit (over ${k.step_mm} mm, ${k.tilt_deg} deg)`, k, text);
}

// The tuned m' and what the loop rendered: the loop steps m' down when frames run late.
function modesText(s) {
  if (s.method.startsWith('vps')) return `none (${s.modes_source})`;
  const r = s.modes_rendered;
  if (!r) return `${s.modes} (${s.modes_source})`;
  const share = formatNumber(100 * r.most_frequent_share, 3);
  return `${s.modes} (${s.modes_source}); the loop rendered ${r.most_frequent} in ${share} % of frames ` +
         `(mean ${formatNumber(r.mean, 5)}, from ${r.start} to ${r.final}, ${r.changes} changes)`;
}

function renderSummary(root, s) {
  const list = element('dl', { class: 'summary', id: 'summary' });
  list.append(summaryItem('scene', 'scene', s.scene, s.scene));
  list.append(summaryItem('device', 'device (fields, spectra)', s.device, s.device));
  list.append(summaryItem('loop_device', 'loop device', s.loop_device, s.loop_device));
  if (s.query_strategy) {
    const q = s.query_strategy;
    // One line: the strategy and why; the comparison is the table and chart under "Query strategies".
    const text = q.why ? `${q.label}: ${q.why} (${q.chosen_by})` : `${q.label} (${q.chosen_by})`;
    list.append(summaryItem('query_strategy', 'query strategy', q, text));
  }
  list.append(summaryItem('modes', "m' (Fourier modes)", s.modes, modesText(s)));
  if (s.frames !== null) {
    list.append(summaryItem('misses', 'missed frames', s.misses,
                            `${s.misses} of ${s.frames} (${formatNumber(100 * s.miss_rate, 3)} %)`,
                            s.miss_rate <= 0.001 ? 'good' : 'bad'));
    list.append(summaryItem('assembled', 'success', s.assembled,
                            s.assembled === null ? 'not evaluated (no assembled pose)'
                                                 : s.assembled ? 'ASSEMBLED' : 'NOT assembled',
                            s.assembled === null ? null : s.assembled ? 'good' : 'bad'));
    list.append(summaryItem('final_error', 'final pose error', s.final_error,
                            `${formatNumber(s.final_error.position)} ${s.units}, surface ` +
                            `${formatNumber(s.final_error.surface_deviation)} ${s.units} off: ${s.final_error.text}`));
    if (s.stiffness_at_fit) list.append(stiffnessItem(s.stiffness_at_fit));
  } else {
    list.append(summaryItem('misses', 'missed frames', null, 'no loop (the scene has no trajectory)'));
    list.append(summaryItem('assembled', 'success', null, 'no loop'));
  }
  list.append(summaryItem('seconds', 'job time', s.seconds, `${formatNumber(s.seconds, 3)} s`));
  root.append(list);
}

// The measured strategies, one row each; the one the rule picks (lowest error that fits) marked.
function strategyTable(rows) {
  const percent = (x) => (x === null ? '-' : `${formatNumber(100 * x, 3)} %`);
  const head = element('tr', {}, ...['strategy', "m'", 'p99 ms', 'E', 'F', 'T', 'fits'].map((t) => element('th', { text: t })));
  const body = rows.map((r) => {
    const tr = element('tr', { 'data-strategy': r.strategy },
                       element('td', { text: r.label, title: r.strategy }), element('td', { text: String(r.modes) }),
                       element('td', { text: formatNumber(r.frame_ms_p99, 3) }), element('td', { text: percent(r.energy_error) }),
                       element('td', { text: percent(r.force_error) }), element('td', { text: percent(r.torque_error) }),
                       element('td', { text: r.fits_budget ? 'yes' : 'no' }));
    if (r.lowest_error_that_fits) tr.className = 'chosen';
    return tr;
  });
  return element('table', { id: 'strategy-table', class: 'strategy-table' }, head, ...body);
}

function legendRow(color, label, valueId) {
  return element('tr', {}, element('td', {}, element('span', { class: 'swatch', style: `background:${color}` }), label),
                 element('td', { id: valueId || '' }));
}

// Index of the last display frame at or before t (0 before the first).
function frameAt(times, t) {
  let lo = 0, hi = times.length - 1;
  if (t <= times[0]) return 0;
  if (t >= times[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

function lerp3(a, i, j, f) { return [0, 1, 2].map((k) => a[3 * i + k] + f * (a[3 * j + k] - a[3 * i + k])); }

function nlerpQuaternion(q, i, j, f) {
  const dot = q[4 * i] * q[4 * j] + q[4 * i + 1] * q[4 * j + 1] + q[4 * i + 2] * q[4 * j + 2] + q[4 * i + 3] * q[4 * j + 3];
  const s = dot < 0 ? -1 : 1;
  const out = [0, 1, 2, 3].map((k) => q[4 * i + k] + f * (s * q[4 * j + k] - q[4 * i + k]));
  const n = Math.hypot(...out) || 1;
  return out.map((v) => v / n);
}

function main() {
  const data = readPageData();
  document.title = data.title;
  const root = document.getElementById('app');
  root.append(element('h1', { text: data.title }));
  renderSummary(root, data.summary);

  // --- 3D playback
  root.append(element('h2', { text: 'Playback' }));
  const view = element('div', { id: 'view' });
  const side = element('div', { class: 'side' });
  const stage = element('div', { class: 'stage' }, view);
  root.append(element('div', { class: 'playback' }, stage, side));
  const pb = data.playback;
  const times = pb ? float32s(pb.time) : new Float32Array(0);
  const positions = pb ? float32s(pb.position) : null;
  const quaternions = pb ? float32s(pb.quaternion) : null;
  const forces = pb ? float32s(pb.force) : null;
  const torques = pb ? float32s(pb.torque) : null;
  const energies = pb ? float32s(pb.energy) : null;
  const modes = pb ? float32s(pb.modes) : null;
  const viewer = createViewer(view, data.parts, positions, quaternions);

  const units = data.summary.units;
  const table = element('table', {},
    legendRow(COLORS.part1, `part 1: ${data.parts[0].name} (fixed)`),
    legendRow(COLORS.part2, `part 2: ${data.parts[1].name} (moving)`),
    legendRow(COLORS.inside, 'triangle inside the other part', 'contact-count'),
    legendRow(COLORS.force, 'force sent (N)', 'value-force'),
    legendRow(COLORS.torque, 'torque sent (N m)', 'value-torque'),
    legendRow('transparent', 'energy', 'value-energy'),
    ...(data.summary.method.startsWith('vps') ? [] : [legendRow('transparent', "m'", 'value-modes')]),
    legendRow('transparent', 'time (s)', 'value-time'));
  side.append(table);
  if (pb) {
    side.append(element('p', { class: 'note', text:
      `Arrows start at part 2's origin; an arrow ${formatNumber(viewer.arrowScale, 3)} ${units} long is the run's largest ` +
      `magnitude (force ${formatNumber(pb.force_max)} N, torque ${formatNumber(pb.torque_max)} N m).` }));
  }
  for (const line of data.notes || []) side.append(element('p', { class: 'note', text: line }));

  const charts = [];
  const contact = pb && pb.contact ? {
    frames: pb.contact.frames,
    bits: [uint8s(pb.contact.part1), uint8s(pb.contact.part2)],
    bytes: pb.contact.bytes,
  } : null;
  let currentTime = times.length ? times[0] : 0;
  let shownContact = -2;

  function showContact(frame) {
    if (!contact) return;
    // The latest display frame with contact data at or before `frame`.
    let k = -1;
    for (let lo = 0, hi = contact.frames.length - 1; lo <= hi;) {
      const mid = (lo + hi) >> 1;
      if (contact.frames[mid] <= frame) { k = mid; lo = mid + 1; } else hi = mid - 1;
    }
    if (k === shownContact) return;
    shownContact = k;
    if (k < 0) { viewer.setContact(null); return; }
    const flags = contact.bits.map((b, p) => b.subarray(k * contact.bytes[p], (k + 1) * contact.bytes[p]));
    viewer.setContact(flags);
    let count = 0;
    for (const f of flags) for (const byte of f) for (let v = byte; v; v &= v - 1) count++;
    document.getElementById('contact-count').textContent = String(count);
  }

  function setTime(t) {
    if (!pb) return;
    currentTime = Math.min(Math.max(t, times[0]), times[times.length - 1]);
    const i = frameAt(times, currentTime), j = Math.min(i + 1, times.length - 1);
    const f = j > i ? (currentTime - times[i]) / (times[j] - times[i]) : 0;
    viewer.setPart2Pose(lerp3(positions, i, j, f), nlerpQuaternion(quaternions, i, j, f));
    const force = lerp3(forces, i, j, f), torque = lerp3(torques, i, j, f);
    viewer.setArrows(force, torque, pb.force_max, pb.torque_max);
    showContact(f < 0.5 ? i : j);
    viewer.render();
    document.getElementById('value-force').textContent = formatNumber(Math.hypot(...force));
    document.getElementById('value-torque').textContent = formatNumber(Math.hypot(...torque));
    document.getElementById('value-energy').textContent = formatNumber(energies[i]);
    const modesCell = document.getElementById('value-modes');
    if (modesCell) modesCell.textContent = String(modes[i]);
    document.getElementById('value-time').textContent = formatNumber(currentTime, 4);
    slider.value = String(currentTime);
    clock.textContent = `${currentTime.toFixed(3)} / ${times[times.length - 1].toFixed(3)} s`;
    for (const c of charts) c.setPlayhead(currentTime);
  }

  // --- controls: play/pause, timeline, speed
  const play = element('button', { id: 'play', type: 'button', text: 'Play' });
  const slider = element('input', { id: 'timeline', type: 'range', step: 'any' });
  const speed = element('select', { id: 'speed' });
  for (const s of [0.1, 0.25, 0.5, 1, 2, 4]) speed.append(element('option', { value: String(s), text: `${s}x` }));
  speed.value = '1';
  const clock = element('span', { class: 'clock' });
  const controls = element('div', { class: 'controls' }, play, slider, speed, clock);
  stage.append(controls);
  let playing = false, last = 0;
  if (pb) {
    slider.min = String(times[0]);
    slider.max = String(times[times.length - 1]);
    slider.addEventListener('input', () => setTime(Number(slider.value)));
    const step = (now) => {
      if (!playing) return;
      const dt = Math.min((now - last) / 1000, 0.1);
      last = now;
      const next = currentTime + dt * Number(speed.value);
      if (next >= times[times.length - 1]) {
        setTime(times[times.length - 1]);
        playing = false;
        play.textContent = 'Play';
        return;
      }
      setTime(next);
      requestAnimationFrame(step);
    };
    play.addEventListener('click', () => {
      playing = !playing;
      play.textContent = playing ? 'Pause' : 'Play';
      if (playing) {
        if (currentTime >= times[times.length - 1]) setTime(times[0]);
        last = performance.now();
        requestAnimationFrame(step);
      }
    });
  } else {
    play.disabled = true;
    slider.disabled = true;
    speed.disabled = true;
    clock.textContent = 'no trajectory: part 2 at its starting pose';
    viewer.setPart2Pose(data.start_pose.position, data.start_pose.rotation.quaternion);
    viewer.setContact(null);
    viewer.render();
  }

  // --- time charts, linked to the playback
  const entries = [];
  if (data.timeline) {
    root.append(element('h2', { text: 'Over time' }));
    for (const line of data.timeline.notes || []) root.append(element('p', { class: 'note', text: line }));
    const grid = element('div', { class: 'charts-grid' });
    root.append(grid);
    data.timeline.charts.forEach((spec, i) => {
      const container = element('div', { class: 'chart', id: `time-chart-${i}` });
      grid.append(container);
      const chart = createChart(container, spec, { height: 240, syncKey: 'time', onPick: (t) => setTime(t) });
      charts.push(chart);
      entries.push({ chart, container });
    });
  }
  if (data.strategy_chart) {
    root.append(element('h2', { text: 'Query strategies: error against frame time' }));
    const strategies = element('div', { class: 'chart', id: 'strategy-chart' });
    const row = element('div', { class: 'strategies' }, strategies);
    if (data.strategy_table) row.append(strategyTable(data.strategy_table));
    root.append(row);
    entries.push({ chart: createChart(strategies, data.strategy_chart, { height: 320 }), container: strategies });
  }
  root.append(element('h2', { text: "Tuning of m'" }));
  if (data.tuning_chart) {
    const tuning = element('div', { class: 'chart', id: 'tuning-chart' });
    root.append(tuning);
    entries.push({ chart: createChart(tuning, data.tuning_chart, { height: 320 }), container: tuning });
  } else {
    const why = data.summary.method.startsWith('vps') ? "Voxmap PointShell has no m' to tune." :
      "m' was fixed by --modes: no tuning sweep ran.";
    root.append(element('p', { class: 'note', id: 'no-tuning', text: why }));
  }
  if (data.frame_time_histogram) {
    root.append(element('h2', { text: 'Frame times' }));
    const histogram = element('div', { class: 'chart', id: 'frame-time-histogram' });
    root.append(histogram);
    entries.push({ chart: createChart(histogram, data.frame_time_histogram, { height: 300 }), container: histogram });
  }
  fitChartsToWidth(entries);

  // --- field slices (the same figures as `snapfit fields --png`)
  if (data.slices && data.slices.length) {
    root.append(element('h2', { text: 'Descriptor fields' }));
    const box = element('div', { class: 'slices' });
    for (const s of data.slices)
      box.append(element('figure', {}, element('img', { src: `data:image/png;base64,${s.png}`, alt: s.caption }),
                         element('figcaption', { text: s.caption })));
    root.append(box);
  }

  if (pb) setTime(times[0]);
  window.snapfitReport = {
    ready: true,
    range: pb ? [times[0], times[times.length - 1]] : null,
    setTime,
    time: () => currentTime,
    partScreenBox: () => viewer.partScreenBox(),
  };
}

main();
