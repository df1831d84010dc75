"""The pendant's user page (chapter 4): the screens, the one displayed, and the keys pressed.

Screens are `values.Screen` (the run-time value of `screen` variables, 14 lines of 40
columns); the default page always exists. Keys come from the scenario (`[[keys]]`) in time
order; only the displayed screen is told of them (4.2.3). The instructions are in
`chapters/ch04_user_page.py`.
"""

from __future__ import annotations

from dataclasses import dataclass

from .values import Screen


@dataclass
class Key:
    at: int  # µs
    code: int  # 4.3 key code
    text: str | None = None  # what the operator types before the key (get(string&), get(num&))
    hold: int = 200_000  # µs the key stays pressed (isKeyPressed)


class UserPage:
    def __init__(self) -> None:
        self.default = Screen("default")
        self.displayed = self.default
        self.keys: list[Key] = []  # in time order
        self._next = 0  # the next key get() takes
        self._seen = 0  # keys getKey() has seen

    def set_keys(self, keys: list[Key]) -> None:
        self.keys = sorted(keys, key=lambda k: k.at)

    def key_available(self, now: int) -> bool:
        return self._next < len(self.keys) and self.keys[self._next].at <= now

    def take_key(self) -> Key:
        k = self.keys[self._next]
        self._next += 1
        self._seen = max(self._seen, self._next)
        return k

    def last_key(self, now: int) -> int:
        """getKey: the last key pressed since the previous call; keys read by get() count too."""
        code = -1
        while self._seen < len(self.keys) and self.keys[self._seen].at <= now:
            code = self.keys[self._seen].code
            self._seen += 1
        self._next = max(self._next, self._seen)
        return code

    def key_held(self, code: int, now: int) -> bool:
        return any(k.code == code and k.at <= now < k.at + k.hold for k in self.keys)
