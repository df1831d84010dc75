"""A synthetic report model, test data for the HTML report's tests and benchmark (not shipped in
the package): a pick-and-place cell run on a real arm model.

    model = synthetic_model(duration=60.0)             # TX2-60, 4 ms samples, a warning
    model = synthetic_model(duration=20.0, failing=True)  # the robot task stops on error 154

Nothing here comes from the simulator: it is a scripted run whose every figure is computed, not
invented, from the arm model (robots/tx2-60.urdf): movej moves are synchronised trapezoids in
joint space at the nominal speeds and accelerations (the slowest axis sets the time), movel moves
are straight TCP lines at `tvel` (2000 mm/s² assumed), solved with the closed-form inverse
kinematics at every 4 ms sample; joint velocities and the TCP speed are central differences of
the samples; a motion's clearance is the smallest distance from the TCP to the cell's
primitive obstacles over the motion. Part arrivals come from a seeded generator, so the same
arguments give the same model.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

from val3check.robot.chain import arm_chain
from val3check.reporting.html.model import VERSION

PROGRAMS = {
    "Cell/robotCycle.pgx": """<?xml version="1.0" encoding="utf-8"?>
<Programs>
  <Program name="robotCycle">
    <Locals>
      <Local name="l_nStart" type="num" size="1" />
    </Locals>
    <Code><![CDATA[begin
  nCycle = 0
  movej(jHome, tGripper, mFast)
  waitEndMove()
  while true
    l_nStart = clock()
    wait(diPartPresent == true)
    sioCamera = "TRIG"
    movej(appro(pPick, trApp), tGripper, mFast)
    movel(pPick, tGripper, mSlow)
    waitEndMove()
    close(tGripper)
    movel(appro(pPick, trApp), tGripper, mDepart)
    movej(appro(pPlace, trApp), tGripper, mFast)
    movel(pPlace, tGripper, mSlow)
    waitEndMove()
    open(tGripper)
    movel(appro(pPlace, trApp), tGripper, mDepart)
    nCycle = nCycle + 1
    putln("cycle " + toString("", nCycle) + ": " + toString(".2", clock() - l_nStart) + " s")
  endWhile
end]]></Code>
  </Program>
</Programs>
""",
    "Cell/monitor.pgx": """<?xml version="1.0" encoding="utf-8"?>
<Programs>
  <Program name="monitor">
    <Code><![CDATA[begin
  // every 0.1 s (taskCreateSync)
  if aiPressure < 5.5
    call logPressure(aiPressure)
  endIf
  nWatch = nWatch + 1
end]]></Code>
  </Program>
</Programs>
""",
}
ROBOT_PGX, MONITOR_PGX = "Cell/robotCycle.pgx", "Cell/monitor.pgx"
LINE = {"home": 9, "loop": 11, "start": 12, "wait": 13, "camera": 14, "app_pick": 15, "pick": 16, "wait1": 17,
        "close": 18, "dep_pick": 19, "app_place": 20, "place": 21, "wait2": 22, "open": 23, "dep_place": 24,
        "putln": 26}

TOOL_TCP = (0.0, 0.0, 120.0)  # tGripper: the TCP 120 mm out of the flange
CART_ACCEL = 2000.0  # mm/s², movel's Cartesian acceleration (assumed for this synthetic cell)
MDESC = {"mFast": {"vel": 80.0, "tvel": None}, "mSlow": {"vel": 100.0, "tvel": 250.0},
         "mDepart": {"vel": 100.0, "tvel": 600.0}}
# TCP targets in the world frame (mm, deg) and the arm's start
TARGETS = {
    "home": (350.0, 0.0, 150.0, 180.0, 0.0, 0.0),
    "app_pick": (430.0, -240.0, -120.0, 180.0, 0.0, 0.0),
    "pick": (430.0, -240.0, -215.0, 180.0, 0.0, 0.0),
    "app_place": (420.0, 280.0, -100.0, 180.0, 0.0, 90.0),
    "place": (420.0, 280.0, -190.0, 180.0, 0.0, 90.0),
}
NEAR = (0.0, 0.0, 90.0, 0.0, 90.0, 0.0)
CAMERA_REPLY = 0.05  # s between "TRIG" and the camera's answer
GRIP_TIME = 0.15  # s: ctime/otime of tGripper, and the scenario's diGripClosed reaction
MONITOR_PERIOD = 0.1


def _pose(x, y, z, rx=0.0, ry=0.0, rz=0.0):
    from val3check.robot.kinematics import trsf_matrix

    return [list(r) for r in trsf_matrix((x, y, z, rx, ry, rz))]


def _obstacles() -> list[dict]:
    # A prism (the place chute) given as a mesh: two triangles at each end and three faces.
    v = [[-60.0, 0.0, 0.0], [60.0, 0.0, 0.0], [0.0, 0.0, 80.0], [-60.0, 140.0, 0.0], [60.0, 140.0, 0.0], [0.0, 140.0, 40.0]]
    tris = [[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]
    return [
        {"name": "pick table", "shape": "box", "size": [320.0, 320.0, 160.0], "pose": _pose(430, -240, -305)},
        {"name": "conveyor", "shape": "box", "size": [260.0, 700.0, 150.0], "pose": _pose(420, 300, -295)},
        {"name": "pillar", "shape": "cylinder", "radius": 60.0, "length": 1000.0, "pose": _pose(-380, -320, 125)},
        {"name": "camera", "shape": "sphere", "radius": 45.0, "pose": _pose(300, -260, 470)},
        {"name": "chute", "shape": "mesh", "vertices": v, "triangles": tris, "pose": _pose(420, 650, -220)},
    ]


def _tool() -> dict:
    return {
        "name": "tGripper",
        "tcp": _pose(*TOOL_TCP),
        "solids": [
            {"name": "body", "shape": "cylinder", "radius": 35.0, "length": 70.0, "pose": _pose(0, 0, 35)},
            {"name": "finger 1", "shape": "box", "size": [12.0, 30.0, 50.0], "pose": _pose(-22, 0, 95)},
            {"name": "finger 2", "shape": "box", "size": [12.0, 30.0, 50.0], "pose": _pose(22, 0, 95)},
        ],
    }


def _distance(p, ob) -> float:
    """Point (world, mm) to the surface of a primitive obstacle (negative inside)."""
    M = ob["pose"]
    d = [p[i] - M[i][3] for i in range(3)]
    q = [sum(M[k][i] * d[k] for k in range(3)) for i in range(3)]  # into the obstacle's frame
    if ob["shape"] == "sphere":
        return math.sqrt(sum(x * x for x in q)) - ob["radius"]
    if ob["shape"] == "box":
        h = [s / 2 for s in ob["size"]]
        out = [max(abs(q[i]) - h[i], 0.0) for i in range(3)]
        inside = max(abs(q[i]) - h[i] for i in range(3))
        return math.sqrt(sum(x * x for x in out)) if inside > 0 else inside
    if ob["shape"] == "cylinder":
        dr = math.hypot(q[0], q[1]) - ob["radius"]
        dz = abs(q[2]) - ob["length"] / 2
        return math.hypot(max(dr, 0.0), max(dz, 0.0)) if max(dr, dz) > 0 else max(dr, dz)
    return math.inf


def _column(path: str, line: int) -> int:
    text = PROGRAMS[path].split("\n")[line - 1]
    return len(text) - len(text.lstrip()) + 1


def _trapezoid(length: float, v: float, a: float) -> tuple[float, float, float]:
    """(duration, cruise speed, acceleration time) of a trapezoid from rest to rest."""
    if length <= 0:
        return 0.0, 0.0, 0.0
    if length >= v * v / a:
        return length / v + v / a, v, v / a
    vp = math.sqrt(length * a)
    return 2 * vp / a, vp, vp / a


def _travel(tau: float, length: float, v: float, ta: float, T: float) -> float:
    """Distance covered at time tau of a trapezoid (acceleration = v / ta)."""
    if T <= 0:
        return length
    tau = min(max(tau, 0.0), T)
    a = v / ta
    if tau < ta:
        return 0.5 * a * tau * tau
    if tau <= T - ta:
        return 0.5 * v * ta + v * (tau - ta)
    r = T - tau
    return length - 0.5 * a * r * r


class _Run:
    """The scripted run: tasks, motions, I/O, transcript, diagnostics, then the samples."""

    def __init__(self, robot, duration: float, dt: float, seed: int, failing: bool):
        self.robot, self.duration, self.dt = robot, duration, dt
        self.rng = random.Random(seed)
        self.failing = failing
        self.tasks: dict[str, list[dict]] = {}
        self.motions: list[dict] = []
        self.pieces: list[tuple] = []  # (start, end, fn(t) -> joints)
        self.io: list[dict] = []
        self.transcript: list[dict] = []
        self.diags: list[dict] = []
        self.iterations: list[dict] = []
        self.arm_free = 0.0  # when the motion queue is empty
        self.joints = (0.0,) * 6
        tcp = TOOL_TCP + (0.0, 0.0, 0.0)
        self.targets = {k: robot.solve(p, initial=NEAR, tool=tcp) for k, p in TARGETS.items()}
        self.tool = tcp

    # ---- records ----------------------------------------------------------------------------

    def seg(self, task: str, start: float, end: float, state: str, detail: str = "") -> None:
        end = min(end, self.duration)
        if end <= start:
            return
        segs = self.tasks.setdefault(task, [])
        if segs and segs[-1]["state"] == state and segs[-1]["detail"] == detail and abs(segs[-1]["end"] - start) < 1e-9:
            segs[-1]["end"] = round(end, 6)
            return
        segs.append({"start": round(start, 6), "end": round(end, 6), "state": state, "detail": detail})

    def say(self, t: float, task: str, kind: str, text: str) -> None:
        if t <= self.duration:
            self.transcript.append({"time": round(t, 6), "task": task, "kind": kind, "text": text, "screen": None})

    def io_event(self, t: float, kind: str, link: str, names: list[str], value, source: str) -> None:
        if t <= self.duration:
            self.io.append({"time": round(t, 6), "kind": kind, "link": link, "names": names, "value": value,
                            "source": source})

    # ---- motions ----------------------------------------------------------------------------

    def queue(self, t: float, kind: str, target: str, mdesc: str, line: int) -> float:
        """Queue a motion at time t; returns when it ends."""
        start = max(t, self.arm_free)
        q0 = self.joints
        desc = MDESC[mdesc]
        if kind == "movej":
            q1 = self.targets[target]
            dist = [abs(b - a) for a, b in zip(q0, q1)]
            vmax = [s * desc["vel"] / 100 for s in self.robot.nominal_speeds]
            amax = list(self.robot.accelerations)
            moving = [i for i in range(6) if dist[i] > 1e-9]
            vs = min(vmax[i] / dist[i] for i in moving) if moving else 1.0
            as_ = min(amax[i] / dist[i] for i in moving) if moving else 1.0
            T, v, ta = _trapezoid(1.0 if moving else 0.0, vs, as_)
            if moving and v >= vs - 1e-12:
                k = min(moving, key=lambda i: vmax[i] / dist[i])
                dominant = f"{self.robot.joint_names[k]} speed"
            elif moving:
                k = min(moving, key=lambda i: amax[i] / dist[i])
                dominant = f"{self.robot.joint_names[k]} acceleration"
            else:
                dominant = None

            def fn(t, q0=q0, q1=q1, start=start, T=T, v=v, ta=ta):
                s = _travel(t - start, 1.0, v, ta, T)
                return tuple(a + (b - a) * s for a, b in zip(q0, q1))
        else:
            from val3check.robot.kinematics import trsf_matrix

            p0 = self.robot.fk_matrix(q0, self.tool)
            p1 = trsf_matrix(TARGETS[target])
            d = [p1[i][3] - p0[i][3] for i in range(3)]
            length = math.sqrt(sum(x * x for x in d))
            T, v, ta = _trapezoid(length, desc["tvel"], CART_ACCEL)
            dominant = "tvel" if v >= desc["tvel"] - 1e-9 else "acceleration"
            cache: dict[float, tuple] = {}

            def fn(t, p0=p0, d=d, length=length, start=start, T=T, v=v, ta=ta, q0=q0, cache=cache):
                s = _travel(t - start, length, v, ta, T) / length if length else 1.0
                pose = [[p0[i][0], p0[i][1], p0[i][2], p0[i][3] + d[i] * s] for i in range(3)]
                near = cache.get("last", q0)
                q = self.robot.solve(pose, initial=near, tool=self.tool)
                cache["last"] = q
                return q
            q1 = self.targets[target]
        end = start + T
        self.pieces.append((start, end, fn))
        self.joints = q1
        self.arm_free = end
        self.motions.append({
            "id": len(self.motions) + 1, "kind": kind, "path": ROBOT_PGX, "line": line, "column": _column(ROBOT_PGX, line),
            "task": "robot", "target": target, "start": round(start, 6), "end": round(end, 6),
            "duration": round(T, 6), "dominant_limit": dominant, "vel": desc["vel"], "tvel": desc["tvel"],
            "min_clearance": None, "clearance_to": None,
        })
        return end

    # ---- the tasks --------------------------------------------------------------------------

    def script(self) -> None:
        tick = self.dt
        # Cell~ creates the tasks and ends
        self.seg("Cell~", 0.0, 2 * tick, "running", "start()")
        self.say(0.0, "Cell~", "title", "Cell")
        self.say(tick, "Cell~", "logMsg", "USR Cell started")
        self.monitor(2 * tick)
        self.hmi(2 * tick)
        self.scenario_pressure()
        self.robot_task(2 * tick)

    def monitor(self, t0: float) -> None:
        t, overrun_at = t0 + self.dt, 17.3
        while t < self.duration:
            run = 0.0004
            if abs(t - overrun_at) < MONITOR_PERIOD / 2:
                run = 0.124
                self.diags.append({
                    "code": "R005", "name": "sync-task-overrun", "severity": "warning",
                    "message": f"task monitor overran its period of {MONITOR_PERIOD:g} s ({run:g} s used): the next run "
                               "is skipped", "path": MONITOR_PGX, "line": 7, "column": 5, "time": round(t + run, 6),
                    "task": "monitor", "program": "monitor"})
            self.seg("monitor", t, t + run, "running", "monitor()")
            nxt = t + MONITOR_PERIOD * (2 if run > MONITOR_PERIOD else 1)
            self.seg("monitor", t + run, nxt, "waiting", "period")
            t = nxt

    def hmi(self, t0: float) -> None:
        key_at = min(31.2, self.duration * 0.52)
        self.seg("hmi", t0, t0 + self.dt, "running", "hmi()")
        self.say(t0 + self.dt, "hmi", "putln", "F1: slow speed")
        self.seg("hmi", t0 + self.dt, key_at, "blocked", "get (key)")
        self.say(key_at, "hmi", "get", "F1 [271]")
        self.seg("hmi", key_at, key_at + self.dt, "running", "hmi()")
        self.say(key_at + self.dt, "hmi", "putln", "speed: 50 %")
        self.seg("hmi", key_at + self.dt, self.duration, "blocked", "get (key)")

    def scenario_pressure(self) -> None:
        t, k = 0.0, 0
        while t <= self.duration:
            value = round(6.0 + 0.4 * math.sin(k * 1.3) - (0.7 if k == 2 else 0.0), 3)
            self.io_event(t, "aio", "Valve\\pressure", ["aiPressure"], value, "scenario")
            t, k = t + 7.5, k + 1

    def robot_task(self, t: float) -> None:
        tick, D = self.dt, self.duration
        self.seg("robot", t, t + tick, "running", "robotCycle()")
        t += tick
        end = self.queue(t, "movej", "home", "mFast", LINE["home"])
        self.seg("robot", t, end, "blocked", "waitEndMove")
        t = end
        part_at = 0.8
        self.io_event(part_at, "dio", "Conveyor\\part", ["diPartPresent"], True, "scenario")
        cycle = 0
        fail_cycle = 7 if self.failing else -1
        while t < D:
            start = t
            self.iterations.append({"start": round(start, 6), "duration": None, "complete": False})
            self.seg("robot", t, t + tick, "running", "robotCycle()")
            t += tick
            if part_at > t:
                self.seg("robot", t, part_at, "waiting", "wait(diPartPresent)")
                t = part_at
            self.io_event(t, "sio", "Camera\\socket", ["sioCamera"], "TRIG", "robot")
            self.seg("robot", t, t + CAMERA_REPLY, "blocked", "sio read")
            t += CAMERA_REPLY
            self.io_event(t, "sio", "Camera\\socket", ["sioCamera"],
                          f"OK {self.rng.uniform(-3, 3):.1f},{self.rng.uniform(-3, 3):.1f}", "scenario")
            if cycle == fail_cycle:
                self.seg("robot", t, t + tick, "running", "robotCycle()")
                self.diags.append({
                    "code": "R001", "name": "runtime-error", "severity": "error",
                    "message": "error 154: the target is out of reach (appro(pPick, trApp) after the camera's offset)",
                    "path": ROBOT_PGX, "line": LINE["app_pick"], "column": 5, "time": round(t + tick, 6),
                    "task": "robot", "program": "robotCycle"})
                self.seg("robot", t + tick, D, "stopped", "error 154")
                self.iterations.pop()
                break
            self.queue(t, "movej", "app_pick", "mFast", LINE["app_pick"])
            end = self.queue(t, "movel", "pick", "mSlow", LINE["pick"])
            self.seg("robot", t, end, "blocked", "waitEndMove")
            t = end
            self.io_event(t, "dio", "Gripper\\close", ["doGripper"], True, "robot")
            self.io_event(t + GRIP_TIME, "dio", "Gripper\\closed", ["diGripClosed"], True, "scenario")
            self.io_event(t + GRIP_TIME, "dio", "Conveyor\\part", ["diPartPresent"], False, "scenario")
            self.seg("robot", t, t + GRIP_TIME, "waiting", "close(tGripper)")
            t += GRIP_TIME
            part_at = t + self.rng.uniform(0.8, 2.6)
            if part_at <= D:
                self.io_event(part_at, "dio", "Conveyor\\part", ["diPartPresent"], True, "scenario")
            self.queue(t, "movel", "app_pick", "mDepart", LINE["dep_pick"])
            self.queue(t, "movej", "app_place", "mFast", LINE["app_place"])
            end = self.queue(t, "movel", "place", "mSlow", LINE["place"])
            self.seg("robot", t, end, "blocked", "waitEndMove")
            t = end
            self.io_event(t, "dio", "Gripper\\close", ["doGripper"], False, "robot")
            self.io_event(t + GRIP_TIME, "dio", "Gripper\\closed", ["diGripClosed"], False, "scenario")
            self.seg("robot", t, t + GRIP_TIME, "waiting", "open(tGripper)")
            t += GRIP_TIME
            self.queue(t, "movel", "app_place", "mDepart", LINE["dep_place"])
            self.seg("robot", t, t + tick, "running", "robotCycle()")
            t += tick
            cycle += 1
            if t <= D:
                self.say(t, "robot", "putln", f"cycle {cycle}: {t - start:.2f} s")
            self.iterations[-1].update(duration=round(t - start, 6), complete=t <= D)
            self.seg("robot", t, t + tick, "running", "robotCycle()")
            t += tick
        if self.iterations and not self.iterations[-1]["complete"]:
            self.iterations[-1]["duration"] = round(min(t, D) - self.iterations[-1]["start"], 6)

    # ---- samples ----------------------------------------------------------------------------

    def sample(self) -> tuple[list[float], list[tuple]]:
        n = int(round(self.duration / self.dt))
        times = [round(k * self.dt, 6) for k in range(n + 1)]
        pieces = sorted(self.pieces, key=lambda p: p[0])
        out, q, i = [], (0.0,) * 6, 0
        for t in times:
            while i < len(pieces) and pieces[i][1] <= t:
                q = pieces[i][2](pieces[i][1])
                i += 1
            if i < len(pieces) and pieces[i][0] <= t:
                q = pieces[i][2](t)
            out.append(tuple(q))
        return times, out


def _central(values: list[float], dt: float) -> list[float]:
    n = len(values)
    if n < 2:
        return [0.0] * n
    out = [(values[1] - values[0]) / dt]
    out += [(values[k + 1] - values[k - 1]) / (2 * dt) for k in range(1, n - 1)]
    out.append((values[-1] - values[-2]) / dt)
    return out


def _arm_segments(motions: list[dict], duration: float) -> list[dict]:
    segs, t = [], 0.0
    for m in motions:
        s, e = m["start"], min(m["end"], duration)
        if s >= duration:
            break
        if s > t + 1e-9:
            segs.append({"start": round(t, 6), "end": round(s, 6), "state": "idle"})
        if segs and segs[-1]["state"] == "moving" and abs(segs[-1]["end"] - s) < 1e-9:
            segs[-1]["end"] = round(e, 6)
        else:
            segs.append({"start": round(s, 6), "end": round(e, 6), "state": "moving"})
        t = e
    if t < duration:
        segs.append({"start": round(t, 6), "end": round(duration, 6), "state": "idle"})
    return segs


def _excerpt(path: str, line: int, around: int = 2) -> dict:
    lines = PROGRAMS[path].split("\n")
    first = max(1, line - around)
    return {"first_line": first, "lines": lines[first - 1:line + around]}


def synthetic_model(duration: float = 60.0, dt: float = 0.004, robot: str = "tx2-60", seed: int = 1,
                    failing: bool = False) -> dict:
    """A report model (docs/html-report.md) of a scripted pick-and-place run of `duration` simulated
    seconds sampled every `dt` seconds. `failing`: the robot task stops on error 154 in its 8th
    cycle (an error, a stopped task, a failed verdict)."""
    from val3check.robot import load_robot
    from val3check import __version__

    arm_model = load_robot(robot)
    run = _Run(arm_model, duration, dt, seed, failing)
    run.script()
    motions = [m for m in run.motions if m["start"] < duration]
    for m in motions:
        if m["end"] > duration:  # cut by the end of the run
            m["end"] = round(duration, 6)
            m["duration"] = round(duration - m["start"], 6)
    times, joints = run.sample()
    positions = [[round(q[i], 6) for q in joints] for i in range(6)]
    velocities = [[round(v, 4) for v in _central(col, dt)] for col in positions]
    tcp = [arm_model.fk_matrix(q, run.tool) for q in joints]
    speed_axes = [_central([T[i][3] for T in tcp], dt) for i in range(3)]
    tcp_speed = [round(math.sqrt(sum(speed_axes[i][k] ** 2 for i in range(3))), 3) for k in range(len(times))]
    obstacles = _obstacles()
    for m in motions:
        best, who = math.inf, None
        k0, k1 = int(math.ceil(m["start"] / dt)), int(math.floor(m["end"] / dt))
        for k in range(k0, min(k1, len(times) - 1) + 1):
            p = [tcp[k][i][3] for i in range(3)]
            for ob in obstacles:
                d = _distance(p, ob)
                if d < best:
                    best, who = d, ob["name"]
        if who is not None:
            m["min_clearance"], m["clearance_to"] = round(best, 1), who

    if duration > 0:
        alive = ", ".join(sorted(t for t in run.tasks if t != "Cell~" and (t != "robot" or not failing)))
        run.diags.append({"code": "R007", "name": "duration-reached", "severity": "info",
                          "message": f"run stopped at --duration {duration:g} s; tasks still alive: {alive}",
                          "path": "Cell/Cell.pjx", "line": None, "column": None, "time": round(duration, 6),
                          "task": None, "program": None})
    diags = sorted(run.diags, key=lambda d: (d["time"], d["task"] or ""))
    for d in diags:
        d["excerpt"] = _excerpt(d["path"], d["line"]) if d["line"] and d["path"] in PROGRAMS else None
    counts = {s: sum(1 for d in diags if d["severity"] == s) for s in ("error", "warning", "info")}
    complete = [it for it in run.iterations if it["complete"]]
    cycle_time = None
    if complete:
        mean = sum(it["duration"] for it in complete) / len(complete)
        cycle_time = {"seconds": round(mean, 6), "task": "robot",
                      "basis": f"mean of {len(complete)} complete iterations of the loop at line {LINE['loop']}"}
    tasks = [{"name": name, "segments": segs} for name, segs in run.tasks.items()]
    arm = arm_chain(arm_model.source, joint_names=arm_model.joint_names, name=arm_model.name,
                    source=f"robots/{Path(arm_model.source).name}")
    limits = arm_model.joint_limits
    return {
        "version": VERSION,
        "title": "Cell (synthetic run)",
        "tool": {"name": "val3check", "version": __version__},
        "application": {"name": "Cell", "path": "Cell/Cell.pjx"},
        "robot": {"name": arm_model.name},
        "synthetic": True,
        "verdict": {
            "counts": counts,
            "fail_on": "error",
            "passed": counts["error"] == 0,
            "end_reason": "duration",
            "end_message": "the simulated duration was reached",
            "simulated_duration": round(duration, 6),
            "cycle_time": cycle_time,
        },
        "diagnostics": diags,
        "motions": motions,
        "cycles": [{"task": "robot", "path": ROBOT_PGX, "line": LINE["loop"], "label": f"while true (line {LINE['loop']})",
                    "iterations": run.iterations}],
        "trajectory": {
            "joints": [{"name": n, "unit": "deg", "min": lo, "max": hi, "speed": s}
                       for n, (lo, hi), s in zip(arm_model.joint_names, limits, arm_model.nominal_speeds)],
            "times": times,
            "positions": positions,
            "velocities": velocities,
            "tcp_speed": tcp_speed,
        },
        "tasks": tasks,
        "arm_timeline": _arm_segments(motions, duration),
        "io": sorted(run.io, key=lambda e: e["time"]),
        "transcript": sorted(run.transcript, key=lambda e: e["time"]),
        "screen": None,
        "scene": {"arm": arm, "tool": _tool(), "obstacles": obstacles},
    }
