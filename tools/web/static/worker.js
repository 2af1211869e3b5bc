/* worker.js - the explorer's background work, off the page's thread: the lit spheres, rendered
 * coarse to fine in row bands (step 8, 4, 2, 1), and the advisor's fits (budget, pareto), which
 * take seconds. The page starts two of these workers, one for spheres and one for the advisor,
 * so a fit never stalls a sphere.
 *
 * Messages in:  {type: "render", gen, size, light: [x, y, z], slots: [{slot, model, params}]}
 *               {type: "budget", id, material, budget}  {type: "pareto", id, material}
 * Messages out: {type: "loaded", ms}  {type: "error", gen|id, message}
 *               {type: "band", gen, slot, step, y0, y1, data: Float32Array(3 * size * (y1 - y0)),
 *                progress: 0..1}
 *               {type: "done", gen, slot, model, ms (time of the step-1 pass)}
 *               {type: "advise", id, kind, result} */
"use strict";

importScripts("abrdf_wasm.js", "abrdf_api.js");

const STEPS = [8, 4, 2, 1];
/* A band should take about this long: short enough that a new request (a slider move) is seen
 * within a frame or two, long enough that posting the band costs little beside computing it. */
const BAND_TARGET_MS = 25;

let api = null;
let latest = 0; /* generation of the newest render request; older renders stop at their next band */
const t0 = performance.now();
const loaded = AbrdfApi.load().then(
  (a) => {
    api = a;
    postMessage({ type: "loaded", ms: performance.now() - t0 });
  },
  (err) => postMessage({ type: "error", gen: 0, message: "worker: the wasm module did not load: " + err })
);

/* Lets messages queued meanwhile (a newer render) run before the next band. A message to
 * ourselves, not setTimeout(0): chained timeouts are clamped to 4 ms each, which cost a
 * progressive render more than its arithmetic. */
const tick = new MessageChannel();
const ticks = [];
tick.port1.onmessage = () => ticks.shift()();
function yieldToEvents() {
  return new Promise((resolve) => {
    ticks.push(resolve);
    tick.port2.postMessage(null);
  });
}

function* bands(job, size) {
  for (const step of STEPS) {
    let y = 0;
    while (y < size) {
      const y1 = Math.min(size, y + job.rows * step);
      yield { step, y0: y, y1 };
      y = y1;
    }
  }
}

async function render(m) {
  const gen = m.gen;
  const size = m.size;
  const jobs = [];
  for (const s of m.slots) {
    const r = api.setModel(s.slot, s.model, s.params, s.diffuse);
    if (!r.ok) {
      postMessage({ type: "error", gen, message: s.model + ": " + r.message });
      return;
    }
    let total = 0;
    for (const step of STEPS) total += Math.ceil(size / step) * Math.ceil(size / step);
    /* rows: sample rows per band; the coarsest pass (32 x 32 samples) is one band */
    jobs.push({ slot: s.slot, model: s.label || s.model, rows: 32, done: 0, total, ms1: 0, it: null });
  }
  for (const j of jobs) j.it = bands(j, size);
  /* Round robin over the slots, one band each: a fast model is not held back by a slow one. */
  while (jobs.length) {
    for (const j of jobs.slice()) {
      const next = j.it.next();
      if (next.done) {
        jobs.splice(jobs.indexOf(j), 1);
        continue;
      }
      const { step, y0, y1 } = next.value;
      const start = performance.now();
      const px = api.sphereRows(j.slot, size, m.light, y0, y1, step);
      const dt = performance.now() - start;
      if (step === 1) j.ms1 += dt;
      /* rows of the next band: aim at BAND_TARGET_MS */
      if (dt < BAND_TARGET_MS / 2) j.rows = Math.min(j.rows * 2, size);
      else if (dt > BAND_TARGET_MS * 2 && j.rows > 1) j.rows = Math.max(1, j.rows >> 1);
      j.done += Math.ceil((y1 - y0) / step) * Math.ceil(size / step);
      const data = new Float32Array(px); /* a copy we own, so it can be transferred */
      postMessage(
        { type: "band", gen, slot: j.slot, step, y0, y1, data, progress: j.done / j.total },
        [data.buffer]
      );
      if (step === 1 && y1 === size) postMessage({ type: "done", gen, slot: j.slot, model: j.model, ms: j.ms1 });
      await yieldToEvents();
      if (latest !== gen) return;
    }
  }
}

function advise(m) {
  try {
    const result = m.type === "budget" ? api.budget(m.material, m.budget) : api.pareto(m.material);
    postMessage({ type: "advise", id: m.id, kind: m.type, result });
  } catch (err) {
    postMessage({ type: "error", id: m.id, message: m.type + ": " + err });
  }
}

onmessage = async (e) => {
  const m = e.data;
  if (m.type === "render") latest = m.gen;
  await loaded;
  if (!api) return;
  if (m.type === "render") {
    if (m.gen === latest) await render(m);
  } else if (m.type === "budget" || m.type === "pareto") {
    advise(m);
  }
};
