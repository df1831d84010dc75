/* val3check HTML report: shared helpers and the time window that every time chart follows.
   Written for val3check; plain DOM and SVG, no library. */
"use strict";
var V3 = (function () {
  const V3 = {};
  const SVGNS = "http://www.w3.org/2000/svg";
  V3.data = JSON.parse(document.getElementById("v3-data").textContent);

  // ---- decoding the packed arrays (pack.py): base64 of little-endian float32 / float64 ----
  function bytes(b64) {
    const bin = atob(b64);
    const u8 = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) u8[i] = bin.charCodeAt(i);
    return u8;
  }
  const LITTLE = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;
  function decode(b64, size) {
    const u8 = bytes(b64);
    const n = u8.length / size;
    if (LITTLE) return size === 4 ? new Float32Array(u8.buffer) : new Float64Array(u8.buffer);
    const dv = new DataView(u8.buffer);
    const out = size === 4 ? new Float32Array(n) : new Float64Array(n);
    for (let i = 0; i < n; i++) out[i] = size === 4 ? dv.getFloat32(4 * i, true) : dv.getFloat64(8 * i, true);
    return out;
  }
  V3.f32 = (s) => decode(s, 4);
  V3.f64 = (s) => decode(s, 8);
  /* a packed series: {v} at full rate, {lo, hi} per bucket when decimated */
  V3.series = function (s) {
    if (!s) return null;
    if (s.v !== undefined) { const v = V3.f32(s.v); return { lo: v, hi: v }; }
    return { lo: V3.f32(s.lo), hi: V3.f32(s.hi) };
  };

  // ---- colours: Okabe-Ito ----
  V3.palette = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"];
  V3.stateStyle = {
    running: { fill: "#0072B2", label: "running" },
    waiting: { fill: "#56B4E9", label: "waiting (delay, wait, period)" },
    blocked: { fill: "#D55E00", label: "blocked (waitEndMove, mutex, key, serial)", hatch: true },
    stopped: { fill: "#6b6b6b", label: "stopped (error, suspended)", hatch: true },
    moving: { fill: "#E69F00", label: "arm moving" },
    idle: { fill: "#e4e6ea", label: "arm idle" },
    low: { fill: "none", label: "false" },
    high: { fill: "#009E73", label: "true" },
  };
  V3.sevStyle = { error: "#D55E00", warning: "#E69F00", info: "#0072B2" };

  // ---- DOM ----
  V3.el = function (tag, attrs, parent, text) {
    const e = document.createElement(tag);
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  };
  V3.svg = function (tag, attrs, parent, text) {
    const e = document.createElementNS(SVGNS, tag);
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  };
  let uid = 0;
  V3.uid = (p) => "v3" + p + (++uid);

  V3.fmtTime = (t) => (t === null || t === undefined || !isFinite(t)) ? "–" : t.toFixed(3) + " s";
  /* a tick label: as many decimals as the tick step needs */
  V3.fmtTick = function (v, step) {
    const d = Math.max(0, Math.min(6, Math.ceil(-Math.log10(step) - 1e-9) + (Math.abs(step / Math.pow(10, Math.floor(Math.log10(step))) - 2.5) < 1e-9 ? 1 : 0)));
    return v.toFixed(d);
  };
  V3.fmtNum = function (v, span) {
    if (!isFinite(v)) return "–";
    const d = span >= 100 ? 0 : span >= 10 ? 1 : span >= 1 ? 2 : 3;
    return v.toFixed(d);
  };

  /* round tick values: 1, 2, 5 x 10^k */
  V3.ticks = function (min, max, count) {
    if (!(max > min)) return [min];
    const raw = (max - min) / Math.max(1, count);
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * p).find((s) => s >= raw) || 10 * p;
    const out = [];
    for (let k = Math.ceil(min / step - 1e-9); k * step <= max + step * 1e-9; k++) out.push(k === 0 ? 0 : k * step);
    out.step = step;
    return out;
  };

  /* first index i with arr[i] >= x */
  V3.lowerBound = function (arr, x) {
    let lo = 0, hi = arr.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (arr[mid] < x) lo = mid + 1; else hi = mid; }
    return lo;
  };

  // ---- the shared time window and the cursor (the 3D view's time) ----
  const duration = Math.max(V3.data.duration || 0, 1e-3);
  const MIN_SPAN = Math.min(0.02, duration);
  const listeners = { window: [], cursor: [] };
  let pending = false;
  const tw = { t0: 0, t1: duration, a: 0, b: duration, cursor: null };
  function notify() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; listeners.window.forEach((f) => f(tw)); });
  }
  tw.on = (what, f) => listeners[what].push(f);
  tw.set = function (a, b) {
    let span = Math.max(b - a, MIN_SPAN);
    span = Math.min(span, tw.t1 - tw.t0);
    a = Math.min(Math.max(a, tw.t0), tw.t1 - span);
    tw.a = a; tw.b = a + span;
    notify();
  };
  tw.zoom = function (factor, center) {
    const c = center === undefined ? (tw.cursor !== null && tw.cursor >= tw.a && tw.cursor <= tw.b ? tw.cursor : (tw.a + tw.b) / 2) : center;
    tw.set(c - (c - tw.a) * factor, c + (tw.b - c) * factor);
  };
  tw.pan = function (frac) { const d = (tw.b - tw.a) * frac; tw.set(tw.a + d, tw.b + d); };
  tw.reset = function () { tw.set(tw.t0, tw.t1); };
  tw.show = function (start, end) {
    if (end === undefined || end === null || !(end > start)) {
      const span = Math.min(tw.b - tw.a, Math.max(2, (tw.t1 - tw.t0) / 20));
      tw.set(start - span / 2, start + span / 2);
    } else {
      const pad = (end - start) * 0.1;
      tw.set(start - pad, end + pad);
    }
    tw.setCursor(start);
  };
  tw.setCursor = function (t) {
    tw.cursor = Math.min(Math.max(t, tw.t0), tw.t1);
    listeners.cursor.forEach((f) => f(tw.cursor));
  };
  V3.time = tw;

  // ---- one tooltip for the page ----
  let tip = null;
  V3.tip = function (text, x, y) {
    if (!tip) tip = V3.el("div", { class: "tip", "aria-hidden": "true" }, document.body);
    if (text === null) { tip.style.display = "none"; return; }
    tip.textContent = text;
    tip.style.display = "block";
    const w = tip.offsetWidth, h = tip.offsetHeight;
    tip.style.left = Math.min(x + 14, window.innerWidth - w - 8) + "px";
    tip.style.top = Math.max(y - h - 10, 8) + "px";
  };

  /* Mouse, wheel and keyboard on a time chart (plots, lanes). `area()` gives the plot area
     {x0, x1, y0, y1} in the SVG's own units; `hover(t, event)` gets the time under the pointer
     (null when it leaves). Drag: zoom on the range; click: set the cursor; double-click: the
     whole run; Ctrl+wheel: zoom; Shift+wheel or a sideways wheel: pan. */
  V3.timeInteraction = function (svg, area, sel, hover) {
    const tw = V3.time;
    function toX(ev) {
      const r = svg.getBoundingClientRect();
      const vb = svg.viewBox.baseVal;
      return (ev.clientX - r.left) * (vb && vb.width ? vb.width / r.width : 1);
    }
    function toT(x) { const g = area(); return tw.a + (x - g.x0) / (g.x1 - g.x0) * (tw.b - tw.a); }
    let drag = null;
    svg.addEventListener("pointerdown", (ev) => {
      if (ev.button !== 0) return;
      const g = area(), x = toX(ev);
      if (x < g.x0 || x > g.x1) return;
      drag = { x: x, moved: false };
      svg.setPointerCapture(ev.pointerId);
    });
    svg.addEventListener("pointermove", (ev) => {
      const g = area(), x = toX(ev);
      const s = typeof sel === "function" ? sel() : sel;
      if (drag) {
        if (Math.abs(x - drag.x) > 4) drag.moved = true;
        if (drag.moved && s) {
          const lo = Math.max(g.x0, Math.min(x, drag.x)), hi = Math.min(g.x1, Math.max(x, drag.x));
          s.setAttribute("x", lo); s.setAttribute("width", hi - lo);
          s.setAttribute("y", g.y0); s.setAttribute("height", g.y1 - g.y0);
          s.setAttribute("visibility", "visible");
        }
      }
      if (hover) hover(x >= g.x0 && x <= g.x1 ? toT(x) : null, ev);
    });
    svg.addEventListener("pointerleave", () => { if (hover) hover(null); });
    svg.addEventListener("pointerup", (ev) => {
      if (!drag) return;
      const x = toX(ev), g = area();
      const s = typeof sel === "function" ? sel() : sel;
      if (s) s.setAttribute("visibility", "hidden");
      if (drag.moved) {
        const a = toT(Math.max(g.x0, Math.min(x, drag.x))), b = toT(Math.min(g.x1, Math.max(x, drag.x)));
        if (b > a) tw.set(a, b);
      } else {
        tw.setCursor(toT(Math.max(g.x0, Math.min(x, g.x1))));
      }
      drag = null;
    });
    svg.addEventListener("dblclick", () => tw.reset());
    svg.addEventListener("wheel", (ev) => {
      const sideways = Math.abs(ev.deltaX) > Math.abs(ev.deltaY);
      if (ev.ctrlKey || ev.metaKey) {
        ev.preventDefault();
        tw.zoom(ev.deltaY > 0 ? 1.25 : 0.8, toT(toX(ev)));
      } else if (ev.shiftKey || sideways) {
        ev.preventDefault();
        const d = sideways ? ev.deltaX : ev.deltaY;
        tw.pan(d > 0 ? 0.1 : -0.1);
      }
    }, { passive: false });
    svg.addEventListener("keydown", (ev) => {
      const k = ev.key;
      if (k === "ArrowLeft") tw.pan(-0.1);
      else if (k === "ArrowRight") tw.pan(0.1);
      else if (k === "+" || k === "=") tw.zoom(0.5);
      else if (k === "-" || k === "_") tw.zoom(2);
      else if (k === "0" || k === "Home") tw.reset();
      else return;
      ev.preventDefault();
    });
  };

  /* Re-render a chart when its container changes width (the window, printing). */
  V3.onResize = function (elem, f) {
    let last = elem.clientWidth;
    const ro = new ResizeObserver(() => {
      const w = elem.clientWidth;
      if (w !== last && w > 0) { last = w; f(); }
    });
    ro.observe(elem);
  };

  /* a legend as an HTML list: [{label, fill, dash, hatch}] */
  V3.legend = function (parent, items) {
    const ul = V3.el("ul", { class: "legend" }, parent);
    items.forEach((it) => {
      const li = V3.el("li", {}, ul);
      if (it.text) { li.textContent = it.label; return; }
      const sw = V3.el("span", { class: "sw", "aria-hidden": "true" }, li);
      if (it.line) {
        sw.style.border = "none";
        sw.style.borderTop = "2px " + (it.dash ? "dashed " : "solid ") + it.line;
        sw.style.height = "0";
        sw.style.verticalAlign = "0.3em";
      } else {
        sw.style.background = it.hatch
          ? "repeating-linear-gradient(45deg, " + it.fill + " 0 3px, #fff 3px 5px)" : it.fill;
      }
      li.appendChild(document.createTextNode(it.label));
    });
    return ul;
  };

  return V3;
})();
