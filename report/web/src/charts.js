// Charts with uPlot from the chart specs the C++ side writes (report/chart_spec.h):
//   {title, x_label, y_label, log_x, log_y, x?, series: [{label, x?, y, style, color?}],
//    markers: [{x, y, label}], hlines: [{y, label}], x_min?, x_max?, y_min?, y_max?}
// A numeric array is a JSON array (null for a missing value) or a base64 string of float32.
// Series share `x` when the spec has one; otherwise each has its own and they are joined
// on the union of their x values (a line spans the x values of other series, and breaks
// only at its own missing values).
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';

import { float32s, formatNumber } from './page_data.js';

export const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f',
                        '#bcbd22', '#17becf'];

export function numbers(values) {
  if (typeof values === 'string') return Array.from(float32s(values), (v) => (Number.isFinite(v) ? v : null));
  return (values || []).map((v) => (v === null || !Number.isFinite(v) ? null : v));
}

const legendValue = (u, v) => (v === null || v === undefined ? '-' : formatNumber(v));

// Drops what a log axis cannot show.
function positiveOnly(values) { return values.map((v) => (v !== null && v > 0 ? v : null)); }

function alignedData(spec) {
  const cleanY = (s) => (spec.log_y ? positiveOnly(numbers(s.y)) : numbers(s.y));
  if (spec.x !== undefined) {
    const x = numbers(spec.x);
    return [x, ...spec.series.map(cleanY)];
  }
  // One table per series, sorted by x, with the points whose x the axis cannot show left out.
  const tables = spec.series.map((s) => {
    const xs = numbers(s.x), ys = cleanY(s);
    const order = xs.map((_, i) => i).filter((i) => xs[i] !== null && (!spec.log_x || xs[i] > 0));
    order.sort((a, b) => xs[a] - xs[b]);
    return [order.map((i) => xs[i]), order.map((i) => ys[i])];
  });
  if (tables.length === 0) return [[]];
  return uPlot.join(tables);
}

// The data range on one axis, with reference lines and markers, widened for display.
function displayRange(values, log, fixedMin, fixedMax) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values)
    if (v !== null && v !== undefined && Number.isFinite(v) && (!log || v > 0)) {
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
  if (lo === Infinity) [lo, hi] = log ? [1, 10] : [0, 1];
  if (log) {
    // At least a decade, so the axis has labelled ticks.
    let a = Math.log10(lo), b = Math.log10(hi);
    if (b - a < 1) {
      const mid = (a + b) / 2;
      a = mid - 0.5;
      b = mid + 0.5;
    }
    const pad = 0.05 * (b - a);
    lo = 10 ** (a - pad);
    hi = 10 ** (b + pad);
  } else if (hi === lo) {
    const pad = Math.abs(lo) > 0 ? 0.1 * Math.abs(lo) : 1;
    lo -= pad;
    hi += pad;
  } else {
    const pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
  }
  if (fixedMin !== null && fixedMin !== undefined) lo = fixedMin;
  if (fixedMax !== null && fixedMax !== undefined) hi = fixedMax;
  return [lo, hi];
}

// Ticks of a log axis at 1..9 x 10^k inside [min, max] (uPlot's own start at min).
function logSplits(u, axisIdx, min, max) {
  const out = [];
  for (let e = Math.floor(Math.log10(min)); e <= Math.ceil(Math.log10(max)); e++)
    for (let m = 1; m <= 9; m++) {
      const v = m * 10 ** e;
      if (v >= min && v <= max) out.push(v);
    }
  return out;
}

function logTickLabels(u, splits) {
  const decades = splits.filter((v) => Math.abs(Math.log10(v) - Math.round(Math.log10(v))) < 1e-9).length;
  return splits.map((v) => {
    const m = v / 10 ** Math.floor(Math.log10(v) + 1e-9);
    const mantissa = Math.round(m * 1e6) / 1e6;
    if (mantissa === 1 || (decades < 3 && (mantissa === 2 || mantissa === 5))) return formatNumber(v, 3);
    return '';
  });
}

// Reference lines (dashed, labelled at their right end) and highlighted points (rings).
function annotationsPlugin(spec) {
  return {
    hooks: {
      draw: [(u) => {
        const ctx = u.ctx, dpr = uPlot.pxRatio;
        const { left, top, width, height } = u.bbox;
        ctx.save();
        ctx.font = `${12 * dpr}px sans-serif`;
        ctx.lineWidth = 1.5 * dpr;
        for (const h of spec.hlines || []) {
          const y = u.valToPos(h.y, 'y', true);
          if (!Number.isFinite(y) || y < top || y > top + height) continue;
          ctx.strokeStyle = '#555';
          ctx.setLineDash([6 * dpr, 4 * dpr]);
          ctx.beginPath();
          ctx.moveTo(left, y);
          ctx.lineTo(left + width, y);
          ctx.stroke();
          ctx.setLineDash([]);
          ctx.fillStyle = '#333';
          ctx.textAlign = 'right';
          ctx.fillText(h.label || '', left + width - 4 * dpr, y - 4 * dpr);
        }
        for (const m of spec.markers || []) {
          const x = u.valToPos(m.x, 'x', true), y = u.valToPos(m.y, 'y', true);
          if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
          ctx.strokeStyle = '#000';
          ctx.beginPath();
          ctx.arc(x, y, 7 * dpr, 0, 2 * Math.PI);
          ctx.stroke();
          ctx.fillStyle = '#000';
          ctx.textAlign = x > left + width * 0.7 ? 'right' : 'left';
          ctx.fillText(m.label || '', x + (ctx.textAlign === 'left' ? 10 : -10) * dpr, y - 10 * dpr);
        }
        ctx.restore();
      }],
    },
  };
}

function axisOptions(label, log, extra) {
  const linear = (u, splits) => splits.map((v) => formatNumber(v, 6));
  return log ? { label: label || '', splits: logSplits, values: logTickLabels, ...extra }
             : { label: label || '', values: linear, ...extra };
}

function seriesOptions(s, index) {
  const color = s.color || PALETTE[index % PALETTE.length];
  const style = s.style || 'line_points';
  const out = { label: s.label || '', stroke: color, width: 1.5, points: { show: false }, value: legendValue };
  if (style === 'points' || style === 'line_points') out.points = { show: true, size: 6, fill: color, stroke: color };
  if (style === 'points') out.paths = () => null;
  if (style === 'bars') {
    out.paths = uPlot.paths.bars({ size: [0.9, Infinity], align: 0 });
    out.fill = color;
    out.width = 0;
  }
  return out;
}

// Builds one chart into `container`. options: {height, syncKey (cursor shared between
// charts with the same key), onPick(x) (a click in the plot area), width}.
// Returns {plot, setPlayhead(x)}: a vertical line at x (null hides it).
export function createChart(container, spec, options = {}) {
  const data = alignedData(spec);
  const markerX = (spec.markers || []).map((m) => m.x), markerY = (spec.markers || []).map((m) => m.y);
  const hlineY = (spec.hlines || []).map((h) => h.y);
  const xRange = displayRange([...data[0], ...markerX], spec.log_x, spec.x_min, spec.x_max);
  const yValues = [].concat(...data.slice(1).map((ys) => ys.filter((v) => v !== undefined)), markerY, hlineY);
  const bars = (spec.series || []).some((s) => s.style === 'bars');
  if (bars) yValues.push(spec.log_y ? 1 : 0);  // bars stand on 0 (on 1 on a log axis: a count of one)
  const yRange = displayRange(yValues, spec.log_y, spec.y_min, spec.y_max);
  const width = options.width || Math.max(320, container.clientWidth || 640);
  const opts = {
    title: spec.title || '',
    width,
    height: options.height || 300,
    scales: {
      x: { time: false, distr: spec.log_x ? 3 : 1, log: 10, range: () => xRange },
      y: { distr: spec.log_y ? 3 : 1, log: 10, range: () => yRange },
    },
    axes: [axisOptions(spec.x_label, spec.log_x, {}), axisOptions(spec.y_label, spec.log_y, { size: 64 })],
    series: [{ label: spec.x_label || 'x', value: legendValue }, ...(spec.series || []).map(seriesOptions)],
    cursor: options.syncKey ? { sync: { key: options.syncKey } } : {},
    legend: { show: true },
    plugins: [annotationsPlugin(spec)],
  };
  const plot = new uPlot(opts, data, container);
  if (data[0].length === 0) container.append(Object.assign(document.createElement('p'), { className: 'no-data', textContent: 'no data' }));

  const playhead = document.createElement('div');
  playhead.className = 'playhead';
  playhead.style.display = 'none';
  plot.over.append(playhead);
  if (options.onPick) {
    plot.over.addEventListener('click', (e) => {
      const x = plot.posToVal(e.offsetX, 'x');
      if (Number.isFinite(x)) options.onPick(x);
    });
  }
  const setPlayhead = (x) => {
    const left = x === null ? NaN : plot.valToPos(x, 'x');
    if (!Number.isFinite(left) || left < 0 || left > plot.over.clientWidth) {
      playhead.style.display = 'none';
      return;
    }
    playhead.style.display = '';
    playhead.style.left = `${left}px`;
  };
  return { plot, setPlayhead };
}

// Keeps every chart of `entries` ({chart, container}) as wide as its container.
export function fitChartsToWidth(entries) {
  const resize = () => {
    for (const { chart, container } of entries) {
      const width = Math.max(320, container.clientWidth);
      if (Math.abs(width - chart.plot.width) > 2) chart.plot.setSize({ width, height: chart.plot.height });
    }
  };
  window.addEventListener('resize', resize);
}
