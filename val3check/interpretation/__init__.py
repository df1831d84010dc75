"""The virtual VAL 3 controller behind `val3check sim` (docs/sim.md).

- `compiler.py` turns each program into a Python generator function, once;
- `machine.py` holds the units (application, libraries), tasks, clock and scheduler;
- `runtime.py`, `instructions.py`, `libraries.py` implement the instructions that act on the
  controller; the pure ones (math, strings, bit fields) are in `builtins/`;
- `geom.py` is chapter 9: `val3check.geometry` and the arm model (`val3check.robot`) behind the
  trsf/frame/tool/point/joint/config instructions and operators, and movej's checks;
- `scenario.py` reads the I/O scenario (docs/scenario.md);
- `simulate.py` is the entry point: `simulate(ws, app, SimOptions(...)) -> SimResult`.

Nothing here is imported by `val3check lint`.
"""
