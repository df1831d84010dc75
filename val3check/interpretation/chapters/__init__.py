"""The instructions of the virtual controller, one module per chapter of the manual.

Each module has `register(registry)`, which puts its instruction handlers, the inline forms
the compiler writes for it and the helpers its generated code calls into a `Registry`
(registry.py). Nothing registers on import: `val3check.simulation` calls them, in this order
(chapter 10, motion, is `val3check.simulation.ch10_motion`, over `val3check.motion`):

- `ch02_variables`     size, isDefined, insert, delete, append, resize, first... getData
- `ch03_simple_types`  num, bit fields, strings (pure: builtins/); dio, aio, sio
- `ch04_user_page`     the user page, keys, the system log, profile, language, date
- `ch05_tasks`         taskCreate... taskResume, delay, clock, wait, watch, setMutex
- `ch06_libraries`     libLoad, libSave, libDelete, libList, libPath, libExist, alias:x
- `ch08_controller`    power, working mode, emergency stop, monitor speed, versions
- `ch09_geometry`      trsf, frame, tool, point, joint, config; the arm's position
"""
