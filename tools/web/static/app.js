/* app.js - the abrdf explorer page: parameter panels, plots of the lobe, lit spheres, the
 * selection trace and the advisor.
 *
 * Plain JavaScript and canvas 2D, no library: the page must work from any static server with no
 * network and no build step, and its plots are a few hundred lines of canvas code.
 *
 * Threads: the page's own Abrdf instance (abrdf_api.js) validates parameters and computes the
 * plots; worker.js renders the spheres coarse to fine and runs the advisor's fits. Every change
 * of model, parameter or light starts a new render generation; the worker drops stale ones. */
"use strict";

(function () {
  const tStart = performance.now();
  const $ = (id) => document.getElementById(id);
  const SIZE = 256; /* sphere canvases, pixels */
  const SLOT_COLOURS = ["#f2a541", "#4cc3e0"];
  const BG = "#1b1c1f";
  const GRID = "#3a3c42";
  const LABEL = "#b9bcc4";

  /* ---- state ------------------------------------------------------------------------------- */
  const state = {
    models: ["blinn_phong", "none"],
    diffuse: ["", ""] /* a diffuse lobe beside the slot's model (a material's choice), or "" */,
    params: [{}, {}],
    light: { theta: 45, phi: 0 },
    exposure: 0,
    goal: "performance",
    material: "",
    useCos: false,
    logPlot: false,
  };
  const last = { plane: null, nmse: null, cls: null, advise: null };
  /* sphereMs: the step-1 pass of a slot's sphere in the worker; renderMs: the whole progressive
   * render of the last change (every pass and slot, transfers and drawing included). */
  const timings = { loadMs: null, sphereMs: {}, renderMs: null, polarMs: null };
  let renderStart = 0;
  let api = null;
  let models = [];
  const byName = {};

  let readyResolve, readyReject;
  const ready = new Promise((res, rej) => {
    readyResolve = res;
    readyReject = rej;
  });
  ready.catch(() => {}); /* reported on the page; a test awaiting it still sees the rejection */

  /* pending work, for idle() */
  const pending = { render: false, plots: false, advise: 0 };
  let idleWaiters = [];
  function checkIdle() {
    if (pending.render || pending.plots || pending.advise) return;
    const w = idleWaiters;
    idleWaiters = [];
    for (const r of w) r();
  }
  function idle() {
    return new Promise((res) => {
      idleWaiters.push(res);
      checkIdle();
    });
  }

  window.explorer = {
    ready,
    api: null,
    state,
    last,
    timings,
    setLight,
    idle,
  };

  function setStatus(text, isError) {
    const s = $("status");
    s.textContent = text;
    s.classList.toggle("error", !!isError);
  }

  /* ---- numbers ----------------------------------------------------------------------------- */
  function fmt(v) {
    if (v === null || v === undefined) return "-";
    if (typeof v !== "number") return String(v);
    if (!isFinite(v)) return String(v);
    if (v === 0) return "0";
    const a = Math.abs(v);
    if (a >= 1e5 || a < 1e-3) return v.toExponential(2);
    return String(+v.toPrecision(4));
  }
  /* A parameter's field shows the value itself when it is short (what the table or the fit
   * gave), else 8 significant digits. */
  function fieldText(v) {
    const s = String(v);
    return s.length <= 12 ? s : String(+v.toPrecision(8));
  }
  function lum(r, g, b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b; /* Rec. 709 luminance of linear RGB */
  }
  function niceStep(span, count) {
    const raw = span / Math.max(1, count);
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  /* ---- slider scales ------------------------------------------------------------------------ */
  /* A range spanning more than 3 decades gets a log slider; with min 0 its low end is 1e-6 of
   * the max (n: 1), and 0 stays reachable by typing it. */
  const SLIDER_STEPS = 1000;
  function scaleOf(p) {
    if (p.kind === "int") return { log: false, lo: p.min, hi: p.max };
    const log = p.min > 0 ? p.max / p.min > 1e3 : p.max >= 1e3;
    return { log, lo: log && !(p.min > 0) ? p.max * 1e-6 : p.min, hi: p.max };
  }
  function toSlider(p, v) {
    const s = scaleOf(p);
    if (!s.log) return ((v - s.lo) / (s.hi - s.lo || 1)) * SLIDER_STEPS;
    const t = Math.log(Math.max(v, s.lo) / s.lo) / Math.log(s.hi / s.lo);
    return Math.min(1, Math.max(0, t)) * SLIDER_STEPS;
  }
  function fromSlider(p, x) {
    const s = scaleOf(p);
    const t = x / SLIDER_STEPS;
    let v = s.log ? s.lo * Math.pow(s.hi / s.lo, t) : s.lo + t * (s.hi - s.lo);
    if (p.kind === "int") v = Math.round(v);
    else v = +v.toPrecision(4);
    return Math.min(p.max, Math.max(p.min, v));
  }

  /* ---- parameter panels --------------------------------------------------------------------- */
  function defaults(name) {
    const out = {};
    const m = byName[name];
    if (!m) return out;
    for (const p of m.params) out[p.name] = p.kind === "rgb" && !Array.isArray(p.def) ? [p.def, p.def, p.def] : p.def;
    return out;
  }
  /* The parameters a slot shows: its diffuse lobe's, then its model's (one block: a name both
   * read appears once). */
  function slotParams(name, diffuse) {
    const seen = new Set();
    const out = [];
    for (const n of [diffuse, name]) {
      const m = byName[n];
      if (!m) continue;
      for (const p of m.params) {
        if (seen.has(p.name)) continue;
        seen.add(p.name);
        out.push(p);
      }
    }
    return out;
  }
  /* The slot's label: "disney_diffuse + disney_specular" or the model alone. */
  function slotLabel(slot) {
    return (state.diffuse[slot] ? state.diffuse[slot] + " + " : "") + state.models[slot];
  }
  /* paramsFor over both lobes of a pair (the model's values win where both read one). */
  function pairParams(name, diffuse, given) {
    return diffuse ? Object.assign(paramsFor(diffuse, given), paramsFor(name, given)) : paramsFor(name, given);
  }

  /* Keeps only the model's own parameters, in the shape its kind asks for. */
  function paramsFor(name, given) {
    const out = defaults(name);
    const m = byName[name];
    if (!m) return out;
    for (const p of m.params) {
      if (!(p.name in given) || given[p.name] === null || given[p.name] === undefined) continue;
      const v = given[p.name];
      if (p.kind === "rgb") out[p.name] = Array.isArray(v) ? v.slice(0, 3) : [v, v, v];
      else out[p.name] = Array.isArray(v) ? (v[0] + v[1] + v[2]) / 3 : v;
    }
    return out;
  }

  function buildParams(slot) {
    const box = $(slot === 0 ? "params-a" : "params-b");
    box.textContent = "";
    const name = state.models[slot];
    const info = $(slot === 0 ? "info-a" : "info-b");
    const m = byName[name];
    if (!m) {
      info.textContent = slot === 1 ? "No comparison: choose a model to compare A against." : "";
      return;
    }
    const notes = [];
    if (m.equation) notes.push(m.equation);
    if (m.needs && m.needs.length) notes.push("needs " + m.needs.join(", "));
    if (!m.closedForm) notes.push("integrates numerically: slow");
    const dm = byName[state.diffuse[slot]];
    info.textContent =
      (dm ? (dm.title || dm.name) + " + " : "") + (m.title || name) + (notes.length ? " (" + notes.join("; ") + ")" : "");
    info.title = (dm && dm.citation ? dm.citation + "; " : "") + (m.citation || "");
    for (const p of slotParams(name, state.diffuse[slot])) {
      const row = document.createElement("div");
      row.className = "param";
      const label = document.createElement("label");
      label.className = "param-name";
      label.textContent = p.name;
      label.title = p.help + " [" + fmt(p.min) + ", " + fmt(p.max) + "]";
      row.appendChild(label);
      const comps = p.kind === "rgb" ? [0, 1, 2] : [null];
      const fields = document.createElement("div");
      fields.className = "fields";
      for (const c of comps) {
        const pair = document.createElement("div");
        pair.className = "pair";
        const range = document.createElement("input");
        range.type = "range";
        range.min = "0";
        range.max = String(SLIDER_STEPS);
        range.step = "1";
        range.dataset.slot = String(slot);
        range.dataset.param = p.name;
        range.dataset.scale = scaleOf(p).log ? "log" : "linear";
        range.title = label.title;
        const text = document.createElement("input");
        text.type = "text";
        text.className = "num";
        text.dataset.slot = String(slot);
        text.dataset.param = p.name;
        text.size = 7;
        text.title = label.title;
        if (c !== null) {
          range.dataset.comp = String(c);
          text.dataset.comp = String(c);
          const ch = document.createElement("span");
          ch.className = "chan chan-" + "rgb"[c];
          ch.textContent = "RGB"[c];
          pair.appendChild(ch);
        }
        pair.appendChild(range);
        pair.appendChild(text);
        fields.appendChild(pair);
        range.addEventListener("input", () => {
          const v = fromSlider(p, +range.value);
          text.value = fieldText(v);
          applyField(slot, p, c, v, text);
        });
        text.addEventListener("change", () => onTyped(slot, p, c, text));
        text.addEventListener("keydown", (e) => {
          if (e.key === "Enter") onTyped(slot, p, c, text);
        });
      }
      row.appendChild(fields);
      if (p.kind === "rgb") {
        const sw = document.createElement("span");
        sw.className = "colour";
        row.appendChild(sw);
      }
      const err = document.createElement("div");
      err.className = "field-error";
      err.dataset.slot = String(slot);
      err.dataset.param = p.name;
      row.appendChild(err);
      box.appendChild(row);
    }
    syncFields(slot);
  }

  /* Shows the slot's current (valid) parameters in its fields. */
  function syncFields(slot) {
    if (!byName[state.models[slot]]) return;
    const box = $(slot === 0 ? "params-a" : "params-b");
    const list = slotParams(state.models[slot], state.diffuse[slot]);
    for (const p of list) {
      const v = state.params[slot][p.name];
      for (const el of box.querySelectorAll('input[data-param="' + p.name + '"]')) {
        const c = el.dataset.comp === undefined ? null : +el.dataset.comp;
        const x = c === null ? v : v[c];
        if (el.type === "range") el.value = String(toSlider(p, x));
        else el.value = fieldText(x);
      }
      if (p.kind === "rgb") {
        const sw = box.querySelector('.param:nth-child(' + (list.indexOf(p) + 1) + ") .colour");
        if (sw) sw.style.background = cssColour(v);
      }
      fieldError(slot, p.name, "all", "");
    }
  }
  function cssColour(rgb) {
    const c = rgb.map((x) => Math.round(255 * srgb(Math.min(1, Math.max(0, x)))));
    return "rgb(" + c.join(",") + ")";
  }
  /* Field errors per slot, parameter and component (null for a one-value parameter): a
   * colour's R can hold a bad value while G is fixed, and keeps its message. comp "all"
   * clears every component. */
  const fieldErrors = [{}, {}];
  function fieldError(slot, param, comp, message) {
    const errs = (fieldErrors[slot][param] = fieldErrors[slot][param] || {});
    if (comp === "all") for (const k of Object.keys(errs)) delete errs[k];
    else if (message) errs[comp] = message;
    else delete errs[comp];
    const box = $(slot === 0 ? "params-a" : "params-b");
    const el = box.querySelector('.field-error[data-param="' + param + '"]');
    if (el) el.textContent = Object.values(errs).join("; ");
    for (const f of box.querySelectorAll('input.num[data-param="' + param + '"]')) {
      const k = f.dataset.comp === undefined ? "null" : f.dataset.comp;
      f.classList.toggle("bad", k in errs);
    }
  }
  /* A decimal number as typed ("0.5", "-2", "1e-3"); anything else (hexadecimal, "Infinity",
   * spaces inside) is NaN. */
  function decimalValue(raw) {
    return /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(raw) ? Number(raw) : NaN;
  }

  function onTyped(slot, p, c, text) {
    const raw = text.value.trim();
    const v = decimalValue(raw);
    const range = "[" + fmt(p.min) + ", " + fmt(p.max) + "]";
    const what = p.name + (c === null ? "" : "[" + "RGB"[c] + "]");
    if (!isFinite(v)) {
      fieldError(slot, p.name, c, what + ": '" + raw + "' is not a number (range " + range + ")");
      return;
    }
    if (v < p.min || v > p.max) {
      fieldError(slot, p.name, c, what + " = " + raw + " is out of range " + range);
      return;
    }
    if (p.kind === "int" && !Number.isInteger(v)) {
      fieldError(slot, p.name, c, what + " = " + raw + " is not an integer (range " + range + ")");
      return;
    }
    applyField(slot, p, c, v, text);
  }

  /* Tries the new value on the page's Abrdf; on refusal the message goes next to the field and
   * the slot keeps its last valid parameters (and images). */
  function applyField(slot, p, c, v, text) {
    const next = Object.assign({}, state.params[slot]);
    if (c === null) next[p.name] = v;
    else {
      next[p.name] = state.params[slot][p.name].slice();
      next[p.name][c] = v;
    }
    const r = api.setModel(slot, state.models[slot], next, state.diffuse[slot]);
    if (!r.ok) {
      fieldError(slot, r.param || p.name, !r.param || r.param === p.name ? c : null, r.message);
      return false;
    }
    state.params[slot] = next;
    fieldError(slot, p.name, c, "");
    if (c !== null) {
      const sw = text && text.closest(".param").querySelector(".colour");
      if (sw) sw.style.background = cssColour(next[p.name]);
    }
    const box = $(slot === 0 ? "params-a" : "params-b");
    for (const el of box.querySelectorAll('input[type="range"][data-param="' + p.name + '"]')) {
      const cc = el.dataset.comp === undefined ? null : +el.dataset.comp;
      if (cc === c) el.value = String(toSlider(p, v));
    }
    changed();
    return true;
  }

  /* Sets a slot's model (and parameters: given ones over the model's defaults), with a diffuse
   * lobe beside it when `diffuse` names one (a material's diffuse + specular choice). */
  function setSlotModel(slot, name, given, diffuse) {
    diffuse = diffuse || "";
    if (slot === 1 && name === "none") {
      state.models[1] = "none";
      state.diffuse[1] = "";
      state.params[1] = {};
      $("model-b").value = "none";
      buildParams(1);
      changed();
      return true;
    }
    const params = pairParams(name, diffuse, given || {});
    const r = api.setModel(slot, name, params, diffuse);
    if (!r.ok) {
      setStatus((r.message.indexOf(name) === 0 ? "" : name + ": ") + r.message, true);
      $(slot === 0 ? "model-a" : "model-b").value = state.models[slot];
      return false;
    }
    state.models[slot] = name;
    state.diffuse[slot] = diffuse;
    state.params[slot] = params;
    $(slot === 0 ? "model-a" : "model-b").value = name;
    buildParams(slot);
    changed();
    return true;
  }

  /* ---- light -------------------------------------------------------------------------------- */
  /* World direction toward the light, viewer on +z, y up: theta from the view direction, phi
   * counter-clockwise from +x. The plots use the same theta as theta_i (light in their x-z plane
   * at phi for the 3-D lobe). */
  function lightVector() {
    const t = (state.light.theta * Math.PI) / 180;
    const f = (state.light.phi * Math.PI) / 180;
    return [Math.sin(t) * Math.cos(f), Math.sin(t) * Math.sin(f), Math.cos(t)];
  }
  function setLight(thetaDeg, phiDeg) {
    const t = Math.min(89, Math.max(0, +thetaDeg));
    let f = +(phiDeg === undefined ? state.light.phi : phiDeg);
    if (!isFinite(t) || !isFinite(f)) return;
    f = ((f % 360) + 360) % 360;
    state.light.theta = Math.round(t * 100) / 100;
    state.light.phi = Math.round(f * 100) / 100;
    $("theta-i").value = String(Math.round(state.light.theta));
    $("theta-i-out").textContent = fmt(state.light.theta) + "\u00b0";
    $("phi-i-out").textContent = fmt(state.light.phi) + "\u00b0";
    drawLightDisk();
    changed();
  }
  function drawLightDisk() {
    const cv = $("light");
    const g = cv.getContext("2d");
    const w = cv.width;
    const c = w / 2;
    const R = c - 8;
    g.clearRect(0, 0, w, w);
    g.fillStyle = "#2b2d33";
    g.beginPath();
    g.arc(c, c, R, 0, 2 * Math.PI);
    g.fill();
    g.strokeStyle = GRID;
    for (const deg of [30, 60]) {
      g.beginPath();
      g.arc(c, c, R * Math.sin((deg * Math.PI) / 180), 0, 2 * Math.PI);
      g.stroke();
    }
    g.beginPath();
    g.moveTo(c - R, c);
    g.lineTo(c + R, c);
    g.moveTo(c, c - R);
    g.lineTo(c, c + R);
    g.stroke();
    const L = lightVector();
    const x = c + R * L[0];
    const y = c - R * L[1];
    g.fillStyle = "#ffe27a";
    g.beginPath();
    g.arc(x, y, 6, 0, 2 * Math.PI);
    g.fill();
    g.fillStyle = LABEL;
    g.font = "10px sans-serif";
    g.fillText("30\u00b0", c + 2, c - R * 0.5 - 2);
    g.fillText("60\u00b0", c + 2, c - R * 0.866 - 2);
  }
  /* Dragging on a disk of radius R (light disk, spheres) points the light at that spot. */
  function dragLight(canvas, radiusOf) {
    let down = false;
    const at = (e) => {
      const b = canvas.getBoundingClientRect();
      const sx = canvas.width / b.width;
      const R = radiusOf(canvas);
      const x = ((e.clientX - b.left) * sx - canvas.width / 2) / R;
      const y = -((e.clientY - b.top) * sx - canvas.height / 2) / R;
      const rho = Math.min(1, Math.hypot(x, y));
      const theta = (Math.asin(rho) * 180) / Math.PI;
      const phi = rho > 0 ? (Math.atan2(y, x) * 180) / Math.PI : state.light.phi;
      setLight(theta, phi);
    };
    canvas.addEventListener("pointerdown", (e) => {
      down = true;
      canvas.setPointerCapture(e.pointerId);
      at(e);
    });
    canvas.addEventListener("pointermove", (e) => {
      if (down) at(e);
    });
    canvas.addEventListener("pointerup", () => (down = false));
  }

  /* ---- change scheduling -------------------------------------------------------------------- */
  let frameQueued = false;
  function changed() {
    pending.plots = true;
    pending.render = true;
    if (frameQueued) return;
    frameQueued = true;
    requestAnimationFrame(() => {
      frameQueued = false;
      requestRender();
      updatePlots();
    });
  }

  /* ---- spheres (worker) --------------------------------------------------------------------- */
  let worker = null;
  let adviceWorker = null;
  let gen = 0;
  const images = [new Float32Array(3 * SIZE * SIZE), new Float32Array(3 * SIZE * SIZE)];
  const done = [false, false];
  let mask = null;
  let renderedModels = ""; /* the models of the sphere-time line */

  function requestRender() {
    gen++;
    renderStart = performance.now();
    const slots = [0, 1]
      .filter((k) => k === 0 || state.models[1] !== "none")
      .map((k) => ({ slot: k, model: state.models[k], params: state.params[k], diffuse: state.diffuse[k], label: slotLabel(k) }));
    done[0] = false;
    done[1] = state.models[1] === "none";
    pending.render = true;
    const key = slotLabel(0) + " | " + slotLabel(1);
    if (key !== renderedModels) $("sphere-time").textContent = "";
    renderedModels = key;
    $("name-a").textContent = slotLabel(0);
    $("name-b").textContent = state.models[1] === "none" ? "(none)" : slotLabel(1);
    if (state.models[1] === "none") {
      images[1].fill(0);
      clearCanvas("sphere-b", "no model B");
      clearCanvas("sphere-diff", "no model B");
      $("progress-b").textContent = "";
      showNmse(null);
    }
    worker.postMessage({ type: "render", gen, size: SIZE, light: lightVector(), slots });
  }

  function onWorker(e) {
    const m = e.data;
    if (m.type === "error") {
      setStatus(m.message, true);
      if (m.gen === gen) {
        pending.render = false;
        checkIdle();
      }
      return;
    }
    if (m.gen !== gen) return; /* a stale band */
    if (m.type === "band") {
      images[m.slot].set(m.data, 3 * SIZE * m.y0);
      drawSphereRows(m.slot, m.y0, m.y1);
      $(m.slot === 0 ? "progress-a" : "progress-b").textContent =
        m.progress < 1 ? "step " + m.step + ", " + Math.floor(100 * m.progress) + "%" : "";
      queueDiff();
    } else if (m.type === "done") {
      done[m.slot] = true;
      timings.sphereMs[m.model] = m.ms;
      $(m.slot === 0 ? "progress-a" : "progress-b").textContent = "";
      if (done[0] && done[1]) sphereComplete();
    }
  }

  function sphereComplete() {
    drawDiff();
    timings.renderMs = performance.now() - renderStart;
    if (state.models[1] !== "none") {
      const r = api.nmse(images[0], images[1]);
      showNmse(r);
    }
    const t = [slotLabel(0), state.models[1] === "none" ? "none" : slotLabel(1)]
      .filter((n) => n !== "none" && timings.sphereMs[n] !== undefined)
      .map((n) => n + " " + fmt(timings.sphereMs[n]) + " ms");
    $("sphere-time").textContent = "256\u00d7256 at full resolution in the worker: " + t.join(", ");
    pending.render = false;
    setStatus("ready");
    readyResolve(); /* the first complete sphere; later calls do nothing */
    checkIdle();
  }

  function showNmse(r) {
    last.nmse = r ? r.nmse : null;
    last.cls = r ? r.cls : null;
    $("nmse").textContent = r ? (r.nmse === 0 ? "0" : r.nmse.toExponential(3)) : "\u2013";
    const c = $("nmse-class");
    c.textContent = r ? r.cls : "\u2013";
    c.className = r ? "cls-" + r.cls : "";
  }

  /* tone map: exposure, clamp to [0, 1], sRGB encode (IEC 61966-2-1) through a table */
  function srgb(x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * Math.pow(x, 1 / 2.4) - 0.055;
  }
  const LUT_N = 4096;
  const srgbLut = new Uint8ClampedArray(LUT_N + 1);
  for (let i = 0; i <= LUT_N; i++) srgbLut[i] = Math.round(255 * srgb(i / LUT_N));

  function drawSphereRows(slot, y0, y1) {
    const g = $(slot === 0 ? "sphere-a" : "sphere-b").getContext("2d");
    const img = g.createImageData(SIZE, y1 - y0);
    const k = Math.pow(2, state.exposure) * LUT_N;
    const src = images[slot];
    const d = img.data;
    for (let y = y0; y < y1; y++) {
      for (let x = 0; x < SIZE; x++) {
        const i = y * SIZE + x;
        const o = 4 * ((y - y0) * SIZE + x);
        for (let ch = 0; ch < 3; ch++) {
          const v = src[3 * i + ch] * k;
          d[o + ch] = srgbLut[v > 0 ? (v < LUT_N ? v | 0 : LUT_N) : 0];
        }
        d[o + 3] = mask[i] ? 255 : 0; /* outside the disk: the page's background */
      }
    }
    g.putImageData(img, 0, y0);
  }
  function redrawSpheres() {
    drawSphereRows(0, 0, SIZE);
    if (state.models[1] !== "none") {
      drawSphereRows(1, 0, SIZE);
      drawDiff();
    }
  }
  function clearCanvas(id, text) {
    const cv = $(id);
    const g = cv.getContext("2d");
    g.clearRect(0, 0, cv.width, cv.height);
    g.fillStyle = "#6b6f78";
    g.font = "13px sans-serif";
    g.textAlign = "center";
    g.fillText(text, cv.width / 2, cv.height / 2);
    g.textAlign = "start";
  }

  /* false colour for |A - B|: black, blue, magenta, orange, yellow, white (monotone lightness) */
  const RAMP = [
    [0, 0, 0],
    [40, 30, 140],
    [170, 40, 150],
    [240, 110, 40],
    [250, 220, 60],
    [255, 255, 255],
  ];
  function ramp(t) {
    t = Math.min(1, Math.max(0, t)) * (RAMP.length - 1);
    const i = Math.min(RAMP.length - 2, Math.floor(t));
    const f = t - i;
    return [0, 1, 2].map((c) => RAMP[i][c] + f * (RAMP[i + 1][c] - RAMP[i][c]));
  }
  let diffQueued = false;
  function queueDiff() {
    if (diffQueued || state.models[1] === "none") return;
    diffQueued = true;
    requestAnimationFrame(() => {
      diffQueued = false;
      drawDiff();
    });
  }
  function drawDiff() {
    if (state.models[1] === "none") return;
    const a = images[0];
    const b = images[1];
    const n = SIZE * SIZE;
    const d = new Float32Array(n);
    let max = 0;
    for (let i = 0; i < n; i++) {
      const v = Math.abs(lum(a[3 * i], a[3 * i + 1], a[3 * i + 2]) - lum(b[3 * i], b[3 * i + 1], b[3 * i + 2]));
      d[i] = v;
      if (v > max) max = v;
    }
    const g = $("sphere-diff").getContext("2d");
    const img = g.createImageData(SIZE, SIZE);
    for (let i = 0; i < n; i++) {
      const c = ramp(max > 0 ? d[i] / max : 0);
      img.data[4 * i] = c[0];
      img.data[4 * i + 1] = c[1];
      img.data[4 * i + 2] = c[2];
      img.data[4 * i + 3] = mask[i] ? 255 : 0;
    }
    g.putImageData(img, 0, 0);
    drawDiffScale(max);
  }
  function drawDiffScale(max) {
    const cv = $("diff-scale");
    const g = cv.getContext("2d");
    g.clearRect(0, 0, cv.width, cv.height);
    const x0 = 8;
    const w = cv.width - 16;
    for (let x = 0; x < w; x++) {
      const c = ramp(x / (w - 1));
      g.fillStyle = "rgb(" + c.map(Math.round).join(",") + ")";
      g.fillRect(x0 + x, 2, 1, 12);
    }
    g.fillStyle = LABEL;
    g.font = "11px sans-serif";
    g.fillText("0", x0, 28);
    g.textAlign = "right";
    g.fillText(fmt(max) + " (radiance, white Lambert = 1)", x0 + w, 28);
    g.textAlign = "start";
  }

  /* ---- plots (the page's own Abrdf) --------------------------------------------------------- */
  let plotToken = 0;
  const plotData = { plane: [null, null], hemi: [null, null], nT: 0, nP: 0 };

  /* Closed-form models use plane()/hemisphere() at full density; integrating models are
   * evaluated by evalPairs in slices of about 20 ms, yielding between slices, at a lower density,
   * so the page stays responsive. */
  async function evalChunked(slot, wi, wo, token) {
    const n = wi.length / 3;
    const out = new Float32Array(3 * n);
    let chunk = 4;
    for (let i = 0; i < n; ) {
      const j = Math.min(n, i + chunk);
      const t = performance.now();
      out.set(api.evalPairs(slot, wi.subarray(3 * i, 3 * j), wo.subarray(3 * i, 3 * j)), 3 * i);
      const dt = performance.now() - t;
      if (dt < 10) chunk *= 2;
      else if (dt > 40 && chunk > 1) chunk >>= 1;
      i = j;
      await new Promise((r) => setTimeout(r, 0));
      if (token !== plotToken) return null;
    }
    return out;
  }
  async function planeOf(slot, ti, token) {
    const m = byName[state.models[slot]];
    if (m.closedForm) return api.plane(slot, ti, 181);
    const count = 61;
    const thetaO = new Float64Array(count);
    const wi = new Float32Array(3 * count);
    const wo = new Float32Array(3 * count);
    const t = (ti * Math.PI) / 180;
    for (let k = 0; k < count; k++) {
      const to = -90 + (180 * k) / (count - 1);
      thetaO[k] = to;
      const r = (to * Math.PI) / 180;
      wi.set([Math.sin(t), 0, Math.cos(t)], 3 * k);
      wo.set([Math.sin(r), 0, Math.cos(r)], 3 * k);
    }
    const f = await evalChunked(slot, wi, wo, token);
    return f ? { thetaO, f } : null;
  }
  async function hemiOf(slot, ti, pi, nT, nP, token) {
    const m = byName[state.models[slot]];
    if (m.closedForm) return api.hemisphere(slot, ti, pi, nT, nP);
    const n = nT * nP;
    const wi = new Float32Array(3 * n);
    const wo = new Float32Array(3 * n);
    const t = (ti * Math.PI) / 180;
    const p = (pi * Math.PI) / 180;
    for (let j = 0; j < nT; j++) {
      const th = (((j + 0.5) / nT) * Math.PI) / 2;
      for (let k = 0; k < nP; k++) {
        const ph = (k / nP) * 2 * Math.PI;
        const i = j * nP + k;
        wi.set([Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)], 3 * i);
        wo.set([Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)], 3 * i);
      }
    }
    return evalChunked(slot, wi, wo, token);
  }

  async function updatePlots() {
    const token = ++plotToken;
    pending.plots = true;
    const slots = state.models[1] === "none" ? [0] : [0, 1];
    const ti = state.light.theta;
    const slow = slots.some((s) => !byName[state.models[s]].closedForm);
    const nT = slow ? 9 : 24;
    const nP = slow ? 18 : 48;
    const planes = [null, null];
    const hemis = [null, null];
    const t0 = performance.now();
    for (const s of slots) {
      planes[s] = await planeOf(s, ti, token);
      if (token !== plotToken) return;
    }
    timings.polarMs = performance.now() - t0;
    plotData.plane = planes;
    last.plane = planes[0];
    drawPolar();
    drawCartesian();
    for (const s of slots) {
      hemis[s] = await hemiOf(s, ti, state.light.phi, nT, nP, token);
      if (token !== plotToken) return;
    }
    plotData.hemi = hemis;
    plotData.nT = nT;
    plotData.nP = nP;
    drawLobe3d();
    pending.plots = false;
    checkIdle();
  }

  /* The scale of the plane plots: the largest value away from grazing (|theta_o| <= 85 deg),
   * where some models grow without bound as cos theta_o -> 0; curves above it are clipped. */
  const SCALE_LIMIT_DEG = 85;
  function planeMax(vals) {
    let max = 0;
    let all = 0;
    vals.forEach((v, s) => {
      if (!v) return;
      const th = plotData.plane[s].thetaO;
      for (let k = 0; k < v.length; k++) {
        all = Math.max(all, v[k]);
        if (Math.abs(th[k]) <= SCALE_LIMIT_DEG) max = Math.max(max, v[k]);
      }
    });
    return max > 0 ? max : all;
  }

  function planeValues(pl) {
    const n = pl.thetaO.length;
    const v = new Float64Array(n);
    for (let k = 0; k < n; k++) {
      let x = lum(pl.f[3 * k], pl.f[3 * k + 1], pl.f[3 * k + 2]);
      if (state.useCos) x *= Math.cos((pl.thetaO[k] * Math.PI) / 180);
      v[k] = Math.max(0, x);
    }
    return v;
  }
  function quantity() {
    return state.useCos ? "f\u1d63 cos \u03b8\u2092 (1/sr)" : "f\u1d63 (1/sr)";
  }

  /* A plot's canvas cleared to the background: {g (its 2-D context), W, H}. */
  function plotCanvas(id) {
    const cv = $(id);
    const g = cv.getContext("2d");
    g.fillStyle = BG;
    g.fillRect(0, 0, cv.width, cv.height);
    return { g, W: cv.width, H: cv.height };
  }

  function drawPolar() {
    const { g, W, H } = plotCanvas("polar");
    const cx = W / 2;
    const cy = H - 24;
    const R = Math.min(W / 2 - 30, H - 44);
    const vals = plotData.plane.map((p) => (p ? planeValues(p) : null));
    const max = planeMax(vals);
    /* grid: half circles at nice radii, spokes every 30 degrees */
    g.strokeStyle = GRID;
    g.fillStyle = LABEL;
    g.font = "11px sans-serif";
    g.lineWidth = 1;
    const step = max > 0 ? niceStep(max, 3) : 1;
    g.textAlign = "center";
    for (let r = step; max > 0 && r <= max * 1.0001; r += step) {
      g.beginPath();
      g.arc(cx, cy, (R * r) / max, Math.PI, 2 * Math.PI);
      g.stroke();
      g.fillText(fmt(r), cx - (R * r) / max, cy + 13); /* radius labels on the left baseline */
    }
    for (let a = -90; a <= 90; a += 30) {
      const t = (a * Math.PI) / 180;
      g.beginPath();
      g.moveTo(cx, cy);
      g.lineTo(cx + R * Math.sin(t), cy - R * Math.cos(t));
      g.stroke();
      g.textAlign = "center";
      g.fillText(a + "\u00b0", cx + (R + 14) * Math.sin(t), cy - (R + 6) * Math.cos(t) + 4);
    }
    g.textAlign = "start";
    g.beginPath();
    g.moveTo(cx - R - 6, cy);
    g.lineTo(cx + R + 6, cy);
    g.stroke();
    /* light (wi at +x) and its mirror direction */
    const ti = (state.light.theta * Math.PI) / 180;
    g.strokeStyle = "#ffe27a";
    g.setLineDash([]);
    g.beginPath();
    g.moveTo(cx, cy);
    g.lineTo(cx + R * Math.sin(ti), cy - R * Math.cos(ti));
    g.stroke();
    g.setLineDash([4, 4]);
    g.strokeStyle = "#8a8d96";
    g.beginPath();
    g.moveTo(cx, cy);
    g.lineTo(cx - R * Math.sin(ti), cy - R * Math.cos(ti));
    g.stroke();
    g.setLineDash([]);
    vals.forEach((v, s) => {
      if (!v || !(max > 0)) return;
      const th = plotData.plane[s].thetaO;
      g.strokeStyle = SLOT_COLOURS[s];
      g.lineWidth = 2;
      g.beginPath();
      for (let k = 0; k < v.length; k++) {
        const t = (th[k] * Math.PI) / 180;
        const r = (R * Math.min(v[k], 1.1 * max)) / max;
        const x = cx + r * Math.sin(t);
        const y = cy - r * Math.cos(t);
        if (k) g.lineTo(x, y);
        else g.moveTo(x, y);
      }
      g.stroke();
    });
    g.lineWidth = 1;
    g.fillStyle = LABEL;
    g.fillText(quantity() + ", light \u03b8\u1d62 = " + fmt(state.light.theta) + "\u00b0 (yellow)", 8, 14);
    $("plot-quantity").textContent = state.useCos ? "f_r cos \u03b8o" : "f_r";
  }

  function drawCartesian() {
    const { g, W, H } = plotCanvas("cartesian");
    const L = 56;
    const Rm = 12;
    const T = 22;
    const B = 34;
    const vals = plotData.plane.map((p) => (p ? planeValues(p) : null));
    const max = planeMax(vals);
    let minPos = Infinity;
    for (const v of vals) if (v) for (const x of v) if (x > 0) minPos = Math.min(minPos, x);
    const log = state.logPlot && max > 0;
    let lo = 0;
    let hi = max > 0 ? max * 1.05 : 1;
    if (log) {
      hi = Math.ceil(Math.log10(max));
      lo = Math.max(hi - 6, Math.floor(Math.log10(minPos)));
      if (lo >= hi) lo = hi - 1;
    }
    const X = (t) => L + ((t + 90) / 180) * (W - L - Rm);
    const Y = (v) => {
      const u = log ? (v > 0 ? Math.log10(v) : lo) : v;
      return H - B - ((Math.max(lo, u) - lo) / (hi - lo)) * (H - B - T);
    };
    g.strokeStyle = GRID;
    g.fillStyle = LABEL;
    g.font = "11px sans-serif";
    g.textAlign = "center";
    for (let t = -90; t <= 90; t += 30) {
      g.beginPath();
      g.moveTo(X(t), T);
      g.lineTo(X(t), H - B);
      g.stroke();
      g.fillText(t + "\u00b0", X(t), H - B + 14);
    }
    g.fillText("\u03b8\u2092 (deg); mirror at \u2212\u03b8\u1d62", (L + W) / 2, H - 4);
    g.textAlign = "right";
    if (log) {
      for (let e = lo; e <= hi; e++) {
        const y = Y(Math.pow(10, e));
        g.beginPath();
        g.moveTo(L, y);
        g.lineTo(W - Rm, y);
        g.stroke();
        g.fillText("1e" + e, L - 4, y + 4);
      }
    } else {
      const st = niceStep(hi, 4);
      for (let v = 0; v <= hi; v += st) {
        const y = Y(v);
        g.beginPath();
        g.moveTo(L, y);
        g.lineTo(W - Rm, y);
        g.stroke();
        g.fillText(fmt(v), L - 4, y + 4);
      }
    }
    g.textAlign = "start";
    const mirror = X(-state.light.theta);
    g.strokeStyle = "#8a8d96";
    g.setLineDash([4, 4]);
    g.beginPath();
    g.moveTo(mirror, T);
    g.lineTo(mirror, H - B);
    g.stroke();
    g.setLineDash([]);
    vals.forEach((v, s) => {
      if (!v) return;
      const th = plotData.plane[s].thetaO;
      g.strokeStyle = SLOT_COLOURS[s];
      g.lineWidth = 2;
      g.beginPath();
      const top = log ? Math.pow(10, hi) : hi;
      for (let k = 0; k < v.length; k++) {
        const y = Y(Math.min(v[k], top));
        if (k) g.lineTo(X(th[k]), y);
        else g.moveTo(X(th[k]), y);
      }
      g.stroke();
    });
    g.lineWidth = 1;
    g.fillStyle = LABEL;
    g.fillText(quantity() + (log ? ", log" : ""), 8, 14);
  }

  /* 3-D lobe: f_r over the hemisphere as a radial surface, wireframe, orthographic view */
  const view = { yaw: -35, pitch: 25 };
  function drawLobe3d() {
    const { g, W, H } = plotCanvas("lobe3d");
    const nT = plotData.nT;
    const nP = plotData.nP;
    let max = 0;
    const vals = plotData.hemi.map((h) => {
      if (!h) return null;
      const v = new Float64Array(nT * nP);
      for (let i = 0; i < nT * nP; i++) {
        let x = lum(h[3 * i], h[3 * i + 1], h[3 * i + 2]);
        if (state.useCos) x *= Math.cos((((Math.floor(i / nP) + 0.5) / nT) * Math.PI) / 2);
        v[i] = Math.max(0, x);
        max = Math.max(max, v[i]);
      }
      return v;
    });
    const cy = Math.cos((view.yaw * Math.PI) / 180);
    const sy = Math.sin((view.yaw * Math.PI) / 180);
    const cp = Math.cos((view.pitch * Math.PI) / 180);
    const sp = Math.sin((view.pitch * Math.PI) / 180);
    const S = Math.min(W, H) * 0.42;
    const ox = W / 2;
    const oy = H * 0.68;
    const proj = (x, y, z) => {
      const x1 = cy * x - sy * y;
      const y1 = sy * x + cy * y;
      return [ox + S * x1, oy - S * (z * cp - y1 * sp)];
    };
    const line = (pts) => {
      g.beginPath();
      pts.forEach((p, i) => (i ? g.lineTo(p[0], p[1]) : g.moveTo(p[0], p[1])));
      g.stroke();
    };
    /* the surface's disk and frame: tangent +x, bitangent +y, normal +z */
    g.strokeStyle = GRID;
    const disk = [];
    for (let k = 0; k <= 64; k++) disk.push(proj(Math.cos((k / 64) * 2 * Math.PI), Math.sin((k / 64) * 2 * Math.PI), 0));
    line(disk);
    g.font = "11px sans-serif";
    g.fillStyle = LABEL;
    for (const [v, name] of [
      [[1, 0, 0], "t"],
      [[0, 1, 0], "b"],
      [[0, 0, 1], "n"],
    ]) {
      const p = proj(v[0] * 1.15, v[1] * 1.15, v[2] * 1.15);
      line([proj(0, 0, 0), p]);
      g.fillText(name, p[0] + 3, p[1]);
    }
    const ti = (state.light.theta * Math.PI) / 180;
    const pi = (state.light.phi * Math.PI) / 180;
    g.strokeStyle = "#ffe27a";
    line([proj(0, 0, 0), proj(1.1 * Math.sin(ti) * Math.cos(pi), 1.1 * Math.sin(ti) * Math.sin(pi), 1.1 * Math.cos(ti))]);
    if (max > 0)
      vals.forEach((v, s) => {
        if (!v) return;
        const P = (j, k) => {
          const th = (((j + 0.5) / nT) * Math.PI) / 2;
          const ph = ((k % nP) / nP) * 2 * Math.PI;
          const r = v[j * nP + (k % nP)] / max;
          return proj(r * Math.sin(th) * Math.cos(ph), r * Math.sin(th) * Math.sin(ph), r * Math.cos(th));
        };
        g.strokeStyle = SLOT_COLOURS[s];
        g.globalAlpha = 0.75;
        for (let j = 0; j < nT; j++) {
          const ring = [];
          for (let k = 0; k <= nP; k++) ring.push(P(j, k));
          line(ring);
        }
        for (let k = 0; k < nP; k += Math.max(1, Math.round(nP / 24))) { /* at most 24 meridians */
          const mer = [proj(0, 0, 0)];
          for (let j = 0; j < nT; j++) mer.push(P(j, k));
          line(mer);
        }
        g.globalAlpha = 1;
      });
    g.fillStyle = LABEL;
    g.fillText(quantity() + ", max " + fmt(max), 8, 14);
  }
  function dragRotate(canvas) {
    let down = null;
    canvas.addEventListener("pointerdown", (e) => {
      down = [e.clientX, e.clientY, view.yaw, view.pitch];
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener("pointermove", (e) => {
      if (!down) return;
      view.yaw = down[2] - (e.clientX - down[0]) * 0.5;
      view.pitch = Math.min(89, Math.max(-10, down[3] + (e.clientY - down[1]) * 0.5));
      drawLobe3d();
    });
    canvas.addEventListener("pointerup", () => (down = null));
  }

  /* ---- material, selection trace ------------------------------------------------------------ */
  function traceList(id, r) {
    const ol = $(id);
    ol.textContent = "";
    if (!r) return;
    if (!r.ok) {
      const li = document.createElement("li");
      li.className = "trace-error";
      li.textContent = r.message;
      ol.appendChild(li);
      return;
    }
    for (const s of r.trace) {
      const li = document.createElement("li");
      li.textContent = s.text;
      if (s.passed === true) li.classList.add("passed");
      else if (s.passed === false) li.classList.add("failed");
      ol.appendChild(li);
    }
    const li = document.createElement("li");
    li.className = "choice";
    li.textContent = "\u2192 " + [r.diffuse, r.specular].filter((x) => x).join(" + ");
    ol.appendChild(li);
  }

  function chooseMaterial() {
    state.material = $("material").value;
    $("trace-material").textContent = state.material ? "of " + state.material : "";
    $("trace-hint").hidden = !!state.material;
    if (!state.material) {
      traceList("trace-performance", null);
      traceList("trace-photoreal", null);
      return;
    }
    const results = {};
    for (const goal of ["performance", "photoreal"]) {
      results[goal] = api.select(state.material, goal);
      traceList("trace-" + goal, results[goal]);
    }
    const r = results[state.goal];
    if (!r.ok) {
      setStatus(state.material + ": " + r.message, true);
      return;
    }
    /* A diffuse + specular choice goes into A whole: the sphere shows the material. */
    setSlotModel(0, r.specular || r.diffuse, r.params, r.specular ? r.diffuse : "");
  }

  /* ---- advisor ------------------------------------------------------------------------------ */
  let adviseId = 0;
  let adviseTimer = null;
  function runAdvisor() {
    const out = $("advise-result");
    const errEl = $("advise-budget-error");
    errEl.textContent = "";
    $("advise-budget").classList.remove("bad");
    if (!state.material) {
      out.innerHTML = '<p class="field-error">Choose a material of the table first: the advisor works on a material.</p>';
      return;
    }
    const mode = $("advise-mode").value;
    if (mode === "goal") {
      const r = api.select(state.material, state.goal);
      showAdvice(r, "goal");
      requestAdvice({ type: "pareto", material: state.material }); /* the front, for context */
      return;
    }
    const raw = $("advise-budget").value.trim();
    const classes = api.classes().map((c) => c.name);
    let budget = raw;
    if (classes.indexOf(raw) < 0 || raw === "significant") {
      budget = Number(raw);
      if (raw === "" || !isFinite(budget) || budget <= 0) {
        errEl.textContent =
          "budget '" + raw + "' is neither a class (none, slight, noticeable) nor a positive NMSE";
        $("advise-budget").classList.add("bad");
        return;
      }
    }
    requestAdvice({ type: "budget", material: state.material, budget });
  }
  function requestAdvice(msg) {
    msg.id = ++adviseId;
    pending.advise++;
    const t0 = performance.now();
    const note = document.createElement("p");
    note.className = "hint working";
    note.id = "advise-working";
    if (msg.type === "budget") {
      $("advise-result").textContent = "";
      $("advise-result").appendChild(note);
    }
    clearInterval(adviseTimer);
    adviseTimer = setInterval(() => {
      const el = $("advise-working");
      if (el) el.textContent = "fitting every candidate in the worker\u2026 " + ((performance.now() - t0) / 1000).toFixed(1) + " s";
    }, 100);
    if (!adviceWorker) {
      adviceWorker = new Worker("worker.js");
      adviceWorker.onmessage = onAdviceWorker;
      adviceWorker.onerror = (e) => setStatus("worker.js (advisor): " + e.message, true);
    }
    adviceWorker.postMessage(msg);
  }
  function onAdviceWorker(e) {
    const m = e.data;
    if (m.type === "loaded") return;
    pending.advise = Math.max(0, pending.advise - 1);
    if (m.id === adviseId) {
      clearInterval(adviseTimer);
      const w = $("advise-working");
      if (w) w.remove();
      if (m.type === "error") $("advise-result").innerHTML = '<p class="field-error"></p>';
      if (m.type === "error") $("advise-result").firstChild.textContent = m.message;
      else if (m.kind === "budget") showAdvice(m.result, "budget");
      else drawPareto(m.result, last.advise); /* goal mode: ring the flowchart's choice */
    }
    checkIdle();
  }

  function paramText(p) {
    return Object.keys(p || {})
      .map((k) => k + " " + (Array.isArray(p[k]) ? p[k].map(fmt).join(",") : fmt(p[k])))
      .join("  ");
  }
  function showAdvice(r, mode) {
    last.advise = r;
    const out = $("advise-result");
    out.textContent = "";
    if (!r || r.ok === false) {
      const p = document.createElement("p");
      p.className = "field-error";
      p.textContent = (r && r.message) || "no answer";
      out.appendChild(p);
      return;
    }
    const rows = [
      ["material", state.material + " (" + (mode === "goal" ? "goal " + state.goal : "budget " + $("advise-budget").value) + ")"],
      ["models", [r.diffuse, r.specular].filter((x) => x).join(" + ") || "-"],
      ["parameters", paramText(r.params)],
    ];
    if (r.error) rows.push(["predicted NMSE", fmt(r.error.nmse_pred) + " (" + r.error.class + ")"]);
    if (r.cost) rows.push(["cost", fmt(r.cost.total) + " " + (r.cost.unit || "")]);
    if (r.reference) rows.push(["reference", [r.reference.diffuse, r.reference.specular].filter((x) => x).join(" + ")]);
    const dl = document.createElement("dl");
    for (const [k, v] of rows) {
      const dt = document.createElement("dt");
      dt.textContent = k;
      const dd = document.createElement("dd");
      dd.textContent = v;
      dl.appendChild(dt);
      dl.appendChild(dd);
    }
    out.appendChild(dl);
    const use = document.createElement("button");
    use.type = "button";
    use.textContent = r.reference ? "Compare: A = choice, B = reference" : "Set A to the choice";
    use.addEventListener("click", () => {
      setSlotModel(0, r.specular || r.diffuse, r.params || {}, r.specular ? r.diffuse : "");
      if (r.reference) {
        const ref = api.select(state.material, "photoreal");
        const rr = r.reference;
        if (ref.ok) setSlotModel(1, rr.specular || rr.diffuse, ref.params, rr.specular ? rr.diffuse : "");
      }
    });
    out.appendChild(use);
    if (r.candidates) drawPareto(r, r);
  }

  /* r: an object with candidates (budget or pareto); chosen: {diffuse, specular} to ring */
  function drawPareto(r, chosen) {
    const { g, W, H } = plotCanvas("pareto");
    g.font = "11px sans-serif";
    g.fillStyle = LABEL;
    if (!r || !r.candidates || !r.candidates.length) {
      g.fillText((r && r.message) || "the advisor's candidates: cost against predicted NMSE", 10, 20);
      return;
    }
    const FLOOR = 1e-7; /* an exact match (NMSE 0) is drawn on the axis' floor */
    const cs = r.candidates.map((c) => ({
      c,
      x: c.cost,
      y: Math.log10(Math.max(FLOOR, c.nmse_pred)),
      name: [c.diffuse, c.specular].filter((x) => x).join("+"),
    }));
    const xs = cs.map((p) => p.x).filter(isFinite);
    const xmax = Math.max(...xs) * 1.08;
    const ymin = Math.floor(Math.min(...cs.map((p) => p.y)));
    const ymax = Math.max(0, Math.ceil(Math.max(...cs.map((p) => p.y))));
    const L = 50;
    const Rm = 14;
    const T = 20;
    const B = 34;
    const X = (x) => L + (x / (xmax || 1)) * (W - L - Rm);
    const Y = (y) => H - B - ((y - ymin) / (ymax - ymin || 1)) * (H - B - T);
    g.strokeStyle = GRID;
    g.textAlign = "right";
    for (let e = ymin; e <= ymax; e++) {
      g.beginPath();
      g.moveTo(L, Y(e));
      g.lineTo(W - Rm, Y(e));
      g.stroke();
      g.fillText(e === Math.log10(FLOOR) ? "\u2264" + "1e" + e : "1e" + e, L - 4, Y(e) + 4);
    }
    g.textAlign = "center";
    const st = niceStep(xmax, 5);
    for (let x = 0; x <= xmax; x += st) {
      g.beginPath();
      g.moveTo(X(x), T);
      g.lineTo(X(x), H - B);
      g.stroke();
      g.fillText(fmt(x), X(x), H - B + 14);
    }
    g.fillText("cost (" + ((r.cost && r.cost.unit) || "ns/eval").split(" (")[0] + ")", (L + W) / 2, H - 4);
    g.textAlign = "start";
    g.fillText("predicted image NMSE (log) vs cost; front in white", 8, 12);
    if (r.budget && r.budget.max_nmse && r.budget.max_nmse < 1) {
      const y = Y(Math.log10(r.budget.max_nmse));
      g.strokeStyle = "#e06c75";
      g.setLineDash([5, 4]);
      g.beginPath();
      g.moveTo(L, y);
      g.lineTo(W - Rm, y);
      g.stroke();
      g.setLineDash([]);
      g.fillStyle = "#e06c75";
      g.fillText("budget " + fmt(r.budget.max_nmse), W - Rm - 90, y - 4);
    }
    /* front labels that would overlap one already drawn are left out (the point stays) */
    const placed = [];
    const labelOnce = (text, x, y) => {
      const w = g.measureText(text).width;
      if (placed.some((b) => x < b[0] + b[2] + 4 && b[0] < x + w + 4 && Math.abs(y - b[1]) < 12)) return;
      placed.push([x, y, w]);
      g.fillStyle = LABEL;
      g.fillText(text, x, y);
    };
    const front = cs.filter((p) => p.c.pareto).sort((a, b) => a.x - b.x);
    g.strokeStyle = "#f0f0f0";
    g.lineWidth = 1.5;
    g.beginPath();
    front.forEach((p, i) => (i ? g.lineTo(X(p.x), Y(p.y)) : g.moveTo(X(p.x), Y(p.y))));
    g.stroke();
    g.lineWidth = 1;
    const isChosen = (p) =>
      !!chosen && (p.c.specular || null) === (chosen.specular || null) && (p.c.diffuse || null) === (chosen.diffuse || null);
    for (const p of cs) {
      g.fillStyle = p.c.pareto ? "#f0f0f0" : "#70747e";
      g.beginPath();
      g.arc(X(p.x), Y(p.y), p.c.pareto ? 4 : 3, 0, 2 * Math.PI);
      g.fill();
      if (isChosen(p)) {
        g.strokeStyle = SLOT_COLOURS[0];
        g.lineWidth = 2;
        g.beginPath();
        g.arc(X(p.x), Y(p.y), 8, 0, 2 * Math.PI);
        g.stroke();
        g.lineWidth = 1;
      }
    }
    /* the choice's label first, then the front's from the cheapest */
    for (const p of cs.filter(isChosen).concat(front)) labelOnce(p.name, X(p.x) + 8, Y(p.y) - 5);
  }

  /* ---- start -------------------------------------------------------------------------------- */
  function fillModelSelects() {
    for (const id of ["model-a", "model-b"]) {
      const sel = $(id);
      for (const m of models) {
        const o = document.createElement("option");
        o.value = m.name;
        o.textContent = m.name;
        o.title = m.title || "";
        /* a model that evaluates a caller's measured table has nothing to show here */
        if ((m.needs || []).indexOf("table") >= 0) {
          o.disabled = true;
          o.textContent = m.name + " (needs a measured table)";
        }
        sel.appendChild(o);
      }
    }
    const mat = $("material");
    for (const m of api.materials()) {
      const o = document.createElement("option");
      o.value = m.name;
      o.textContent = m.name + " (" + m.surface + ")";
      mat.appendChild(o);
    }
  }

  function wire() {
    $("model-a").addEventListener("change", (e) => setSlotModel(0, e.target.value, {}));
    $("model-b").addEventListener("change", (e) => setSlotModel(1, e.target.value, {}));
    $("material").addEventListener("change", chooseMaterial);
    $("goal").addEventListener("change", (e) => {
      state.goal = e.target.value;
      if (state.material) chooseMaterial();
    });
    $("theta-i").addEventListener("input", (e) => setLight(+e.target.value, state.light.phi));
    $("exposure").addEventListener("input", (e) => {
      state.exposure = +e.target.value;
      $("exposure-out").textContent = (state.exposure > 0 ? "+" : "") + state.exposure + " EV";
      redrawSpheres();
    });
    $("use-cos").addEventListener("change", (e) => {
      state.useCos = e.target.checked;
      drawPolar();
      drawCartesian();
      drawLobe3d();
    });
    $("log-plot").addEventListener("change", (e) => {
      state.logPlot = e.target.checked;
      drawCartesian();
    });
    dragLight($("light"), (c) => c.width / 2 - 8);
    dragLight($("sphere-a"), (c) => c.width / 2);
    dragLight($("sphere-b"), (c) => c.width / 2);
    dragRotate($("lobe3d"));
    $("advise-run").addEventListener("click", runAdvisor);
  }

  function start() {
    if (typeof AbrdfApi === "undefined") {
      setStatus("abrdf_api.js did not load: serve this page from the build's web/ folder", true);
      readyReject(new Error("AbrdfApi missing"));
      return;
    }
    /* The sphere worker loads its own module meanwhile; the advisor's starts at its first use,
     * so that three module loads do not compete for the first sphere. */
    worker = new Worker("worker.js");
    worker.onmessage = onWorker;
    worker.onerror = (e) => setStatus("worker.js: " + e.message, true);
    AbrdfApi.load().then(
      (a) => {
        api = a;
        window.explorer.api = a;
        timings.loadMs = performance.now() - tStart;
        $("version").textContent = "libabrdf " + api.version();
        models = api.models();
        for (const m of models) byName[m.name] = m;
        mask = api.mask(SIZE);
        fillModelSelects();
        wire();
        setStatus("rendering\u2026");
        const first = byName[state.models[0]] ? state.models[0] : models[0].name;
        setSlotModel(0, first, {});
        buildParams(1);
        setLight(state.light.theta, state.light.phi);
        drawPareto(null);
      },
      (err) => {
        setStatus("the wasm module did not load: " + err, true);
        readyReject(err);
      }
    );
  }
  start();
})();
