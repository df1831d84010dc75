"""Chapter 4: the user page (screens, keys, the system log) and the operator's profile,
language and date. The page model is `user_page.UserPage`; what is written goes to the run's
transcript with the time, the task and the screen."""

from __future__ import annotations

import datetime
import math
import re
from typing import Any

from ...language.runtime_errors import Val3RuntimeError
from .. import builtins
from ..values import Screen, clip_string
from ..waiting import WAIT, YIELD

E = Val3RuntimeError


def _int(v: float) -> int:
    return int(math.floor(v + 0.5))


def _screen(task, args: tuple) -> tuple[Screen, tuple]:
    """The optional screen first argument (4.2.3), else the displayed page."""
    if args and type(args[0]) is Screen:
        return args[0], args[1:]
    return task.machine.user_page.displayed, args


def _text(v: Any) -> str:
    if type(v) is float:
        return builtins.format_num_default(v)  # 4.3 put(num)
    if type(v) is bool:
        return "true" if v else "false"
    return str(v)


def PAGE(task, kind: str, *args: Any) -> None:
    """put, putln, title (4.3)."""
    scr, rest = _screen(task, args)
    text = _text(rest[0]) if rest else ""
    if kind == "title":
        scr.title = text
    else:
        scr.write(text, kind == "putln")
    task.machine.transcript_add(task, kind, text, scr)


def GET(task, *args: Any):
    """4.3 get: wait for a key press (scripted in the scenario); returns its code."""
    scr, rest = _screen(task, args)
    pair, vtype = (rest[0], rest[1]) if len(rest) >= 2 else (None, None)
    machine = task.machine
    page = machine.user_page
    clock = machine.clock
    # 4.2.3: only the screen displayed on the pendant is told of the keys pressed
    # 4.2: the operator may also show another screen (User-Up/User-Down); the scenario's keys
    # reach the screen displayed
    shown = "" if page.displayed is scr else f" (once {scr.name or 'the default page'} is displayed: userPage)"
    yield from WAIT(task, (lambda: page.displayed is scr and page.key_available(clock.now)), False, "get",
                    f"an operator's key press{shown}: the scenario's [[keys]] (docs/scenario.md)")
    key = page.take_key()
    code = float(key.code)
    if pair is not None and key.code != 255 and key.text is not None:  # Esc leaves it unchanged
        c, k = pair
        if vtype == "num":
            try:
                c[k] = float(key.text)
            except ValueError:
                raise E(70, f"get: {key.text!r} is not a number") from None
        else:
            c[k] = clip_string(key.text)
    shown = key.text if key.text is not None else ""
    machine.transcript_add(task, "get", f"{shown}[{key.code}]", scr)
    return code


def I_userpage(task, unit, *args) -> float | None:
    """4.3 userPage(), userPage(screen), userPage(bool); s8 userPage(string sPage): shows the web
    user page of that name (language/s8.toml), which the simulator records (R041) and answers 0."""
    machine = task.machine
    page = machine.user_page
    if args and type(args[0]) is str:
        machine.transcript_add(task, "userPage", args[0], None)
        machine.note_outside(task, f'userPage("{args[0]}"): a web user page of the CS9 (s8), not simulated: '
                                   "recorded in the transcript; its value is 0")
        return 0.0
    if args and type(args[0]) is Screen:
        page.displayed = args[0]
        machine.transcript_add(task, "userPage", args[0].name, args[0])
    else:
        if not args:
            page.displayed = page.default
        machine.transcript_add(task, "userPage", "" if not args else ("fixed" if args[0] else "free"), page.displayed)


def I_gotoxy(task, unit, *args) -> None:
    scr, (x, y) = _screen(task, args)
    scr.x = _int(x) % Screen.COLS  # 4.3: nX modulo 40, nY modulo 14
    scr.y = _int(y) % Screen.ROWS
    task.machine.transcript_add(task, "gotoxy", f"{scr.x},{scr.y}", scr)


def I_cls(task, unit, *args) -> None:
    scr, _ = _screen(task, args)
    scr.cls()
    task.machine.transcript_add(task, "cls", "", scr)


def I_settextmode(task, unit, *args) -> None:
    scr, (mode,) = _screen(task, args)
    scr.mode = _int(mode)


def I_getkey(task, unit, *args) -> float:
    """4.3 getKey: the last key pressed since the previous call, -1 if none; never waits. A
    screen that is not displayed is told of no key (4.2.3)."""
    scr, _ = _screen(task, args)
    page = task.machine.user_page
    if scr is not page.displayed:
        return -1.0
    return float(page.last_key(task.machine.clock.now))


def I_iskeypressed(task, unit, *args) -> bool:
    """4.3: a key is seen only by the screen displayed, except the keys (1), (2), (3) (281-283)."""
    scr, (code,) = _screen(task, args)
    n = _int(code)
    page = task.machine.user_page
    if scr is not page.displayed and n not in (281, 282, 283):
        return False
    return page.key_held(n, task.machine.clock.now)


def I_popupmsg(task, unit, text: str) -> None:
    task.machine.transcript_add(task, "popUpMsg", text, None)


def I_logmsg(task, unit, text: str, level: float | None = None) -> bool:
    """4.3 logMsg: "USR" is added before the text in the system log (s8: a level follows, as
    language/s8.toml says; the log keeps the text)."""
    task.machine.transcript_add(task, "logMsg", "USR " + text, None)
    return True


def I_getprofile(task, unit) -> str:
    return task.machine.controller.profile


def I_setprofile(task, unit, login: str, password: str):
    """4.3 setProfile: 0 done, 1 unknown profile, 2 wrong password, 3/4 'staubli'."""
    ctl = task.machine.controller
    yield from YIELD(task)
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


def I_getlanguage(task, unit) -> str:
    return task.machine.controller.language


def I_setlanguage(task, unit, lang: str) -> bool:
    ctl = task.machine.controller
    if lang in ctl.languages:
        ctl.language = lang
        return True
    return False


def I_getdate(task, unit, fmt: str) -> str:
    """4.3 getDate: the simulated date (scenario [controller] date) plus the simulated time."""
    machine = task.machine
    d = machine.controller.date + datetime.timedelta(microseconds=machine.clock.time_of(task))
    rep = {"%y": f"{d.year % 100:02d}", "%Y": f"{d.year:04d}", "%m": f"{d.month:02d}", "%d": f"{d.day:02d}",
           "%H": f"{d.hour:02d}", "%I": f"{(d.hour % 12) or 12:02d}", "%p": "AM" if d.hour < 12 else "PM",
           "%M": f"{d.minute:02d}", "%S": f"{d.second:02d}"}
    return clip_string(re.sub(r"%[yYmdHIpMS]", lambda m: rep[m.group(0)], fmt))


# ---- the web user pages of s8 (CS9 controllers, language/s8.toml) --------------------------------
# The page itself is a web page of the controller, outside the simulation: each call goes to the
# transcript (its kind is the instruction's name); an operator's answer the scenario cannot give
# is the one that lets the application go on (confirmed; the text left as it is), said by R041.


def I_userpagealert(task, unit, text: str) -> None:
    """userPageAlert(sMessage): shows a message to the operator, as popUpMsg does."""
    task.machine.transcript_add(task, "userPageAlert", text, None)


def I_userpageconfirm(task, unit, text: str) -> bool:
    """bool userPageConfirm(sMessage): the operator confirms (true)."""
    task.machine.transcript_add(task, "userPageConfirm", text, None)
    task.machine.note_outside(task, "userPageConfirm: the operator's answer on the web user page is not simulated: "
                                    "true (confirmed)")
    return True


def I_userpageprompt(task, unit, prompt: str, pair) -> bool:
    """bool userPagePrompt(sPrompt, string& sInput): the operator validates the text as it is (true)."""
    task.machine.transcript_add(task, "userPagePrompt", prompt, None)
    task.machine.note_outside(task, "userPagePrompt: the operator's text on the web user page is not simulated: the "
                                    "text is left as it is and the value is true (validated)")
    return True


def I_userpageset(task, unit, text: str, used: str):
    """userPageSet(...): its parameters are not public; the call is recorded."""
    task.machine.transcript_add(task, "userPageSet", text, None)
    task.machine.note_outside(task, "userPageSet: a web user page of the CS9 (s8), not simulated: recorded in the "
                                    "transcript" + (", its value is 0" if used else ""))
    return 0.0 if used == "num" else (False if used == "bool" else ("" if used == "string" else None))


def register(registry) -> None:
    for name, func in (("userPageAlert", I_userpagealert), ("userPageConfirm", I_userpageconfirm),
                       ("userPagePrompt", I_userpageprompt)):
        registry.instruction(name, func)
    registry.instruction("userPageSet", I_userpageset, raw=True)
    for entry in builtins.PURE.values():  # getDisplayLen
        if entry.section.startswith("4."):
            registry.builtin(entry)
    registry.inline("put", "putln", "title", "get", chapter=__name__)
    registry.helpers(PAGE=PAGE, GET=GET)
    for name, func in (("userPage", I_userpage), ("gotoxy", I_gotoxy), ("cls", I_cls), ("setTextMode", I_settextmode),
                       ("getKey", I_getkey), ("isKeyPressed", I_iskeypressed), ("popUpMsg", I_popupmsg),
                       ("logMsg", I_logmsg), ("getProfile", I_getprofile), ("getLanguage", I_getlanguage),
                       ("setLanguage", I_setlanguage), ("getDate", I_getdate)):
        registry.instruction(name, func)
    registry.instruction("setProfile", I_setprofile, blocking=True)
