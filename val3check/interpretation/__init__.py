"""The virtual VAL 3 controller behind `val3check sim` (docs/sim.md, docs/architecture.md).

Where things are:
- a task is scheduled in `scheduler.py` (tasks, their states, the 4 ms cycle, the jumps of
  the clock to the next event), on the clock of `clock.py`; a task waits with `waiting.py`;
- an instruction is registered in `registry.py`, by the module of its chapter in `chapters/`
  (`ch05_tasks.py`...; chapter 10 is `val3check.simulation.ch10_motion`); what is not simulated
  stops the task (`not_simulated.py`);
- the arm's position comes through `arm_port.py` (implemented by `val3check.simulation` over
  the motion queue of `val3check.motion`);
- what changes with time besides the tasks is a `Subsystem` (`subsystem.py`): the cell and
  its scenario (`io_cell.py`, `events.py`; the scenario file is read by `val3check.simulation`),
  the arm's motion;
- `compiler/` turns each program into a Python generator function, once; `code_support.py`
  holds the helpers the generated code calls;
- `machine.py` puts a run together: units (`units.py`, `libraries.py`, `system_io.py`), values
  and memory (`values.py`, `memory.py`), the user page (`user_page.py`), the controller's state
  (`controller.py`), what the run records (`recorder.py`);
- the pure instructions (math, strings, bit fields) are in `builtins/`.

`val3check.simulation` assembles and runs a machine. Nothing here is imported by
`val3check lint`.
"""
