"""Length units, each conversion written once: the controller's millimetre, an application's inch
(`millimeterUnit` false, 2.1.4.1) and the metre of URDF files, pinocchio and Foxglove."""

from __future__ import annotations

INCH_MM = 25.4  # millimetres in an inch (2.1.4.1)
M_MM = 1000.0  # millimetres in a metre: URDF and pinocchio lengths to the controller's
MM_M = 0.001  # metres in a millimetre: the controller's lengths to Foxglove's


def app_mm(millimeter_unit: bool) -> float:
    """Millimetres in one length unit of an application (`millimeterUnit`, 2.1.4.1)."""
    return 1.0 if millimeter_unit else INCH_MM
