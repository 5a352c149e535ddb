// The floor plan panel: each item's base to scale at its catalogue pose, coloured by mode (or by
// P(overturned)), and the item under a click.
import { $, colourOf, modeOf, view } from './state.js';

export function footprint(it) {
  const w = it.width > 0 ? it.width : 0.3;
  const d = it.depth > 0 ? it.depth : w;  // an x-plane-only item: drawn square
  const nu = it.eccentricity > 0 ? it.eccentricity : 0.5, nuy = it.eccentricity_y > 0 ? it.eccentricity_y : 0.5;
  return { w, d, nu, nuy };
}

export function layoutPlan() {
  // Items without a pose in the catalogue go on a row below the others (their place is unknown).
  let minx = Infinity, maxx = -Infinity, miny = Infinity, maxy = -Infinity;
  const posed = view.items.filter((it) => it.pose);
  for (const it of posed) {
    const f = footprint(it), r = Math.hypot(f.w, f.d);
    minx = Math.min(minx, it.pose.x - r); maxx = Math.max(maxx, it.pose.x + r);
    miny = Math.min(miny, it.pose.y - r); maxy = Math.max(maxy, it.pose.y + r);
  }
  if (!posed.length) { minx = 0; maxx = 4; miny = 0; maxy = 3; }
  const loose = view.items.filter((it) => !it.pose);
  const perRow = Math.max(1, Math.ceil(Math.sqrt(loose.length * 4)));
  loose.forEach((it, k) => {
    it.auto = { x: minx + 0.5 + 1.0 * (k % perRow), y: miny - 1.0 - 1.0 * Math.floor(k / perRow), yaw: 0 };
  });
  if (loose.length) miny -= 1.5 + Math.ceil(loose.length / perRow);
  view.bounds = { minx, maxx, miny, maxy };
}

function placeOf(it) { return it.pose || it.auto || { x: 0, y: 0, yaw: 0 }; }

function fitCanvas(c) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(50, Math.round(c.clientWidth * dpr)), h = Math.max(50, Math.round(c.clientHeight * dpr));
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  return dpr;
}

export function drawPlan() {
  const c = $('plan'), ctx = c.getContext('2d');
  const dpr = fitCanvas(c);
  const W = c.width, H = c.height, pad = 28 * dpr;
  ctx.clearRect(0, 0, W, H);
  if (!view.bounds) return;
  const b = view.bounds;
  const s = Math.min((W - 2 * pad) / (b.maxx - b.minx), (H - 2 * pad) / (b.maxy - b.miny));
  const ox = pad + ((W - 2 * pad) - s * (b.maxx - b.minx)) / 2 - s * b.minx;
  const oy = H - pad - ((H - 2 * pad) - s * (b.maxy - b.miny)) / 2 + s * b.miny;
  view.plan = { s, ox, oy, dpr };  // canvas = (ox + s x, oy - s y): x right, y up (REP 103)

  // 1 m grid (coarser when the site is large), so distances read off the plan.
  let step = 1;
  while (s * step < 25 * dpr) step *= 5;
  ctx.strokeStyle = '#e6eaee';
  ctx.lineWidth = 1;
  ctx.beginPath();
  for (let x = Math.ceil(b.minx / step) * step; x <= b.maxx; x += step) { ctx.moveTo(ox + s * x, 0); ctx.lineTo(ox + s * x, H); }
  for (let y = Math.ceil(b.miny / step) * step; y <= b.maxy; y += step) { ctx.moveTo(0, oy - s * y); ctx.lineTo(W, oy - s * y); }
  ctx.stroke();
  // scale bar
  ctx.fillStyle = '#444';
  ctx.fillRect(pad, H - 12 * dpr, s * step, 3 * dpr);
  ctx.font = 11 * dpr + 'px system-ui, sans-serif';
  ctx.fillText(step + ' m', pad + s * step + 6 * dpr, H - 8 * dpr);
  ctx.fillText('x \u2192   y \u2191', W - 80 * dpr, H - 8 * dpr);

  const labels = view.items.length <= 300;
  for (const it of view.items) {
    const p = placeOf(it), f = footprint(it), m = modeOf(it);
    ctx.save();
    ctx.translate(ox + s * p.x, oy - s * p.y);
    ctx.rotate(-p.yaw);  // canvas y points down: a counter-clockwise yaw turns the other way here
    // The item frame's origin is under the centre of mass: the base spans -nu B .. (1 - nu) B.
    const x0 = -f.nu * f.w * s, y0 = -(1 - f.nuy) * f.d * s;
    ctx.fillStyle = colourOf(it);
    ctx.globalAlpha = it.pose ? 1 : 0.6;
    ctx.fillRect(x0, y0, f.w * s, f.d * s);
    ctx.globalAlpha = 1;
    ctx.lineWidth = (it.id === view.selected ? 3 : 1) * dpr;
    ctx.strokeStyle = it.id === view.selected ? '#0b3d91' : '#0006';
    ctx.strokeRect(x0, y0, f.w * s, f.d * s);
    if (m === 'OVERTURNED') {  // a cross as well as the colour: readable in grey print too
      ctx.beginPath();
      ctx.moveTo(x0, y0); ctx.lineTo(x0 + f.w * s, y0 + f.d * s);
      ctx.moveTo(x0 + f.w * s, y0); ctx.lineTo(x0, y0 + f.d * s);
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 2 * dpr;
      ctx.stroke();
    }
    ctx.restore();
    if (labels) {
      ctx.fillStyle = '#222';
      ctx.font = (it.id === view.selected ? 'bold ' : '') + 12 * dpr + 'px system-ui, sans-serif';
      const r = Math.hypot(f.w, f.d) * s / 2, tw = ctx.measureText(it.id).width;
      let lx = ox + s * p.x + r + 4 * dpr;
      if (lx + tw > W - 4 * dpr) lx = ox + s * p.x - r - 4 * dpr - tw;  // near the right edge: on the left
      ctx.fillText(it.id, lx, oy - s * p.y - r);
    }
  }
}

export function pickAt(px, py) {
  const P = view.plan;
  if (!P) return null;
  const wx = (px * P.dpr - P.ox) / P.s, wy = (P.oy - py * P.dpr) / P.s;
  const tol = 4 * P.dpr / P.s;  // a few pixels around small items
  let best = null, bestArea = Infinity;
  for (const it of view.items) {
    const p = placeOf(it), f = footprint(it);
    const dx = wx - p.x, dy = wy - p.y, c = Math.cos(p.yaw), sn = Math.sin(p.yaw);
    const lx = c * dx + sn * dy, ly = -sn * dx + c * dy;  // into the item's frame
    if (lx >= -f.nu * f.w - tol && lx <= (1 - f.nu) * f.w + tol && ly >= -f.nuy * f.d - tol && ly <= (1 - f.nuy) * f.d + tol) {
      const area = f.w * f.d;
      if (area < bestArea) { best = it; bestArea = area; }  // the smaller one when they overlap
    }
  }
  return best;
}
