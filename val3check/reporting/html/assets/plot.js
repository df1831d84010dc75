/* val3check HTML report: line plots of time series against their limits (SVG).
   Each plot follows the shared time window; the samples are reduced to at most four points per
   pixel column (first, min, max, last) so that a peak is never hidden, however long the run. */
(function (V3) {
  const M = { left: 58, right: 14, top: 24, bottom: 26 };
  V3.yfit = "limits";
  const plots = [];

  class Plot {
    /* o: {title, unit, times, series: [{name, color, lo, hi}], height,
           lines: [{y, label, color, dash}]      horizontal limit lines
           outside: [{from, to}]                 y ranges outside the limits (shaded)
           steps: [{label, color, dash, segs: [[t0, t1, v]], mirror}]   limits that change per motion
           describe: text for screen readers} */
    constructor(parent, o) {
      this.o = o;
      this.wrap = V3.el("div", { class: "plot" }, parent);
      this.height = o.height || 160;
      this.svg = V3.svg("svg", { class: "chart", tabindex: "0", role: "img", "aria-label": o.describe || o.title }, this.wrap);
      let mn = Infinity, mx = -Infinity;
      o.series.forEach((s) => {
        for (let i = 0; i < s.lo.length; i++) { if (s.lo[i] < mn) mn = s.lo[i]; if (s.hi[i] > mx) mx = s.hi[i]; }
      });
      this.dmin = isFinite(mn) ? mn : 0;
      this.dmax = isFinite(mx) ? mx : 1;
      V3.time.on("window", () => this.render());
      V3.time.on("cursor", (t) => this.moveCursor(t));
      V3.onResize(this.wrap, () => this.render());
      V3.timeInteraction(this.svg, () => this.g, () => this.sel, (t, ev) => this.hover(t, ev));
      plots.push(this);
      this.render();
    }

    yRange() {
      let lo = this.dmin, hi = this.dmax;
      if (V3.yfit === "limits") {
        (this.o.lines || []).forEach((l) => { lo = Math.min(lo, l.y); hi = Math.max(hi, l.y); });
      }
      const span = hi - lo || Math.max(Math.abs(hi), 1);
      return [lo - span * 0.06, hi + span * 0.06];
    }

    render() {
      const o = this.o, svg = this.svg, tw = V3.time;
      const W = Math.max(this.wrap.clientWidth, 320), H = this.height;
      while (svg.firstChild) svg.removeChild(svg.firstChild);
      svg.setAttribute("viewBox", "0 0 " + W + " " + H);
      const g = this.g = { x0: M.left, x1: W - M.right, y0: M.top, y1: H - M.bottom };
      const [ylo, yhi] = this.yr = this.yRange();
      const sx = (g.x1 - g.x0) / (tw.b - tw.a);
      const X = (t) => g.x0 + (t - tw.a) * sx;
      const Y = (v) => g.y1 - (v - ylo) / (yhi - ylo) * (g.y1 - g.y0);
      this.X = X; this.Y = Y;
      const clip = V3.uid("clip");
      const defs = V3.svg("defs", {}, svg);
      V3.svg("rect", { x: g.x0, y: g.y0, width: g.x1 - g.x0, height: g.y1 - g.y0 }, V3.svg("clipPath", { id: clip }, defs));
      const hatch = V3.uid("hatch");
      const pat = V3.svg("pattern", { id: hatch, width: 6, height: 6, patternUnits: "userSpaceOnUse", patternTransform: "rotate(45)" }, defs);
      V3.svg("rect", { width: 6, height: 6, fill: "#fbe3d4" }, pat);
      V3.svg("line", { x1: 0, y1: 0, x2: 0, y2: 6, stroke: "#e8a27a", "stroke-width": 2 }, pat);
      V3.svg("rect", { class: "bg", x: g.x0, y: g.y0, width: g.x1 - g.x0, height: g.y1 - g.y0 }, svg);
      const body = V3.svg("g", { "clip-path": "url(#" + clip + ")" }, svg);
      // outside the limits
      (o.outside || []).forEach((b) => {
        const a = Math.max(b.from, ylo), c = Math.min(b.to, yhi);
        if (c > a) V3.svg("rect", { x: g.x0, width: g.x1 - g.x0, y: Y(c), height: Y(a) - Y(c), fill: "url(#" + hatch + ")" }, body);
      });
      // grid and axes
      const grid = V3.svg("g", { class: "grid" }, svg);
      const axis = V3.svg("g", { class: "axis" }, svg);
      const yt = V3.ticks(ylo, yhi, Math.max(3, Math.floor((g.y1 - g.y0) / 24)));
      yt.forEach((v) => {
        V3.svg("line", { x1: g.x0, x2: g.x1, y1: Y(v), y2: Y(v) }, grid);
        V3.svg("text", { x: g.x0 - 5, y: Y(v) + 3.5, "text-anchor": "end" }, axis, V3.fmtTick(v, yt.step));
      });
      const xt = V3.ticks(tw.a, tw.b, Math.max(2, Math.floor((g.x1 - g.x0) / 80)));
      xt.forEach((t) => {
        V3.svg("line", { x1: X(t), x2: X(t), y1: g.y0, y2: g.y1 }, grid);
        V3.svg("text", { x: X(t), y: g.y1 + 15, "text-anchor": "middle" }, axis, V3.fmtTick(t, xt.step));
      });
      V3.svg("text", { x: g.x0 - 14, y: g.y1 + 15, "text-anchor": "end" }, axis, "time (s)");
      // limits
      (o.lines || []).forEach((l) => {
        if (l.y < ylo || l.y > yhi) return;
        V3.svg("line", { x1: g.x0, x2: g.x1, y1: Y(l.y), y2: Y(l.y), stroke: l.color, "stroke-width": 1.3,
          "stroke-dasharray": l.dash ? "5 3" : "none" }, body);
        V3.svg("text", { x: g.x1 - 4, y: Y(l.y) + (l.y >= (ylo + yhi) / 2 ? 12 : -4), "text-anchor": "end", fill: l.color, class: "lim" }, body, l.label);
      });
      (o.steps || []).forEach((s) => {
        const signs = s.mirror ? [1, -1] : [1];
        signs.forEach((sg) => {
          let d = "";
          s.segs.forEach((seg) => {
            if (seg[1] < tw.a || seg[0] > tw.b) return;
            const y = Y(sg * seg[2]);
            d += "M" + X(seg[0]).toFixed(1) + "," + y.toFixed(1) + "H" + X(seg[1]).toFixed(1);
          });
          if (d) V3.svg("path", { d: d, fill: "none", stroke: s.color, "stroke-width": 1.5, "stroke-dasharray": s.dash ? "4 3" : "none" }, body);
        });
      });
      // the data
      o.series.forEach((s) => {
        if (s.lo !== s.hi) {  // min/max buckets of a long run: the band, when few enough to show it
          const band = Plot.band(o.times, s.lo, s.hi, tw.a, tw.b, X, Y, g.x1 - g.x0);
          if (band) {
            V3.svg("path", { d: band.area, fill: s.color, "fill-opacity": 0.3, stroke: "none" }, body);
            V3.svg("path", { class: "series", d: band.mid, fill: "none", stroke: s.color, "stroke-width": 1.4 }, body);
            return;
          }
        }
        const d = Plot.path(o.times, s.lo, s.hi, tw.a, tw.b, X, Y, g.x1 - g.x0);
        if (d) V3.svg("path", { class: "series", d: d, fill: "none", stroke: s.color, "stroke-width": 1.6, "stroke-linejoin": "round" }, body);
      });
      V3.svg("rect", { class: "frame", x: g.x0, y: g.y0, width: g.x1 - g.x0, height: g.y1 - g.y0 }, svg);
      V3.svg("text", { class: "title", x: g.x0, y: 15 }, svg, o.title);
      this.cursor = V3.svg("line", { class: "cursor", y1: g.y0, y2: g.y1, visibility: "hidden" }, svg);
      this.hoverLine = V3.svg("line", { class: "hover", y1: g.y0, y2: g.y1, visibility: "hidden" }, svg);
      this.readout = V3.svg("g", { class: "readout", visibility: "hidden" }, svg);
      this.readoutBox = V3.svg("rect", { rx: 3, height: 17 }, this.readout);
      this.readoutText = V3.svg("text", {}, this.readout);
      this.sel = V3.svg("rect", { class: "sel", visibility: "hidden" }, svg);
      this.moveCursor(tw.cursor);
    }

    /* the SVG path of a series between times a and b: every sample when there are few, else
       first/min/max/last of each pixel column */
    static path(times, lo, hi, a, b, X, Y, width) {
      const n = times.length;
      if (!n) return "";
      const i0 = Math.max(0, V3.lowerBound(times, a) - 1);
      const i1 = Math.min(n, V3.lowerBound(times, b) + 1);
      const out = [];
      if (i1 - i0 <= 2 * width) {
        for (let i = i0; i < i1; i++) {
          const x = X(times[i]).toFixed(1);
          out.push((out.length ? "L" : "M") + x + "," + Y(lo[i]).toFixed(1));
          if (hi[i] !== lo[i]) out.push("L" + x + "," + Y(hi[i]).toFixed(1));
        }
        return out.join("");
      }
      let col = null, first = 0, last = 0, mn = 0, mx = 0;
      const flush = () => {
        const x = (X(a) + col + 0.5).toFixed(1);
        out.push((out.length ? "L" : "M") + x + "," + Y(first).toFixed(1) + "L" + x + "," + Y(mn).toFixed(1)
          + "L" + x + "," + Y(mx).toFixed(1) + "L" + x + "," + Y(last).toFixed(1));
      };
      const x0 = X(a);
      for (let i = i0; i < i1; i++) {
        const c = Math.floor(X(times[i]) - x0);
        if (c !== col) {
          if (col !== null) flush();
          col = c; first = lo[i]; mn = lo[i]; mx = hi[i];
        } else {
          if (lo[i] < mn) mn = lo[i];
          if (hi[i] > mx) mx = hi[i];
        }
        last = hi[i];
      }
      flush();
      return out.join("");
    }

    /* the band between the bucket minima and maxima and the line through their middle, or null
       when there are more buckets than pixels (then `path` draws each column's extent) */
    static band(times, lo, hi, a, b, X, Y, width) {
      const n = times.length;
      const i0 = Math.max(0, V3.lowerBound(times, a) - 1);
      const i1 = Math.min(n, V3.lowerBound(times, b) + 1);
      if (i1 - i0 < 1 || i1 - i0 > 2 * width) return null;
      const up = [], down = [], mid = [];
      for (let i = i0; i < i1; i++) {
        const x = X(times[i]).toFixed(1);
        up.push(x + "," + Y(hi[i]).toFixed(1));
        down.push(x + "," + Y(lo[i]).toFixed(1));
        mid.push(x + "," + Y((lo[i] + hi[i]) / 2).toFixed(1));
      }
      return { area: "M" + up.join("L") + "L" + down.reverse().join("L") + "Z", mid: "M" + mid.join("L") };
    }

    moveCursor(t) {
      if (!this.cursor) return;
      const tw = V3.time;
      if (t === null || t < tw.a || t > tw.b) { this.cursor.setAttribute("visibility", "hidden"); return; }
      const x = this.X(t);
      this.cursor.setAttribute("x1", x); this.cursor.setAttribute("x2", x);
      this.cursor.setAttribute("visibility", "visible");
    }

    hover(t) {
      if (t === null) {
        this.hoverLine.setAttribute("visibility", "hidden");
        this.readout.setAttribute("visibility", "hidden");
        return;
      }
      const times = this.o.times;
      let i = V3.lowerBound(times, t);
      if (i >= times.length) i = times.length - 1;
      if (i > 0 && t - times[i - 1] < times[i] - t) i--;
      const x = this.X(times[i]);
      this.hoverLine.setAttribute("x1", x); this.hoverLine.setAttribute("x2", x);
      this.hoverLine.setAttribute("visibility", "visible");
      const vals = this.o.series.map((s) => {
        const span = this.yr[1] - this.yr[0];
        const v = s.lo[i] === s.hi[i] ? V3.fmtNum(s.lo[i], span / 10) : V3.fmtNum(s.lo[i], span / 10) + "…" + V3.fmtNum(s.hi[i], span / 10);
        return v + " " + (this.o.unit || "");
      });
      this.readoutText.textContent = "t " + times[i].toFixed(3) + " s   " + vals.join("  ");
      const g = this.g;
      const w = this.readoutText.getComputedTextLength() + 10;
      const rx = Math.min(Math.max(x + 8, g.x0 + 2), g.x1 - w - 2);
      this.readoutBox.setAttribute("x", rx); this.readoutBox.setAttribute("y", g.y0 + 2); this.readoutBox.setAttribute("width", w);
      this.readoutText.setAttribute("x", rx + 5); this.readoutText.setAttribute("y", g.y0 + 14);
      this.readout.setAttribute("visibility", "visible");
    }
  }

  V3.Plot = Plot;
  V3.refit = function (mode) { V3.yfit = mode; plots.forEach((p) => p.render()); };
})(V3);
