// rangefitd's page: polls /v1/state and /v1/results, shows the newest result's cloud in 3D, and
// sends requests from the form to POST /v1/detect with the token (kept in this browser only).
import { parsePly } from '/ply.js';
import { View3d } from '/view3d.js';

const $ = (id) => document.getElementById(id);
const view = new View3d($('view'));
let generation = -1;
let shownId = null;
let selectedByUser = false;
let configured = false;

const vector = (text) => {
  const v = text.split(/[\s,]+/).filter((s) => s !== '').map(Number);
  if (v.length !== 3 || v.some((x) => !Number.isFinite(x))) throw new Error(`"${text}" is not x, y, z`);
  return v;
};

function outcome(r) {
  if (r.found) return ['found', 'found'];
  return r.status === 'ok' ? ['notfound', 'not found: ' + r.reason] : ['failed', r.status + ': ' + r.reason];
}

async function json(url, options) {
  const response = await fetch(url, options);
  return { code: response.status, body: await response.json() };
}

async function showCloud(result) {
  if (!result.files || !result.files['cloud.ply']) return;
  shownId = result.request_id;
  $('view-caption').textContent = `${result.request_id}: loading`;
  const response = await fetch(result.files['cloud.ply']);
  if (!response.ok) { $('view-caption').textContent = `${result.request_id}: cloud gone`; return; }
  const cloud = parsePly(await response.arrayBuffer());
  view.show(cloud, result);
  $('view-caption').textContent = `${result.request_id}: ${cloud.count} points` +
    (cloud.shown < cloud.count ? ` (${cloud.shown} shown)` : '') + `, ${outcome(result)[1]}`;
  for (const li of document.querySelectorAll('#results li')) {
    li.classList.toggle('selected', li.dataset.id === shownId);
  }
}

function renderResults(results) {
  const list = $('results');
  list.replaceChildren();
  for (const r of results) {
    const li = document.createElement('li');
    li.dataset.id = r.request_id;
    const [cls, text] = outcome(r);
    const title = document.createElement('div');
    title.innerHTML = '<b></b> <span></span>';
    title.firstChild.textContent = `${r.request_id} (${r.kind}${r.model ? ' ' + r.model : ''})`;
    title.lastChild.textContent = text;
    title.lastChild.className = cls;
    li.append(title);
    if (r.files && r.files['picture.png']) {
      const img = document.createElement('img');
      img.src = r.files['picture.png'];
      img.alt = `picture of ${r.request_id}`;
      li.append(img);
    }
    li.addEventListener('click', () => { selectedByUser = true; showCloud(r); });
    li.classList.toggle('selected', r.request_id === shownId);
    list.append(li);
  }
}

function renderState(s) {
  $('state').textContent = s.state + (s.active_id ? ` (${s.active_id})` : '');
  $('state').className = 'badge ' + s.state;
  $('queue').textContent = `queue ${s.queue_depth}, ${s.completed} scans, ${s.rejected_busy} busy`;
  $('last-error').textContent = s.last_error ? 'last error: ' + s.last_error : '';
  const rows = s.diagnostics.map((d) => {
    const tr = document.createElement('tr');
    for (const [text, cls] of [[d.name, ''], [d.level, d.level], [d.message, '']]) {
      const td = document.createElement('td');
      td.textContent = text;
      if (cls) td.className = cls;
      tr.append(td);
    }
    return tr;
  });
  $('diagnostics').tBodies[0].replaceChildren(...rows);
  if (!configured && s.models) {
    configured = true;
    for (const m of s.models) $('object-model').append(new Option(m, m));
    for (const d of s.sensors) {
      $('sensor').append(new Option(d, d));
      $('learn-sensors').append(new Option(d, d));
      $('calibrate-sensors').append(new Option(d, d));
    }
  }
}

async function poll() {
  try {
    const state = await json('/v1/state');
    renderState(state.body);
    if (state.body.generation !== generation) {
      generation = state.body.generation;
      const list = await json('/v1/results?n=12');
      renderResults(list.body.results);
      const newest = list.body.results[0];
      if (newest && !selectedByUser && newest.request_id !== shownId) await showCloud(newest);
    }
  } catch (e) {
    $('state').textContent = 'offline';
    $('state').className = 'badge offline';
  }
  setTimeout(poll, 1000);
}

function numbers(text, count, what) {
  const v = text.split(/[\s,]+/).filter((s) => s !== '').map(Number);
  if (v.length !== count || v.some((x) => !Number.isFinite(x))) {
    throw new Error(`${what}: ${count} numbers, comma separated`);
  }
  return v;
}

function calibrationTarget() {
  const kind = $('calibrate-target').value;
  const t = { kind };
  const scans = $('calibrate-scans').value.split(',').map((s) => s.trim()).filter((s) => s);
  if (kind === 'css') {
    t.radius_mm = Number($('calibrate-radius').value);
    t.robot_pose = numbers($('calibrate-robot-pose').value, 6, 'robot pose');
  } else {
    t.size_mm = numbers($('calibrate-cube').value, 2, 'cube edge, bar');
    t.pose = numbers($('calibrate-pose').value, 6, 'cube pose');
    if (kind === 'pantilt' && $('calibrate-tilt').value.trim() !== '') {
      t.tilt_rad = Number($('calibrate-tilt').value);
    }
  }
  if (scans.length) t.scans = scans;
  return t;
}

// The sensors a multiple select chose: several go as sensors, one as the sensor, none leaves
// the sensor field's choice.
function chooseSensors(r, id) {
  const chosen = [...$(id).selectedOptions].map((o) => o.value);
  if (chosen.length > 1) {
    r.sensors = chosen;
    r.sensor = '';
  } else if (chosen.length === 1) {
    r.sensor = chosen[0];
  }
}

function request() {
  const kind = $('kind').value;
  const r = { kind, sensor: $('sensor').value };
  if (kind === 'bore') {
    r.bore = { position_mm: vector($('bore-position').value), axis: vector($('bore-axis').value),
               radius_mm: Number($('bore-radius').value) };
  } else if (kind === 'learn') {
    r.model = $('learn-name').value;
    r.parts = Number($('learn-parts').value);
    chooseSensors(r, 'learn-sensors');
  } else if (kind === 'calibrate') {
    r.target = calibrationTarget();
    if (r.target.kind === 'stripe') chooseSensors(r, 'calibrate-sensors');
  } else {
    r.model = $('object-model').value;
    r.instances = Number($('object-instances').value) || 1;
  }
  return r;
}

async function send(event) {
  event.preventDefault();
  const status = $('request-status');
  let body;
  try { body = request(); } catch (e) { status.textContent = e.message; return; }
  localStorage.setItem('rangefit-token', $('token').value);
  $('send').disabled = true;
  $('result-files').replaceChildren();
  status.textContent = 'sending';
  try {
    const sent = await json('/v1/detect?wait=0', {
      method: 'POST', body: JSON.stringify(body),
      headers: { 'Content-Type': 'application/json', Authorization: `Bearer ${$('token').value}` } });
    if (sent.code !== 202) {
      status.textContent = `${sent.body.status}: ${sent.body.error}`;
      return;
    }
    const id = sent.body.id;
    status.textContent = `${id}: queued`;
    for (;;) {
      await new Promise((done) => setTimeout(done, 400));
      const r = await json(`/v1/results/${encodeURIComponent(id)}`);
      if (r.code === 202) { status.textContent = `${id}: running`; continue; }
      status.textContent = `${id}: ${outcome(r.body)[1]}`;
      status.className = outcome(r.body)[0];
      $('last-result').textContent = JSON.stringify(r.body, null, 1);
      // What the result wrote for the user (model.toml, calibration_*.toml and its report, a
      // recorded calibration scan): one link each.
      for (const [name, href] of Object.entries(r.body.files || {})) {
        const a = document.createElement('a');
        a.href = href;
        a.download = name;
        a.textContent = name;
        $('result-files').append(a);
      }
      selectedByUser = false;
      await showCloud(r.body);
      break;
    }
  } catch (e) {
    status.textContent = 'error: ' + e.message;
  } finally {
    $('send').disabled = false;
  }
}

$('kind').addEventListener('change', () => {
  const kind = $('kind').value;
  $('bore-fields').hidden = kind !== 'bore';
  $('object-fields').hidden = kind !== 'object';
  $('learn-fields').hidden = kind !== 'learn';
  $('calibrate-fields').hidden = kind !== 'calibrate';
  $('send').textContent = { learn: 'Scan and learn', calibrate: 'Scan and calibrate' }[kind] ||
    'Scan and detect';
});
function showTargetFields() {
  const target = $('calibrate-target').value;
  // Each target's own fields, and the cube's for both cube targets.
  for (const field of $('calibrate-fields').querySelectorAll('label[class], p[class~="stripe"]')) {
    field.hidden = !field.classList.contains(target) &&
      !(target !== 'css' && field.classList.contains('cube'));
  }
}
$('calibrate-target').addEventListener('change', showTargetFields);
showTargetFields();
$('token').value = localStorage.getItem('rangefit-token') || '';
$('request-form').addEventListener('submit', send);
poll();
