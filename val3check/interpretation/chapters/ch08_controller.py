"""Chapter 8: control of the robot (8.1): power, calibration, working mode, emergency stop,
safety faults, field bus status, monitor speed, versions. The state is `controller.Controller`,
set by the scenario's `[controller]` table."""

from __future__ import annotations

from ..events import PowerChange
from ..values import Arr, clip_string
from ..waiting import YIELD


def I_disablepower(task, unit):
    """8.1 disablePower: cuts the arm power and waits until it is off."""
    machine = task.machine
    if machine.controller.powered:
        machine.controller.powered = False
        machine.transcript_add(task, "power", "off", None)
    yield from YIELD(task)


def I_enablepower(task, unit) -> None:
    """8.1 enablePower: only in remote mode (workingMode 4) without emergency stop; the power
    comes after the scenario's power_delay."""
    machine = task.machine
    ctl = machine.controller
    if ctl.powered:
        return
    if ctl.working_mode != 4 or ctl.es_status != 0:
        machine.transcript_add(task, "logMsg", "enablePower refused: not in remote mode or emergency stop", None)
        return
    machine.cell_subsystem.schedule(machine.clock.time_of(task) + ctl.power_delay_us, PowerChange(True))


def I_ispowered(task, unit) -> bool:
    return task.machine.controller.powered


def I_iscalibrated(task, unit) -> bool:
    return task.machine.controller.calibrated


def I_workingmode(task, unit, state=None) -> float:
    ctl = task.machine.controller
    if state is not None:
        state[0][state[1]] = float(ctl.working_state)
    return float(ctl.working_mode)


def I_esstatus(task, unit) -> float:
    return float(task.machine.controller.es_status)


def I_safetyfault(task, unit, name) -> bool:
    sig = task.machine.controller.safety_fault
    if sig:
        name[0][name[1]] = sig
        return True
    return False


def I_iobusstatus(task, unit, arr: Arr) -> float:
    """8.1 ioBusStatus: the number of field bus devices in error: the devices of the
    inputs/outputs the scenario's [io] table gives status -3 (a device is the link without its
    last component, 'deviceName\\moduleName'). One description "-3:deviceName\\moduleName" per
    device is written to the array (a global one grows as needed), the rest is set to ""."""
    devices = sorted({_device(io.link) for io in task.machine.cell.points.values() if io.status == -3 and io.link})
    arr.fill_strings([clip_string(f"-3:{d}") for d in devices])
    return float(len(devices))


def _device(link: str) -> str:
    for sep in ("\\", "/"):
        if sep in link:
            return link.rsplit(sep, 1)[0]
    return link


def I_getmonitorspeed(task, unit) -> float:
    return float(task.machine.controller.monitor_speed)


def I_setmonitorspeed(task, unit, speed: float) -> float:
    """8.1: 0 done; -1 not in remote mode; -2 controlled by the operator; -3 not in [0, 100]."""
    ctl = task.machine.controller
    if ctl.working_mode != 4:
        return -1.0
    if not 0 <= speed <= 100:
        return -3.0
    if ctl.operator_speed and speed > ctl.monitor_speed:
        return -2.0
    ctl.monitor_speed = float(speed)
    return 0.0


def I_getversion(task, unit, component: str) -> str:
    """8.1 getVersion: the version of a component of the controller (controller.default_versions,
    the scenario's [controller] versions); "" for a component it does not know, as for a licence
    that is not installed."""
    return task.machine.controller.versions.get(component, "")


def register(registry) -> None:
    for name, func in (("enablePower", I_enablepower), ("isPowered", I_ispowered), ("isCalibrated", I_iscalibrated),
                       ("workingMode", I_workingmode), ("esStatus", I_esstatus), ("safetyFault", I_safetyfault),
                       ("ioBusStatus", I_iobusstatus), ("getMonitorSpeed", I_getmonitorspeed),
                       ("setMonitorSpeed", I_setmonitorspeed), ("getVersion", I_getversion)):
        registry.instruction(name, func)
    registry.instruction("disablePower", I_disablepower, blocking=True)
