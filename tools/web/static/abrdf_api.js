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
      const p = this._alloc(n, 1);
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
    // Module memory for n values of `bytes` each; sizes the 32-bit module cannot address, and
    // a failed allocation, throw rather than wrap around.
    _alloc(n, bytes) {
      const size = bytes * Math.max(1, n);
      if (!Number.isSafeInteger(size) || size < 0 || size >= 2 ** 31)
        throw new Error(`${n} values do not fit in the module's memory`);
      const p = this.m._malloc(size);
      if (!p) throw new Error(`out of memory for ${n} values`);
      return p;
    }
    _floats(n) {
      return this._alloc(n, 4);
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

    // Calls fn(pointers...) with blocks of [count, bytes] each, freed afterwards whatever
    // happens (an allocation that fails frees the ones before it).
    _blocks(sizes, fn) {
      const ptrs = [];
      try {
        for (const [n, bytes] of sizes) ptrs.push(this._alloc(n, bytes));
        return fn(...ptrs);
      } finally {
        ptrs.forEach((p) => this.m._free(p));
      }
    }
    _whole(what, v) {
      if (!Number.isInteger(v)) throw new Error(`${what} ${v} is not a whole number`);
      return v;
    }

    evalPairs(slot, wi, wo) {
      const count = Math.floor(Math.min(wi.length, wo.length) / 3);
      return this._blocks([[3 * count, 4], [3 * count, 4], [3 * count, 4]], (pi, po, pf) => {
        this.m.HEAPF32.set(wi.subarray(0, 3 * count), pi >> 2);
        this.m.HEAPF32.set(wo.subarray(0, 3 * count), po >> 2);
        if (this.m._aw_eval(slot, pi, po, count, pf) !== 0) throw new Error(this._error());
        return this._readF32(pf, 3 * count);
      });
    }

    plane(slot, thetaIDeg, count) {
      this._whole('plane: count', count);
      return this._blocks([[count, 8], [3 * count, 4]], (pt, pf) => {
        if (this.m._aw_plane(slot, thetaIDeg, count, pt, pf) !== 0) throw new Error(this._error());
        const thetaO = new Float64Array(this.m.HEAPF64.buffer, pt, count).slice();
        return { thetaO, f: this._readF32(pf, 3 * count) };
      });
    }

    hemisphere(slot, thetaIDeg, phiIDeg, nTheta, nPhi) {
      this._whole('hemisphere: nTheta', nTheta);
      this._whole('hemisphere: nPhi', nPhi);
      if (nTheta < 1 || nPhi < 1 || nTheta * nPhi > 1 << 20)
        throw new Error(`hemisphere: a ${nTheta} x ${nPhi} grid is outside 1 to 1024 per side ` +
                        `and ${1 << 20} views`);
      const n = 3 * nTheta * nPhi;
      return this._blocks([[n, 4]], (pf) => {
        if (this.m._aw_hemisphere(slot, thetaIDeg, phiIDeg, nTheta, nPhi, pf) !== 0)
          throw new Error(this._error());
        return this._readF32(pf, n);
      });
    }

    sphereRows(slot, size, light, y0, y1, step) {
      for (const [k, v] of Object.entries({ size, y0, y1, step })) this._whole('sphereRows: ' + k, v);
      if (size < 1 || size > 4096) throw new Error(`sphere: size ${size} is outside [1, 4096]`);
      if (y0 < 0 || y1 > size || y0 >= y1)
        throw new Error(`sphere: rows [${y0}, ${y1}) are not within [0, ${size})`);
      const n = 3 * size * (y1 - y0);
      return this._blocks([[n, 4]], (pf) => {
        if (this.m._aw_sphere_rows(slot, size, light[0], light[1], light[2], y0, y1, step, pf) !== 0)
          throw new Error(this._error());
        return this._readF32(pf, n);
      });
    }

    mask(size) {
      this._whole('mask: size', size);
      if (size < 1 || size > 4096) throw new Error(`mask: size ${size} is outside [1, 4096]`);
      return this._blocks([[size * size, 1]], (p) => {
        if (this.m._aw_mask(size, p) !== 0) throw new Error(this._error());
        return new Uint8Array(this.m.HEAPU8.buffer, p, size * size).slice();
      });
    }

    nmse(img, ref) {
      const n = Math.min(img.length, ref.length);
      return this._blocks([[n, 4], [n, 4]], (pa, pb) => {
        this.m.HEAPF32.set(img.subarray(0, n), pa >> 2);
        this.m.HEAPF32.set(ref.subarray(0, n), pb >> 2);
        const v = this.m._aw_nmse(pa, pb, n);
        return { nmse: v, cls: this.m.UTF8ToString(this.m._aw_nmse_class(v)) };
      });
    }

    // ---- the selection ----
    // material: a table name ("gold"), or {base: "gold", r: 0.1, ...}, or explicit values
    // {type: "general", n: 300, kd: [..], ks: [..], f0: [..], eta, anisotropy, melanin,
    // redness} ("surface" is taken for "type").
    // The material as the module's text ("name=gold;r=0.1"), or {error} naming a key the
    // material has not (a misspelt key must not pass unnoticed).
    _materialSpec(material) {
      if (typeof material === 'string') return { spec: `name=${material}` };
      const known = ['base', 'name', 'surface', 'type', 'n', 'r', 'kd', 'ks', 'f0', 'eta',
                     'anisotropy', 'melanin', 'redness'];
      const m = Object.assign({}, material);
      for (const k of Object.keys(m))
        if (!known.includes(k))
          return { error: { ok: false, param: k, message:
                            `unknown material value '${k}' (${known.join(', ')})` } };
      const parts = [];
      if (m.base !== undefined) parts.push(`name=${m.base}`);
      else if (m.name !== undefined && m.type === undefined && m.surface === undefined)
        parts.push(`name=${m.name}`);
      if (m.surface !== undefined && m.type === undefined) m.type = m.surface;
      for (const k of ['type', 'n', 'r', 'kd', 'ks', 'f0', 'eta', 'anisotropy', 'melanin',
                       'redness']) {
        if (m[k] === undefined || m[k] === null) continue;
        parts.push(`${k}=${Array.isArray(m[k]) ? m[k].join(',') : m[k]}`);
      }
      return { spec: parts.join(';') };
    }
    _call(fn) {
      try {
        return Object.assign({ ok: true }, JSON.parse(this._text(fn())));
      } catch (e) {
        const param = this.m.UTF8ToString(this.m._aw_error_param());
        return { ok: false, param: param || null, message: e.message };
      }
    }
    _withMaterial(material, strings, fn) {
      const m = this._materialSpec(material);
      if (m.error) return m.error;
      return this._withStr([m.spec, ...strings], (...ptrs) => this._call(() => fn(...ptrs)));
    }
    select(material, goal) {
      return this._withMaterial(material, [goal || 'photoreal'], (pm, pg) =>
        this.m._aw_select(pm, pg));
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
      return this._withMaterial(material, [], (pm) => this.m._aw_budget(pm, max, 0));
    }
    pareto(material) {
      return this._withMaterial(material, [], (pm) => this.m._aw_budget(pm, 1, 1));
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
