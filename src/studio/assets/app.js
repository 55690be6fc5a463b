// rccpack studio: record demonstrations, learn rules, synthesise layouts.
import { drawScene, drawObject, el, overlaps, inside, darker } from '/assets/board.js';

const $ = (id) => document.getElementById(id);
const state = {
  task: null,
  placed: [],          // movable objects on the table
  selected: null,      // id of the selected object
  drag: null,          // { obj, fromPalette, dx, dy, original, over, valid, why }
  view: null,
  demos: [],
  learnResult: null,
  learned: null,       // { exists, text, version, rules?, error? }
  tab: 'record',
  boardMode: 'edit',   // 'edit' | 'result' | 'probe'
  result: null,        // synthesis result shown on the board
  question: null,      // the open "Check rules" question
  probe: null,         // { scene, violators, title, info } shown on the board
  checked: false,      // rules were checked since the last Learn: synthesize with learned.rcc
};

// ---- helpers ------------------------------------------------------------------

async function api(method, url, body) {
  const init = { method, headers: {} };
  // Every request that changes something is JSON: the studio refuses any
  // other content type (docs/studio.md#security-model, trust of the studio).
  if (method !== 'GET') init.headers['content-type'] = 'application/json';
  if (body !== undefined) {
    init.body = typeof body === 'string' ? body : JSON.stringify(body);
  }
  const res = await fetch(url, init);
  let data = null;
  try { data = await res.json(); } catch { data = { error: `${res.status} ${res.statusText}` }; }
  return { ok: res.ok, status: res.status, data };
}

let toastTimer = null;
function toast(msg, kind = 'info') {
  const t = $('toast');
  t.textContent = msg;
  t.className = `toast show ${kind}`;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => { t.className = 'toast'; }, kind === 'error' ? 8000 : 3500);
}

function fmtP(p) {
  if (p === null || p === undefined) return '–';
  if (p === 0) return '0';
  if (p >= 0.001) return p.toPrecision(2);
  const [m, e] = p.toExponential(1).split('e');
  return `${m}·10<sup>${Number(e)}</sup>`;
}
function pct(q) { return q === null || q === undefined ? '–' : `${(q * 100).toFixed(q < 0.01 ? 2 : 1)}%`; }
function esc(s) { return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c])); }

function fixedObjects() { return state.task.problem.objects.filter((o) => o.fixed); }
function boardScene() {
  const p = state.task.problem;
  return { space: p.space, grid: p.grid, objects: [...fixedObjects(), ...state.placed] };
}
function drawOpts(extra = {}) {
  return { colours: state.task.colours, fixedColour: state.task.fixed_colour, ...extra };
}

// ---- board ------------------------------------------------------------------

function redraw() {
  const svg = $('board');
  const shown = state.boardMode === 'result' ? state.result : state.boardMode === 'probe' ? state.probe : null;
  if (shown) {
    const { view } = drawScene(svg, shown.scene, drawOpts({ violators: shown.violators, moved: shown.moved }));
    state.view = view;
    return;
  }
  const { view, layer } = drawScene(svg, boardScene(), drawOpts({ selected: state.selected }));
  state.view = view;
  const d = state.drag;
  if (d && d.over) {
    const g = drawObject(layer, view, d.obj, drawOpts());
    g.classList.add('ghost', d.valid ? 'ok' : 'bad');
    const r = view.rect(d.obj);
    el('rect', { x: r.x - 1.5, y: r.y - 1.5, width: r.w + 3, height: r.h + 3, fill: 'none',
      stroke: d.valid ? '#2e7d32' : '#c62828', 'stroke-width': 2, class: 'ghost-outline' }, g);
  }
  const n = state.placed.length;
  $('stage-info').textContent = `${n} object${n === 1 ? '' : 's'} placed · grid ${state.task.problem.grid} · north is up`;
  $('btn-delete').disabled = !state.selected;
}

function toWorld(ev) {
  const svg = $('board');
  const pt = svg.createSVGPoint();
  pt.x = ev.clientX; pt.y = ev.clientY;
  const ctm = svg.getScreenCTM();
  if (!ctm) return null;
  const p = pt.matrixTransform(ctm.inverse());
  return state.view.world(p.x, p.y);
}

function overBoard(ev) {
  const r = $('board').getBoundingClientRect();
  return ev.clientX >= r.left && ev.clientX <= r.right && ev.clientY >= r.top && ev.clientY <= r.bottom;
}

// Why `o` cannot go where it is, or null.
function refusal(o) {
  const p = state.task.problem;
  if (!inside(o, p.space)) return 'outside the table';
  for (const other of [...fixedObjects(), ...state.placed]) {
    if (other.id !== o.id && overlaps(o, other)) return `it would overlap ${other.id}`;
  }
  return null;
}

function snap(w) {
  const p = state.task.problem;
  const g = p.grid;
  return {
    x: p.space.x + Math.round((w.x - state.drag.dx - p.space.x) / g) * g,
    y: p.space.y + Math.round((w.y - state.drag.dy - p.space.y) / g) * g,
  };
}

function nextId(cls) {
  const base = cls.toLowerCase();
  const used = new Set([...fixedObjects(), ...state.placed].map((o) => o.id));
  let i = 1;
  while (used.has(`${base}${i}`)) i++;
  return `${base}${i}`;
}

function startDrag(ev, obj, fromPalette) {
  if (state.boardMode !== 'edit') showEditor();
  ev.preventDefault();
  const w = fromPalette ? null : toWorld(ev);
  state.drag = {
    obj: { ...obj }, fromPalette, original: fromPalette ? null : { ...obj },
    dx: fromPalette ? obj.width / 2 : w.x - obj.x,
    dy: fromPalette ? obj.height / 2 : w.y - obj.y,
    over: !fromPalette, valid: true,
  };
  if (!fromPalette) {
    state.selected = obj.id;
    state.placed = state.placed.filter((o) => o.id !== obj.id);
  }
  document.body.classList.add('dragging');
  moveDrag(ev);
}

function moveDrag(ev) {
  const d = state.drag;
  if (!d) return;
  d.over = overBoard(ev);
  const w = toWorld(ev);
  if (w) Object.assign(d.obj, snap(w));
  d.why = d.over ? refusal(d.obj) : 'dropped outside the table';
  d.valid = !d.why;
  redraw();
}

function endDrag(ev) {
  const d = state.drag;
  if (!d) return;
  moveDrag(ev);
  state.drag = null;
  document.body.classList.remove('dragging');
  if (d.valid) {
    state.placed.push(d.obj);
    state.selected = d.obj.id;
    redraw();
    return;
  }
  if (d.original) state.placed.push(d.original);
  // A block from the palette released off the table: the user changed their mind.
  const moved = d.original ? d.original.x !== d.obj.x || d.original.y !== d.obj.y : d.over;
  redraw();
  if (moved) {
    toast(`Drop refused: ${d.why}.`, 'error');
    flashRefused(d.obj);
  }
}

function flashRefused(o) {
  if (!state.view) return;
  const r = state.view.rect(o);
  const svg = $('board');
  const f = el('rect', { x: r.x, y: r.y, width: r.w, height: r.h, class: 'refused', fill: '#c62828',
    'fill-opacity': 0.25, stroke: '#c62828', 'stroke-width': 2 }, svg);
  setTimeout(() => f.remove(), 900);
}

// Turn the selected block by a quarter turn (a square one has nothing to
// turn), unless it would then overlap or leave the table.
function turnSelected() {
  const o = state.placed.find((p) => p.id === state.selected);
  if (!o || o.width === o.height) return;
  const turned = { ...o, turned: !o.turned };
  if (!turned.turned) delete turned.turned;
  const why = refusal(turned);
  if (why) {
    toast(`Turn refused: ${why}.`, 'error');
    flashRefused(turned);
    return;
  }
  state.placed = state.placed.map((p) => (p.id === o.id ? turned : p));
  redraw();
}

function deleteSelected() {
  if (!state.selected) return;
  state.placed = state.placed.filter((o) => o.id !== state.selected);
  state.selected = null;
  redraw();
}

function showEditor() {
  state.boardMode = 'edit';
  $('stage-title').textContent = 'New demonstration';
  renderLegend();
  redraw();
}

// ---- record pane ----------------------------------------------------------------

function renderPalette() {
  const pal = $('palette');
  pal.replaceChildren();
  for (const k of state.task.kinds) {
    const item = document.createElement('div');
    item.className = 'kind';
    item.dataset.class = k.class;
    item.title = `Drag a ${k.class} block (${k.width}×${k.height}) onto the table`;
    const scale = Math.min(1.6, 40 / Math.max(k.width, k.height));
    item.innerHTML = `<span class="swatch" style="width:${Math.max(10, k.width * scale)}px;height:${Math.max(10, k.height * scale)}px;background:${k.colour};border-color:${darker(k.colour)}"></span>
      <span class="kind-label"><b>${esc(k.class)}</b><span class="muted small">${k.width}×${k.height}</span></span>`;
    item.addEventListener('pointerdown', (ev) => startDrag(ev, { id: nextId(k.class), class: k.class, width: k.width, height: k.height }, true));
    pal.appendChild(item);
  }
}

function renderLegend() {
  const items = state.task.kinds.map((k) => `<span><i style="background:${k.colour}"></i>${esc(k.class)}</span>`);
  items.push(`<span><i style="background:${state.task.fixed_colour}"></i>fixed</span>`);
  if (state.boardMode === 'result') {
    items.push('<span><i class="ring soft"></i>breaks a rule</span>', '<span><i class="ring hard"></i>breaks a hard rule</span>');
  }
  if (state.boardMode === 'probe') {
    items.push('<span><i class="ring probe"></i>breaks the rule asked about</span>');
  }
  $('legend').innerHTML = items.join('');
}

async function loadDemos() {
  const r = await api('GET', '/api/demos');
  const box = $('demos');
  if (!r.ok) {
    box.innerHTML = `<div class="error-box">${esc(r.data.error)}</div>`;
    $('demo-count').textContent = '!';
    state.demos = [];
    return;
  }
  state.demos = r.data.demos;
  state.demosVersion = r.data.version;
  $('demo-count').textContent = r.data.count;
  box.replaceChildren();
  if (!r.data.count) {
    box.innerHTML = '<p class="hint">None yet. Place the blocks the way you like them and save.</p>';
  }
  r.data.demos.forEach((scene, i) => {
    const item = document.createElement('div');
    item.className = 'demo';
    item.dataset.index = i;
    const svg = el('svg', { class: 'thumb' });
    item.appendChild(svg);
    drawScene(svg, scene, drawOpts({ thumb: true }));
    const n = scene.objects.filter((o) => !o.fixed).length;
    const meta = document.createElement('div');
    meta.className = 'demo-meta';
    meta.innerHTML = `<b>#${i + 1}</b><span class="muted small">${n} objects</span>`;
    const show = document.createElement('button');
    show.className = 'btn small'; show.textContent = 'Show'; show.title = 'Load a copy onto the table';
    show.onclick = () => {
      state.placed = scene.objects.filter((o) => !o.fixed).map((o) => ({ ...o }));
      state.selected = null;
      showEditor();
      $('stage-title').textContent = `Copy of demonstration #${i + 1}`;
      toast(`Demonstration #${i + 1} is on the table; saving adds a new one.`);
    };
    const del = document.createElement('button');
    del.className = 'btn small danger'; del.textContent = 'Delete';
    del.onclick = async () => {
      if (!confirm(`Delete demonstration #${i + 1}?`)) return;
      const d = await api('DELETE', `/api/demos/${i}?version=${encodeURIComponent(state.demosVersion)}`);
      if (d.ok) { toast(`Deleted demonstration #${i + 1}.`, 'ok'); state.suspects = []; } else toast(d.data.error, 'error');
      loadDemos();
    };
    meta.append(show, del);
    item.appendChild(meta);
    box.appendChild(item);
  });
  markSuspects();
}

async function saveDemo() {
  const r = await api('POST', '/api/demos', boardScene());
  if (!r.ok) { toast(r.data.error, 'error'); return; }
  toast(`Saved demonstration #${r.data.index + 1} to demos.json.`, 'ok');
  state.suspects = [];
  state.placed = [];
  state.selected = null;
  showEditor();
  loadDemos();
}

// ---- learn pane -------------------------------------------------------------------

async function learn() {
  const btn = $('btn-learn');
  btn.disabled = true;
  btn.textContent = 'Learning…';
  $('learn-summary').innerHTML = '<div class="progress"><span></span></div>';
  const slip = Number($('learn-slip-rate').value) || 0;
  const r = await api('POST', '/api/learn', slip ? { slip_rate: slip } : {});
  btn.disabled = false;
  btn.textContent = 'Learn again';
  if (!r.ok) {
    $('learn-summary').innerHTML = `<pre class="error-box">${esc(r.data.error)}</pre>`;
    return;
  }
  const d = r.data;
  state.learnResult = d;
  state.checked = false;
  state.question = null;
  $('learn-summary').innerHTML = `<p><b>${d.rules.length}</b> rules learned from <b>${d.demonstrations}</b> demonstrations:
    ${d.candidates} of ${d.statements} ${d.source === 'given' ? 'statements from statements.rcc' : 'template statements'} hold in every demonstration;
    the rest are rejected as likely by chance (${d.samples} random layouts).</p>`;
  const suspects = d.suspects || [];
  if (suspects.length) {
    $('learn-summary').insertAdjacentHTML('beforeend', `<div class="suspects" data-testid="suspects"><p><b>Looks like a slip?</b></p>${
      suspects.map((s) => `<p class="small" data-demo="${s.demonstration}">demonstration #${s.demonstration + 1}: ${s.object ? `<b>${esc(s.object)}</b>` : 'it'}
        breaks ${s.breaks.length} rule${s.breaks.length === 1 ? '' : 's'} the others keep (${esc(s.breaks.slice(0, 4).join(', '))}${s.breaks.length > 4 ? ', …' : ''})</p>`).join('')
    }<p class="hint">Check rules (with a slip rate) asks about each.</p></div>`);
  }
  state.suspects = suspects;
  markSuspects();
  renderRules();
}

/// Mark the demonstrations with a suspect on the demonstrations board.
function markSuspects() {
  const by = new Map();
  for (const s of state.suspects || []) {
    if (!by.has(s.demonstration)) by.set(s.demonstration, []);
    if (s.object) by.get(s.demonstration).push(s.object);
  }
  for (const item of document.querySelectorAll('#demos .demo')) {
    const objs = by.get(Number(item.dataset.index));
    item.classList.toggle('suspect', !!objs);
    item.querySelector('.pill.slip')?.remove();
    if (objs) {
      const pill = document.createElement('span');
      pill.className = 'pill slip';
      pill.dataset.testid = 'slip';
      pill.textContent = 'a slip?';
      pill.title = `${objs.join(', ')} break${objs.length === 1 ? 's' : ''} rules the other demonstrations keep`;
      item.querySelector('.demo-meta')?.prepend(pill);
    }
  }
}

function renderRules() {
  const d = state.learnResult;
  $('rules-card').hidden = false;
  const box = $('rules');
  box.replaceChildren();
  if (!d.rules.length) {
    box.innerHTML = '<p class="hint">No rule is strong enough yet. Save more demonstrations.</p>';
  }
  d.rules.forEach((rule, i) => {
    const row = document.createElement('label');
    row.className = 'rule';
    row.innerHTML = `<input type="checkbox" checked data-i="${i}">
      <span class="rule-body">
        <span class="rule-head"><b>${esc(rule.name)}</b>
          <span class="pill" title="posterior probability that this is NOT one of your rules">P ${fmtP(rule.posterior)}</span>
          <span class="pill light" title="how often random layouts satisfy it">chance ${pct(rule.q)}</span></span>
        <span class="english">${esc(rule.english)}</span>
        <code>${esc(rule.formula)}</code>
      </span>`;
    box.appendChild(row);
  });
}

function chosenRulesText() {
  const d = state.learnResult;
  const chosen = [...document.querySelectorAll('#rules input[type=checkbox]')]
    .filter((c) => c.checked).map((c) => d.rules[Number(c.dataset.i)]);
  return { text: `${d.header}\n${chosen.map((r) => r.rcc).join('\n')}`, count: chosen.length };
}

async function loadLearned() {
  const r = await api('GET', '/api/learned');
  if (r.ok) state.learned = r.data;
  renderLearned();
}

function renderLearned() {
  const l = state.learned;
  const box = $('learned-file');
  if (!l) { box.textContent = ''; return; }
  if (!l.exists) {
    box.innerHTML = '<p class="hint">Not saved yet.</p>';
    return;
  }
  const n = l.rules ? `${l.rules.length} rules` : 'does not parse';
  box.innerHTML = `<p><b>${n}</b> <span class="muted small">version ${esc(l.version.slice(0, 8))}</span>
    <button class="btn small" id="btn-reload-learned">Reload from disk</button></p>
    ${l.error ? `<pre class="error-box">${esc(l.error)}</pre>` : ''}
    <details><summary>Show file</summary><pre class="file">${esc(l.text)}</pre></details>`;
  $('btn-reload-learned').onclick = async () => { await loadLearned(); toast('Reloaded learned.rcc from disk.'); };
}

async function saveRules() {
  const { text, count } = chosenRulesText();
  const base = state.learned ? state.learned.version : 'absent';
  const r = await api('PUT', '/api/learned', { text, base_version: base });
  if (r.status === 409) {
    state.learned = r.data.current;
    renderLearned();
    toast(r.data.error, 'error');
    return;
  }
  if (!r.ok) { toast(r.data.error, 'error'); return; }
  state.learned = r.data;
  renderLearned();
  toast(`Saved ${count} rules to learned.rcc.`, 'ok');
}

// ---- synthesize pane ------------------------------------------------------------------

// The rules to solve with: the ticked learned rules of this session, else learned.rcc.
function synthRules() {
  if (state.checked && state.learned && state.learned.exists && state.learned.rules) {
    return { text: state.learned.text, label: `learned.rcc, checked (${state.learned.rules.length} rules)` };
  }
  if (state.learnResult && state.learnResult.rules.length) {
    const { text, count } = chosenRulesText();
    return { text, label: `the ${count} rules ticked in Learn` };
  }
  if (state.learned && state.learned.exists && state.learned.rules) {
    return { text: state.learned.text, label: `learned.rcc (${state.learned.rules.length} rules)` };
  }
  return null;
}

function renderSynthPane() {
  const r = synthRules();
  $('synth-rules').innerHTML = r ? `Rules: <b>${esc(r.label)}</b>` : 'No rules yet: run Learn first, or save learned.rcc.';
  $('btn-synth').disabled = !r || state.job !== undefined && state.job !== null;
}

async function synthesize() {
  const r = synthRules();
  if (!r) return;
  const limit = Number($('synth-limit').value) || 30;
  const res = await api('POST', '/api/synth', { rules: r.text, time_limit: limit });
  if (!res.ok) { toast(res.data.error, 'error'); return; }
  state.job = res.data.job;
  $('btn-synth').disabled = true;
  $('btn-cancel').hidden = false;
  $('synth-progress').hidden = false;
  $('synth-progress-text').textContent = 'starting…';
  pollJob();
}

async function pollJob() {
  const id = state.job;
  if (id === null || id === undefined) return;
  const res = await api('GET', `/api/synth/${id}`);
  if (!res.ok) { finishJob(); toast(res.data.error, 'error'); return; }
  const d = res.data;
  if (d.state === 'running') {
    const best = d.best_score === null ? 'no layout yet' : `best score so far ${d.best_score.toFixed(3)}`;
    $('synth-progress-text').textContent = `${d.cancelled ? 'cancelling' : 'searching'} · ${(d.elapsed_ms / 1000).toFixed(1)} s · ${best}`;
    setTimeout(pollJob, 250);
    return;
  }
  finishJob();
  if (d.state === 'error') { toast(d.error, 'error'); return; }
  showResult(d.result, d.cancelled);
}

function finishJob() {
  state.job = null;
  $('btn-cancel').hidden = true;
  $('synth-progress').hidden = true;
  renderSynthPane();
}

function showResult(r, cancelled) {
  const box = $('synth-result');
  box.hidden = false;
  const ev = r.evaluation;
  const score = ev ? `<div class="score"><b>${ev.score.toFixed(3)}</b><span class="muted small">score · ${fmtW(ev.satisfied_weight)} of ${fmtW(ev.total_weight)} weight</span></div>` : '';
  let rows = '';
  if (ev) {
    for (const rule of ev.rules) {
      const okAll = rule.satisfied === rule.subjects;
      // A broken group statement names the objects off the main group.
      const off = rule.group && !okAll && rule.violators.length
        ? `<div class="muted small">off the main ${esc(rule.group.shape)}: ${rule.violators.map(esc).join(', ')}</div>` : '';
      rows += `<tr class="${okAll ? 'good' : 'bad'}"><td>${okAll ? '✓' : '✗'}</td><td>${esc(rule.name)}${rule.hard ? ' <span class="pill hard">hard</span>' : ''}${off}</td>
        <td class="num">${rule.satisfied} / ${rule.subjects}</td></tr>`;
    }
  }
  let conflict = '';
  if (r.conflict) {
    const c = r.conflict;
    conflict = `<div class="error-box">${c.objects_cannot_fit ? 'The objects cannot all fit in the space.' : ''}
      ${c.hard_rules.length ? `These hard rules cannot hold together: ${c.hard_rules.map(esc).join(', ')}` : ''}
      ${c.limit_struck ? 'A limit struck before the conflict was explained.' : ''}</div>`;
  }
  if (!r.sampled && ev) state.likeScore = ev.score;
  const head = r.sampled
    ? `another layout of score ≥ ${state.likeScore.toFixed(3)} (draw ${state.sampleSeed})`
    : `${(r.time_ms / 1000).toFixed(2)} s · ${r.stats.nodes} nodes${cancelled ? ' · cancelled' : ''}`;
  box.innerHTML = `<div class="result-head"><span class="status ${r.status}">${r.status}</span>
      <span class="muted small">${head}</span></div>
    ${score}${conflict}
    ${rows ? `<div class="rule-table-wrap"><table class="rule-table"><thead><tr><th></th><th>rule</th><th class="num">objects keeping it</th></tr></thead><tbody>${rows}</tbody></table></div>` : ''}
    ${r.scene ? '<button class="btn small" id="btn-back">Back to the table</button>' : ''}
    ${r.scene && ev ? '<button class="btn small" id="btn-another">Another layout like this</button>' : ''}`;
  if (r.scene) {
    const violators = new Map();
    for (const rule of ev.rules) for (const id of rule.violators) {
      if (rule.hard || !violators.has(id)) violators.set(id, rule.hard ? 'hard' : 'soft');
    }
    const title = `Synthesized layout · ${r.status}`;
    const info = violators.size ? `${violators.size} objects break a rule (outlined)` : 'every object keeps every rule';
    state.result = { scene: r.scene, violators, title, info };
    state.boardMode = 'result';
    $('stage-title').textContent = title;
    $('stage-info').textContent = info;
    renderLegend();
    redraw();
    $('btn-back').onclick = showEditor;
    if (ev) $('btn-another').onclick = anotherLayout;
  }
}

// "Another layout like this": the next draw of `rccpack sample` with at least
// the score of the synthesized layout.
async function anotherLayout() {
  const r = synthRules();
  if (!r || state.likeScore === undefined) return;
  state.sampleSeed = (state.sampleSeed || 0) + 1;
  const res = await api('POST', '/api/sample', { rules: r.text, min_score: state.likeScore, seed: state.sampleSeed });
  if (!res.ok) { toast(res.data.error, 'error'); return; }
  showResult(res.data, false);
}

function fmtW(w) { return Number.isInteger(w) ? String(w) : w.toFixed(2); }

// ---- check rules pane (docs/guide.md#questions) ----------------------------------------------------

function setAskState(s) { document.body.dataset.ask = s; }

function renderAskProgress(p) {
  if (!p) return;
  const extra = [];
  if (p.implied) extra.push(`${p.implied} follow from the others`);
  if (p.unknown) extra.push(`${p.unknown} unsettled (probe time limit)`);
  $('ask-progress').innerHTML = `<p id="ask-progress-line" data-testid="ask-progress-line">asked ${p.asked} · dropped ${p.dropped} · confirmed ${p.confirmed}
    <span class="muted small">· ${p.held} rules held${extra.length ? ` · ${extra.join(' · ')}` : ''}</span></p>`;
}

function renderAskRules() {
  const l = state.learned;
  const box = $('ask-rules');
  $('ask-rules-card').hidden = !(l && l.exists);
  box.replaceChildren();
  if (!l || !l.exists) return;
  if (!l.rules) { box.innerHTML = `<pre class="error-box">${esc(l.error || 'learned.rcc does not parse')}</pre>`; return; }
  for (const r of l.rules) {
    const row = document.createElement('div');
    row.className = 'rule static';
    row.dataset.name = r.name;
    row.innerHTML = `<span class="rule-body"><span class="rule-head"><b>${esc(r.name)}</b>
        ${r.confirmed ? '<span class="pill confirmed">confirmed</span>' : ''}${r.hard ? '<span class="pill hard">hard</span>' : ''}</span>
      <code>${esc(r.formula)}</code></span>`;
    box.appendChild(row);
  }
}

function showProbe(q) {
  const violators = new Map(q.broken.map((id) => [id, 'hard']));
  const s = q.suspect;
  const title = s
    ? `Question ${q.number} · demonstration #${s.demonstration + 1} as you meant it?`
    : `Question ${q.number} · is this acceptable?`;
  const group = q.group || [];
  const info = s
    ? `${s.objects.length ? s.objects[0] : 'it'} (outlined) breaks ${s.breaks.length} rule${s.breaks.length === 1 ? '' : 's'} the other demonstrations keep: a slip?`
    : group.length
    ? `this layout breaks ${group.length} rules: ${group.map((g) => g.rule).join(', ')}${q.broken.length ? ` (outlined: ${q.broken.join(', ')})` : ''}`
    : q.broken.length
    ? `${q.broken.join(', ')} break${q.broken.length === 1 ? 's' : ''} ${q.rule} (outlined)`
    : `the layout breaks ${q.rule}`;
  const moved = q.edit ? q.edit.moved : [];
  const info2 = q.edit
    ? `${info} · demonstration ${q.edit.demo + 1} with ${moved.map((m) => m.id).join(' and ')} moved (dashed: where it was)`
    : info;
  state.probe = { scene: q.scene, violators, title, info: info2, moved };
  state.boardMode = 'probe';
  $('stage-title').textContent = title;
  $('stage-info').textContent = info2;
  renderLegend();
  redraw();
}

function applyAsk(d) {
  state.learned = d.learned;
  renderLearned();
  renderAskRules();
  renderAskProgress(d.progress);
  const q = d.question;
  state.question = q;
  $('ask-question').hidden = !q;
  $('ask-done').hidden = !!q;
  if (!q) {
    const p = d.progress;
    $('ask-done').innerHTML = `<h3>No more questions</h3>
      <p id="ask-summary" data-testid="ask-summary">${p.asked} answered${p.grouped ? ` (${p.grouped} about a group of rules)` : ''}: ${p.dropped} rules dropped, ${p.confirmed} confirmed${p.deduced ? ` (${p.deduced} as the one left of a rejected group)` : ''};
      ${p.held} rules held${p.implied ? `, ${p.implied} of them follow from the others` : ''}${p.unknown ? `, ${p.unknown} deferred (the question budget did not decide them)` : ''}.
      learned.rcc holds the checked rules.</p>`;
    state.probe = null;
    if (state.boardMode === 'probe') showEditor();
    setAskState('done');
    return;
  }
  $('ask-number').textContent = `question ${q.number}`;
  const s = q.suspect;
  $('ask-heading').textContent = s
    ? `Demonstration #${s.demonstration + 1} as you meant it?`
    : 'Is this layout acceptable?';
  $('ask-question').dataset.suspect = s ? String(s.demonstration) : '';
  const group = q.group || [];
  $('ask-rule').textContent = group.length ? `${group.length} rules` : q.rule;
  $('ask-english').textContent = group.length
    ? group.map((g) => `${g.rule}: ${g.english}`).join(' · ')
    : q.english;
  $('ask-statement').textContent = group.length
    ? group.map((g) => g.statement).join('  ·  ')
    : q.statement;
  $('ask-question').dataset.group = String(group.length);
  $('ask-broken').textContent = s
    ? `It breaks ${s.breaks.join(', ')}, which the other demonstrations keep. Looks right: it is meant, and those rules are dropped. Not like that: a slip; it no longer counts against those rules (demos.json keeps it).`
    : group.length
    ? `It breaks all ${group.length}; every other learned rule holds. Acceptable: none of them is meant, all are dropped. Not acceptable: at least one is meant, and the next questions find which.`
    : q.broken.length
    ? `Outlined: ${q.broken.join(', ')} break${q.broken.length === 1 ? 's' : ''} it; every other learned rule holds.`
    : 'Every other learned rule holds.';
  $('ask-question').dataset.rule = q.rule;
  $('ask-question').dataset.broken = String(q.broken.length);
  $('ask-question').dataset.objects = String(q.scene.objects.filter((o) => !o.fixed).length);
  $('ask-question').dataset.moved = String(q.edit ? q.edit.moved.length : 0);
  $('btn-ask-yes').disabled = false;
  $('btn-ask-no').disabled = false;
  showProbe(q);
  setAskState('question');
}

async function askNext() {
  const btn = $('btn-check');
  btn.disabled = true;
  btn.textContent = 'Looking for a layout…';
  setAskState('busy');
  const samples = Number($('ask-samples').value) || 1000;
  const slip = Number($('ask-slip-rate').value) || 0;
  const groups = $('ask-groups').checked;
  const r = await api('POST', '/api/ask/next', { samples, slip_rate: slip, groups });
  btn.disabled = false;
  btn.textContent = 'Check rules';
  if (!r.ok) {
    setAskState('error');
    $('ask-progress').innerHTML = `<pre class="error-box">${esc(r.data.error)}</pre>`;
    toast(r.data.error, 'error');
    return;
  }
  if (r.data.backup) toast(`learned.rcc now holds every learned rule; the one before is kept as ${r.data.backup}.`);
  applyAsk(r.data);
}

async function askAnswer(accepted) {
  const q = state.question;
  if (!q) return;
  $('btn-ask-yes').disabled = true;
  $('btn-ask-no').disabled = true;
  setAskState('busy');
  const r = await api('POST', '/api/ask/answer', { rule: q.rule, accepted });
  if (!r.ok) {
    toast(r.data.error, 'error');
    if (r.status === 409) { await askNext(); return; }
    $('btn-ask-yes').disabled = false;
    $('btn-ask-no').disabled = false;
    setAskState('question');
    return;
  }
  state.checked = true;
  state.learned = r.data.learned;
  renderLearned();
  renderAskRules();
  renderAskProgress(r.data.progress);
  if (q.suspect) {
    toast(accepted
      ? `Demonstration #${q.suspect.demonstration + 1} is meant: dropped ${q.suspect.breaks.join(', ')}.`
      : `Demonstration #${q.suspect.demonstration + 1} holds a slip; it no longer counts, confirmed ${q.suspect.breaks.join(', ')}.`, 'ok');
  } else if (accepted) {
    const what = (q.group || []).length ? `${q.group.length} rules (${q.group.map((g) => g.rule).join(', ')})` : q.rule;
    toast(`Dropped ${what}: the layout is now demonstration #${r.data.answer.demo + 1}.`, 'ok');
    loadDemos();
  } else if ((q.group || []).length) {
    toast(`At least one of ${q.group.length} rules is meant; the next questions find which.`, 'ok');
  } else {
    toast(`Confirmed ${q.rule}.`, 'ok');
  }
  await askNext();
}

// ---- tabs -------------------------------------------------------------------------

function setTab(tab) {
  state.tab = tab;
  for (const b of document.querySelectorAll('.tab')) b.classList.toggle('active', b.dataset.tab === tab);
  for (const p of document.querySelectorAll('.pane')) p.hidden = p.dataset.pane !== tab;
  if (tab === 'record') showEditor();
  if (tab === 'check') {
    renderAskRules();
    if (state.question && state.probe) showProbe(state.question);
    else if (state.boardMode !== 'edit') showEditor();
  }
  if (tab === 'synth') {
    renderSynthPane();
    if (state.result) {
      state.boardMode = 'result';
      $('stage-title').textContent = state.result.title;
      $('stage-info').textContent = state.result.info;
      renderLegend();
      redraw();
    }
  }
}

// ---- start ------------------------------------------------------------------------

async function main() {
  const r = await api('GET', '/api/task');
  if (!r.ok) { toast(r.data.error, 'error'); return; }
  state.task = r.data;
  $('task-name').textContent = r.data.name;
  document.title = `${r.data.name} · rccpack studio`;
  $('learn-source').textContent = r.data.statements
    ? 'Statements come from statements.rcc in the task folder.'
    : 'No statements.rcc: candidate statements are generated from templates.';
  renderPalette();
  renderLegend();
  redraw();
  document.addEventListener('pointermove', moveDrag);
  document.addEventListener('pointerup', endDrag);
  $('board').addEventListener('pointerdown', (ev) => {
    if (state.boardMode !== 'edit') return;
    // The right button turns a block (`contextmenu` below); it does not drag.
    if (ev.button !== 0) return;
    const g = ev.target.closest('.obj');
    if (!g || g.classList.contains('fixed')) { state.selected = null; redraw(); return; }
    const o = state.placed.find((p) => p.id === g.dataset.id);
    if (o) startDrag(ev, o, false);
  });
  document.addEventListener('keydown', (ev) => {
    if (ev.target.closest('input, textarea')) return;
    if ((ev.key === 'Delete' || ev.key === 'Backspace') && state.selected) { ev.preventDefault(); deleteSelected(); }
    if ((ev.key === 't' || ev.key === 'T') && state.selected) { ev.preventDefault(); turnSelected(); }
  });
  $('board').addEventListener('contextmenu', (ev) => {
    if (state.boardMode !== 'edit') return;
    const g = ev.target.closest('.obj');
    if (!g || g.classList.contains('fixed')) return;
    ev.preventDefault();
    state.selected = g.dataset.id;
    turnSelected();
  });
  $('btn-delete').onclick = deleteSelected;
  $('btn-clear').onclick = () => { state.placed = []; state.selected = null; redraw(); };
  $('btn-save').onclick = saveDemo;
  $('btn-learn').onclick = learn;
  $('btn-save-rules').onclick = saveRules;
  $('btn-synth').onclick = synthesize;
  $('btn-check').onclick = askNext;
  $('btn-ask-yes').onclick = () => askAnswer(true);
  $('btn-ask-no').onclick = () => askAnswer(false);
  $('btn-cancel').onclick = async () => {
    if (state.job !== null && state.job !== undefined) await api('POST', `/api/synth/${state.job}/cancel`);
  };
  $('btn-all').onclick = () => document.querySelectorAll('#rules input').forEach((c) => { c.checked = true; });
  $('btn-none').onclick = () => document.querySelectorAll('#rules input').forEach((c) => { c.checked = false; });
  for (const b of document.querySelectorAll('.tab')) b.onclick = () => setTab(b.dataset.tab);
  window.addEventListener('resize', redraw);
  await Promise.all([loadDemos(), loadLearned()]);
  document.body.dataset.ready = '1';
}

main();
