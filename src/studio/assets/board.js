// Drawing scenes as SVG, north up (the same colours as `rccpack render`).

const NS = 'http://www.w3.org/2000/svg';

export function el(name, attrs = {}, parent = null) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

export function darker(hex) {
  const v = parseInt(hex.slice(1), 16);
  const c = (s) => Math.floor(((v >> s) & 255) * 0.7).toString(16).padStart(2, '0');
  return `#${c(16)}${c(8)}${c(0)}`;
}

export function textOn(hex) {
  const v = parseInt(hex.slice(1), 16);
  const l = 0.299 * ((v >> 16) & 255) + 0.587 * ((v >> 8) & 255) + 0.114 * (v & 255);
  return l > 165 ? '#222222' : '#ffffff';
}

// What an object covers: its size, height × width when it lies turned.
export function footprint(o) {
  return o.turned ? { w: o.height, h: o.width } : { w: o.width, h: o.height };
}

export function overlaps(a, b) {
  const fa = footprint(a);
  const fb = footprint(b);
  return a.x < b.x + fb.w && b.x < a.x + fa.w && a.y < b.y + fb.h && b.y < a.y + fa.h;
}

export function inside(o, s) {
  const f = footprint(o);
  return o.x >= s.x && o.y >= s.y && o.x + f.w <= s.x + s.width && o.y + f.h <= s.y + s.height;
}

// Geometry of a drawing: world (north up) -> SVG user units (y down).
export class View {
  constructor(space, margin) {
    this.space = space;
    this.m = margin;
  }
  sx(x) { return x - this.space.x + this.m; }
  sy(y) { return this.space.y + this.space.height - y + this.m; }
  // Screen rect of an object.
  rect(o) {
    const f = footprint(o);
    return { x: this.sx(o.x), y: this.sy(o.y + f.h), w: f.w, h: f.h };
  }
  // World point from SVG user units.
  world(px, py) { return { x: px - this.m + this.space.x, y: this.space.y + this.space.height - (py - this.m) }; }
  get width() { return this.space.width + 2 * this.m; }
  get height() { return this.space.height + 2 * this.m; }
}

// Draw the table, grid and objects into `svg` (cleared first).
// opts: { colours, fixedColour, grid, thumb, violators: Map(id -> 'soft'|'hard'), selected }
export function drawScene(svg, scene, opts) {
  svg.replaceChildren();
  const margin = opts.thumb ? 4 : 26;
  const view = new View(scene.space, margin);
  svg.setAttribute('viewBox', `0 0 ${view.width} ${view.height}`);
  const s = scene.space;
  el('rect', { class: 'table', x: view.sx(s.x), y: view.sy(s.y + s.height), width: s.width, height: s.height,
    fill: '#f5f6f8', stroke: '#b9bfc8', 'stroke-width': opts.thumb ? 2 : 1 }, svg);
  if (!opts.thumb) {
    let step = scene.grid;
    while (step * (svg.clientWidth || 600) / view.width < 6) step *= 2;
    let d = '';
    for (let x = s.x + step; x < s.x + s.width; x += step) d += `M${view.sx(x)} ${view.sy(s.y)}V${view.sy(s.y + s.height)}`;
    for (let y = s.y + step; y < s.y + s.height; y += step) d += `M${view.sx(s.x)} ${view.sy(y)}H${view.sx(s.x + s.width)}`;
    el('path', { class: 'grid', d, stroke: '#e3e6eb', 'stroke-width': 0.6, fill: 'none' }, svg);
    const n = el('text', { x: view.width - 6, y: 16, 'font-size': 13, 'font-weight': 'bold', 'text-anchor': 'end',
      fill: '#555555', class: 'north' }, svg);
    n.textContent = 'N ↑';
  }
  const layer = el('g', { class: 'objects' }, svg);
  for (const o of scene.objects) {
    if (o.x === undefined || o.y === undefined) continue;
    drawObject(layer, view, o, opts);
  }
  // A probe that is an edit of a demonstration: where each moved object
  // was (dashed), a line to where it is, and an outline.
  if (opts.moved && opts.moved.length) {
    const marks = el('g', { class: 'moved' }, svg);
    for (const m of opts.moved) {
      const o = scene.objects.find((x) => x.id === m.id);
      if (!o || o.x === undefined) continue;
      const was = view.rect({ ...o, x: m.x, y: m.y });
      const now = view.rect(o);
      const g = el('g', { class: 'move', 'data-id': m.id }, marks);
      el('rect', { class: 'was', x: was.x, y: was.y, width: was.w, height: was.h, fill: 'none',
        stroke: '#1f5fbf', 'stroke-width': 2, 'stroke-dasharray': '5 3' }, g);
      el('line', { x1: was.x + was.w / 2, y1: was.y + was.h / 2, x2: now.x + now.w / 2, y2: now.y + now.h / 2,
        stroke: '#1f5fbf', 'stroke-width': 1.5, 'stroke-dasharray': '2 3' }, g);
      el('rect', { class: 'now', x: now.x - 4, y: now.y - 4, width: now.w + 8, height: now.h + 8, fill: 'none',
        stroke: '#1f5fbf', 'stroke-width': 2.5 }, g);
    }
  }
  return { view, layer };
}

export function drawObject(layer, view, o, opts) {
  const r = view.rect(o);
  const fill = o.fixed ? opts.fixedColour : (opts.colours[o.class] || '#888888');
  const g = el('g', { class: o.fixed ? 'obj fixed' : 'obj', 'data-id': o.id }, layer);
  el('rect', { x: r.x, y: r.y, width: r.w, height: r.h, fill, stroke: darker(fill), 'stroke-width': 1 }, g);
  if (o.turned) {
    // A quarter-turn arrow in the north-east corner, as `rccpack render` draws it.
    const q = Math.max(2, Math.min(9, Math.min(r.w, r.h) * 0.3));
    const ax = r.x + r.w - q - 1.5;
    const ay = r.y + 1.5;
    el('path', { class: 'turn-mark', d: `M ${ax} ${ay} A ${q} ${q} 0 0 1 ${ax + q} ${ay + q} l ${-q / 2} 0 l 0 ${-q / 2}`,
      fill: 'none', stroke: darker(fill), 'stroke-width': 1.6, 'pointer-events': 'none' }, g);
  }
  if (!o.fixed && !opts.thumb && Math.min(r.w, r.h) >= 12) {
    const t = el('text', { x: r.x + r.w / 2, y: r.y + r.h / 2, 'font-size': Math.min(r.w, r.h) * 0.5,
      'text-anchor': 'middle', 'dominant-baseline': 'central', fill: textOn(fill), 'pointer-events': 'none' }, g);
    t.textContent = o.class;
  }
  const bad = opts.violators && opts.violators.get(o.id);
  if (bad) {
    el('rect', { x: r.x - 2, y: r.y - 2, width: r.w + 4, height: r.h + 4, fill: 'none',
      stroke: bad === 'hard' ? '#c0392b' : '#ff8c00', 'stroke-width': 2.5, class: 'violation' }, g);
  }
  if (opts.selected === o.id) {
    el('rect', { x: r.x - 1.5, y: r.y - 1.5, width: r.w + 3, height: r.h + 3, fill: 'none', stroke: '#111111',
      'stroke-width': 1.5, 'stroke-dasharray': '3 2', class: 'selection' }, g);
  }
  return g;
}
