"""Instructions of chapters 3 (I/O), 4 (user page), 5 (tasks), 6 (libraries) and 8 (robot
control) that act on the simulated controller. Pure ones (math, strings, bit fields) are in
`builtins/`; those on variables (size, insert...) are helpers in `runtime.py`.

`I_<name>(T, A, *args)`: T the running task, A the unit executing the line. Names in `ASYNC`
are generators (they may block or hand over, 5.4).
"""

from __future__ import annotations

import math
import re
from typing import Any

from ..language.runtime_errors import Val3RuntimeError
from .runtime import DELAY, YIELD, _linked, _sio, _sio_wait, help_text
from .values import Arr, Screen, clip_string, is_io

E = Val3RuntimeError
SYNC: set[str] = set()
ASYNC: set[str] = set()
TABLE: dict[str, Any] = {}


def sync(fn):
    name = fn.__name__[2:]
    SYNC.add(name)
    TABLE[f"I_{name}"] = fn
    return fn


def async_(fn):
    name = fn.__name__[2:]
    ASYNC.add(name)
    TABLE[f"I_{name}"] = fn
    return fn


def _int(v: float) -> int:
    return int(math.floor(v + 0.5))


# ---- chapter 5: tasks ---------------------------------------------------------------------------


@async_
def I_tasksuspend(T, A, name: str):
    """5.10 taskSuspend: error 30 when no task of this name is visible (5.3)."""
    target = T.M.find_task(A, name)
    if target is None:
        raise E(30, f'no task "{name}"')
    T.M.suspend(target)
    if target is T:
        yield


@async_
def I_taskresume(T, A, name: str, jump: float):
    """5.10 taskResume: restart a STOPPED task `jump` lines from where it stopped."""
    target = T.M.find_task(A, name)
    if target is None:
        raise E(30, f'no task "{name}"')
    T.M.resume(target, _int(jump))
    yield from YIELD(T)


@async_
def I_taskkill(T, A, name: str):
    """5.10 taskKill: no effect when no such task is visible."""
    target = T.M.find_task(A, name)
    if target is None:
        return
    T.M.kill(target, by=T)
    yield from YIELD(T)


@sync
def I_taskstatus(T, A, name: str) -> float:
    target = T.M.find_task(A, name)
    if target is None:
        return -1.0
    return float(T.M.status_code(target))


@sync
def I_help(T, A, code: float) -> str:
    return clip_string(help_text(code))


@async_
def I_delay(T, A, s: float):
    yield from DELAY(T, s)


@sync
def I_clock(T, A) -> float:
    """5.10 clock: seconds since the controller started, millisecond precision."""
    return round(T.M.clock_us(T) / 1000.0) / 1000.0


# ---- chapter 3: dio, aio, sio -------------------------------------------------------------------


def _link_to(pair, src: Any, kind: str) -> None:
    if not is_io(src) or src.kind != kind:
        raise E(70, f"{kind}Link: the source is not a {kind}")
    c, k = pair
    c[k] = src


@sync
def I_diolink(T, A, pair, src) -> None:
    _link_to(pair, src, "dio")


@sync
def I_aiolink(T, A, pair, src) -> None:
    _link_to(pair, src, "aio")


@sync
def I_siolink(T, A, pair, src) -> None:
    _link_to(pair, src, "sio")


@sync
def I_dioget(T, A, arr: Arr) -> float:
    """3.5.3: diArray[0] + 2*diArray[1] + 4*diArray[2] + ..."""
    total = 0
    for i, io in enumerate(arr.data[arr.off:]):
        if _linked(io, "dio").value:
            total += 1 << i
    return float(total)


@sync
def I_dioset(T, A, arr: Arr, value: float) -> float:
    """3.5.3: the integer part of the value, in binary, on the outputs; returns what was set."""
    from .runtime import IOW

    n = int(value) if value >= 0 else 0
    ios = arr.data[arr.off:]
    for io in ios:
        _linked(io, "dio")
    total = 0
    for i, io in enumerate(ios):
        bit = bool((n >> i) & 1)
        IOW(T, io, bit)
        if bit:
            total += 1 << i
    return float(total)


@sync
def I_iostatus(T, A, io, desc=None, path=None) -> float:
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


@sync
def I_aioget(T, A, io) -> float:
    io = _linked(io, "aio")
    return float(io.value)


@sync
def I_aioset(T, A, io, value: float) -> float:
    """3.6.2 aioSet: writes the value and returns the value the output really takes (an integer
    output rounds it: aioSet(aiCommand, 12.3) writes and returns 12)."""
    io = _linked(io, "aio")
    if io.driven:
        raise E(122, f"write to the input {io.link}")
    if io.integer:
        value = float(_int(value))
    if io.status == 1:  # locked by the operator: writing has no effect
        return float(io.value)
    if io.value != value:
        io.value = float(value)
        T.M.output_changed(T, io)
    return float(value)


@sync
def I_clearbuffer(T, A, io) -> float:
    io = _sio(io)
    n = len(io.rx)
    io.rx.clear()
    return float(n)


@async_
def I_sioget(T, A, io, arr: Arr):
    """3.7.3 sioGet: read what was received into the array (waits for data; -1 on timeout)."""
    io = _sio(io)
    ok = yield from _sio_wait(T, io, lambda: len(io.rx) > 0)
    if not ok:
        return -1.0
    room = arr.size()
    n = min(room, len(io.rx))
    for i in range(n):
        arr.data[arr.off + i] = float(io.rx[i])
    del io.rx[:n]
    return float(n)


@async_
def I_sioset(T, A, io, arr: Arr):
    """3.7.3 sioSet: write the array's values (nearest integer modulo 256)."""
    io = _sio(io)
    data = bytes(int(math.floor(v + 0.5)) % 256 for v in arr.data[arr.off:])
    T.M.sio_sent(T, io, data)
    yield from YIELD(T)
    return float(len(data))


_SIO_PARAMS = {"port": float, "target": str, "clients": float, "endOfString": float, "timeout": float,
               "baudRate": float, "parity": str, "bits": float, "stopBits": float, "mode": str,
               "flowControl": str, "nagle": bool}


_SIO_VALUES = {"parity": ("none", "even", "odd"), "bits": (5, 6, 7, 8), "stopBits": (1, 2), "mode": ("rs232", "rs422"),
               "flowControl": ("none", "hardware")}


@sync
def I_sioctrl(T, A, io, name: str, value: Any) -> float:
    """3.7.3 sioCtrl: 0 changed, -1 unknown parameter, -2 wrong type, -3 value not supported."""
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
        if value < 0:
            return -3.0
        io.timeout = float(value)
    elif (name in _SIO_VALUES and (_int(value) if want is float else value) not in _SIO_VALUES[name]
          or name in ("port", "clients", "baudRate") and (value < 0 or value != _int(value))):
        return -3.0
    io.params[name] = value
    return 0.0


# ---- chapter 4: user page ------------------------------------------------------------------------


def _scr(T, args):
    if args and type(args[0]) is Screen:
        return args[0], args[1:]
    return T.M.page, args


@sync
def I_userpage(T, A, *args) -> None:
    if args and type(args[0]) is Screen:
        T.M.page = args[0]
        T.M.transcript_add(T, "userPage", args[0].name, args[0])
    else:
        if not args:
            T.M.page = T.M.default_page
        T.M.transcript_add(T, "userPage", "" if not args else ("fixed" if args[0] else "free"), T.M.page)


@sync
def I_gotoxy(T, A, *args) -> None:
    scr, (x, y) = _scr(T, args)
    scr.x = _int(x) % Screen.COLS  # 4.3: nX modulo 40, nY modulo 14
    scr.y = _int(y) % Screen.ROWS
    T.M.transcript_add(T, "gotoxy", f"{scr.x},{scr.y}", scr)


@sync
def I_cls(T, A, *args) -> None:
    scr, _ = _scr(T, args)
    scr.cls()
    T.M.transcript_add(T, "cls", "", scr)


@sync
def I_settextmode(T, A, *args) -> None:
    scr, (mode,) = _scr(T, args)
    scr.mode = _int(mode)


@sync
def I_getkey(T, A, *args) -> float:
    """4.3 getKey: the last key pressed since the previous call, -1 if none; never waits. A
    screen that is not displayed is told of no key (4.2.3)."""
    scr, _ = _scr(T, args)
    if scr is not T.M.page:
        return -1.0
    return float(T.M.last_key())


@sync
def I_iskeypressed(T, A, *args) -> bool:
    """4.3: a key is seen only by the screen displayed, except the keys (1), (2), (3) (281-283)."""
    scr, (code,) = _scr(T, args)
    n = _int(code)
    if scr is not T.M.page and n not in (281, 282, 283):
        return False
    return T.M.key_held(n)


@sync
def I_popupmsg(T, A, text: str) -> None:
    T.M.transcript_add(T, "popUpMsg", text, None)


@sync
def I_logmsg(T, A, text: str) -> bool:
    """4.3 logMsg: "USR" is added before the text in the system log."""
    T.M.transcript_add(T, "logMsg", "USR " + text, None)
    return True


@sync
def I_getprofile(T, A) -> str:
    return T.M.ctl.profile


@async_
def I_setprofile(T, A, login: str, password: str):
    """4.3 setProfile: 0 done, 1 unknown profile, 2 wrong password, 3/4 'staubli'."""
    ctl = T.M.ctl
    yield from YIELD(T)
    if login == "staubli":
        return 3.0
    if ctl.profile == "staubli":
        return 4.0
    if login not in ctl.profiles:
        return 1.0
    if ctl.profiles[login] != password:
        return 2.0
    ctl.profile = login
    return 0.0


@sync
def I_getlanguage(T, A) -> str:
    return T.M.ctl.language


@sync
def I_setlanguage(T, A, lang: str) -> bool:
    if lang in T.M.ctl.languages:
        T.M.ctl.language = lang
        return True
    return False


@sync
def I_getdate(T, A, fmt: str) -> str:
    """4.3 getDate: the simulated date (scenario [controller] date) plus the simulated time."""
    import datetime

    base = T.M.ctl.date
    d = base + datetime.timedelta(microseconds=T.M.clock_us(T))
    rep = {"%y": f"{d.year % 100:02d}", "%Y": f"{d.year:04d}", "%m": f"{d.month:02d}", "%d": f"{d.day:02d}",
           "%H": f"{d.hour:02d}", "%I": f"{(d.hour % 12) or 12:02d}", "%p": "AM" if d.hour < 12 else "PM",
           "%M": f"{d.minute:02d}", "%S": f"{d.second:02d}"}
    return clip_string(re.sub(r"%[yYmdHIpMS]", lambda m: rep[m.group(0)], fmt))


# ---- chapter 6: libraries (no alias: the unit itself) -------------------------------------------


@async_
def I_libsave(T, A, *args):
    return (yield from T.M.lib_op(T, A, None, "libsave", *args))


@async_
def I_libdelete(T, A, path: str):
    return (yield from T.M.lib_op(T, A, None, "libdelete", path))


@async_
def I_liblist(T, A, path: str, arr: Arr):
    return (yield from T.M.lib_op(T, A, None, "liblist", path, arr))


@sync
def I_libpath(T, A) -> str:
    return A.disk_path


# ---- chapter 8: robot control state --------------------------------------------------------------


@async_
def I_disablepower(T, A):
    """8.1 disablePower: cuts the arm power and waits until it is off."""
    T.M.set_power(T, False)
    yield from YIELD(T)


@sync
def I_enablepower(T, A) -> None:
    """8.1 enablePower: only in remote mode (workingMode 4); power comes after the scenario's
    power_delay."""
    T.M.request_power(T)


@sync
def I_ispowered(T, A) -> bool:
    return T.M.ctl.powered


@sync
def I_iscalibrated(T, A) -> bool:
    return T.M.ctl.calibrated


@sync
def I_workingmode(T, A, state=None) -> float:
    ctl = T.M.ctl
    if state is not None:
        state[0][state[1]] = float(ctl.working_state)
    return float(ctl.working_mode)


@sync
def I_esstatus(T, A) -> float:
    return float(T.M.ctl.es_status)


@sync
def I_safetyfault(T, A, name) -> bool:
    sig = T.M.ctl.safety_fault
    if sig:
        name[0][name[1]] = sig
        return True
    return False


@sync
def I_iobusstatus(T, A, arr: Arr) -> float:
    """8.1 ioBusStatus: the number of field bus devices in error: the devices of the
    inputs/outputs the scenario's [io] table gives status -3 (a device is the link without its
    last component, 'deviceName\\moduleName'). One description "-3:deviceName\\moduleName" per
    device is written to the array (a global one grows as needed), the rest is set to ""."""
    devices = sorted({_device(io.link) for io in T.M.cell.points.values() if io.status == -3 and io.link})
    arr.fill_strings([clip_string(f"-3:{d}") for d in devices])
    return float(len(devices))


def _device(link: str) -> str:
    for sep in ("\\", "/"):
        if sep in link:
            return link.rsplit(sep, 1)[0]
    return link


@sync
def I_getmonitorspeed(T, A) -> float:
    return float(T.M.ctl.monitor_speed)


@sync
def I_setmonitorspeed(T, A, speed: float) -> float:
    """8.1: 0 done; -1 not in remote mode; -2 controlled by the operator; -3 not in [0, 100]."""
    ctl = T.M.ctl
    if ctl.working_mode != 4:
        return -1.0
    if not 0 <= speed <= 100:
        return -3.0
    if ctl.operator_speed and speed > ctl.monitor_speed:
        return -2.0
    ctl.monitor_speed = float(speed)
    return 0.0


@sync
def I_getversion(T, A, component: str) -> str:
    return T.M.ctl.versions.get(component, "")


# chapter 9 (geometry and the arm model) registers its instructions in the same table
from . import geom as _geom  # noqa: E402,F401
