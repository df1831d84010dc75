"""Motion control of VAL 3 chapter 10 in simulated time (see docs/motion.md): where the arm is
at each simulated time. Pure: it imports nothing of the interpreter (its adapters, the arm port
and the instructions of chapter 10, are in val3check.simulation).

- `queue`          the motion queue: the state machine of 10.2/10.6 (record, waitEndMove,
                   stopMove/restartMove, power, monitor speed, resetMotion, getMoveId);
- `queued`         a command in the queue: what was asked, its geometry, where it lies on the path;
- `commands`       what a motion instruction hands to the queue (`MoveCommand`, `Target`);
- `construction`   a command's joint-space geometry (10.1), or why it cannot be executed;
- `failures`       the findings of commands the arm cannot execute (R010-R013), error 150;
- `blending`       leave and reach points, the blend between two commands (10.1.2);
- `planner`        the path built from the commands, the blend-or-stop choice, the replans;
- `timing/`        a path plus its limits -> a time parameterisation (10.3): the one interface;
- `paths`, `cartesian`, `tracking`, `kin`: joint-space geometry, TCP curves, the joints along a
                   Cartesian curve, the arm's vectorised kinematics;
- `trajectory`     the path parameter over time, and the joints at any time;
- `mdesc`, `checks`, `findings`: limits (10.3, 10.5), singularity thresholds, motion diagnostics;
- `records`, `cycle`: the motion table and the cycle time of a run; `reach`: the static reach
                   check; `dynamics`: getJointForce.
"""
