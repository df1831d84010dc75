/* val3check HTML report: lanes over time (tasks and arm Gantt chart, I/O timeline) and the
   bar chart of loop iterations. Lanes follow the shared time window; states are reduced to the
   one that covers most of each pixel column, so thousands of 4 ms segments stay cheap. */
(function (V3) {
  const LABEL = 170, RIGHT = 14, TOP = 6, AXIS = 24;

  function cut(s, n) { return s.length > n ? s.slice(0, n - 1) + "…" : s; }

  class Lanes {
    /* rows: {label, kind, ...}
         kind "states": segs [[t0, t1, state, detail]], states [names], details [texts]
         kind "aio": t [], v [] (a step per event)       kind "sio": t [], v [] (texts), src []
         kind "marks": marks [{t, severity, text}] */
    constructor(parent, rows, describe) {
      this.rows = rows;
      this.wrap = V3.el("div", { class: "lanes" }, parent);
      this.svg = V3.svg("svg", { class: "chart", tabindex: "0", role: "img", "aria-label": describe }, this.wrap);
      rows.forEach((r) => {
        r.h = r.kind === "marks" ? 18 : 20;
        if (r.kind === "states") r.segs.sort((a, b) => a[0] - b[0]);
        if (r.kind === "aio") {
          const vals = r.v.filter((x) => x !== null && isFinite(x));
          r.vmin = vals.length ? Math.min.apply(null, vals) : 0;
          r.vmax = vals.length ? Math.max.apply(null, vals) : 1;
        }
      });
      V3.time.on("window", () => this.render());
      V3.time.on("cursor", (t) => this.moveCursor(t));
      V3.onResize(this.wrap, () => this.render());
      V3.timeInteraction(this.svg, () => this.g, () => this.sel, (t, ev) => this.hover(t, ev));
      this.render();
    }

    render() {
      const svg = this.svg, tw = V3.time;
      const W = Math.max(this.wrap.clientWidth, 360);
      let y = TOP;
      this.rows.forEach((r) => { r.y = y; y += r.h + 4; });
      const H = y + AXIS;
      while (svg.firstChild) svg.removeChild(svg.firstChild);
      svg.setAttribute("viewBox", "0 0 " + W + " " + H);
      const g = this.g = { x0: LABEL, x1: W - RIGHT, y0: TOP, y1: y };
      const sx = (g.x1 - g.x0) / (tw.b - tw.a);
      const X = this.X = (t) => g.x0 + (t - tw.a) * sx;
      const defs = V3.svg("defs", {}, svg);
      const clip = V3.uid("clip");
      V3.svg("rect", { x: g.x0, y: 0, width: g.x1 - g.x0, height: H }, V3.svg("clipPath", { id: clip }, defs));
      const hatches = {};
      Object.keys(V3.stateStyle).forEach((k) => {
        const st = V3.stateStyle[k];
        if (!st.hatch) return;
        const id = hatches[k] = V3.uid("h");
        const p = V3.svg("pattern", { id: id, width: 5, height: 5, patternUnits: "userSpaceOnUse", patternTransform: "rotate(45)" }, defs);
        V3.svg("rect", { width: 5, height: 5, fill: st.fill }, p);
        V3.svg("line", { x1: 0, y1: 0, x2: 0, y2: 5, stroke: "#fff", "stroke-width": 1.6 }, p);
      });
      const stripes = V3.svg("g", {}, svg);
      const grid = V3.svg("g", { class: "grid" }, svg);
      const axis = V3.svg("g", { class: "axis" }, svg);
      const xt = V3.ticks(tw.a, tw.b, Math.max(2, Math.floor((g.x1 - g.x0) / 80)));
      xt.forEach((t) => {
        V3.svg("line", { x1: X(t), x2: X(t), y1: g.y0, y2: g.y1 }, grid);
        V3.svg("text", { x: X(t), y: g.y1 + 14, "text-anchor": "middle" }, axis, V3.fmtTick(t, xt.step));
      });
      V3.svg("text", { x: 6, y: g.y1 + 14 }, axis, "time (s)");
      const body = V3.svg("g", { "clip-path": "url(#" + clip + ")" }, svg);
      const cols = Math.ceil(g.x1 - g.x0);
      this.rows.forEach((r, k) => {
        if (k % 2 === 0) V3.svg("rect", { x: 0, y: r.y - 2, width: W, height: r.h + 4, fill: "#f6f7f9" }, stripes);
        const label = V3.svg("text", { x: 6, y: r.y + r.h / 2 + 4 }, svg, cut(r.label, 26));
        if (r.label.length > 26) V3.svg("title", {}, label, r.label);
        if (r.kind === "states") this.states(r, body, cols, hatches);
        else if (r.kind === "aio") this.analog(r, body, cols);
        else if (r.kind === "sio") this.ticks(r, body, cols);
        else if (r.kind === "marks") this.marks(r, body);
      });
      V3.svg("rect", { class: "frame", x: g.x0, y: g.y0 - 3, width: g.x1 - g.x0, height: g.y1 - g.y0 + 2 }, svg);
      this.cursor = V3.svg("line", { class: "cursor", y1: g.y0, y2: g.y1, visibility: "hidden" }, svg);
      this.sel = V3.svg("rect", { class: "sel", visibility: "hidden" }, svg);
      this.moveCursor(tw.cursor);
    }

    /* the state covering most of each pixel column, drawn as runs of rectangles */
    states(r, body, cols, hatches) {
      const tw = V3.time, ns = r.states.length, x0 = this.g.x0;
      const cov = new Float32Array(cols * ns);
      const segs = r.segs;
      let i = Math.max(0, V3.lowerBound(this.starts(r), tw.a) - 1);
      for (; i < segs.length; i++) {
        const s = segs[i];
        if (s[0] > tw.b) break;
        if (s[1] < tw.a) continue;
        const a = Math.max(0, this.X(s[0]) - x0), b = Math.min(cols, this.X(s[1]) - x0);
        if (b <= a) continue;
        for (let c = Math.floor(a); c < b; c++) cov[c * ns + s[2]] += Math.min(b, c + 1) - Math.max(a, c);
      }
      let run = null;
      const emit = () => {
        if (!run) return;
        const name = r.states[run.s], st = V3.stateStyle[name] || {};
        const y = r.y, h = r.h;
        if (st.fill === "none") {
          V3.svg("rect", { x: x0 + run.c0, y: y + h - 2, width: run.c1 - run.c0, height: 2, fill: "#9aa1ab" }, body);
        } else {
          V3.svg("rect", { x: x0 + run.c0, y: y, width: run.c1 - run.c0, height: h,
            fill: st.hatch ? "url(#" + hatches[name] + ")" : (st.fill || "#999") }, body);
        }
      };
      for (let c = 0; c < cols; c++) {
        let best = -1, bv = 0;
        for (let s = 0; s < ns; s++) if (cov[c * ns + s] > bv) { bv = cov[c * ns + s]; best = s; }
        if (run && run.s === best && run.c1 === c) { run.c1 = c + 1; continue; }
        emit();
        run = best >= 0 ? { s: best, c0: c, c1: c + 1 } : null;
      }
      emit();
    }

    starts(r) {
      if (!r.starts) r.starts = r.segs.map((s) => s[0]);
      return r.starts;
    }

    analog(r, body, cols) {
      const tw = V3.time, n = r.t.length, end = V3.time.t1;
      const span = r.vmax - r.vmin || 1;
      const Y = (v) => r.y + r.h - 2 - (v - r.vmin) / span * (r.h - 4);
      let d = "";
      const i0 = Math.max(0, V3.lowerBound(r.t, tw.a) - 1);
      for (let i = i0; i < n; i++) {
        if (r.t[i] > tw.b) break;
        const v = r.v[i];
        if (v === null) continue;
        const t1 = i + 1 < n ? r.t[i + 1] : end;
        d += (d ? "L" : "M") + this.X(r.t[i]).toFixed(1) + "," + Y(v).toFixed(1) + "H" + this.X(t1).toFixed(1);
      }
      if (d) V3.svg("path", { d: d, fill: "none", stroke: "#CC79A7", "stroke-width": 1.6 }, body);
      V3.svg("text", { x: this.g.x1 - 4, y: r.y + 9, "text-anchor": "end", fill: "#5a6270" }, body,
        V3.fmtNum(r.vmin, span) + " … " + V3.fmtNum(r.vmax, span));
    }

    ticks(r, body, cols) {
      const tw = V3.time, x0 = this.g.x0;
      let last = -1, d = "";
      const i0 = V3.lowerBound(r.t, tw.a);
      for (let i = i0; i < r.t.length && r.t[i] <= tw.b; i++) {
        const c = Math.floor(this.X(r.t[i]) - x0);
        if (c === last) continue;
        last = c;
        const up = r.src[i] === "scenario";
        d += "M" + (x0 + c + 0.5) + "," + (r.y + (up ? r.h / 2 : 2)) + "V" + (r.y + (up ? r.h - 2 : r.h / 2));
      }
      if (d) V3.svg("path", { d: d, stroke: "#000", "stroke-width": 1.5 }, body);
    }

    marks(r, body) {
      const tw = V3.time;
      r.marks.forEach((m) => {
        if (m.t < tw.a || m.t > tw.b) return;
        const x = this.X(m.t), y = r.y + r.h / 2, s = 6;
        const fill = V3.sevStyle[m.severity] || "#000";
        let shape;
        if (m.severity === "error") shape = V3.svg("path", { d: "M" + (x - s) + "," + (y - s) + "H" + (x + s) + "L" + x + "," + (y + s) + "Z" }, body);
        else if (m.severity === "warning") shape = V3.svg("path", { d: "M" + x + "," + (y - s) + "L" + (x + s) + "," + y + "L" + x + "," + (y + s) + "L" + (x - s) + "," + y + "Z" }, body);
        else shape = V3.svg("circle", { cx: x, cy: y, r: s - 1 }, body);
        shape.setAttribute("fill", fill);
        shape.setAttribute("stroke", "#000");
        shape.setAttribute("stroke-width", "0.8");
      });
    }

    moveCursor(t) {
      if (!this.cursor) return;
      const tw = V3.time;
      if (t === null || t < tw.a || t > tw.b) { this.cursor.setAttribute("visibility", "hidden"); return; }
      this.cursor.setAttribute("x1", this.X(t)); this.cursor.setAttribute("x2", this.X(t));
      this.cursor.setAttribute("visibility", "visible");
    }

    /* the tooltip: what the row under the pointer was doing at that time */
    hover(t, ev) {
      if (t === null || !ev) { V3.tip(null); return; }
      const r0 = this.svg.getBoundingClientRect();
      const vb = this.svg.viewBox.baseVal;
      const y = (ev.clientY - r0.top) * (vb.height / r0.height);
      const row = this.rows.find((r) => y >= r.y - 2 && y <= r.y + r.h + 2);
      if (!row) { V3.tip(null); return; }
      const px = 5 * (V3.time.b - V3.time.a) / (this.g.x1 - this.g.x0);  // 5 pixels, in seconds
      let text = null;
      if (row.kind === "states") {
        const i = V3.lowerBound(this.starts(row), t + 1e-12) - 1;
        const s = i >= 0 ? row.segs[i] : null;
        if (s && t <= s[1]) {
          const det = row.details && row.details[s[3]] ? " – " + row.details[s[3]] : "";
          text = row.label + ": " + row.states[s[2]] + det + "\n" + V3.fmtTime(s[0]) + " → " + V3.fmtTime(s[1]);
        }
      } else if (row.kind === "aio" || row.kind === "sio") {
        const i = V3.lowerBound(row.t, t + 1e-12) - 1;
        if (row.kind === "aio" && i >= 0) text = row.label + " = " + row.v[i] + " since " + V3.fmtTime(row.t[i]) + " (" + row.src[i] + ")";
        if (row.kind === "sio") {
          const cands = [i, i + 1].filter((k) => k >= 0 && k < row.t.length && Math.abs(row.t[k] - t) <= px);
          if (cands.length) {
            const k = cands[0];
            text = row.label + (row.src[k] === "scenario" ? " received " : " sent by " + row.src[k] + ": ") + JSON.stringify(row.v[k]) + "\nat " + V3.fmtTime(row.t[k]);
          }
        }
      } else if (row.kind === "marks") {
        const near = row.marks.filter((m) => Math.abs(m.t - t) <= px);
        if (near.length) text = near.map((m) => m.text).join("\n");
      }
      if (text) V3.tip(text, ev.clientX, ev.clientY); else V3.tip(null);
    }
  }

  /* the Gantt chart: diagnostics, tasks, arm */
  V3.gantt = function (parent) {
    const D = V3.data, rows = [];
    const marks = D.diags.filter((d) => d.time !== null).map((d) => ({
      t: d.time, severity: d.severity,
      text: d.code + " " + d.severity + " at " + V3.fmtTime(d.time) + (d.task ? " (task " + d.task + ")" : "") + "\n" + d.message,
    }));
    if (marks.length) rows.push({ label: "diagnostics", kind: "marks", marks: marks });
    D.tasks.forEach((t) => rows.push({ label: "task " + t.name, kind: "states", segs: t.segs, states: D.task_states, details: D.details }));
    if (D.arm.length) rows.push({ label: "arm", kind: "states", segs: D.arm, states: D.arm_states, details: [] });
    const describe = "Gantt chart of " + D.tasks.length + " tasks and the arm over time. Keys: arrows move, + and − zoom, 0 whole run.";
    const lanes = new Lanes(parent, rows, describe);
    const items = D.task_states.map((s) => ({ label: V3.stateStyle[s].label, fill: V3.stateStyle[s].fill, hatch: V3.stateStyle[s].hatch }));
    if (D.arm.length) D.arm_states.forEach((s) => items.push({ label: V3.stateStyle[s].label, fill: V3.stateStyle[s].fill }));
    V3.legend(parent, items);
    if (marks.length) V3.legend(parent, [{ label: "diagnostics row: ▼ error, ◆ warning, ● info", text: true }]);
    return lanes;
  };

  /* the I/O timeline: one lane per input/output */
  V3.ioLanes = function (parent) {
    const rows = V3.data.io.map((s) => {
      const label = s.kind + " " + s.label;
      if (s.kind === "dio") {
        const who = Array.from(new Set(s.src));
        const segs = s.t.map((t, i) => [t, i + 1 < s.t.length ? s.t[i + 1] : V3.time.t1, s.v[i] ? 1 : 0, who.indexOf(s.src[i])]);
        return { label: label, kind: "states", segs: segs, states: ["low", "high"], details: who.map((x) => "set by " + x) };
      }
      return { label: label, kind: s.kind, t: s.t, v: s.v, src: s.src };
    });
    const lanes = new Lanes(parent, rows, "Timeline of " + rows.length + " inputs and outputs. Keys: arrows move, + and − zoom, 0 whole run.");
    V3.legend(parent, [{ label: "digital true", fill: "#009E73" }, { label: "digital false (baseline)", fill: "#9aa1ab" },
      { label: "analog value (range at the right)", line: "#CC79A7" }, { label: "serial: sent (top half) / received (bottom half)", line: "#000" }]);
    return lanes;
  };

  /* the duration of each loop iteration */
  V3.cycleBars = function (parent, cycle) {
    const its = cycle.it;
    const W0 = Math.max(parent.clientWidth, 320), H = 150, M = { l: 52, r: 12, t: 10, b: 26 };
    const svg = V3.svg("svg", { class: "chart", viewBox: "0 0 " + W0 + " " + H }, parent);
    const max = Math.max.apply(null, its.map((x) => x[1]).concat([1e-3]));
    const done = its.filter((x) => x[2]);
    const mean = done.length ? done.reduce((s, x) => s + x[1], 0) / done.length : null;
    const bw = (W0 - M.l - M.r) / its.length;
    const Y = (v) => H - M.b - v / (max * 1.1) * (H - M.t - M.b);
    const grid = V3.svg("g", { class: "grid" }, svg), axis = V3.svg("g", { class: "axis" }, svg);
    const yt = V3.ticks(0, max * 1.1, 4);
    yt.forEach((v) => {
      V3.svg("line", { x1: M.l, x2: W0 - M.r, y1: Y(v), y2: Y(v) }, grid);
      V3.svg("text", { x: M.l - 5, y: Y(v) + 3.5, "text-anchor": "end" }, axis, V3.fmtTick(v, yt.step) + " s");
    });
    const step = Math.max(1, Math.ceil(its.length / 20));
    its.forEach((it, k) => {
      const x = M.l + k * bw;
      const bar = V3.svg("rect", { x: x + bw * 0.12, width: Math.max(bw * 0.76, 1), y: Y(it[1]), height: Y(0) - Y(it[1]),
        fill: it[2] ? "#0072B2" : "#b9c2cc", tabindex: its.length <= 300 ? "0" : "-1", role: "button",
        "aria-label": "iteration " + (k + 1) + ": " + it[1].toFixed(3) + " s" + (it[2] ? "" : " (cut by the end of the run)") }, svg);
      V3.svg("title", {}, bar, "iteration " + (k + 1) + ": " + it[1].toFixed(3) + " s from " + it[0].toFixed(3) + " s");
      const go = () => V3.time.show(it[0], it[0] + it[1]);
      bar.addEventListener("click", go);
      bar.addEventListener("keydown", (ev) => { if (ev.key === "Enter" || ev.key === " ") { ev.preventDefault(); go(); } });
      if (k % step === 0) V3.svg("text", { x: x + bw / 2, y: H - M.b + 14, "text-anchor": "middle" }, axis, String(k + 1));
    });
    if (mean !== null) {
      V3.svg("line", { x1: M.l, x2: W0 - M.r, y1: Y(mean), y2: Y(mean), stroke: "#D55E00", "stroke-width": 1.5, "stroke-dasharray": "5 3" }, svg);
      V3.svg("text", { x: W0 - M.r - 4, y: Y(mean) - 4, "text-anchor": "end", fill: "#b84a00" }, svg, "mean " + mean.toFixed(3) + " s");
    }
    V3.svg("rect", { class: "frame", x: M.l, y: M.t, width: W0 - M.l - M.r, height: H - M.t - M.b }, svg);
    return svg;
  };
})(V3);
