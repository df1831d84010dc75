"""Two MCAP traces of the same run compared message by message (issue 29): the same topics and
stamps in the same order, and for each JSON field the largest difference between the two, so that
a change said to move the last bits only is seen to:

    python bench/trace_diff.py /tmp/before/pickplace-tx2-60.mcap /tmp/after/pickplace-tx2-60.mcap
    38658 messages, 5700 differ
      /velocity: max |diff| 1.2e-10

Exits 1 when the topics, stamps, encodings or any non-number field differ.
"""

from __future__ import annotations

import json
import sys

from mcap.reader import make_reader


def _messages(path: str):
    with open(path, "rb") as f:
        for _schema, channel, message in make_reader(f).iter_messages(log_time_order=True):
            yield channel.topic, message.log_time, channel.message_encoding, message.data


def _walk(a, b, widest: dict, path: str = "") -> None:
    """Record in `widest` the largest difference of each number field; raise on any other."""
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            raise ValueError(f"{path or '/'}: fields {sorted(a)} against {sorted(b)}")
        for k in a:
            _walk(a[k], b[k], widest, f"{path}/{k}")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            raise ValueError(f"{path}: {len(a)} items against {len(b)}")
        for x, y in zip(a, b):
            _walk(x, y, widest, path)
    elif isinstance(a, float) or isinstance(b, float):
        widest[path] = max(widest.get(path, 0.0), abs(a - b))
    elif a != b:
        raise ValueError(f"{path}: {a!r} against {b!r}")


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__)
        return 2
    count = differ = 0
    widest: dict = {}
    try:
        pairs = zip(_messages(argv[0]), _messages(argv[1]), strict=True)
        for (t1, s1, e1, d1), (t2, s2, e2, d2) in pairs:
            count += 1
            if (t1, s1, e1) != (t2, s2, e2):
                raise ValueError(f"message {count}: {t1} at {s1} ns ({e1}) against {t2} at {s2} ns ({e2})")
            if d1 != d2:
                differ += 1
                if e1 != "json":
                    raise ValueError(f"message {count} on {t1}: {e1} bytes differ")
                _walk(json.loads(d1), json.loads(d2), widest)
    except ValueError as e:
        print(f"differ: {e}")
        return 1
    print(f"{count} messages, {differ} differ")
    for field, d in sorted(widest.items(), key=lambda kv: -kv[1]):
        if d:
            print(f"  {field}: max |diff| {d:.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
