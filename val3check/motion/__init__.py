"""The arm's motion (chapter 10): where the arm is at each simulated time.

- `arm_state`    the arm as the interpreter sees it (the `Arm` port of
                 interpretation/arm_port.py, and a `Subsystem` of the scheduler): its model,
                 its commanded joints as a function of simulated time, the motion queue, the
                 unit conversions. Today the arm does not move (`MotionlessArm`);
- `ch10_motion`  the instructions of chapter 10, registered with `register(registry)`: movej
                 checks that its target is reachable, then the task stops with R002 (motion is
                 not simulated yet); the others stop with R002 (registry.py).

The planner (paths, timing, the motion queue) plugs in here: a moving arm implements the same
port, tells the scheduler when its state next changes (`next_time`: the end of the motion
being executed, the next blend...) and brings it up to date (`advance`).
"""
