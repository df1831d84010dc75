"""The trajectory's long series (its times, each joint's positions and velocities, the TCP speed).

A model built from a run (from_run.py) holds them as `array('d')`: 8 bytes a value where a list
of Python floats takes 32, made, checked (model.py) and packed (pack.py) in bulk with numpy. A
model read from JSON holds lists; every reader takes both, and the page is the same bytes.

    times = doubles(rounded(t, 6))   # as [round(x, 6) + 0.0 for x in t], in bulk
    a = floats(times)                # numpy's view of an array('d'); None for a list

The page of a run holds none of them: its trajectory is a `Packed`, the page's data made block by
block (run_trajectory.py).
"""

from __future__ import annotations

from array import array
from typing import Any


def doubles(values: Any) -> array:
    """A numpy array of floats as an array('d') (one copy, no Python float)."""
    import numpy as np

    return array("d", np.ascontiguousarray(values, dtype=float).tobytes())


def floats(values: Any) -> Any:
    """numpy's view (no copy) of an array('d'); None for anything else (a list: read one by one)."""
    if isinstance(values, array) and values.typecode == "d":
        import numpy as np

        return np.frombuffer(values, dtype=float) if len(values) else np.zeros(0)
    return None


def rounded(values: Any, digits: int) -> Any:
    """`round(float(x), digits) + 0.0` for each x of a float array, as a float array, in bulk.

    numpy's round is rint(x * 10**digits) / 10**digits: the division is correctly rounded, so it
    gives Python's result (the double nearest the decimal rounded correctly) unless the product's
    own rounding crosses a half: those few values (x * 10**digits within a few ulps of a half, or
    beyond 2**52, or not finite) are rounded by Python."""
    import numpy as np

    shape = np.shape(values)
    x = np.asarray(values, dtype=float).ravel()  # any shape: value by value
    scale = 10.0 ** digits
    with np.errstate(invalid="ignore", over="ignore"):
        y = x * scale
        out = np.rint(y) / scale + 0.0
        near = np.abs(np.abs(y - np.floor(y)) - 0.5) <= np.abs(y) * 2.0 ** -49 + 1e-300
    near |= ~(np.abs(y) < 2.0 ** 52)  # beyond, or not finite: as Python rounds them
    for k in np.flatnonzero(near).tolist():
        out[k] = round(float(x[k]), digits) + 0.0
    return out.reshape(shape)


def dump_json(obj: Any, fh) -> None:
    """`json.dump(obj, fh, sort_keys=True, indent=1)` byte for byte (`val3check html --model-out`),
    each array('d') written from the array block by block: json would need it as a list of floats."""
    import json
    import uuid

    arrays: dict[str, array] = {}
    mark = uuid.uuid4().hex  # no text of the model can hold it

    def default(o: Any) -> str:
        if not isinstance(o, array):
            raise TypeError(f"Object of type {type(o).__name__} is not JSON serializable")
        key = f"{mark}{len(arrays)}"
        arrays[json.dumps(key)] = o
        return key

    depth = 0  # the leading spaces of the line being written: an array's level
    for chunk in json.JSONEncoder(sort_keys=True, indent=1, default=default).iterencode(obj):
        values = arrays.pop(chunk, None)
        if values is None:
            fh.write(chunk)
            nl = chunk.rfind("\n")
            if nl >= 0:
                rest = chunk[nl + 1:]
                depth = len(rest) - len(rest.lstrip(" "))
            continue
        if not len(values):
            fh.write("[]")
            continue
        inner = "\n" + " " * (depth + 1)
        fh.write("[")
        for lo in range(0, len(values), _BLOCK):
            fh.write(("," if lo else "") + inner + ("," + inner).join(map(_json_float, values[lo:lo + _BLOCK])))
        fh.write("\n" + " " * depth + "]")


_BLOCK = 65_536  # values of an array formatted at once


def _json_float(x: float) -> str:
    """A float as json writes it (NaN and infinities as json's words)."""
    return repr(x) if x - x == 0.0 else {"nan": "NaN", "inf": "Infinity", "-inf": "-Infinity"}[repr(x)]


class Packed:
    """A run's trajectory as the page's script reads it (pack._packed), made block by block from the
    run (from_run.page_pieces), so that its full-rate series are never held: the model's
    "trajectory" of a run's page. `joints` as a model's, `samples` their count, `data` the page's."""

    __slots__ = ("joints", "samples", "data")

    def __init__(self, joints: list[dict], samples: int, data: dict) -> None:
        self.joints, self.samples, self.data = joints, samples, data

    def get(self, key: str, default: Any = None) -> Any:
        """As a model's trajectory for the page's sections: "times" (its count), "tcp_speed"."""
        if key == "times":
            return self.samples
        if key == "tcp_speed":
            return True if self.data["tcp"] is not None else None
        if key == "joints":
            return self.joints
        return default
