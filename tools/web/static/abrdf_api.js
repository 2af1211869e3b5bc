/* abrdf_api.js - libabrdf in the browser: the JavaScript face of the WebAssembly module
 * (tools/web/abrdf_web.c, built into abrdf_wasm.js + abrdf_wasm.wasm). A classic script, so
 * the page loads it with <script> and a worker with importScripts('abrdf_wasm.js',
 * 'abrdf_api.js'). It defines one global, AbrdfApi:
 *
 *   AbrdfApi.load() -> Promise<Abrdf>   one module instance; every call on it is synchronous
 *
 * Abrdf: version(), models(), materials(), classes(), setModel(slot, model, params[, diffuse]),
 * evalPairs(slot, wi, wo), plane(slot, thetaIDeg, count), hemisphere(slot, thetaIDeg, phiIDeg,
 * nTheta, nPhi), sphereRows(slot, size, light, y0, y1, step), mask(size), nmse(img, ref),
 * select(material, goal), budget(material, maxNmseOrClass), pareto(material).
 * docs/EXPLORER.md describes each; the conventions are libabrdf's (abrdf.h): wi toward the
 * light, wo toward the viewer, f_r without the cosine, local frame with the normal +z. */
(function (root) {
  'use strict';

  // Table 8 of the paper: the largest NMSE of each visibility class.
  const CLASSES = [
    { name: 'none', max: 1e-4 },
    { name: 'slight', max: 2.5e-4 },
    { name: 'noticeable', max: 1e-3 },
    { name: 'significant', max: Infinity },
  ];

  class Abrdf {
    constructor(mod) {
      this.m = mod;
      this._models = JSON.parse(this._text(mod._aw_models()));
      this._byName = new Map(this._models.map((m) => [m.name, m]));
    }

    // ---- memory helpers ----
    _text(ptr) {
      if (!ptr) throw new Error(this._error());
      return this.m.UTF8ToString(ptr);
    }
    _error() {
      return this.m.UTF8ToString(this.m._aw_error());
    }
    _str(s) {
      const n = this.m.lengthBytesUTF8(s) + 1;
      const p = this.m._malloc(n);
      this.m.stringToUTF8(s, p, n);
      return p;
    }
    _withStr(strings, fn) {
      const ptrs = strings.map((s) => this._str(String(s)));
      try {
        return fn(...ptrs);
      } finally {
        ptrs.forEach((p) => this.m._free(p));
      }
    }
    _floats(n) {
      return this.m._malloc(4 * Math.max(1, n));
    }
    _readF32(p, n) {
      return new Float32Array(this.m.HEAPF32.buffer, p, n).slice();
    }

    // ---- the registry and the material table ----
    version() {
      return this.m.UTF8ToString(this.m._aw_version());
    }
    models() {
      return this._models;
    }
    model(name) {
      return this._byName.get(name) || null;
    }
    materials() {
      if (!this._materials) this._materials = JSON.parse(this._text(this.m._aw_materials()));
      return this._materials;
    }
    classes() {
      return CLASSES.map((c) => Object.assign({}, c));
    }
    classOf(nmse) {
      if (!(nmse >= 0)) return 'undefined';
      for (const c of CLASSES) if (nmse < c.max) return c.name;
      return 'significant';
    }

    // ---- a model in a slot ----
    // params: {r: 0.3, kd: [0.5, 0.5, 0.5], ...}; values must be finite numbers. diffuse
    // (optional): a diffuse lobe reading the same parameters, whose f_r is added (a material's
    // diffuse + specular choice, as abrdf_shade evaluates it).
    setModel(slot, model, params, diffuse) {
      const parts = [];
      for (const [k, v] of Object.entries(params || {})) {
        const vals = Array.isArray(v) ? v : [v];
        for (const x of vals) {
          if (typeof x !== 'number' || !Number.isFinite(x))
            return { ok: false, param: k, message: `${k}: '${x}' is not a finite number` };
        }
        parts.push(`${k}=${vals.join(',')}`);
      }
      const rc = this._withStr([diffuse || '', model, parts.join(';')], (pd, pm, ps) =>
        this.m._aw_set_pair(slot, pd, pm, ps));
      if (rc === 0) return { ok: true };
      const param = this.m.UTF8ToString(this.m._aw_error_param());
      return { ok: false, param: param || null, message: this._error() };
    }

    evalPairs(slot, wi, wo) {
      const count = Math.floor(Math.min(wi.length, wo.length) / 3);
      const pi = this._floats(3 * count), po = this._floats(3 * count),
            pf = this._floats(3 * count);
      try {
        this.m.HEAPF32.set(wi.subarray(0, 3 * count), pi >> 2);
        this.m.HEAPF32.set(wo.subarray(0, 3 * count), po >> 2);
        if (this.m._aw_eval(slot, pi, po, count, pf) !== 0) throw new Error(this._error());
        return this._readF32(pf, 3 * count);
      } finally {
        [pi, po, pf].forEach((p) => this.m._free(p));
      }
    }

    plane(slot, thetaIDeg, count) {
      const pt = this.m._malloc(8 * count), pf = this._floats(3 * count);
      try {
        if (this.m._aw_plane(slot, thetaIDeg, count, pt, pf) !== 0)
          throw new Error(this._error() || 'plane: bad arguments');
        const thetaO = new Float64Array(this.m.HEAPF64.buffer, pt, count).slice();
        return { thetaO, f: this._readF32(pf, 3 * count) };
      } finally {
        this.m._free(pt);
        this.m._free(pf);
      }
    }

    hemisphere(slot, thetaIDeg, phiIDeg, nTheta, nPhi) {
      const n = 3 * nTheta * nPhi, pf = this._floats(n);
      try {
        if (this.m._aw_hemisphere(slot, thetaIDeg, phiIDeg, nTheta, nPhi, pf) !== 0)
          throw new Error(this._error() || 'hemisphere: bad arguments');
        return this._readF32(pf, n);
      } finally {
        this.m._free(pf);
      }
    }

    sphereRows(slot, size, light, y0, y1, step) {
      const n = 3 * size * (y1 - y0), pf = this._floats(n);
      try {
        if (this.m._aw_sphere_rows(slot, size, light[0], light[1], light[2], y0, y1, step, pf) !== 0)
          throw new Error(this._error() || 'sphereRows: bad arguments');
        return this._readF32(pf, n);
      } finally {
        this.m._free(pf);
      }
    }

    mask(size) {
      const p = this.m._malloc(size * size);
      try {
        this.m._aw_mask(size, p);
        return new Uint8Array(this.m.HEAPU8.buffer, p, size * size).slice();
      } finally {
        this.m._free(p);
      }
    }

    nmse(img, ref) {
      const n = Math.min(img.length, ref.length);
      const pa = this._floats(n), pb = this._floats(n);
      try {
        this.m.HEAPF32.set(img.subarray(0, n), pa >> 2);
        this.m.HEAPF32.set(ref.subarray(0, n), pb >> 2);
        const v = this.m._aw_nmse(pa, pb, n);
        return { nmse: v, cls: this.m.UTF8ToString(this.m._aw_nmse_class(v)) };
      } finally {
        this.m._free(pa);
        this.m._free(pb);
      }
    }

    // ---- the selection ----
    // material: a table name ("gold"), or {base: "gold", r: 0.1, ...}, or explicit values
    // {type: "general", n: 300, kd: [..], ks: [..], f0: [..], eta, anisotropy, melanin,
    // redness} ("surface" is taken for "type").
    _materialSpec(material) {
      if (typeof material === 'string') return `name=${material}`;
      const parts = [];
      const m = Object.assign({}, material);
      if (m.base !== undefined) parts.push(`name=${m.base}`);
      else if (m.name !== undefined && m.type === undefined && m.surface === undefined)
        parts.push(`name=${m.name}`);
      if (m.surface !== undefined && m.type === undefined) m.type = m.surface;
      for (const k of ['type', 'n', 'r', 'kd', 'ks', 'f0', 'eta', 'anisotropy', 'melanin',
                       'redness']) {
        if (m[k] === undefined || m[k] === null) continue;
        parts.push(`${k}=${Array.isArray(m[k]) ? m[k].join(',') : m[k]}`);
      }
      return parts.join(';');
    }
    _call(fn) {
      try {
        return Object.assign({ ok: true }, JSON.parse(this._text(fn())));
      } catch (e) {
        const param = this.m.UTF8ToString(this.m._aw_error_param());
        return { ok: false, param: param || null, message: e.message };
      }
    }
    select(material, goal) {
      return this._withStr([this._materialSpec(material), goal || 'photoreal'], (pm, pg) =>
        this._call(() => this.m._aw_select(pm, pg)));
    }
    budget(material, maxNmseOrClass) {
      let max = maxNmseOrClass;
      if (typeof max === 'string') {
        const c = CLASSES.find((x) => x.name === max && Number.isFinite(x.max));
        max = c ? c.max : Number(max);
      }
      if (!(max > 0 && max <= 1))
        return { ok: false, param: 'budget', message:
                 `budget '${maxNmseOrClass}': none, slight, noticeable or a number in (0, 1]` };
      return this._withStr([this._materialSpec(material)], (pm) =>
        this._call(() => this.m._aw_budget(pm, max, 0)));
    }
    pareto(material) {
      return this._withStr([this._materialSpec(material)], (pm) =>
        this._call(() => this.m._aw_budget(pm, 1, 1)));
    }
    free() {}
  }

  const AbrdfApi = {
    load(options) {
      return root.createAbrdfModule(options || {}).then((mod) => new Abrdf(mod));
    },
    Abrdf,
  };
  root.AbrdfApi = AbrdfApi;
})(typeof self !== 'undefined' ? self : this);
