// shadelab's live lab: the lesson's controls, re-rendered by the WebAssembly renderer while
// they move (a reduced preview), at full size when they are let go. Written by `shadelab site`;
// needs live/shadelab_wasm_bg.js (the module as base64), live/shadelab_wasm.js (wasm-bindgen's
// glue) and <lesson>/live.js (SHADELAB_LESSON) before it. No network: everything is beside
// the page, so it works from file:// too.
(function () {
  "use strict";
  const L = window.SHADELAB_LESSON;
  const root = document.getElementById("live-lab");
  if (!L || !root || !window.SHADELAB_WASM || typeof wasm_bindgen !== "function") return;
  // The page's words (in its language), with {holes}.
  const say = (name, holes) => (root.dataset[name] || "").replace(/\{(\w+)\}/g, (_, k) => (holes || {})[k]);
  const $ = (id) => document.getElementById(id);

  const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  const quote = (s) => (/^[\w.=,\-\/#+:\[\]]+$/.test(s) ? s : "'" + s.replace(/'/g, "'\\''") + "'");
  const round = (v) => Number(Number(v).toPrecision(4));
  const toSrgb = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
  const hex = (rgb) => "#" + rgb.map((c) => Math.round(Math.min(1, Math.max(0, toSrgb(c))) * 255).toString(16).padStart(2, "0")).join("");

  // Where the light comes from, as (azimuth, elevation) in degrees, for a travel direction d.
  function azEl(d) {
    const n = Math.hypot(d[0], d[1], d[2]) || 1;
    const f = [-d[0] / n, -d[1] / n, -d[2] / n];
    return [(Math.atan2(f[0], f[2]) * 180) / Math.PI, (Math.asin(Math.max(-1, Math.min(1, f[1]))) * 180) / Math.PI];
  }
  function travel(az, el) {
    const a = (az * Math.PI) / 180, e = (el * Math.PI) / 180;
    return [-Math.cos(e) * Math.sin(a), -Math.sin(e), -Math.cos(e) * Math.cos(a)].map((x) => Number(x.toFixed(4)));
  }

  // Each control: its element(s), its `--set` value now, and its value as the lesson gives it.
  const controls = [];
  const form = $("live-controls");
  function row(label, input, shown) {
    const l = document.createElement("label");
    const k = document.createElement("code");
    k.textContent = label;
    l.append(k, input, shown);
    form.append(l);
  }
  for (const c of L.controls) {
    const out = document.createElement("output");
    if (c.kind === "number") {
      const s = document.createElement("input");
      s.type = "range";
      s.min = 0;
      s.max = 1000;
      s.dataset.key = c.key;
      const lo = c.log ? Math.log(c.min) : c.min, hi = c.log ? Math.log(c.max) : c.max;
      const toValue = (t) => {
        const x = lo + ((hi - lo) * t) / 1000;
        const v = c.log ? Math.exp(x) : x;
        return c.integer ? Math.round(v) : round(v);
      };
      const toPos = (v) => Math.round(((c.log ? Math.log(Math.max(v, c.min)) : v) - lo) / (hi - lo || 1) * 1000);
      const ctl = { key: c.key, initial: String(c.value), value: String(c.value) };
      ctl.read = () => (ctl.value = String(toValue(Number(s.value))));
      ctl.reset = () => { s.value = toPos(c.value); ctl.value = ctl.initial; out.textContent = ctl.value; };
      s.addEventListener("input", () => { out.textContent = ctl.read(); schedule(true); });
      s.addEventListener("change", () => { ctl.read(); schedule(false); });
      ctl.reset();
      controls.push(ctl);
      row(c.label, s, out);
    } else if (c.kind === "colour") {
      const p = document.createElement("input");
      p.type = "color";
      p.dataset.key = c.key;
      const ctl = { key: c.key, initial: hex(c.value), value: hex(c.value) };
      ctl.reset = () => { p.value = ctl.initial; ctl.value = ctl.initial; out.textContent = ctl.value; };
      p.addEventListener("input", () => { ctl.value = p.value; out.textContent = p.value; schedule(true); });
      p.addEventListener("change", () => { ctl.value = p.value; schedule(false); });
      ctl.reset();
      controls.push(ctl);
      row(c.label, p, out);
    } else if (c.kind === "direction") {
      const [az0, el0] = azEl(c.value);
      const box = document.createElement("span");
      const az = document.createElement("input"), el = document.createElement("input");
      Object.assign(az, { type: "range", min: -180, max: 180, step: 1 });
      Object.assign(el, { type: "range", min: -89, max: 89, step: 1 });
      az.dataset.key = c.key + "#azimuth";
      el.dataset.key = c.key + "#elevation";
      az.title = say("tAz");
      el.title = say("tEl");
      box.append(az, el);
      const initial = "[" + c.value.map(round).join(", ") + "]";
      const ctl = { key: c.key, initial, value: initial };
      const read = () => { ctl.value = "[" + travel(Number(az.value), Number(el.value)).join(", ") + "]"; out.textContent = az.value + "°, " + el.value + "°"; };
      ctl.reset = () => { az.value = Math.round(az0); el.value = Math.round(el0); ctl.value = initial; out.textContent = az.value + "°, " + el.value + "°"; };
      for (const s of [az, el]) {
        s.addEventListener("input", () => { read(); schedule(true); });
        s.addEventListener("change", () => { read(); schedule(false); });
      }
      ctl.reset();
      controls.push(ctl);
      row(c.label + say("tAzel"), box, out);
    } else if (c.kind === "choice") {
      const m = document.createElement("select");
      m.dataset.key = c.key;
      for (const n of c.names) m.append(new Option(n, n));
      const ctl = { key: c.key, initial: String(c.value), value: String(c.value) };
      ctl.reset = () => { m.value = ctl.initial; ctl.value = ctl.initial; };
      m.addEventListener("change", () => { ctl.value = m.value; schedule(false); });
      ctl.reset();
      controls.push(ctl);
      row(c.label, m, out);
    }
  }

  // The `--set` arguments that differ from the lesson, in the controls' order.
  const changed = () => controls.filter((c) => c.value !== c.initial).map((c) => c.key + "=" + c.value);

  function cliLine() {
    const sets = L.sets.concat(changed());
    $("live-cli").textContent = ["shadelab render", L.path].concat(sets.map((s) => "--set " + quote(s))).join(" ");
  }

  const views = ["live-total", "live-ambient", "live-diffuse", "live-specular"].map($);
  const lab = (window.shadelabLab = { renders: 0, errors: 0, lastMs: 0, busy: false, frame: null });

  function draw(frame, preview) {
    const [W, H] = L.size;
    views.forEach((canvas, i) => {
      const px = frame.layer(i);
      const shown = px.length > 0;
      (i === 0 ? canvas : canvas.parentElement).hidden = !shown;
      if (!shown) return;
      canvas.width = W;
      canvas.height = H;
      const img = new ImageData(new Uint8ClampedArray(px.buffer, px.byteOffset, px.length), frame.width, frame.height);
      const ctx = canvas.getContext("2d");
      if (frame.width === W && frame.height === H) {
        ctx.putImageData(img, 0, 0);
      } else {
        // A preview: drawn smaller, scaled up to the full frame.
        const off = document.createElement("canvas");
        off.width = frame.width;
        off.height = frame.height;
        off.getContext("2d").putImageData(img, 0, 0);
        ctx.imageSmoothingEnabled = true;
        ctx.drawImage(off, 0, 0, W, H);
      }
    });
    lab.frame = { width: frame.width, height: frame.height, preview };
  }

  function render(preview) {
    const [W, H] = L.size;
    const sets = L.sets.concat(changed());
    if (preview) {
      sets.push("camera.size=[" + Math.max(16, Math.round(W / 2)) + ", " + Math.max(16, Math.round(H / 2)) + "]", "render.aa=1");
      if (L.method === "path") sets.push("render.spp=1");
    }
    const t0 = performance.now();
    let frame;
    try {
      frame = wasm_bindgen.render(L.path, L.text, sets);
    } catch (e) {
      lab.errors += 1;
      $("live-error").hidden = false;
      $("live-error").textContent = String(e);
      return;
    }
    const ms = performance.now() - t0;
    $("live-error").hidden = true;
    draw(frame, preview);
    const size = frame.width + "×" + frame.height;
    $("live-status").textContent = say(preview ? "tPreview" : "tFull", { size, ms: ms.toFixed(1) });
    if (frame.nan_samples > 0) $("live-status").textContent += say("tNan", { n: frame.nan_samples });
    frame.free();
    lab.lastMs = ms;
    lab.renders += 1;
    cliLine();
  }

  // One render per animation frame, the last asked for: a drag does not queue renders.
  let pending = null;
  function schedule(preview) {
    const first = pending === null;
    pending = preview && pending === false ? false : preview;
    if (!first) return;
    lab.busy = true;
    requestAnimationFrame(() => {
      const p = pending;
      pending = null;
      render(p);
      lab.busy = pending !== null;
    });
  }

  $("live-reset").addEventListener("click", () => { controls.forEach((c) => c.reset()); schedule(false); });
  $("live-copy").addEventListener("click", () => {
    const text = $("live-cli").textContent;
    if (navigator.clipboard) navigator.clipboard.writeText(text).catch(() => {});
  });

  lab.ready = wasm_bindgen({ module_or_path: bytes(window.SHADELAB_WASM) }).then(() => {
    for (const [path, b64] of Object.entries(L.files)) wasm_bindgen.provide_file(path, bytes(b64));
    root.hidden = false;
    render(false);
  });
})();
