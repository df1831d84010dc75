/* val3check HTML report: build the figures, wire the time toolbar, then say "rendered"
   (document.body.dataset.rendered = "1", for tests and tools that wait for the page). */
(function (V3) {
  const D = V3.data;
  const failures = [];

  /* each figure is built on its own: one that fails says so in place and the rest still shows */
  function build(where, what, f) {
    const host = typeof where === "string" ? document.getElementById(where) : where;
    if (!host) return;
    try {
      f(host);
    } catch (err) {
      failures.push(what);
      V3.el("p", { class: "fig-error" }, host, "The " + what + " could not be drawn: " + err.message);
      console.error("val3check report: " + what + ": " + (err && err.stack ? err.stack : err));
    }
  }

  function unitOf(j) { return j.unit === "deg" ? "°" : j.unit; }

  function jointPlots(host) {
    const tr = D.traj, times = V3.f64(tr.t);
    const vel = D.motions.filter((m) => m.vel !== null && m.vel !== undefined);
    tr.joints.forEach((j, k) => {
      const color = V3.palette[k % 6], u = unitOf(j);
      const pos = V3.series(j.pos), v = V3.series(j.vel);
      const lines = [], outside = [];
      if (j.max !== null) { lines.push({ y: j.max, label: "max " + j.max + u, color: "#b84a00" }); outside.push({ from: j.max, to: Infinity }); }
      if (j.min !== null) { lines.push({ y: j.min, label: "min " + j.min + u, color: "#b84a00" }); outside.push({ from: -Infinity, to: j.min }); }
      new V3.Plot(host, { title: j.name + " position (" + u + ")", unit: u, times: times, lines: lines, outside: outside,
        series: [{ name: j.name, color: color, lo: pos.lo, hi: pos.hi }],
        describe: j.name + " position in " + u + " over time, with its limits " + j.min + " and " + j.max + ". Keys: arrows move, + and − zoom, 0 whole run." });
      const vl = [], vo = [];
      if (j.speed !== null) {
        vl.push({ y: j.speed, label: "nominal " + j.speed + u + "/s", color: "#b84a00" }, { y: -j.speed, label: "−nominal", color: "#b84a00" });
        vo.push({ from: j.speed, to: Infinity }, { from: -Infinity, to: -j.speed });
      }
      const steps = j.speed !== null && vel.length ? [{ label: "vel", color: "#E69F00", dash: true, mirror: true,
        segs: vel.map((m) => [m.start, m.end, j.speed * m.vel / 100]) }] : [];
      new V3.Plot(host, { title: j.name + " speed (" + u + "/s)", unit: u + "/s", times: times, lines: vl, outside: vo, steps: steps,
        series: [{ name: j.name, color: color, lo: v.lo, hi: v.hi }],
        describe: j.name + " speed in " + u + " per second over time, against its nominal speed " + j.speed + ". Keys: arrows move, + and − zoom, 0 whole run." });
    });
    const legend = [{ label: "outside the joint range or above the nominal speed", fill: "#fbe3d4", hatch: true },
      { label: "limit", line: "#b84a00" }, { label: "speed allowed by the motion's vel", line: "#E69F00", dash: true }];
    if (tr.decimated) legend.push({ label: "long run: each point is the min/max of " + tr.bucket + " samples", text: true });
    host.parentNode.insertBefore(V3.legend(document.createElement("div"), legend), host);
    document.querySelectorAll("button.yfit").forEach((b) => b.addEventListener("click", () => {
      document.querySelectorAll("button.yfit").forEach((x) => x.setAttribute("aria-pressed", x === b ? "true" : "false"));
      V3.refit(b.dataset.fit);
    }));
  }

  function tcpPlot(host) {
    const tr = D.traj, times = V3.f64(tr.t), s = V3.series(tr.tcp);
    const tv = D.motions.filter((m) => m.tvel !== null && m.tvel !== undefined);
    new V3.Plot(host, { title: "TCP speed (mm/s)", unit: "mm/s", times: times, height: 200,
      series: [{ name: "TCP", color: "#000000", lo: s.lo, hi: s.hi }],
      steps: tv.length ? [{ label: "tvel", color: "#D55E00", dash: true, segs: tv.map((m) => [m.start, m.end, m.tvel]) }] : [],
      describe: "Speed of the tool centre point in mm/s over time, with the tvel of each motion. Keys: arrows move, + and − zoom, 0 whole run." });
    V3.legend(host, [{ label: "TCP speed", line: "#000000" }, { label: "tvel of the motion descriptor", line: "#D55E00", dash: true }]);
  }

  function timebar() {
    const tw = V3.time, out = document.getElementById("tw-range");
    const on = (id, f) => { const b = document.getElementById(id); if (b) b.addEventListener("click", f); };
    on("tw-in", () => tw.zoom(0.5));
    on("tw-out", () => tw.zoom(2));
    on("tw-left", () => tw.pan(-0.25));
    on("tw-right", () => tw.pan(0.25));
    on("tw-reset", () => tw.reset());
    if (out) tw.on("window", () => { out.textContent = tw.a.toFixed(3) + " – " + tw.b.toFixed(3) + " s"; });
    document.querySelectorAll("button.goto").forEach((b) => b.addEventListener("click", () => {
      const s = parseFloat(b.dataset.start), e = b.dataset.end !== undefined ? parseFloat(b.dataset.end) : null;
      tw.show(s, e);
      const fig = document.getElementById("joints");
      if (fig && b.closest("#motions, #diagnostics, #cycles")) fig.scrollIntoView({ behavior: "smooth", block: "start" });
    }));
    /* the motion under the cursor is highlighted in the table */
    const rows = Array.from(document.querySelectorAll("table.motions tbody tr"));
    let lit = null;
    tw.on("cursor", (t) => {
      const m = D.motions.findIndex((x) => t >= x.start && t <= x.end);
      const r = m >= 0 ? rows[m] : null;
      if (r === lit) return;
      if (lit) lit.classList.remove("now");
      if (r) r.classList.add("now");
      lit = r;
    });
  }

  function start() {
    timebar();
    if (D.traj) {
      build("joint-plots", "joint plots", jointPlots);
      if (D.traj.tcp) build("tcp-plot", "TCP speed plot", tcpPlot);
    }
    build("gantt", "task timeline", (h) => V3.gantt(h));
    if (D.io.length) build("io-lanes", "I/O timeline", (h) => V3.ioLanes(h));
    document.querySelectorAll(".cyclebars").forEach((h) => build(h, "cycle chart", () => V3.cycleBars(h, D.cycles[parseInt(h.dataset.cycle, 10)])));
    build("view3d-section", "3D view", () => { V3.view = V3.view3d(); });
    window.addEventListener("beforeprint", () => document.querySelectorAll("details").forEach((d) => { d.open = true; }));
    window.val3checkReport = V3.testHooks;
    // the figures draw on the next animation frame: say "rendered" after it
    requestAnimationFrame(() => requestAnimationFrame(() => {
      document.body.dataset.failures = String(failures.length);
      document.body.dataset.rendered = "1";
    }));
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start); else start();
})(V3);
