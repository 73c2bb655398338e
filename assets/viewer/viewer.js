// The run viewer: shows an output folder of shapegen (a run, a multi-objective run, a
// comparison or a study) from the files the command writes. Served by `shapegen view`,
// it polls the folder once a second; in a report written by `shapegen report` the files
// are inline (window.SHAPEGEN_FILES) and read once.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const EMBEDDED = window.SHAPEGEN_FILES || null;
const $ = (id) => document.getElementById(id);
const BACKGROUND = 0xf2f2ef;

// ---- the folder's files -------------------------------------------------------------

const seen = new Map(); // name -> entity tag (served) or true (embedded), once read

/** The folder's file names. */
async function listFiles() {
  if (EMBEDDED) return Object.keys(EMBEDDED);
  const response = await fetch('/list', { cache: 'no-store' });
  if (!response.ok) throw new Error(`/list: ${response.status}`);
  return (await response.json()).files;
}

/**
 * The bytes of file `name` if it changed since it was last read (or `always`), else
 * null; null too when it is missing. A file being replaced by the run is read whole,
 * old or new: the run renames complete files into place.
 */
async function readFile(name, always = false) {
  if (EMBEDDED) {
    if (!(name in EMBEDDED) || (seen.has(name) && !always)) return null;
    seen.set(name, true);
    const binary = atob(EMBEDDED[name]);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return bytes.buffer;
  }
  const url = '/files/' + name.split('/').map(encodeURIComponent).join('/');
  let response;
  try {
    response = await fetch(url, { cache: 'no-cache' });
  } catch (e) {
    return null;
  }
  if (!response.ok) return null;
  const tag = response.headers.get('ETag');
  if (!always && tag && seen.get(name) === tag) return null;
  const bytes = await response.arrayBuffer();
  seen.set(name, tag);
  return bytes;
}

const text = (bytes) => new TextDecoder().decode(bytes);

async function readJson(name, always = false) {
  const bytes = await readFile(name, always);
  if (!bytes) return null;
  try {
    return JSON.parse(text(bytes));
  } catch (e) {
    return null; // a file the run has not finished is skipped, not shown broken
  }
}

/** Rows of a CSV file with a header line, as objects of strings. */
function parseCsv(source) {
  const lines = source.split(/\r?\n/).filter((l) => l.length > 0);
  const split = (line) => {
    const out = [];
    let field = '';
    let quoted = false;
    for (let i = 0; i < line.length; i++) {
      const c = line[i];
      if (quoted) {
        if (c === '"' && line[i + 1] === '"') { field += '"'; i++; }
        else if (c === '"') quoted = false;
        else field += c;
      } else if (c === '"') quoted = true;
      else if (c === ',') { out.push(field); field = ''; }
      else field += c;
    }
    out.push(field);
    return out;
  };
  if (lines.length === 0) return { header: [], rows: [] };
  const header = split(lines[0]);
  const rows = lines.slice(1).map((l) => {
    const values = split(l);
    return Object.fromEntries(header.map((h, i) => [h, values[i] ?? '']));
  });
  return { header, rows };
}

// ---- the 3D view ----------------------------------------------------------------------

const canvas = $('canvas');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(BACKGROUND);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8070, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(0.5, 1, 0.8);
scene.add(sun);

const freeCamera = new THREE.PerspectiveCamera(45, 1, 0.01, 1e5);
freeCamera.position.set(10, 8, 14);
const controls = new OrbitControls(freeCamera, canvas);
// The target's camera: its view and projection as the scorer uses them (camera.json),
// world straight to clip space.
const targetCamera = new THREE.Camera();
targetCamera.matrixWorldAutoUpdate = false;
let camera = freeCamera;
let model = null;
let target = null;
let framed = false;
let targetView = null; // { width, height }

function render() {
  const view = $('view');
  const width = view.clientWidth;
  const height = view.clientHeight;
  if (canvas.width !== Math.floor(width * renderer.getPixelRatio()) ||
      canvas.height !== Math.floor(height * renderer.getPixelRatio())) {
    renderer.setSize(width, height, false);
  }
  freeCamera.aspect = width / Math.max(height, 1);
  freeCamera.updateProjectionMatrix();
  renderer.render(scene, camera);
  const r = canvas.getBoundingClientRect();
  canvas.dataset.rect = [r.left, r.top, r.width, r.height].map(Math.round).join(',');
}
controls.addEventListener('change', render);
// Turning the view by hand leaves the target's camera.
controls.addEventListener('start', () => {
  if (camera !== freeCamera) useFreeCamera();
});
window.addEventListener('resize', render);

function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  if (box.isEmpty()) return;
  const center = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2;
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(freeCamera.fov / 2));
  freeCamera.position.copy(center).add(new THREE.Vector3(0.8, 0.6, 1).normalize().multiplyScalar(distance));
  freeCamera.near = distance / 100;
  freeCamera.far = distance * 100;
  controls.target.copy(center);
  controls.update();
}

function showModel(object, name) {
  if (model) {
    scene.remove(model);
    model.traverse((o) => {
      if (o.geometry) o.geometry.dispose();
      if (o.material) o.material.dispose();
    });
  }
  model = object;
  model.traverse((o) => {
    if (o.material) o.material.side = THREE.DoubleSide;
  });
  scene.add(model);
  if (!framed) {
    frame(target && target.visible ? target : model);
    framed = true;
  }
  $('model-name').textContent = name;
  canvas.dataset.model = name;
  render();
}

const gltfLoader = new GLTFLoader();
async function loadModel(name, always = false) {
  const bytes = await readFile(name, always);
  if (!bytes) return false;
  await new Promise((resolve) => {
    gltfLoader.parse(bytes, '', (gltf) => { showModel(gltf.scene, name); resolve(); }, () => resolve());
  });
  return true;
}

async function loadTargets(files) {
  if (files.includes('target.obj') && !target) {
    const bytes = await readFile('target.obj');
    if (bytes) {
      target = new OBJLoader().parse(text(bytes));
      target.traverse((o) => {
        if (o.isMesh) {
          o.material = new THREE.MeshStandardMaterial({
            color: 0x4a78c8, transparent: true, opacity: 0.25, depthWrite: false, side: THREE.DoubleSide,
          });
        }
      });
      scene.add(target);
      $('target-toggle').hidden = false;
      if (!model) frame(target);
      render();
    }
  }
  if (files.includes('camera.json') && files.includes('target.png') && !targetView) {
    const cam = await readJson('camera.json');
    const png = await readFile('target.png');
    if (cam && png && Array.isArray(cam.view_projection) && cam.view_projection.length === 16) {
      targetCamera.projectionMatrix.fromArray(cam.view_projection);
      targetCamera.projectionMatrixInverse.copy(targetCamera.projectionMatrix).invert();
      targetView = { width: cam.width, height: cam.height };
      $('overlay').src = URL.createObjectURL(new Blob([png], { type: 'image/png' }));
      $('snap').hidden = false;
      // `?camera=target` opens the page looking through the target's camera.
      if (new URLSearchParams(location.search).get('camera') === 'target') useTargetCamera();
    }
  }
}

function useTargetCamera() {
  if (!targetView) return;
  camera = targetCamera;
  $('view').style.aspectRatio = `${targetView.width} / ${targetView.height}`;
  $('overlay').hidden = false;
  $('snap').hidden = true;
  $('free').hidden = false;
  render();
}

function useFreeCamera() {
  camera = freeCamera;
  $('view').style.aspectRatio = '';
  $('overlay').hidden = true;
  $('snap').hidden = !targetView;
  $('free').hidden = true;
  render();
}

$('snap').addEventListener('click', useTargetCamera);
$('free').addEventListener('click', useFreeCamera);
$('show-target').addEventListener('change', (e) => {
  if (target) target.visible = e.target.checked;
  render();
});

// ---- numbers and curves ---------------------------------------------------------------

function setNumber(id, value, shown) {
  const cell = $(id);
  if (value === undefined || value === null) return;
  // How often the page has shown a new generation: a test follows a live run by it.
  if (id === 'generation' && cell.dataset.value !== String(value)) {
    $('status').dataset.updates = String(Number($('status').dataset.updates || 0) + 1);
  }
  cell.dataset.value = String(value);
  cell.textContent = shown ?? String(value);
}

function showNumbers(info) {
  if (!info) return;
  setNumber('method', info.method);
  setNumber('seed', info.seed);
  setNumber('generation', info.generations ?? info.generation);
  setNumber('evaluations', info.evaluations);
  if (info.elapsed_s !== undefined) {
    setNumber('elapsed', info.elapsed_s, `${Number(info.elapsed_s).toFixed(1)} s`);
    if (info.evaluations !== undefined && info.elapsed_s > 0) {
      const rate = info.evaluations / info.elapsed_s;
      setNumber('rate', rate, rate.toFixed(0));
    }
  }
  if (info.best_fitness !== undefined) {
    setNumber('best', info.best_fitness, Number(info.best_fitness).toPrecision(6));
  }
}

const charts = new Map();
function chart(element, title, xLabel, names, data, extra = {}) {
  const old = charts.get(element.id);
  const width = Math.max(element.clientWidth, 300);
  const colours = ['#1e3c8c', '#e68c28', '#2a8a4a', '#b03a48', '#6a4aa0', '#3a9ab0', '#908020', '#505050'];
  const same = old && old.series.length === names.length + 1;
  if (same) {
    old.setData(data);
  } else {
    if (old) old.destroy();
    const series = [{ label: xLabel }].concat(names.map((n, i) => ({
      label: n, stroke: colours[i % colours.length], width: 1.5, spanGaps: true, ...(extra.series || {}),
    })));
    const options = {
      title, width, height: 260, series,
      scales: { x: { time: false } },
      axes: [{ label: xLabel }, { label: extra.yLabel || 'fitness' }],
      ...(extra.options || {}),
    };
    charts.set(element.id, new uPlot(options, data, element));
  }
  element.dataset.points = String(data[0].length);
  return charts.get(element.id);
}

function showCurve(source, name) {
  const { header, rows } = parseCsv(source);
  if (name === 'fitness.csv') {
    const data = [rows.map((r) => +r.generation), rows.map((r) => +r.best), rows.map((r) => +r.mean)];
    chart($('curve'), 'fitness per generation', 'generation', ['best', 'mean'], data);
    const last = rows[rows.length - 1];
    return last;
  }
  // history.csv of a multi-objective run: the best of each objective per generation.
  const names = header.filter((h) => h.startsWith('best_'));
  const data = [rows.map((r) => +r.generation)].concat(names.map((n) => rows.map((r) => +r[n])));
  chart($('curve'), 'best of each objective per generation', 'generation', names.map((n) => n.slice(5)), data,
    { yLabel: 'objective' });
  return rows[rows.length - 1];
}

// ---- multi-objective fronts -------------------------------------------------------------

let front = null; // { header, rows }
function showFront() {
  if (!front) return;
  const objectives = front.header.slice(2);
  for (const id of ['front-x', 'front-y']) {
    const select = $(id);
    if (select.options.length !== objectives.length) {
      select.innerHTML = '';
      for (const o of objectives) select.add(new Option(o, o));
      if (id === 'front-y' && objectives.length > 1) select.selectedIndex = 1;
    }
  }
  const [x, y] = [$('front-x').value, $('front-y').value];
  const rows = front.rows.slice().sort((a, b) => +a[x] - +b[x]);
  const data = [rows.map((r) => +r[x]), rows.map((r) => +r[y])];
  const u = chart($('front'), 'front (click a point to see its model)', x, [y], data, {
    yLabel: y,
    series: { paths: () => null, points: { show: true, size: 9 } },
  });
  u.frontRows = rows;
  if (!u.clickable) {
    u.clickable = true;
    u.over.addEventListener('click', () => showPoint(u, u.cursor.idx));
  }
  // `#point=K` in the page's address shows the K-th point from the left, as a click
  // on it does.
  const chosen = /^#point=(\d+)$/.exec(location.hash);
  if (chosen && !pointChosen) {
    pointChosen = true;
    return showPoint(u, +chosen[1]);
  }
}
let pointChosen = false;

/** Shows the model of the front's `i`-th point from the left in the 3D view. */
function showPoint(u, i) {
  if (i === null || i === undefined || !u.frontRows[i]) return;
  const index = String(u.frontRows[i].model).padStart(3, '0');
  $('front').dataset.point = String(i);
  return loadModel(`front/model_${index}.glb`, true);
}
$('front-x').addEventListener('change', () => { charts.get('front')?.destroy(); charts.delete('front'); showFront(); });
$('front-y').addEventListener('change', () => { charts.get('front')?.destroy(); charts.delete('front'); showFront(); });

// ---- comparisons and studies ----------------------------------------------------------

function runsTable(columns, rows, modelOf) {
  const table = $('runs');
  table.innerHTML = '';
  const head = table.insertRow();
  for (const c of columns.concat(['model'])) {
    const th = document.createElement('th');
    th.textContent = c;
    head.appendChild(th);
  }
  for (const row of rows) {
    const tr = table.insertRow();
    for (const c of columns) tr.insertCell().textContent = row[c] ?? '';
    const cell = tr.insertCell();
    const glb = modelOf(row);
    if (glb) {
      const button = document.createElement('button');
      button.textContent = 'show';
      button.addEventListener('click', () => loadModel(glb, true));
      cell.appendChild(button);
    }
  }
}

async function showCompare(files) {
  const bytes = await readFile('compare.csv');
  if (!bytes) return;
  const { rows } = parseCsv(text(bytes));
  const byRun = new Map();
  for (const r of rows) {
    const key = `${r.method}-${r.run}`;
    if (!byRun.has(key)) byRun.set(key, []);
    byRun.get(key).push(r);
  }
  const keys = [...byRun.keys()];
  const tables = keys.map((k) => [byRun.get(k).map((r) => +r.elapsed_s), byRun.get(k).map((r) => +r.best)]);
  const data = tables.length ? uPlot.join(tables) : [[]];
  chart($('curve'), 'best fitness of each run', 'seconds', keys, data);
  const last = keys.map((k) => {
    const h = byRun.get(k);
    const r = h[h.length - 1];
    return { run: k, seed: r.seed, evaluations: r.evaluations, seconds: r.elapsed_s, best: r.best };
  });
  runsTable(['run', 'seed', 'evaluations', 'seconds', 'best'], last, (r) => {
    const glb = `runs/${r.run}/best.glb`;
    return files.includes(glb) ? glb : null;
  });
  if (!model) {
    const first = last.find((r) => files.includes(`runs/${r.run}/best.glb`));
    if (first) await loadModel(`runs/${first.run}/best.glb`);
  }
}

/** Each finished cell's curve of a study, its best against seconds, by cell. */
const cellCurves = new Map();
async function showCellCurves(files) {
  const tables = files.filter((f) => /^cells\/\d+\/fitness\.csv$/.test(f)).sort();
  let changed = false;
  for (const name of tables) {
    const bytes = await readFile(name);
    if (!bytes) continue;
    const { rows } = parseCsv(text(bytes));
    cellCurves.set(`cell ${name.split('/')[1]}`, [rows.map((r) => +r.elapsed_s), rows.map((r) => +r.best)]);
    changed = true;
  }
  if (!changed) return;
  const names = [...cellCurves.keys()].sort();
  const data = names.length ? uPlot.join(names.map((n) => cellCurves.get(n))) : [[]];
  chart($('curve'), 'best fitness of each cell', 'seconds', names, data);
  $('curve').dataset.series = String(names.length);
}

async function showSweep(files) {
  const bytes = await readFile('sweep.csv');
  if (bytes) {
    const { header, rows } = parseCsv(text(bytes));
    // Each row's cell folder is cells/NNNN, its `cell` number.
    const cells = [...new Set(files.filter((f) => f.startsWith('cells/')).map((f) => f.split('/')[1]))];
    const modelOf = (r) => {
      const cell = cells.find((c) => r.cell !== undefined && r.cell !== '' && Number(c) === Number(r.cell));
      const glb = cell && `cells/${cell}/best.glb`;
      return glb && files.includes(glb) ? glb : null;
    };
    runsTable(header, rows, modelOf);
    const first = rows.map(modelOf).find((glb) => glb);
    if (!model && first) await loadModel(first);
  }
  await showCellCurves(files);
  const md = await readFile('summary.md');
  if (md) $('summary-md').textContent = text(md);
}

// ---- the loop -------------------------------------------------------------------------

function setStatus(state, message) {
  const status = $('status');
  status.dataset.state = state;
  status.textContent = message;
}

function kindOf(files) {
  if (files.includes('front.csv')) return 'front';
  if (files.includes('fitness.csv') || files.includes('run.json') || files.includes('best.glb')) return 'run';
  if (files.includes('compare.csv')) return 'compare';
  if (files.includes('sweep.csv')) return 'sweep';
  return null;
}

async function update() {
  const files = await listFiles();
  const kind = kindOf(files);
  document.body.dataset.kind = kind || 'none';
  $('kind').textContent = kind ? `— ${{ run: 'run', front: 'multi-objective run', compare: 'comparison', sweep: 'study' }[kind]}` : '';
  if (!kind) {
    setStatus('waiting', 'waiting for the run’s first files…');
    return false;
  }
  await loadTargets(files);
  const summary = await readJson('summary.json', true);
  const live = await readJson('run.json', true);
  // A resumed run has its earlier summary.json until it ends again: run.json says
  // whether it is running.
  const running = Boolean(live && live.running);
  const finished = EMBEDDED || (live ? !running : Boolean(summary));
  if (kind === 'run' || kind === 'front') {
    const csvName = kind === 'run' ? 'fitness.csv' : 'history.csv';
    const csv = await readFile(csvName);
    let last = null;
    if (csv) last = showCurve(text(csv), csvName);
    const info = (running ? live : summary || live) || (last && {
      generation: +last.generation, evaluations: +last.evaluations, elapsed_s: +last.elapsed_s,
    });
    showNumbers(info);
    if (kind === 'run') {
      await loadModel('best.glb');
    } else {
      $('front-panel').hidden = false;
      const table = await readFile('front.csv');
      if (table) {
        front = parseCsv(text(table));
        await showFront();
        if (!model) await loadModel('front/model_000.glb');
      }
    }
  } else {
    $('runs-panel').hidden = false;
    $('numbers').hidden = true;
    $('runs-title').textContent = kind === 'compare' ? 'runs' : 'runs of the study';
    showNumbers(summary);
    if (kind === 'compare') await showCompare(files);
    else await showSweep(files);
  }
  if (EMBEDDED) setStatus('report', 'report');
  else setStatus(finished ? 'finished' : 'live', finished ? 'finished' : 'live: following the folder');
  return finished;
}

/**
 * Resolves when the run next saves: the server holds a request for run.json until the
 * file's tag changes (at most 10 s), so that a page follows a run with one request per
 * save. Without a run.json yet, after a second.
 */
async function nextSave() {
  const tag = seen.get('run.json');
  if (!tag) return new Promise((resolve) => setTimeout(resolve, 1000));
  try {
    await fetch(`/files/run.json?wait=${encodeURIComponent(tag)}`, { cache: 'no-store' });
  } catch (e) {
    await new Promise((resolve) => setTimeout(resolve, 1000));
  }
  // A short pause so that a burst of saves is shown as one.
  await new Promise((resolve) => setTimeout(resolve, 200));
}

async function loop() {
  try {
    const finished = await update();
    if (EMBEDDED) return;
    // A finished folder changes no more; it is checked less often.
    if (finished) setTimeout(loop, 5000);
    else nextSave().then(loop);
  } catch (e) {
    setStatus('error', `cannot read the folder: ${e.message}; retrying`);
    if (!EMBEDDED) setTimeout(loop, 2000);
  }
}

render();
loop();
