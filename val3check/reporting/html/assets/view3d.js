/* val3check HTML report: the 3D view (Canvas 2D). The page computes the forward kinematics of
   the arm's chain (docs/html-report.md, scene.arm) from the joint samples, places the link
   solids, the tool, the cell's obstacles (on their frames' values at the time shown) and the
   parts (carried or left), and paints their faces far to near with flat shading. Orbit with the mouse or the keyboard; play, pause and scrub along the run. */
(function (V3) {
  const DEG = Math.PI / 180;

  // ---- 3x4 row-major matrices as arrays of 12 numbers (millimetres) ----
  const I = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0];
  function M(rows) { return [rows[0][0], rows[0][1], rows[0][2], rows[0][3], rows[1][0], rows[1][1], rows[1][2], rows[1][3], rows[2][0], rows[2][1], rows[2][2], rows[2][3]]; }
  function mul(A, B) {
    const o = new Array(12);
    for (let r = 0; r < 3; r++) {
      const a0 = A[4 * r], a1 = A[4 * r + 1], a2 = A[4 * r + 2];
      o[4 * r] = a0 * B[0] + a1 * B[4] + a2 * B[8];
      o[4 * r + 1] = a0 * B[1] + a1 * B[5] + a2 * B[9];
      o[4 * r + 2] = a0 * B[2] + a1 * B[6] + a2 * B[10];
      o[4 * r + 3] = a0 * B[3] + a1 * B[7] + a2 * B[11] + A[4 * r + 3];
    }
    return o;
  }
  function axisAngle(ax, a) {
    const x = ax[0], y = ax[1], z = ax[2], c = Math.cos(a), s = Math.sin(a), C = 1 - c;
    return [c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0,
      y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0,
      z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0];
  }
  function motion(j, v) {
    if (j.type === "prismatic") return [1, 0, 0, j.axis[0] * v, 0, 1, 0, j.axis[1] * v, 0, 0, 1, j.axis[2] * v];
    return axisAngle(j.axis, v * DEG);
  }
  function rows(A) { return [[A[0], A[1], A[2], A[3]], [A[4], A[5], A[6], A[7]], [A[8], A[9], A[10], A[11]]]; }

  /* every link's pose in the world frame for joint values q (degrees / mm, trajectory order) */
  function linkPoses(arm, q) {
    const poses = {};
    poses[arm.root] = M(arm.root_in_world);
    arm.joints.forEach((j) => {
      let T = mul(poses[j.parent], j.O || (j.O = M(j.origin)));
      if (j.type !== "fixed" && j.index !== null && j.index < q.length) T = mul(T, motion(j, q[j.index]));
      poses[j.child] = T;
    });
    return poses;
  }
  V3.linkPoses = linkPoses;

  // ---- solids as polygons in their own frame ----
  function cylinder(r, L, n) {
    const v = [], f = [];
    for (let i = 0; i < n; i++) {
      const a = 2 * Math.PI * i / n, x = r * Math.cos(a), y = r * Math.sin(a);
      v.push(x, y, -L / 2, x, y, L / 2);
    }
    const bottom = [], top = [];
    for (let i = 0; i < n; i++) {
      const k = (i + 1) % n;
      f.push([2 * i, 2 * k, 2 * k + 1, 2 * i + 1]);
      bottom.push(2 * (n - 1 - i));
      top.push(2 * i + 1);
    }
    f.push(bottom, top);
    return { v: v, f: f, closed: true };
  }
  /* a box, each face cut into tiles of at most BOX_TILE mm (8 x 8 at most): the painter's sort
     orders faces by their mean depth, and a table's whole top would hide a pallet lying on it */
  const BOX_TILE = 150;
  function box(sx, sy, sz) {
    const v = [], f = [], size = [sx, sy, sz];
    // outward normal axis and sign, then the two axes u, v with u x v = normal
    [[0, 1, 1, 2], [0, -1, 2, 1], [1, 1, 2, 0], [1, -1, 0, 2], [2, 1, 0, 1], [2, -1, 1, 0]].forEach((d) => {
      const ax = d[0], sg = d[1], u = d[2], w = d[3];
      const nu = Math.min(8, Math.max(1, Math.ceil(size[u] / BOX_TILE)));
      const nw = Math.min(8, Math.max(1, Math.ceil(size[w] / BOX_TILE)));
      const base = v.length / 3;
      for (let i = 0; i <= nu; i++) {
        for (let j = 0; j <= nw; j++) {
          const p = [0, 0, 0];
          p[ax] = sg * 0.5 * size[ax];
          p[u] = (i / nu - 0.5) * size[u];
          p[w] = (j / nw - 0.5) * size[w];
          v.push(p[0], p[1], p[2]);
        }
      }
      for (let i = 0; i < nu; i++) {
        for (let j = 0; j < nw; j++) {
          const a = base + i * (nw + 1) + j;
          f.push([a, a + nw + 1, a + nw + 2, a + 1]);
        }
      }
    });
    return { v: v, f: f, closed: true };
  }
  function sphere(r, nlat, nlon) {
    const v = [], f = [];
    for (let i = 0; i <= nlat; i++) {
      const th = Math.PI * i / nlat;
      for (let k = 0; k < nlon; k++) {
        const ph = 2 * Math.PI * k / nlon;
        v.push(r * Math.sin(th) * Math.cos(ph), r * Math.sin(th) * Math.sin(ph), r * Math.cos(th));
      }
    }
    for (let i = 0; i < nlat; i++) {
      for (let k = 0; k < nlon; k++) {
        const a = i * nlon + k, b = i * nlon + (k + 1) % nlon;
        f.push([a, a + nlon, b + nlon, b]);
      }
    }
    return { v: v, f: f, closed: true };
  }
  function geometry(s) {
    if (s.shape === "cylinder") return cylinder(s.radius, s.length, 24);
    if (s.shape === "box") return box(s.size[0], s.size[1], s.size[2]);
    if (s.shape === "sphere") return sphere(s.radius, 10, 18);
    const v = [];
    s.vertices.forEach((p) => v.push(p[0], p[1], p[2]));
    return { v: v, f: s.triangles.map((t) => t.slice()), closed: false };
  }

  function rgb(hex) { return [parseInt(hex.slice(1, 3), 16), parseInt(hex.slice(3, 5), 16), parseInt(hex.slice(5, 7), 16)]; }
  const COLORS = { arm: rgb("#F2B51C"), flange: rgb("#5d6670"), tool: rgb("#3d4650"), obstacle: rgb("#8ea6bf"), part: rgb("#009E73") };

  class View3D {
    constructor(canvas, scene, anim, joints) {
      this.canvas = canvas;
      this.ctx = canvas.getContext("2d");
      this.scene = scene;
      this.arm = scene.arm || null;
      this.anim = anim;  // {t: Float64Array, q: [Float32Array per joint]} or null
      this.joints = joints || [];
      this.parts = [];
      const arm = this.arm;
      if (arm) {
        arm.links.forEach((l) => l.solids.forEach((s) => this.parts.push({
          frame: l.name, pose: M(s.pose), g: geometry(s), color: l.name === arm.flange_frame ? COLORS.flange : COLORS.arm, alpha: 1,
          name: "arm: " + l.name + (s.name ? " (" + s.name + ")" : "") })));
        if (scene.tool) scene.tool.solids.forEach((s) => this.parts.push({
          frame: arm.flange_frame, pose: M(s.pose), track: s.track, g: geometry(s), color: COLORS.tool, alpha: 1,
          name: "tool " + scene.tool.name + (s.name ? ": " + s.name : "") }));
      }
      (scene.obstacles || []).forEach((s) => this.parts.push({
        frame: null, pose: M(s.pose), track: s.track, g: geometry(s), color: s.color ? rgb(s.color) : COLORS.obstacle,
        alpha: 0.88, walls: 0.3, name: "cell: " + (s.name || s.shape) }));
      // frames and tools over the run (changes: a pose holds until the next one), and the parts,
      // carried on the flange or left in the cell over each of their spans
      this.tracks = {};
      Object.keys(scene.tracks || {}).forEach((k) => {
        const tr = scene.tracks[k];
        this.tracks[k] = { t: tr.times, P: tr.poses.map((p) => (p ? M(p) : null)) };
      });
      (scene.parts || []).forEach((p) => {
        const gs = p.solids.map((s) => ({ pose: M(s.pose), g: geometry(s) }));
        p.spans.forEach((sp) => gs.forEach((s) => this.parts.push({
          frame: sp.carried ? (arm ? arm.flange_frame : "") : null, pose: mul(M(sp.pose), s.pose), g: s.g,
          when: [sp.start, sp.end === null ? Infinity : sp.end], color: COLORS.part, alpha: 1, name: "part: " + p.name })));
      });
      this.tcpOffset = scene.tool ? M(scene.tool.tcp) : I;
      this.t = 0;
      this.q = this.jointsAt(0);
      this.bounds();
      this.resetView();
      this.trail = this.makeTrail();
      this.bind();
    }

    /* a track's pose at time t (the last change at or before t; before the first, the first) */
    trackAt(name, t) {
      const tr = this.tracks[name];
      if (!tr) return null;
      const k = Math.max(V3.lowerBound(tr.t, t + 1e-9) - 1, 0);
      return tr.P[k];
    }

    /* a solid's pose in its frame at time t, or null when it is not in the scene then */
    placed(part, t) {
      if (part.when && (t < part.when[0] || t >= part.when[1])) return null;
      if (!part.track) return part.pose;
      const B = this.trackAt(part.track, t);
      return B ? mul(B, part.pose) : null;
    }

    /* joint values at time t: linear between the samples */
    jointsAt(t) {
      const a = this.anim;
      if (!a || !a.t.length) return (this.scene.joints || this.joints.map(() => 0)).slice();
      let i = V3.lowerBound(a.t, t);
      if (i <= 0) return a.q.map((c) => c[0]);
      if (i >= a.t.length) return a.q.map((c) => c[a.t.length - 1]);
      const t0 = a.t[i - 1], t1 = a.t[i], u = t1 > t0 ? (t - t0) / (t1 - t0) : 0;
      return a.q.map((c) => c[i - 1] + (c[i] - c[i - 1]) * u);
    }

    tcp(poses) {
      const F = poses[this.arm.flange_frame];
      return mul(F, this.tcpOffset);
    }

    makeTrail() {
      const a = this.anim;
      if (!this.arm || !a || !a.t.length) return null;
      const n = a.t.length, stride = Math.max(1, Math.ceil(n / 4000));
      const t = [], p = [];
      for (let i = 0; i < n; i += stride) {
        const T = this.tcp(linkPoses(this.arm, a.q.map((c) => c[i])));
        t.push(a.t[i]); p.push([T[3], T[7], T[11]]);
      }
      return { t: t, p: p };
    }

    bounds() {
      let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      const add = (x, y, z) => { lo = [Math.min(lo[0], x), Math.min(lo[1], y), Math.min(lo[2], z)]; hi = [Math.max(hi[0], x), Math.max(hi[1], y), Math.max(hi[2], z)]; };
      if (this.arm) {
        // where the arm goes: its links' origins and the TCP over (up to) 200 samples of the run
        const R = M(this.arm.root_in_world), a = this.anim;
        this.floor = R[11];
        add(R[3], R[7], R[11]);
        const n = a && a.t.length ? a.t.length : 1, stride = Math.max(1, Math.ceil(n / 200));
        for (let i = 0; i < n; i += stride) {
          const P = linkPoses(this.arm, a && a.t.length ? a.q.map((c) => c[i]) : this.q);
          Object.keys(P).forEach((k) => add(P[k][3], P[k][7], P[k][11]));
          const T = this.tcp(P);
          add(T[3], T[7], T[11]);
        }
      }
      this.parts.filter((p) => p.frame === null).forEach((p) => {
        // a solid on a track: where it is at up to 20 of its changes
        const tr = p.track ? this.tracks[p.track] : null, n = tr ? tr.t.length : 1, stride = Math.max(1, Math.ceil(n / 20));
        for (let i = 0; i < n; i += stride) {
          const P = tr ? (tr.P[i] ? mul(tr.P[i], p.pose) : null) : p.pose;
          for (let k = 0; P && k < p.g.v.length; k += 3) {
            const x = p.g.v[k], y = p.g.v[k + 1], z = p.g.v[k + 2];
            add(P[0] * x + P[1] * y + P[2] * z + P[3], P[4] * x + P[5] * y + P[6] * z + P[7], P[8] * x + P[9] * y + P[10] * z + P[11]);
          }
        }
      });
      if (!isFinite(lo[0])) { lo = [-500, -500, -500]; hi = [500, 500, 500]; }
      // room for the solids around the points
      const pad = 0.08 * Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) + 100;
      lo = lo.map((v) => v - pad); hi = hi.map((v) => v + pad);
      if (this.floor === undefined) this.floor = lo[2];
      this.lo = lo; this.hi = hi;
      this.center = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
      this.radius = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2, 100);
    }

    resetView() {
      this.yaw = -55 * DEG; this.pitch = 24 * DEG;
      this.dist = this.radius / Math.sin(20 * DEG) * 0.85;
      this.target = this.center.slice();
      this.draw();
    }

    camera() {
      const cp = Math.cos(this.pitch), sp = Math.sin(this.pitch), cy = Math.cos(this.yaw), sy = Math.sin(this.yaw);
      const back = [cp * cy, cp * sy, sp];
      const eye = [this.target[0] + back[0] * this.dist, this.target[1] + back[1] * this.dist, this.target[2] + back[2] * this.dist];
      const fwd = [-back[0], -back[1], -back[2]];
      let right = [fwd[1] * 1 - fwd[2] * 0, fwd[2] * 0 - fwd[0] * 1, 0];
      const rn = Math.hypot(right[0], right[1], right[2]) || 1;
      right = [right[0] / rn, right[1] / rn, right[2] / rn];
      const up = [right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2], right[0] * fwd[1] - right[1] * fwd[0]];
      return { eye: eye, fwd: fwd, right: right, up: up };
    }

    setTime(t) {
      this.t = t;
      this.q = this.jointsAt(t);
      this.draw();
    }

    draw() {
      const cv = this.canvas, dpr = window.devicePixelRatio || 1;
      const w = cv.clientWidth || 800, h = cv.clientHeight || 500;
      if (cv.width !== Math.round(w * dpr) || cv.height !== Math.round(h * dpr)) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
      const ctx = this.ctx;
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.clearRect(0, 0, w, h);
      const sky = ctx.createLinearGradient(0, 0, 0, h);
      sky.addColorStop(0, "#f4f7fb"); sky.addColorStop(1, "#e3e8ee");
      ctx.fillStyle = sky; ctx.fillRect(0, 0, w, h);
      const cam = this.camera();
      const f = 0.5 * Math.min(w, h) / Math.tan(20 * DEG);
      const near = 10;
      const proj = (p) => {
        const dx = p[0] - cam.eye[0], dy = p[1] - cam.eye[1], dz = p[2] - cam.eye[2];
        const z = dx * cam.fwd[0] + dy * cam.fwd[1] + dz * cam.fwd[2];
        const x = dx * cam.right[0] + dy * cam.right[1] + dz * cam.right[2];
        const y = dx * cam.up[0] + dy * cam.up[1] + dz * cam.up[2];
        return [w / 2 + f * x / z, h / 2 - f * y / z, z];
      };
      this.grid(ctx, proj, near);
      const poses = this.arm ? linkPoses(this.arm, this.q) : {};
      const light = [-cam.fwd[0] * 0.6 + 0.25, -cam.fwd[1] * 0.6 + 0.2, -cam.fwd[2] * 0.6 + 0.75];
      const ln = Math.hypot(light[0], light[1], light[2]);
      const prims = [];
      this.parts.forEach((part) => {
        const F = part.frame === null ? I : poses[part.frame], P = this.placed(part, this.t);
        if (!F || !P) return;
        const T = mul(F, P), v = part.g.v, n = v.length / 3;
        const wv = new Float64Array(v.length), sv = new Array(n);
        for (let k = 0; k < n; k++) {
          const x = v[3 * k], y = v[3 * k + 1], z = v[3 * k + 2];
          wv[3 * k] = T[0] * x + T[1] * y + T[2] * z + T[3];
          wv[3 * k + 1] = T[4] * x + T[5] * y + T[6] * z + T[7];
          wv[3 * k + 2] = T[8] * x + T[9] * y + T[10] * z + T[11];
          sv[k] = proj([wv[3 * k], wv[3 * k + 1], wv[3 * k + 2]]);
        }
        part.g.f.forEach((face) => {
          // Newell normal, centroid, depth
          let nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0, zmin = Infinity, depth = 0;
          for (let i = 0; i < face.length; i++) {
            const a = face[i], b = face[(i + 1) % face.length];
            const ax = wv[3 * a], ay = wv[3 * a + 1], az = wv[3 * a + 2], bx = wv[3 * b], by = wv[3 * b + 1], bz = wv[3 * b + 2];
            nx += (ay - by) * (az + bz); ny += (az - bz) * (ax + bx); nz += (ax - bx) * (ay + by);
            cx += ax; cy += ay; cz += az;
            zmin = Math.min(zmin, sv[a][2]); depth += sv[a][2];
          }
          if (zmin < near) return;
          const nn = Math.hypot(nx, ny, nz) || 1;
          nx /= nn; ny /= nn; nz /= nn;
          cx /= face.length; cy /= face.length; cz /= face.length;
          const facing = nx * (cam.eye[0] - cx) + ny * (cam.eye[1] - cy) + nz * (cam.eye[2] - cz);
          if (part.g.closed && facing <= 0) return;
          let lam = (nx * light[0] + ny * light[1] + nz * light[2]) / ln;
          if (!part.g.closed && facing < 0) lam = -lam;
          const k = 0.45 + 0.55 * Math.max(0, lam);
          const c = part.color;
          // the cell's upright faces are see-through, so a fence or a wall never hides the arm;
          // tops (tables, pallets) stay solid
          const alpha = part.walls !== undefined && Math.abs(nz) < 0.5 ? part.walls : part.alpha;
          prims.push({ depth: depth / face.length, pts: face.map((i) => sv[i]), part: part,
            fill: "rgba(" + Math.round(c[0] * k) + "," + Math.round(c[1] * k) + "," + Math.round(c[2] * k) + "," + alpha + ")" });
        });
      });
      if (this.trail) {
        const tr = this.trail;
        for (let i = 1; i < tr.p.length; i++) {
          const a = proj(tr.p[i - 1]), b = proj(tr.p[i]);
          if (a[2] < near || b[2] < near) continue;
          prims.push({ depth: (a[2] + b[2]) / 2, line: [a, b], past: tr.t[i] <= this.t });
        }
      }
      prims.sort((a, b) => b.depth - a.depth);
      this.prims = prims;
      ctx.lineJoin = "round";
      for (const p of prims) {
        if (p.line) {
          ctx.strokeStyle = p.past ? "rgba(0,114,178,0.95)" : "rgba(0,114,178,0.28)";
          ctx.lineWidth = p.past ? 2 : 1.5;
          ctx.beginPath(); ctx.moveTo(p.line[0][0], p.line[0][1]); ctx.lineTo(p.line[1][0], p.line[1][1]); ctx.stroke();
          continue;
        }
        ctx.beginPath();
        ctx.moveTo(p.pts[0][0], p.pts[0][1]);
        for (let i = 1; i < p.pts.length; i++) ctx.lineTo(p.pts[i][0], p.pts[i][1]);
        ctx.closePath();
        ctx.fillStyle = p.fill; ctx.fill();
        ctx.strokeStyle = p.fill; ctx.lineWidth = 0.6; ctx.stroke();
      }
      this.axes(ctx, cam, h);
      if (this.arm && this.scene.tool) {
        const T = this.tcp(poses), s = proj([T[3], T[7], T[11]]);
        if (s[2] > near) {
          ctx.fillStyle = "#D55E00"; ctx.strokeStyle = "#fff"; ctx.lineWidth = 1.5;
          ctx.beginPath(); ctx.arc(s[0], s[1], 4.5, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
        }
      }
      ctx.fillStyle = "#1b1f24"; ctx.font = "13px system-ui, sans-serif";
      ctx.fillText("t = " + this.t.toFixed(3) + " s", 10, 20);
      this.drawn = (this.drawn || 0) + 1;
    }

    grid(ctx, proj, near) {
      const step = Math.pow(10, Math.floor(Math.log10(this.radius / 2)));
      const s = this.radius > 5 * step ? step * 2 : step;
      const x0 = Math.floor(this.lo[0] / s) * s - s, x1 = Math.ceil(this.hi[0] / s) * s + s;
      const y0 = Math.floor(this.lo[1] / s) * s - s, y1 = Math.ceil(this.hi[1] / s) * s + s;
      const z = this.floor;
      ctx.lineWidth = 1;
      const line = (a, b, strong) => {
        const p = proj(a), q = proj(b);
        if (p[2] < near || q[2] < near) return;
        ctx.strokeStyle = strong ? "#a9b3bf" : "#cdd3da";
        ctx.beginPath(); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
      };
      for (let x = x0; x <= x1 + 1e-6; x += s) line([x, y0, z], [x, y1, z], Math.abs(x) < 1e-6);
      for (let y = y0; y <= y1 + 1e-6; y += s) line([x0, y, z], [x1, y, z], Math.abs(y) < 1e-6);
      this.gridStep = s;
    }

    /* the world axes as seen from the camera, in the corner (the world frame's origin is inside the arm) */
    axes(ctx, cam, h) {
      const o = [44, h - 44], L = 30;
      ctx.fillStyle = "rgba(255,255,255,0.8)";
      ctx.beginPath(); ctx.arc(o[0], o[1], 40, 0, 2 * Math.PI); ctx.fill();
      [[[1, 0, 0], "#D55E00", "X"], [[0, 1, 0], "#009E73", "Y"], [[0, 0, 1], "#0072B2", "Z"]].forEach((a) => {
        const v = a[0];
        const x = v[0] * cam.right[0] + v[1] * cam.right[1] + v[2] * cam.right[2];
        const y = v[0] * cam.up[0] + v[1] * cam.up[1] + v[2] * cam.up[2];
        ctx.strokeStyle = a[1]; ctx.lineWidth = 2.5;
        ctx.beginPath(); ctx.moveTo(o[0], o[1]); ctx.lineTo(o[0] + x * L, o[1] - y * L); ctx.stroke();
        ctx.fillStyle = a[1]; ctx.font = "bold 12px system-ui, sans-serif";
        ctx.fillText(a[2], o[0] + x * (L + 6) - 4, o[1] - y * (L + 6) + 4);
      });
    }

    /* the solid drawn at a point of the canvas (CSS pixels): the nearest face that covers it */
    pick(x, y) {
      const prims = this.prims || [];
      for (let k = prims.length - 1; k >= 0; k--) {
        const p = prims[k];
        if (!p.pts) continue;
        let inside = false;
        for (let i = 0, j = p.pts.length - 1; i < p.pts.length; j = i++) {
          const a = p.pts[i], b = p.pts[j];
          if ((a[1] > y) !== (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
        }
        if (inside) return p.part.name;
      }
      return null;
    }

    bind() {
      const cv = this.canvas;
      let drag = null;
      cv.addEventListener("pointerdown", (ev) => {
        drag = { x: ev.clientX, y: ev.clientY, pan: ev.shiftKey || ev.button === 2 };
        cv.setPointerCapture(ev.pointerId);
        cv.style.cursor = "grabbing";
      });
      cv.addEventListener("pointermove", (ev) => {
        if (!drag) {
          const r = cv.getBoundingClientRect(), name = this.pick(ev.clientX - r.left, ev.clientY - r.top);
          V3.tip(name, ev.clientX, ev.clientY);
          return;
        }
        V3.tip(null);
        const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
        drag.x = ev.clientX; drag.y = ev.clientY;
        if (drag.pan) {
          const cam = this.camera(), k = this.dist / 600;
          for (let i = 0; i < 3; i++) this.target[i] += (-dx * cam.right[i] + dy * cam.up[i]) * k;
        } else {
          this.yaw -= dx * 0.008;
          this.pitch = Math.max(-85 * DEG, Math.min(85 * DEG, this.pitch + dy * 0.008));
        }
        this.draw();
      });
      const end = () => { drag = null; cv.style.cursor = ""; };
      cv.addEventListener("pointerup", end);
      cv.addEventListener("pointerleave", () => V3.tip(null));
      cv.addEventListener("pointercancel", end);
      cv.addEventListener("contextmenu", (ev) => ev.preventDefault());
      cv.addEventListener("wheel", (ev) => {
        ev.preventDefault();
        this.dist *= ev.deltaY > 0 ? 1.12 : 1 / 1.12;
        this.draw();
      }, { passive: false });
      cv.addEventListener("keydown", (ev) => {
        const k = ev.key;
        if (k === "ArrowLeft") this.yaw += 5 * DEG;
        else if (k === "ArrowRight") this.yaw -= 5 * DEG;
        else if (k === "ArrowUp") this.pitch = Math.min(85 * DEG, this.pitch + 5 * DEG);
        else if (k === "ArrowDown") this.pitch = Math.max(-85 * DEG, this.pitch - 5 * DEG);
        else if (k === "+" || k === "=") this.dist /= 1.15;
        else if (k === "-" || k === "_") this.dist *= 1.15;
        else if (k === "Home") { this.resetView(); ev.preventDefault(); return; }
        else if (k === " " && this.onSpace) { this.onSpace(); ev.preventDefault(); return; }
        else if ((k === "," || k === ".") && this.onStep) { this.onStep(k === "." ? 1 : -1); ev.preventDefault(); return; }
        else return;
        ev.preventDefault();
        this.draw();
      });
      new ResizeObserver(() => this.draw()).observe(cv);
    }
  }

  /* wire the canvas, the playback controls and the joint table */
  V3.view3d = function () {
    const D = V3.data, canvas = document.getElementById("view3d");
    if (!canvas || !D.scene) return null;
    const tr = D.traj;
    let anim = null;
    if (tr) {
      anim = tr.anim ? { t: V3.f64(tr.anim.t), q: tr.anim.q.map(V3.f32) }
        : { t: V3.f64(tr.t), q: tr.joints.map((j) => V3.f32(j.pos.v)) };
    }
    // without a trajectory, the joints and their ranges come from the arm's chain
    const chainJoint = (n) => (D.scene.arm ? D.scene.arm.joints.find((j) => j.name === n) : null) || {};
    const joints = tr ? tr.joints : (D.scene.arm ? D.scene.arm.joint_names : []).map((n) => {
      const j = chainJoint(n);
      return { name: n, unit: j.type === "prismatic" ? "mm" : "deg", min: j.lower, max: j.upper };
    });
    const view = new View3D(canvas, D.scene, anim, joints);
    const end = anim && anim.t.length ? anim.t[anim.t.length - 1] : D.duration;
    const play = document.getElementById("play"), scrub = document.getElementById("scrub");
    const out = document.getElementById("scrub-time"), speed = document.getElementById("speed");
    const state = document.getElementById("view3d-state"), tbody = document.getElementById("jointnow");
    const motions = D.motions.slice().sort((a, b) => a.start - b.start);
    const mstart = motions.map((m) => m.start);
    const cells = joints.map((j) => {
      const tr = V3.el("tr", {}, tbody);
      V3.el("th", { scope: "row" }, tr, j.name);
      const v = V3.el("td", { class: "n" }, tr);
      const u = j.unit === "deg" ? "°" : " " + j.unit;
      V3.el("td", { class: "muted" }, tr, j.min != null && j.max != null ? j.min + " … " + j.max + u : "–");
      return { j: j, v: v, u: u };
    });
    function show(t) {
      view.setTime(t);
      if (scrub) scrub.value = String(Math.round(t / (end || 1) * 1000));
      if (out) out.textContent = t.toFixed(3) + " s";
      cells.forEach((c, i) => {
        const x = view.q[i];
        if (x === undefined) { c.v.textContent = "–"; return; }
        c.v.textContent = x.toFixed(2) + c.u;
        const span = (c.j.max - c.j.min) || 1;
        const close = c.j.min != null && c.j.max != null && (x - c.j.min < 0.05 * span || c.j.max - x < 0.05 * span);
        c.v.classList.toggle("near", !!close);
        c.v.title = close ? "within 5 % of the joint range from a limit" : "";
      });
      const k = V3.lowerBound(mstart, t + 1e-9) - 1;
      const m = k >= 0 && t <= motions[k].end ? motions[k] : null;
      state.textContent = "t = " + t.toFixed(3) + " s: " + (m ? "motion " + m.id + " (" + m.kind + (m.line ? ", line " + m.line : "") + ")" : "arm not moving");
    }
    let playing = false, last = 0;
    function frame(now) {
      if (!playing) return;
      const dt = Math.min((now - last) / 1000, 0.1);
      last = now;
      let t = view.t + dt * parseFloat(speed.value);
      if (t >= end) { t = end; setPlaying(false); }
      V3.time.setCursor(t);
      if (playing) requestAnimationFrame(frame);
    }
    function setPlaying(on) {
      playing = on;
      play.setAttribute("aria-pressed", on ? "true" : "false");
      play.textContent = on ? "Pause" : "Play";
      if (on) {
        if (view.t >= end) V3.time.setCursor(0);
        last = performance.now();
        requestAnimationFrame(frame);
      }
    }
    if (play) {
      play.addEventListener("click", () => setPlaying(!playing));
      view.onSpace = () => setPlaying(!playing);
      scrub.addEventListener("input", () => V3.time.setCursor(parseInt(scrub.value, 10) / 1000 * end));
    }
    view.onStep = (d) => {
      const a = view.anim;
      if (!a) return;
      const i = Math.min(Math.max(V3.lowerBound(a.t, view.t) + (d > 0 ? 1 : -1), 0), a.t.length - 1);
      V3.time.setCursor(a.t[i]);
    };
    document.getElementById("reset-view").addEventListener("click", () => view.resetView());
    V3.time.on("cursor", show);
    show(0);
    return view;
  };

  V3.testHooks = {
    /* every link's pose (3x4 nested lists, mm) in the world frame for joint values q */
    linkPoses: (q) => {
      const arm = V3.data.scene && V3.data.scene.arm;
      if (!arm) return null;
      const P = linkPoses(arm, q), out = {};
      Object.keys(P).forEach((k) => { out[k] = rows(P[k]); });
      return out;
    },
  };
})(V3);
