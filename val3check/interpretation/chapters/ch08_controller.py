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


# ---- what s8 (CS9) adds, language/s8.toml ---------------------------------------------------------


def I_opcuaexport(task, unit, text: str, used: str):
    """opcuaExport(...): exports data to the controller's OPC UA server; its parameters are not
    public. The server and its clients are outside the simulation: the call is recorded."""
    task.machine.transcript_add(task, "opcuaExport", text, None)
    task.machine.note_outside(task, "opcuaExport: the controller's OPC UA server is not simulated: recorded in the "
                                    "transcript")
    return 0.0 if used == "num" else None


def I_setsafetyrestart(task, unit) -> bool:
    """bool setSafetyRestart(): after a safety fault (esStatus() 1: to acknowledge), restarts the
    safety (esStatus() 0) and returns true; true when there is nothing to restart, false while the
    emergency stop is open (2)."""
    ctl = task.machine.controller
    if ctl.es_status == 2:
        return False
    ctl.es_status = 0
    return True


def I_hascpuextpowersupply(task, unit) -> bool:
    """bool hasCpuExtPowerSupply(): the CPU's external 24 V supply is there (a cell that works)."""
    return True


def I_wakeuprobot(task, unit) -> float:
    """num wakeUpRobot(): 0, done (the simulated arm never loses its supply)."""
    return 0.0


def I_getsaferefstatus(task, unit) -> float:
    """num getSafeRefStatus(): the safe referencing of the arm is not simulated: 0, with R041."""
    task.machine.note_outside(task, "getSafeRefStatus: the safe referencing of the arm is not simulated: its value "
                                    "is 0")
    return 0.0


# ---- the controller's recorder, system library ($rec..., a public description of the CS8
# "Expansion" add-on): the recorder samples data to a file for analysis; outside the simulation,
# each call is recorded in the transcript (kind "recorder") and said once per line (R041).


def _recorder(name: str):
    def S_rec(task, unit, *args):
        task.machine.transcript_add(task, "recorder", f"{name}({', '.join(_shown(a) for a in args)})", None)
        task.machine.note_outside(task, f"{name}: the controller's recorder is not simulated: recorded in the "
                                        "transcript")
    S_rec.__name__ = "S_" + name[1:].lower()
    return S_rec


def _shown(v) -> str:
    return f'"{v}"' if isinstance(v, str) else f"{v:g}" if isinstance(v, float) else str(v)


RECORDER = (("$recClean", ("value",)), ("$recAdd", ("value", "value")), ("$recSize", ("value", "value")),
            ("$recStart", ("value", "value", "value")), ("$recStop", ("value",)), ("$recStore", ("value", "value")))


def S_getcycletime(task, unit) -> float:
    """num $getCycleTime(): the period of the controller's cycle, 0.004 s (the 4 ms of 5.4-5.5)."""
    return 0.004


def register(registry) -> None:
    for name, params in RECORDER:
        registry.system(name, _recorder(name), params, "void")
    registry.system("$getCycleTime", S_getcycletime, (), "num")
    registry.instruction("opcuaExport", I_opcuaexport, raw=True)
    for name, func in (("setSafetyRestart", I_setsafetyrestart), ("hasCpuExtPowerSupply", I_hascpuextpowersupply),
                       ("wakeUpRobot", I_wakeuprobot), ("getSafeRefStatus", I_getsaferefstatus)):
        registry.instruction(name, func)
    for name, func in (("enablePower", I_enablepower), ("isPowered", I_ispowered), ("isCalibrated", I_iscalibrated),
                       ("workingMode", I_workingmode), ("esStatus", I_esstatus), ("safetyFault", I_safetyfault),
                       ("ioBusStatus", I_iobusstatus), ("getMonitorSpeed", I_getmonitorspeed),
                       ("setMonitorSpeed", I_setmonitorspeed), ("getVersion", I_getversion)):
        registry.instruction(name, func)
    registry.instruction("disablePower", I_disablepower, blocking=True)
