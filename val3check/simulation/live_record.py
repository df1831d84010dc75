"""The run's motion records taken as the run goes (issue 29): a command's record is made once it
is final, and the command then leaves the queue's history, so that what a finished command keeps
is its record (motion_records.MotionRecord), its loops and what its row of the motion table reads.

A command is final when its state can no longer change (done, or failed at its recording) and the
profile and path its record reads are final: the profile up to the first breakpoint past its end
(its record reads the interval that straddles its end, and the arm's rests there), before the time
the queue says the profile can no longer change (`MotionQueue.final_before`), and the path's span
there wholly behind the arm (resetMotion cuts the path where the arm stops). Commands are taken in
recording order: a cancelled command (its record reads the profile as the run ends) and everything
after it wait for the end of the run, as do the commands not final by then. The records are made
by the same `RecordMaker`, in the same order, as after the run; the blocks not full are evaluated
every RECORD_BLOCK commands, the near ties decided once DECIDE_BLOCK of them wait (a record's
figures do not depend on the commands evaluated with it): the same bits
(tests/interpretation/test_live_record.py).

Commands are released from the history only while nothing of chapter 11 reads it by index
(arm_layers.Residuals, alteration.py, compliance.py): once one does, the history is kept whole
from then on.

    live = LiveRecord()
    live.take(arm, queue)              # after each advance of the queue
    records = live.records(queue, end_s)    # after the run: every record, in recording order
    live.kept, live.contexts                # per command: (request, q_start, q_end, state), its loops
"""

from __future__ import annotations

import bisect
from typing import Any

from ..motion import trajectory
from ..motion.history import History
from ..motion.motion_records import RECORD_BLOCK, MotionRecord, RecordMaker

RELEASE_AT = 256  # commands taken before the history is trimmed (a trim moves what is left)


class LiveRecord:
    """See the module docstring."""

    def __init__(self) -> None:
        self._bind(None)

    def _bind(self, queue: Any) -> None:
        """Nothing taken yet, of `queue`."""
        self.queue = queue
        self.maker = None if queue is None else RecordMaker(queue)
        self.kept: list[tuple] = []  # per command taken: (request, q_start, q_end, state)
        self.contexts: list = []  # per command taken: the loops it was recorded in
        self.cursor = 0  # commands of the history taken and not yet released
        self.releasing = True
        self.blocked = False  # a cancelled command met: the rest waits for the end of the run
        self._records: tuple | None = None  # (end_s, the records) once finished
        self._flushed = 0  # commands taken when the maker last made every record
        self._wait: tuple | None = None  # (the next command, the time before which it is not final)

    def take(self, arm: Any, queue: Any) -> None:
        """Make the records of the commands become final (module docstring), release them."""
        if queue is not self.queue:
            self._bind(queue)
        if self.blocked or self._records is not None:
            return
        history = queue.history
        i = self.cursor
        if i >= len(history):
            return
        state = history[i].state
        if state != "done" and state != "failed":  # (mostly: the next command is still under way)
            self.blocked = state == "cancelled"
            return
        final = queue.final_before()
        wait = self._wait
        if wait is not None and wait[0] is history[i] and final < wait[1]:
            return  # (asked at every advance of the arm: mostly nothing new is final)
        self._wait = None
        prof, path = queue.planner.profile, queue.path
        S, T = prof.S, prof.T
        # the chunk being written, read in place (History; T is chunked as S): the hot case
        tail = S.tail if S.__class__ is History and S.tail_len else None
        offsets, spans = path.offsets, path.spans
        behind = None  # where the arm is at `final` (found when first needed)
        while i < len(history):
            command = history[i]
            state = command.state
            if state == "done":
                place = command.placement
                if place.s_begin is not None:
                    s = max(place.s_begin, place.s_end)
                    x = s + 1e-9 * max(1.0, abs(s))
                    if tail is not None and tail[0] <= x:  # (mostly)
                        m = bisect.bisect_right(tail, x, 0, S.tail_len)
                        if m >= S.tail_len:
                            break
                        t_k, s_k = T.tail[m], tail[m]
                    else:
                        k = trajectory.bisect_right(S, x)
                        if k >= len(S):
                            break
                        t_k, s_k = T[k], S[k]
                    if t_k > final:
                        self._wait = (command, t_k)  # (the breakpoint is there: only its time can come)
                        break
                    if behind is None:
                        behind = prof.state(final)[0]
                    if spans:  # (path.locate)
                        j = min(max(bisect.bisect_right(offsets, s_k) - 1, 0), len(spans) - 1)
                        end = offsets[j] + spans[j].length
                        if end > behind:
                            # a resetMotion could still cut that span: not before the arm leaves it
                            t = prof.time_at(end)
                            self._wait = None if t is None else (command, t)
                            break
            elif state != "failed":
                self.blocked = state == "cancelled"
                break
            self._take(arm, command)
            i += 1
        self.cursor = i
        if len(self.kept) - self._flushed >= RECORD_BLOCK:  # their records made now, not after the run
            self.maker.flush(ties=False)
            self._flushed = len(self.kept)
        if i >= RELEASE_AT and self.releasing:
            # what chapter 11 does to the arm stays in its state (the layers, the alterable keys,
            # the compliant moves): asked only when about to release
            if _history_read(arm):
                self.releasing = False
            else:
                queue.release(i)
                self.cursor = 0

    def _take(self, arm: Any, command: Any, end_s: float | None = None, reached: float | None = None) -> None:
        """The record of a final command, and what the motion table and the cycles read of it
        (`end_s`, `reached`: as `RecordMaker.add`)."""
        self.maker.add(command, end_s, reached)
        g = command.geometry
        self.kept.append((command.request, g.q_start, g.q_end, command.state))
        self.contexts.append(arm.contexts.pop(command.key, ()))

    def settle(self, arm: Any, queue: Any, now_s: float) -> None:
        """Before setDH changes the geometry (11.4): it "attend que le mouvement soit vide", so every
        command recorded so far has ended and nothing can change what its record reads; their
        records are made now, with the geometry they ran in (made later, they would read the new
        one). No later command is taken for a repeat of them: repeats are keyed by the path's
        geometry objects (record_repeats.py), which setDH makes anew (kin.Reuse cleared)."""
        if queue is not self.queue:
            self._bind(queue)
        if self._records is not None:
            return
        self.take(arm, queue)
        history = queue.history
        reached = queue.trajectory.profile.state(now_s)[0]
        for command in history[self.cursor:]:  # the last ones (no breakpoint after them yet), a cancelled one
            self._take(arm, command, now_s, reached)
        self.cursor, self.blocked, self._wait = len(history), False, None
        self.maker.flush()
        self._flushed = len(self.kept)

    def records(self, arm: Any, queue: Any, end_s: float) -> list[MotionRecord]:
        """Every command's record after the run (ended at queue time `end_s`): those taken, then the
        rest of the history made as `motion_records` makes them. Once: asked again with the same
        end, the same list."""
        if queue is not self.queue:
            self._bind(queue)
        if self._records is not None:
            if self._records[0] != end_s:
                raise ValueError("the run's records are already made for another end")
            return self._records[1]
        prof = queue.trajectory.profile  # (up to date)
        reached = prof.state(end_s)[0]
        for command in queue.history[self.cursor:]:
            self.maker.add(command, end_s, reached)
            g = command.geometry
            self.kept.append((command.request, g.q_start, g.q_end, command.state))
            self.contexts.append(arm.contexts.get(command.key, ()))
        self.cursor = len(queue.history)
        self._records = (end_s, self.maker.finish())
        self.maker = None
        return self._records[1]


def _history_read(arm: Any) -> bool:
    """Whether chapter 11 reads the queue's history by index or by search (module docstring)."""
    layers = getattr(arm, "layers", None)
    alteration = getattr(arm, "alteration", None)
    compliance = getattr(arm, "compliance", None)
    return ((layers is not None and not layers.trivial)
            or (alteration is not None and (alteration.alterable or alteration.state != "off" or alteration.deferred))
            or (compliance is not None and bool(compliance.moves)))
