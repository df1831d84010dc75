"""Motion control of VAL 3 chapter 10 in simulated time (see docs/motion.md): where the arm is
at each simulated time.

- `arm_state`    the arm as the interpreter sees it (the `Arm` port of
                 interpretation/arm_port.py, and a `Subsystem` of the scheduler): its model,
                 its commanded joints as a function of simulated time, the motion queue, the
                 unit conversions. `MotionlessArm` is the arm that does not move;
- `ch10_motion`  the instructions of chapter 10, registered with `register(registry)`;
- the planner (paths, timing, the motion queue, checks, records) is pure: it imports nothing
  of the interpreter (docs/motion.md).

A moving arm implements the same port, tells the scheduler when its state next changes
(`next_time`: the end of the motion being executed, the next blend...) and brings it up to
date (`advance`); docs/architecture.md, "How motion plugs in".
"""
