"""Chapter 3: the simple types. num, bit fields and strings are pure (`builtins/`, registered
here); dio, aio and sio act on the cell's inputs/outputs (3.5 - 3.7).

Inputs/outputs are links (3.5.1): a dio/aio/sio variable holds the `IOPoint` of the physical
input/output, shared by every variable linked to it. Writing an output tells the machine
(I/O log, the cell's reactions); reading a sio waits for data the scenario sends.
"""

from __future__ import annotations

import math
from typing import Any

from ...language.runtime_errors import Val3RuntimeError
from .. import builtins
from ..values import Arr, FaultyIOPoint, IOPoint, clip_string, is_io
from ..waiting import WAIT, WATCH, YIELD

E = Val3RuntimeError


def _int(v: float) -> int:
    return int(math.floor(v + 0.5))


# ---- operators of num and string (3.2.2, 3.4.2) ------------------------------------------------

# 3.2.2 `%`: remainder of the integer division, sign of the left operand, error 10 on zero;
# 3.4.2 `+`: concatenation limited to 128 bytes.
MOD = builtins.OPERATORS[("%", "num")]
CAT = builtins.OPERATORS[("+", "string")]


# ---- inputs / outputs (3.5 - 3.7) ----------------------------------------------------------------


def linked(io: Any, what: str) -> IOPoint:
    """The input/output of a dio/aio/sio value: 123 when not linked (3.5.1), 123/125 when the
    scenario says it does not work (ioStatus -2/-3)."""
    if type(io) is not IOPoint:
        if type(io) is FaultyIOPoint and io.link:
            _faulty(io)
        raise E(70, f"{what}: not an input/output")
    if not io.link:
        raise E(123, f"{io.kind} not linked to an input/output of the system")
    return io


def _faulty(io: IOPoint) -> None:
    """3.5.3: -2 the link matches no input/output of the system (error 123), -3 the device is in
    error (error 125, field bus error)."""
    if io.status == -2:
        raise E(123, f"{io.link} is not an input/output of the system (ioStatus -2)")
    raise E(125, f"the device of {io.link} is in error (ioStatus {io.status})")


def IOR(io: Any) -> bool:
    """The state of a dio (3.5.2)."""
    if type(io) is bool:
        return io
    if type(io) is not IOPoint or not io.link:
        linked(io, "dio")
    return io.value


def IOW(task, io: Any, v: bool) -> bool:
    """`dio = bool` (3.5.2): writes the output; error 123 unlinked, 122 on an input."""
    linked(io, "dio")
    if io.driven:
        raise E(122, f"write to the input {io.link}")
    v = bool(v)
    if io.status == 1:  # 3.5.3: locked by the operator, writing has no effect
        return v
    if io.value is not v:
        io.value = v
        task.machine.output_changed(task, io)
    return v


def _sio(io: Any) -> IOPoint:
    io = linked(io, "sio")
    if io.kind != "sio":
        raise E(70, "not a sio")
    return io


def peer_hint(machine, io: IOPoint) -> str:
    """What ends a wait for data on a sio: its peer (a serial device, a socket client or
    server), played by the scenario's [[serial]] entries (the deadlock report's R009)."""
    names = machine.link_names.get(("sio", io.link)) or [io.link]
    return (f"data from the peer of {', '.join(names)} ({io.link}): the scenario's [[serial]] entry with "
            f'sio = "{names[0]}" (docs/scenario.md)')


def _sio_wait(task, io: IOPoint, ready, what: str):
    """Wait for received data; returns False on the sio timeout (sioCtrl "timeout")."""
    if ready():
        return True
    if io.timeout > 0:
        return (yield from WATCH(task, ready, io.timeout, False, what))
    yield from WAIT(task, ready, False, what, peer_hint(task.machine, io))
    return True


def SIOR(task, io: Any, want: str):
    """3.7.2 `num = sio` reads one byte; `string = sio` reads up to the end-of-string
    character or 128 bytes."""
    io = _sio(io)
    if want == "num":
        ok = yield from _sio_wait(task, io, lambda: len(io.rx) > 0, "sio read")
        if not ok:
            raise E(125, f"timeout reading {io.link}")
        b = io.rx.pop(0)
        return float(b)

    def complete() -> bool:
        return io.eos in io.rx or len(io.rx) >= 128

    ok = yield from _sio_wait(task, io, complete, "sio read")
    if not ok:
        raise E(125, f"timeout reading {io.link}")
    if io.eos in io.rx[:129]:
        n = io.rx.index(io.eos)
        raw = bytes(io.rx[:n])
        del io.rx[: n + 1]
    else:
        raw = bytes(io.rx[:128])
        del io.rx[:128]
    return clip_string(raw.decode("utf-8", "ignore"))


def SIOW(task, io: Any, v: Any, vtype: str):
    """3.7.2 `sio = string` writes the UTF-8 text and the end-of-string character; `sio = num`
    writes the nearest integer modulo 256 and returns it."""
    io = _sio(io)
    if vtype == "string":
        data = v.encode("utf-8") + bytes([io.eos])
        result = v
    else:
        b = int(math.floor(v + 0.5)) % 256
        data = bytes([b])
        result = float(b)
    task.machine.sio_sent(task, io, data)
    if False:  # pragma: no cover - keeps this a generator
        yield
    return result


def _link_to(pair, src: Any, kind: str) -> None:
    if not is_io(src) or src.kind != kind:
        raise E(70, f"{kind}Link: the source is not a {kind}")
    c, k = pair
    c[k] = src


def I_diolink(task, unit, pair, src) -> None:
    _link_to(pair, src, "dio")


def I_aiolink(task, unit, pair, src) -> None:
    _link_to(pair, src, "aio")


def I_siolink(task, unit, pair, src) -> None:
    _link_to(pair, src, "sio")


def I_dioget(task, unit, arr: Arr) -> float:
    """3.5.3: diArray[0] + 2*diArray[1] + 4*diArray[2] + ..."""
    total = 0
    for i, io in enumerate(arr.data[arr.off:]):
        if linked(io, "dio").value:
            total += 1 << i
    return float(total)


def I_dioset(task, unit, arr: Arr, value: float) -> float:
    """3.5.3: the integer part of the value, in binary, on the outputs; returns what was set."""
    n = int(value) if value >= 0 else 0
    ios = arr.data[arr.off:]
    for io in ios:
        linked(io, "dio")
    total = 0
    for i, io in enumerate(ios):
        bit = bool((n >> i) & 1)
        IOW(task, io, bit)
        if bit:
            total += 1 << i
    return float(total)


def I_iostatus(task, unit, io, desc=None, path=None) -> float:
    """3.5.3 / 3.6.2: 0 works, 1 locked by the operator, 2 simulated, -1 link not defined,
    -2 the link matches no input/output, -3 the device is in error. A linked input/output
    works (0) unless the scenario's [io] table says otherwise (docs/scenario.md)."""
    if not is_io(io):
        raise E(70, "ioStatus: not an input/output")
    if desc is not None:
        desc[0][desc[1]] = clip_string(io.description)
    if path is not None:
        path[0][path[1]] = clip_string(io.link)
    return float(io.status) if io.link else -1.0


def I_aioget(task, unit, io) -> float:
    io = linked(io, "aio")
    return float(io.value)


def I_aioset(task, unit, io, value: float) -> float:
    """3.6.2 aioSet: writes the value and returns the value the output really takes (an integer
    output rounds it: aioSet(aiCommand, 12.3) writes and returns 12)."""
    io = linked(io, "aio")
    if io.driven:
        raise E(122, f"write to the input {io.link}")
    if io.integer:
        value = float(_int(value))
    if io.status == 1:  # locked by the operator: writing has no effect
        return float(io.value)
    if io.value != value:
        io.value = float(value)
        task.machine.output_changed(task, io)
    return float(value)


def I_clearbuffer(task, unit, io) -> float:
    io = _sio(io)
    n = len(io.rx)
    io.rx.clear()
    return float(n)


def I_sioget(task, unit, io, arr: Arr):
    """3.7.3 sioGet: read what was received into the array (waits for data; -1 on timeout)."""
    io = _sio(io)
    ok = yield from _sio_wait(task, io, lambda: len(io.rx) > 0, "sioGet")
    if not ok:
        return -1.0
    room = arr.size()
    n = min(room, len(io.rx))
    for i in range(n):
        arr.data[arr.off + i] = float(io.rx[i])
    del io.rx[:n]
    return float(n)


def I_sioset(task, unit, io, arr: Arr, count: float | None = None):
    """3.7.3 sioSet: write the array's values (nearest integer modulo 256). s8 calls it with a
    third argument whose meaning is not public (language/s8.toml); the simulator reads it as the
    number of values to send (docs/sim.md)."""
    io = _sio(io)
    values = arr.data[arr.off:]
    if count is not None:
        values = values[:max(0, _int(count)) if math.isfinite(count) else 0]
    data = bytes(int(math.floor(v + 0.5)) % 256 for v in values)
    task.machine.sio_sent(task, io, data)
    yield from YIELD(task)
    return float(len(data))


_SIO_PARAMS = {"port": float, "target": str, "clients": float, "endOfString": float, "timeout": float,
               "baudRate": float, "parity": str, "bits": float, "stopBits": float, "mode": str,
               "flowControl": str, "nagle": bool}


_SIO_VALUES = {"parity": ("none", "even", "odd"), "bits": (5, 6, 7, 8), "stopBits": (1, 2), "mode": ("rs232", "rs422"),
               "flowControl": ("none", "hardware")}


def I_sioctrl(task, unit, io, name: str, value: Any) -> float:
    """3.7.3 sioCtrl: 0 changed, -1 unknown parameter, -2 wrong type, -3 value not supported.

    "timeout": "0 signifie : pas de limite de délai"; a negative timeout is what the pendant's
    socket configuration and public code that runs on controllers write for no time limit (the
    ROS-Industrial driver's sioCtrl(siSocket, "timeout", -1), "Timeout: -1" in its README): no
    limit too. "port" is a TCP port (0 to 65535)."""
    io = _sio(io)
    want = _SIO_PARAMS.get(name)
    if want is None:
        return -1.0
    if type(value) is not want:
        return -2.0
    if name == "endOfString":
        if not 0 <= value <= 255:
            return -3.0
        io.eos = _int(value)
    elif name == "timeout":
        io.timeout = float(value) if value > 0 else 0.0
    elif (name in _SIO_VALUES and (_int(value) if want is float else value) not in _SIO_VALUES[name]
          or name in ("port", "clients", "baudRate") and (value < 0 or value != _int(value))
          or name == "port" and value > 65535):
        return -3.0
    io.params[name] = value
    return 0.0


def register(registry) -> None:
    for entry in builtins.PURE.values():  # num (3.2), bit fields (3.3), string (3.4)
        if entry.section.startswith("3."):
            registry.builtin(entry)
    for name, func in (("dioLink", I_diolink), ("aioLink", I_aiolink), ("sioLink", I_siolink), ("dioGet", I_dioget),
                       ("dioSet", I_dioset), ("ioStatus", I_iostatus), ("aioGet", I_aioget), ("aioSet", I_aioset),
                       ("clearBuffer", I_clearbuffer), ("sioCtrl", I_sioctrl)):
        registry.instruction(name, func)
    registry.instruction("sioGet", I_sioget, blocking=True)
    registry.instruction("sioSet", I_sioset, blocking=True)
    registry.helpers(MOD=MOD, CAT=CAT, IOR=IOR, IOW=IOW, SIOR=SIOR, SIOW=SIOW)
