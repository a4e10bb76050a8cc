// The page: files in, mission edited and checked, flown, plotted, downloaded; the Monte
// Carlo study flown by Web Workers (or, opened from disk where workers cannot start, on the
// page itself, slice by slice).
"use strict";

const MAX_FILE_BYTES = 64 * 1024 * 1024;
const MAX_MISSION_BYTES = 4 * 1024 * 1024;
const $ = (id) => document.getElementById(id);
const files = new Map(); // name -> Uint8Array
const outputs = { summary: null, trajectory: null, kml: null, samples: null, studySummary: null };
let karman = null; // the wasm_bindgen namespace once initialised

function wasmBytes() {
  const text = atob(KARMAN_WASM_BASE64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) { bytes[i] = text.charCodeAt(i); }
  return bytes;
}

const ready = wasm_bindgen({ module_or_path: wasmBytes() }).then(() => { karman = wasm_bindgen; });

function setStatus(text, kind) {
  const s = $("status");
  s.textContent = text;
  s.className = kind || "";
}

// A thrown failure of karman-web: {message, problems: [{line, column, key, message}]}.
function failure(error) {
  if (typeof error === "string") {
    try { return JSON.parse(error); } catch (_) { return { message: error, problems: [] }; }
  }
  return { message: String(error && error.message ? error.message : error), problems: [] };
}

function missionName() {
  return $("mission-name").value.trim() || "mission.toml";
}

function fileSet() {
  const set = new karman.Files();
  for (const [name, bytes] of files) { set.add(name, bytes); }
  return set;
}

function showProblems(f) {
  const list = $("errors");
  list.replaceChildren();
  const problems = f.problems.length ? f.problems : [{ line: null, column: null, key: "", message: f.message }];
  for (const p of problems) {
    const li = document.createElement("li");
    li.className = "error";
    li.textContent = p.message;
    if (p.line) {
      li.dataset.line = p.line;
      li.dataset.column = p.column;
      li.title = "go to line " + p.line;
      li.addEventListener("click", () => goTo(p.line, p.column));
    }
    list.append(li);
  }
}

function showWarnings(warnings) {
  const list = $("errors");
  list.replaceChildren();
  for (const w of warnings) {
    const li = document.createElement("li");
    li.className = "warning";
    li.textContent = w;
    list.append(li);
  }
}

// Selects line `line` (1-based) of the mission from column `column`.
function goTo(line, column) {
  const area = $("mission");
  const lines = area.value.split("\n");
  let start = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) { start += lines[i].length + 1; }
  const end = start + (lines[line - 1] || "").length;
  area.focus();
  area.setSelectionRange(Math.min(start + Math.max(column - 1, 0), end), end);
  const lineHeight = area.scrollHeight / Math.max(lines.length, 1);
  area.scrollTop = Math.max(0, (line - 3) * lineHeight);
}

// ---------------------------------------------------------------------------- files

function listFiles() {
  const list = $("file-list");
  list.replaceChildren();
  for (const [name, bytes] of files) {
    const li = document.createElement("li");
    li.textContent = `${name} (${bytes.length} bytes)`;
    const remove = document.createElement("button");
    remove.textContent = "remove";
    remove.addEventListener("click", () => { files.delete(name); listFiles(); });
    li.append(remove);
    list.append(li);
  }
}

async function addFiles(list) {
  const notes = [];
  const designs = [];
  const warnings = [];
  for (const file of list) {
    if (file.size > MAX_FILE_BYTES) {
      notes.push(`${file.name}: ${file.size} bytes, larger than the 64 MiB a file may have; not read`);
      continue;
    }
    const bytes = new Uint8Array(await file.arrayBuffer());
    if (/\.toml$/i.test(file.name)) {
      if (bytes.length > MAX_MISSION_BYTES) {
        notes.push(`${file.name}: a mission of ${bytes.length} bytes, larger than 4 MiB; not read`);
        continue;
      }
      let text;
      try {
        text = new TextDecoder("utf-8", { fatal: true }).decode(bytes);
      } catch (_) {
        notes.push(`${file.name}: not a UTF-8 text file (a binary file?); not read`);
        continue;
      }
      $("mission").value = text;
      $("mission-name").value = file.name;
    } else if (/\.ork$/i.test(file.name)) {
      designs.push([file.name, bytes]);
    } else {
      files.set(file.name, bytes);
    }
  }
  listFiles();
  // An OpenRocket design, once its motor files are in: imported as `karman import` does.
  for (const [name, bytes] of designs) {
    await ready;
    try {
      const imported = JSON.parse(karman.import_ork(name, bytes, fileSet()));
      $("mission").value = imported.mission;
      $("mission-name").value = name.replace(/\.ork$/i, ".toml");
      warnings.push(...imported.warnings.map((w) => `${name}: warning: ${w}`));
    } catch (e) {
      notes.push(failure(e).message);
    }
  }
  if (notes.length) {
    showProblems({ message: notes.join("\n"), problems: notes.map((m) => ({ line: null, column: null, key: "", message: m })) });
    setStatus("some files were not read", "warning");
  } else {
    showWarnings(warnings);
    setStatus(`${list.length} file(s) read`);
  }
}

$("file-input").addEventListener("change", (e) => addFiles([...e.target.files]));
const drop = $("drop");
drop.addEventListener("dragover", (e) => { e.preventDefault(); drop.classList.add("over"); });
drop.addEventListener("dragleave", () => drop.classList.remove("over"));
drop.addEventListener("drop", (e) => {
  e.preventDefault();
  drop.classList.remove("over");
  addFiles([...e.dataTransfer.files]);
});

// ---------------------------------------------------------------------------- check and fly

async function check() {
  await ready;
  setStatus("checking…");
  try {
    const warnings = JSON.parse(karman.check(missionName(), $("mission").value, fileSet()));
    showWarnings(warnings);
    setStatus("ok", "ok");
  } catch (e) {
    showProblems(failure(e));
    setStatus("the mission has problems", "error");
  }
}

const SUMMARY_ROWS = [
  ["apogee_agl_m", "Apogee above ground (m)"],
  ["apogee_asl_m", "Apogee above sea level (m)"],
  ["apogee_time_s", "Apogee time (s)"],
  ["out_of_rail_time_s", "Rail exit time (s)"],
  ["out_of_rail_velocity_mps", "Rail exit speed (m/s)"],
  ["out_of_rail_stability_margin", "Rail exit stability margin (cal)"],
  ["initial_static_margin", "Initial static margin (cal)"],
  ["burnout_static_margin", "Burnout static margin (cal)"],
  ["max_speed_mps", "Maximum speed (m/s)"],
  ["max_mach", "Maximum Mach"],
  ["max_dynamic_pressure_pa", "Maximum dynamic pressure (Pa)"],
  ["impact_time_s", "Impact time (s)"],
  ["impact_x_m", "Impact east of the pad (m)"],
  ["impact_y_m", "Impact north of the pad (m)"],
  ["impact_velocity_mps", "Impact speed (m/s)"],
];

function showFlight(result, ms) {
  const json = JSON.parse(result.json);
  const body = $("summary").tBodies[0];
  body.replaceChildren();
  for (const [key, label] of SUMMARY_ROWS) {
    if (!(key in json)) { continue; }
    const tr = document.createElement("tr");
    tr.dataset.key = key;
    const th = document.createElement("th");
    th.textContent = label;
    const td = document.createElement("td");
    td.className = "value";
    td.textContent = json[key] === null ? "—" : String(json[key]);
    tr.append(th, td);
    body.append(tr);
  }
  $("json").textContent = result.json;
  $("timing").textContent = `flown in ${ms.toFixed(1)} ms`;
  $("timing").dataset.ms = String(ms);
  $("early").hidden = !result.early;
  $("early").textContent = result.early || "";
  const s = result.series;
  $("plots").innerHTML = [
    lineChart("Altitude", "time (s)", "altitude AGL (m)", [{ label: "altitude", x: s.t, y: s.altitude }]),
    lineChart("Speed and Mach", "time (s)", "speed (m/s), Mach × 100", [
      { label: "speed (m/s)", x: s.t, y: s.speed },
      { label: "Mach × 100", x: s.t, y: s.mach.map((m) => 100 * m) },
    ]),
    lineChart("Static and stability margin (ascent)", "time (s)", "margin (calibres)", [
      { label: "static margin", x: s.ascent_t, y: s.static_margin },
      { label: "stability margin", x: s.ascent_t, y: s.stability_margin },
    ]),
    trackChart("Ground track", s.x, s.y),
  ].join("");
  outputs.summary = result.summary_json;
  outputs.trajectory = result.trajectory_csv;
  outputs.kml = result.kml;
  $("results").hidden = false;
}

async function fly() {
  await ready;
  setStatus("flying…");
  // Let the status paint before the flight takes the thread.
  await new Promise((r) => setTimeout(r, 0));
  try {
    const set = fileSet();
    const started = performance.now();
    const result = karman.fly(missionName(), $("mission").value, set);
    const ms = performance.now() - started;
    showFlight(JSON.parse(result), ms);
    $("errors").replaceChildren();
    setStatus("flown", "ok");
  } catch (e) {
    showProblems(failure(e));
    setStatus("the flight failed", "error");
  }
}

function download(name, text, type) {
  if (text === null) { return; }
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

$("check").addEventListener("click", check);
$("fly").addEventListener("click", fly);
$("download-summary").addEventListener("click", () => download("summary.json", outputs.summary, "application/json"));
$("download-trajectory").addEventListener("click", () => download("trajectory.csv", outputs.trajectory, "text/csv"));
$("download-kml").addEventListener("click", () => download("flight.kml", outputs.kml, "application/vnd.google-earth.kml+xml"));
$("mc-download").addEventListener("click", () => download("samples.csv", outputs.samples, "text/csv"));
$("mc-download-summary").addEventListener("click", () => download("summary.json", outputs.studySummary, "application/json"));

// ---------------------------------------------------------------------------- Monte Carlo

const SLICE = 5; // samples a worker flies between two progress reports
let stopRequested = false;
let running = [];

// Impact points of the rows of samples.csv (completed flights with an impact).
function landings(csv) {
  const lines = csv.split("\n").filter((l) => l.length);
  const header = lines[0].split(",");
  const ix = header.indexOf("impact_x_m"), iy = header.indexOf("impact_y_m"), st = header.indexOf("status");
  const points = [];
  for (const line of lines.slice(1)) {
    if (line.includes('"')) { continue; } // a failure's quoted message: no impact anyway
    const f = line.split(",");
    if (f[st] !== "ok") { continue; }
    const x = parseFloat(f[ix]), y = parseFloat(f[iy]);
    if (Number.isFinite(x) && Number.isFinite(y)) { points.push([x, y]); }
  }
  return points;
}

// Flies samples [first, end) on this page, a slice at a time, yielding between slices.
async function flyHere(study, first, end, report) {
  for (let i = first; i < end && !stopRequested; i += SLICE) {
    const stop = Math.min(i + SLICE, end);
    report(i, study.lines(i, stop), stop - i);
    await new Promise((r) => setTimeout(r, 0));
  }
}

function startWorker(job, report) {
  return new Promise((resolve, reject) => {
    const worker = new Worker("worker.js");
    running.push(worker);
    worker.onmessage = (e) => {
      const m = e.data;
      if (m.type === "lines") { report(m.first, m.lines, m.count); }
      else if (m.type === "done") { worker.terminate(); resolve(); }
      else if (m.type === "error") { worker.terminate(); reject(m.error); }
    };
    worker.onerror = (e) => { e.preventDefault(); worker.terminate(); reject(e.message || "a worker failed"); };
    worker.postMessage(job);
  });
}

async function montecarlo() {
  await ready;
  const name = missionName(), text = $("mission").value;
  const samples = parseInt($("mc-samples").value, 10);
  const seed = $("mc-seed").value.trim();
  let study;
  try {
    if (!(samples >= 1 && samples <= 1000000)) { throw JSON.stringify({ message: "samples: a whole number from 1 to 1000000", problems: [] }); }
    study = new karman.Study(name, text, fileSet(), samples, seed || undefined);
  } catch (e) {
    showProblems(failure(e));
    $("mc-status").textContent = "the study cannot run";
    return;
  }
  const total = study.samples();
  const header = study.header();
  const pieces = new Map(); // first index -> lines
  let done = 0;
  const progress = $("mc-progress");
  progress.max = total;
  progress.value = 0;
  stopRequested = false;
  $("mc-run").disabled = true;
  $("mc-stop").disabled = false;
  $("mc-download").disabled = true;
  $("mc-download-summary").disabled = true;
  const started = performance.now();
  const report = (first, lines, count) => {
    pieces.set(first, lines);
    done += count;
    progress.value = done;
    $("mc-status").textContent = `${done} of ${total} samples`;
  };
  const workers = Math.max(1, Math.min(parseInt($("mc-workers").value, 10) || navigator.hardwareConcurrency || 2, 16, total));
  const job = { name, text, files: [...files], samples: total, seed: study.seed(), slice: SLICE };
  try {
    if (location.protocol === "file:") {
      // Opened from disk: the browser refuses workers from file:// pages.
      await flyHere(study, 0, total, report);
    } else {
      const share = Math.ceil(total / workers);
      const jobs = [];
      for (let w = 0; w < workers; w++) {
        const first = w * share, end = Math.min(total, first + share);
        if (first < end) { jobs.push(startWorker({ ...job, first, end }, report)); }
      }
      await Promise.all(jobs);
    }
    if (stopRequested) { throw JSON.stringify({ message: `stopped after ${done} of ${total} samples`, problems: [] }); }
    const csv = header + [...pieces.keys()].sort((a, b) => a - b).map((k) => pieces.get(k)).join("");
    outputs.samples = csv;
    const points = landings(csv);
    outputs.studySummary = study.summary(csv);
    // The landing ellipses holding 68 %, 95 % and 99.7 % of a normal spread (summary.json's
    // `probability` contours), as `karman montecarlo` draws them.
    const ellipses = [];
    for (const e of JSON.parse(outputs.studySummary).ellipses || []) {
      if (e.name !== "landing") { continue; }
      for (const c of e.probability) {
        ellipses.push({ label: `${e.body ? e.body + " " : ""}${(100 * c.normal_probability).toFixed(1)} %`, points: ellipsePoints(e.center_m, c.semi_major_m, c.semi_minor_m, e.orientation_deg) });
      }
    }
    $("mc-plot").innerHTML = landingChart(`Landing points (${points.length} of ${total}) and ellipses`, points, ellipses);
    const seconds = (performance.now() - started) / 1000;
    $("mc-status").textContent = `${total} samples in ${seconds.toFixed(1)} s on ${location.protocol === "file:" ? "this page" : workers + " workers"}`;
    $("mc-status").dataset.done = "1";
    $("mc-download").disabled = false;
    $("mc-download-summary").disabled = false;
  } catch (e) {
    for (const w of running) { w.terminate(); }
    showProblems(failure(e));
    $("mc-status").textContent = "the study failed";
  } finally {
    running = [];
    $("mc-run").disabled = false;
    $("mc-stop").disabled = true;
  }
}

$("mc-run").addEventListener("click", montecarlo);
$("mc-stop").addEventListener("click", () => { stopRequested = true; for (const w of running) { w.terminate(); } });
