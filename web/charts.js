// SVG charts of the page: lines over a shared x axis, and plan views (east/north, equal
// scales) of tracks and landing points. Plain functions that return the SVG's text.
"use strict";

const CHART = { width: 420, height: 280, left: 58, right: 12, top: 26, bottom: 40 };
const COLOURS = ["#1f5f9f", "#b5441b", "#3f7f3f", "#7a4f9f", "#9f7f1f"];

function escapeXml(text) {
  return String(text).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
}

// Round tick values covering [lo, hi].
function ticks(lo, hi, count) {
  if (!(hi > lo)) { hi = lo + 1; }
  const raw = (hi - lo) / count;
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
    out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  }
  return out;
}

function extent(values) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) { if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }
  if (lo === Infinity) { return [0, 1]; }
  if (lo === hi) { return [lo - 1, hi + 1]; }
  return [lo, hi];
}

function frame(title, xlabel, ylabel, [x0, x1], [y0, y1]) {
  const c = CHART;
  const w = c.width - c.left - c.right, h = c.height - c.top - c.bottom;
  const sx = (x) => c.left + ((x - x0) / (x1 - x0)) * w;
  const sy = (y) => c.top + h - ((y - y0) / (y1 - y0)) * h;
  let svg = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 ${c.width} ${c.height}" role="img" aria-label="${escapeXml(title)}">`;
  svg += `<text x="${c.width / 2}" y="16" text-anchor="middle" font-weight="bold">${escapeXml(title)}</text>`;
  for (const t of ticks(x0, x1, 6)) {
    svg += `<line class="grid" x1="${sx(t)}" x2="${sx(t)}" y1="${c.top}" y2="${c.top + h}"/>`;
    svg += `<text x="${sx(t)}" y="${c.top + h + 14}" text-anchor="middle">${+t.toPrecision(6)}</text>`;
  }
  for (const t of ticks(y0, y1, 5)) {
    svg += `<line class="grid" x1="${c.left}" x2="${c.left + w}" y1="${sy(t)}" y2="${sy(t)}"/>`;
    svg += `<text x="${c.left - 4}" y="${sy(t) + 4}" text-anchor="end">${+t.toPrecision(6)}</text>`;
  }
  svg += `<rect class="axis" fill="none" x="${c.left}" y="${c.top}" width="${w}" height="${h}"/>`;
  svg += `<text x="${c.left + w / 2}" y="${c.height - 6}" text-anchor="middle">${escapeXml(xlabel)}</text>`;
  svg += `<text transform="translate(12 ${c.top + h / 2}) rotate(-90)" text-anchor="middle">${escapeXml(ylabel)}</text>`;
  return { svg, sx, sy, w, h };
}

function polyline(xs, ys, sx, sy, colour) {
  const points = [];
  for (let i = 0; i < xs.length; i++) {
    if (Number.isFinite(xs[i]) && Number.isFinite(ys[i])) {
      points.push(`${sx(xs[i]).toFixed(1)},${sy(ys[i]).toFixed(1)}`);
    }
  }
  return `<polyline fill="none" stroke="${colour}" stroke-width="1.5" points="${points.join(" ")}"/>`;
}

function legend(labels, c) {
  let svg = "";
  labels.forEach((label, i) => {
    const y = CHART.top + 12 + 14 * i;
    svg += `<line x1="${CHART.left + 8}" x2="${CHART.left + 26}" y1="${y - 4}" y2="${y - 4}" stroke="${COLOURS[i % COLOURS.length]}" stroke-width="2"/>`;
    svg += `<text x="${CHART.left + 30}" y="${y}">${escapeXml(label)}</text>`;
  });
  return svg;
}

// series: [{label, x: [...], y: [...]}]
function lineChart(title, xlabel, ylabel, series) {
  const xr = extent(series.flatMap((s) => s.x));
  const yr = extent(series.flatMap((s) => s.y));
  const f = frame(title, xlabel, ylabel, xr, yr);
  let svg = f.svg;
  series.forEach((s, i) => { svg += polyline(s.x, s.y, f.sx, f.sy, COLOURS[i % COLOURS.length]); });
  if (series.length > 1) { svg += legend(series.map((s) => s.label)); }
  return svg + "</svg>";
}

// The same scale east and north: the ranges widened to the plot's aspect.
function planRanges(xs, ys) {
  let [x0, x1] = extent(xs.concat([0]));
  let [y0, y1] = extent(ys.concat([0]));
  const w = CHART.width - CHART.left - CHART.right, h = CHART.height - CHART.top - CHART.bottom;
  const scale = Math.max((x1 - x0) / w, (y1 - y0) / h) * 1.05;
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  return [[cx - (scale * w) / 2, cx + (scale * w) / 2], [cy - (scale * h) / 2, cy + (scale * h) / 2]];
}

function pad(f) {
  return `<circle cx="${f.sx(0)}" cy="${f.sy(0)}" r="4" fill="none" stroke="#1b1f24"/>`;
}

function trackChart(title, x, y) {
  const [xr, yr] = planRanges(x, y);
  const f = frame(title, "east of the pad (m)", "north of the pad (m)", xr, yr);
  return f.svg + pad(f) + polyline(x, y, f.sx, f.sy, COLOURS[0]) + "</svg>";
}

// The boundary of an ellipse: centre, semi-axes and the major axis's direction (degrees
// counter-clockwise from east).
function ellipsePoints([cx, cy], a, b, degrees) {
  const phi = (degrees * Math.PI) / 180;
  const out = [];
  for (let i = 0; i <= 72; i++) {
    const t = (2 * Math.PI * i) / 72;
    const [u, v] = [a * Math.cos(t), b * Math.sin(t)];
    out.push([cx + u * Math.cos(phi) - v * Math.sin(phi), cy + u * Math.sin(phi) + v * Math.cos(phi)]);
  }
  return out;
}

// points: [[x, y]]; ellipses: [{points: [[x, y]], label}] drawn over them.
function landingChart(title, points, ellipses = []) {
  const outline = ellipses.flatMap((e) => e.points);
  const xs = points.concat(outline).map((p) => p[0]), ys = points.concat(outline).map((p) => p[1]);
  const [xr, yr] = planRanges(xs, ys);
  const f = frame(title, "east of the pad (m)", "north of the pad (m)", xr, yr);
  let svg = f.svg + pad(f);
  for (const [x, y] of points) {
    svg += `<circle cx="${f.sx(x).toFixed(1)}" cy="${f.sy(y).toFixed(1)}" r="2" fill="${COLOURS[1]}" fill-opacity="0.6"/>`;
  }
  ellipses.forEach((e, i) => {
    svg += polyline(e.points.map((p) => p[0]), e.points.map((p) => p[1]), f.sx, f.sy, COLOURS[0]).replace("<polyline", `<polyline class="ellipse" data-label="${escapeXml(e.label)}"`);
  });
  return svg + "</svg>";
}
