"""The arm's plan: the path built from the commands as they are recorded, and its time
parameterisation over simulated time (docs/motion.md, "When the program is ahead of the arm").

    planner = Planner(kin, q0, limits_of, on_fallback)
    opened = planner.extend(command, previous, now, can_move)  # join a command to the path
    planner.close(command)                                     # a blended command goes to its target
    planner.flush()                                            # do the replan due (before reading)
    planner.brake(now)                                         # stop on the path

The path (paths.Path) only grows at its end; the profile (trajectory.Profile) is cut at the
replanning time and continued from the exact state there. A replan is due from the start of the
final braking of the trajectory planned so far (everything before it does not depend on where
the path ends), or from the moment of the record when that is later; it is done when something
reads the profile (`flush`), so that a burst of records is timed once: a record merges into the
replan due when it comes before that replan's start (exactly the same result) or, from rest,
within MERGE_WINDOW of the first record.

Blends (10.1.2): `extend` builds the blend from the previous command (blending.candidate) and
keeps it only when it is no slower than stopping at the via point (`blend_pays`, docs/motion.md).
Times come from timing.Timing, the one place where a path and its limits become a profile.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .blending import candidate, distance_lambda
from .paths import Path, Span
from .queued import Nominal
from .timing import Timing
from .trajectory import Profile, Trajectory
from .trial_memo import TrialMemo, frozen

# Commands recorded less than this apart while the arm starts from rest are timed together: in
# that time the arm moves less than a micrometre, the same whichever way it is computed.
MERGE_WINDOW = 0.001


class DueReplan(NamedTuple):
    """A replan not done yet: from time `t_from`, asked at `t_asked`, the arm then at rest."""

    t_from: float
    t_asked: float
    from_rest: bool


class Planner:
    """See the module docstring. `limits_of(key)`: the mdesc.Limits of a command (by key);
    `on_fallback(key)`: called when a planned piece of path that command starts fell back to the
    safe profile (R019)."""

    def __init__(self, kin, q0: np.ndarray, limits_of, on_fallback, value_keys: dict | None = None) -> None:
        """An arm at rest at joints q0, nothing planned (`value_keys`: trial_memo.TrialMemo's)."""
        self.kin = kin
        self.limits_of = limits_of
        self.on_fallback = on_fallback
        self.path = Path(q0)
        self.profile = Profile(0.0, 0.0)
        self.trajectory = Trajectory(self.path, self.profile)
        self.timing = Timing(kin)
        self.memo = TrialMemo(kin, self.timing, limits_of, value_keys)  # a repeated blend decision's timings
        self.due: DueReplan | None = None
        self.changes = 0  # counts the changes of the profile (what is read from it is kept until it changes)
        self.fallbacks = 0  # pieces planned with the safe profile
        self.stops_chosen = 0  # junctions where stopping at the via point was chosen (`blend_pays`)
        self._samples: dict = {}  # samples of spans timed in trials, reused when the span is added

    # ---- building the path ---------------------------------------------------------------------

    def extend(self, command, previous, now: float, can_move: bool) -> bool:
        """Join `command` (a QueuedCommand) to the end of the path, after `previous` (the last
        command, left blended, or None): through the blend when it pays, else `previous` is closed
        and the arm stops at its target. True when `command` is left blended, waiting for the
        next command (it ends, for now, at its leave point)."""
        hard = True
        if previous is not None:
            cand = (candidate(self.kin, previous, command, self.limits_of)
                    if command.geometry.joint_curve is not None else None)
            if cand is not None and not self.blend_pays(previous, command, cand, now, can_move):
                cand = None  # stopping at the via point is faster: the arm does that
            if cand is None:
                self.close(previous)
            else:
                self._commit_blend(previous, command, cand)
                hard = False
        opened = False
        place = command.placement
        curve = command.geometry.joint_curve
        if curve is None:
            place.s_begin = place.s_end = self.path.end
        else:
            if place.blend != "off":
                lam_l = distance_lambda(self.kin, command, command.request.mdesc.leave, from_end=True)
                if lam_l is None or lam_l <= place.lam_in + 1e-9:
                    place.blend = "off"
                else:
                    place.lam_leave = lam_l
            if hard:
                place.s_begin = self.path.end
            b = place.lam_leave if place.blend != "off" else 1.0
            s0 = self.path.end
            if b > place.lam_in + 1e-12:
                sp = self.span(curve, place.lam_in, b, [(command.key, 0.0)], smooth=not hard, tool=command.tool)
                self.path.append(sp)
                place.spans.append(sp)
            place.nominal = Nominal(s0, self.path.end, b)
            if place.blend != "off":
                opened = True
                place.s_provisional = self.path.end + (1.0 - place.lam_leave) * curve.ell
            else:
                place.s_end = self.path.end
        self.replan(now, previous is not None, can_move)
        return opened

    def close(self, command) -> None:
        """The command goes to its target and stops there (no blend): the rest of its path."""
        place = command.placement
        if place.lam_leave < 1.0 - 1e-12:
            sp = self.span(command.geometry.joint_curve, place.lam_leave, 1.0, [(command.key, 0.0)], smooth=True,
                           tool=command.tool)
            self.path.append(sp)
            place.spans.append(sp)
            if place.nominal is not None:
                place.nominal = Nominal(place.nominal.s_start, self.path.end, 1.0)
        place.blend = "off"
        place.lam_leave = 1.0
        place.s_end = self.path.end
        place.s_provisional = None

    def _commit_blend(self, previous, command, cand) -> Span:
        """Add the blend `cand` (blending.Candidate) from `previous` to `command` to the path."""
        sp = self.span(cand.curve, 0.0, 1.0, [(previous.key, 0.0), (command.key, cand.split)], smooth=True,
                       tool=previous.tool)
        off = self.path.append(sp)
        previous.placement.spans.append(sp)
        command.placement.spans.append(sp)
        previous.placement.s_end = off + cand.split
        previous.placement.s_provisional = None
        command.placement.s_begin = off + cand.split
        command.placement.lam_in = cand.lam_reach
        return sp

    def span(self, curve, a, b, owners, smooth, tool) -> Span:
        """A span, with the samples of an identical one timed in a trial (`blend_pays`)."""
        sp = Span(curve, a, b, owners, smooth, tool)
        hit = self._samples.get((id(curve), a, b))
        if hit is not None and hit[0] is curve and hit[1] is tool:
            sp._cache = hit[2]
        return sp

    def _remember(self, sp: Span) -> None:
        """Keep the samples of a span timed in a trial, for `span`."""
        if sp._cache is not None:
            if len(self._samples) > 64:
                self._samples.clear()
            self._samples[(id(sp.geom), sp.a, sp.b)] = (sp.geom, sp.tool, sp._cache)

    # ---- the blend or the stop -----------------------------------------------------------------

    def blend_pays(self, previous, command, cand, now: float, can_move: bool) -> bool:
        """Whether the arm gets to `command`'s target through the blend `cand` no later than by
        stopping at the via point (`previous`'s target), from the state the re-timing will start
        from.

        10.1.2.1: blending is there to make the motion faster, and 10.1.2.3 lets the controller
        choose the blend's shape for speed; a blend of an awkward shape (very different leave
        and reach) can be slower than the stop it replaces, and then the arm stops at the via
        point instead. The blend is timed exactly (as the plan will time it, `command` closed at
        its target), and so is the stop (to the via point, then `command` alone from rest to
        rest); the blend is kept when it is no slower. By induction over the commands
        (docs/motion.md), a chain recorded ahead of the arm is then never slower than the same
        commands unblended."""
        prof = self.profile
        if self.due is not None:
            t0 = self.due.t_from
        elif can_move:
            t0 = max(now, prof.T[prof.final_decel_start()])
        else:
            t0 = prof.t_end
        s0, v0, _ = prof.state(t0)
        if t0 >= prof.t_end:
            s0, v0 = prof.s_end, 0.0
        t_blend, t_stop, rest = self._trials(s0, v0, previous, command, cand)
        if command.rest_time is None:
            command.rest_time = rest
        t_stop += command.rest_time
        if t_blend <= t_stop * (1.0 + 1e-9):
            return True
        self.stops_chosen += 1
        return False

    def _trials(self, s0: float, v0: float, previous, command, cand):
        """What `blend_pays` compares, from path position s0 at speed v0: the blend trial's duration
        (the blend `cand`, then `command` to its target), the stop trial's duration (`previous` to
        its target), and the time of `command` alone from rest to rest.
        Trials are timed as `plan_from` times the path followed by their spans (not added to it).
        The three are remembered together (trial_memo.py): a cyclic program decides the same blend
        from the same state every cycle. Their spans are a function of the two commands' classes
        (queued.QueuedCommand.cls), `previous`'s blend and leave point (the blend too: blending.candidate),
        so the key names them by those and they are built only when the trials are computed."""
        path = self.path
        ahead, shift = [], 0.0
        if path.spans:
            i0, _ = path.locate(s0)
            ahead, shift = path.spans[i0:], path.offsets[i0]
        a = s0 - shift
        place = previous.placement
        key = None
        if previous.cls is not None and command.cls is not None:
            key = self.memo.key(ahead, a, v0, previous.cls, place.blend, place.lam_leave, command.cls, "pays",
                                owners=(previous.key, command.key))
            hit = self.memo.get(key, ahead, self.profile.speed_at, shift)
            if hit is not None:  # (the hit path: nothing else is built)
                return hit

        def trials(asked):
            blended = [self.span(cand.curve, 0.0, 1.0, [(previous.key, 0.0), (command.key, cand.split)], smooth=True,
                                 tool=previous.tool),
                       self.span(command.geometry.joint_curve, cand.lam_reach, 1.0, [(command.key, 0.0)], smooth=True,
                                 tool=command.tool)]
            tail = self.span(previous.geometry.joint_curve, previous.placement.lam_leave, 1.0, [(previous.key, 0.0)],
                             smooth=True, tool=previous.tool)
            alone = self.span(command.geometry.joint_curve, 0.0, 1.0, [(command.key, 0.0)], smooth=False,
                              tool=command.tool)
            t_blend = _duration(self._timed(ahead, a, v0, blended, asked))
            t_stop = _duration(self._timed(ahead, a, v0, [tail], asked))
            answer = (t_blend, t_stop, self._rest_time(alone, command.geometry.q_start))
            for sp in blended + [tail]:  # the one chosen is sampled once
                self._remember(sp)
            return answer, True

        return self._computed(key, ahead, shift, trials)

    def _rest_time(self, alone: Span, q_start) -> float:
        """The time of a command alone (its whole curve, the span `alone`, from joints q_start),
        from rest to rest."""
        trial = Path(q_start)
        trial.append(alone)
        rest = self.timing.time(trial, 0.0, trial.end, 0.0, self.limits_of).duration
        self._remember(alone)
        return rest

    def _timed(self, ahead: list, a: float, v0: float, extra: list, asked) -> list:
        """The timed pieces (timing.TimedPiece) of the arm from position a of the spans `ahead` (the
        path's, a relative to the first) at speed v0 to the end of them followed by the spans
        `extra`: s relative to the first span ahead, so that a repeated motion is timed on the same
        grid to the bit wherever it lies on the run's path. `asked(g, a)`: the plan's speed where
        the re-timing starts (timing.Timing.time_from)."""
        trial = Path(self.path.q_rest)
        for sp in ahead:
            trial.append(Span(sp.geom, sp.a, sp.b, sp.owners, sp.smooth, sp.tool, _cache=sp._cache))
        for sp in extra:
            trial.append(sp)
        pieces = []
        for b in trial.stops_after(a) + [trial.end]:
            if b - a <= _eps(b):
                a = b
                continue
            pieces.append(self.timing.time_from(trial, a, b, v0, self.limits_of, asked))
            a, v0 = b, 0.0
        return pieces

    # ---- timing ----------------------------------------------------------------------------------

    def merges(self, now: float) -> bool:
        """A record at `now` merges into the replan due (the same result as a replan of its own)."""
        due = self.due
        return due is not None and (now <= due.t_from + 1e-12 or (due.from_rest and now - due.t_asked <= MERGE_WINDOW))

    def replan(self, now: float, from_final_decel: bool, can_move: bool) -> None:
        """Re-time what the path added changes, from the start of the final braking (or the end of
        the motion ahead), or now when that is past (see the module docstring). Nothing while the
        arm cannot move."""
        if not can_move:
            return
        if self.due is not None:
            if self.merges(now):
                return
            self.flush()
        if from_final_decel:
            k = self.profile.final_decel_start()
            t_r = max(now, self.profile.T[k])
        else:
            t_r = max(now, self.profile.t_end)
        self.due = DueReplan(t_r, now, t_r >= self.profile.t_end)

    def flush(self) -> None:
        """Do the replan due (before anything reads the profile)."""
        if self.due is not None:
            t_r = self.due.t_from
            self.due = None
            self.plan_from(t_r)

    def plan_from(self, t_r: float) -> None:
        """Cut the profile at t_r and time the rest of the path from the arm's state there: timed
        relative to the span the arm is on (`_plan`), then shifted to the path's positions."""
        prof = self.profile
        self.changes += 1
        prof.cut(t_r)
        s_r, sd_r = prof.s_end, prof.SD[-1]
        path = self.path
        if path.end - s_r <= _eps(s_r):
            if sd_r > 0:  # numerically at the end: stop there
                prof.SD[-1] = 0.0
            return
        i0, _ = path.locate(s_r)
        shift = path.offsets[i0]
        T, S, SD = self._plan(path.spans[i0:], s_r - shift, sd_r, shift)
        prof.extend_shifted(max(t_r, prof.t_end), T, S, SD, shift, path.end)

    def _plan(self, ahead: list, a: float, v0: float, shift: float) -> tuple:
        """The plan of the spans `ahead` (the path's from the one holding the arm, at `shift`) from
        a (relative to the first) at speed v0: its breakpoints after the start as read-only arrays
        (times from the start, s relative to the first span, ṡ). Remembered (trial_memo.py) with
        the plan's speeds it asked: a cyclic program plans the same spans from the same state every
        cycle, and its plan is then one look-up (pieces that fell back, R019, are not kept)."""
        key = self.memo.key(ahead, a, v0, "plan")
        hit = self.memo.get(key, ahead, self.profile.speed_at, shift)
        if hit is not None:
            return hit

        def plan(asked):
            pieces = self._timed(ahead, a, v0, [], asked)
            fell = False
            for piece in pieces:
                if piece.fallback:
                    fell = True
                    self.fallbacks += 1
                    self.on_fallback(piece.owner)
            return _joined(pieces), not fell

        return self._computed(key, ahead, shift, plan)

    def _computed(self, key, spans: list, shift: float, compute):
        """`compute(asked)`'s answer, remembered under `key` (trial_memo.py; None: not remembered)
        with the plan's speeds it asked: `asked(g, a)` reads them on the path, the spans being at
        `shift`. `compute` returns (answer, whether it may be kept). The look-up comes first
        (`TrialMemo.get`, the same speeds read): a hit builds nothing."""
        speed_at = self.profile.speed_at
        calls = []

        def asked(g, a_):
            v = speed_at(g + shift, a_ + shift)
            calls.append((g, a_, v))
            return v

        started = self.memo.start()
        try:
            answer, keep = compute(asked)
        finally:
            self.memo.stop()
        if keep:
            self.memo.keep(key, spans, started, calls, answer)
        return answer

    def brake(self, now: float) -> None:
        """Stop on the path at once with the decelerations of the commands being executed
        (stopMove, resetMotion, power off, monitor speed 0)."""
        self.flush()
        prof = self.profile
        self.changes += 1
        prof.cut(now)
        sd = prof.SD[-1]
        if sd <= 0.0:
            return
        s_r = prof.s_end
        stops = self.path.stops_after(s_r) + [self.path.end]
        s, v = self.timing.brake(self.path, s_r, stops[0], sd, self.limits_of)
        prof.append(prof.t_end, s, v)


def _eps(s: float) -> float:
    """A tolerance on path positions: s grows over a run (and so do its rounding errors)."""
    return 1e-12 * max(1.0, abs(s))


def _duration(pieces: list) -> float:
    """The time of timed pieces one after the other."""
    total = 0.0
    for piece in pieces:
        total += piece.duration
    return total


def _joined(pieces: list) -> tuple:
    """Timed pieces (each from rest but the first, to rest) as one plan: the breakpoints after the
    start (times from it, s, ṡ), read-only, as trajectory.Profile.append would add them piece by
    piece (an interval that does not move is dropped)."""
    dts, ss, sds = [], [], []
    for piece in pieces:
        s, sd = piece.s, piece.sd
        ds = s[1:] - s[:-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            dt = np.where(ds > 0, 2.0 * ds / np.maximum(sd[:-1] + sd[1:], 1e-300), 0.0)
        keep = ~(ds <= 0.0)
        dts.append(dt[keep])
        ss.append(s[1:][keep])
        sds.append(sd[1:][keep])
    if not dts:
        return tuple(frozen(np.zeros(0)) for _ in range(3))
    return frozen(np.cumsum(np.concatenate(dts))), frozen(np.concatenate(ss)), frozen(np.concatenate(sds))
