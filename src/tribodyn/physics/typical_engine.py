"""Typical values of the engine a case describes: the elastic constants of cam and tappet
steels and coatings, the valvetrain's masses, spring rate and preload, the cam's sizes and
the engine speed, each a :class:`~tribodyn.physics.typical.TypicalValue` with its source
and how far that source was checked (``status``, :mod:`tribodyn.physics.typical`).

They are the defaults of a case that leaves these keys out; the run then warns, naming
each value that decides the contact force (:mod:`tribodyn.config.origins`). The paper's
values (Andreou et al. 2023) are stated in its case files, ``cases/andreou2023*.toml``.
SI units throughout.
"""

from __future__ import annotations

from .typical import TypicalValue, typical_names

# ----------------------------------------------------------------------------- steel
_STEEL_HANDBOOK = (
    "ASM Handbook Vol. 1, Properties and Selection: Irons, Steels, and High-Performance "
    "Alloys, ASM International, 1990 (elastic constants of carbon and low-alloy steels)"
)
#: Young's modulus of hardened cam and tappet steels (carbon, low-alloy, case-hardened).
STEEL_MODULUS = TypicalValue(
    210e9,
    200e9,
    215e9,
    "Pa",
    _STEEL_HANDBOOK,
    "ASSUMED: the commonly quoted 200–215 GPa of carbon and low-alloy steels at room "
    "temperature, nearly independent of the heat treatment; the handbook's table was not "
    "seen here.",
    status="assumed",
)
#: Poisson's ratio of the same steels.
STEEL_POISSON = TypicalValue(
    0.3,
    0.27,
    0.3,
    "-",
    _STEEL_HANDBOOK,
    "ASSUMED: the commonly quoted 0.27–0.30; the handbook's table was not seen here.",
    status="assumed",
)
#: Density of the same steels (the flexible valve, tappet, spring and camshaft).
STEEL_DENSITY = TypicalValue(
    7850.0,
    7750.0,
    7900.0,
    "kg/m³",
    _STEEL_HANDBOOK,
    "ASSUMED: the commonly quoted 7.75–7.90 g/cm³ of carbon and low-alloy steels; the "
    "handbook's table was not seen here.",
    status="assumed",
)

#: Young's modulus of hydrogenated amorphous carbon (a-C:H, "DLC") tappet coatings.
DLC_MODULUS = TypicalValue(
    150e9,
    100e9,
    200e9,
    "Pa",
    "J. Robertson, Diamond-like amorphous carbon, Mater. Sci. Eng. R 37 (2002) 129-281",
    "ASSUMED: the commonly quoted 100–200 GPa of a-C:H films (hardness 10–20 GPa); the "
    "review's table was not seen here. Replace it by the supplier's or a nanoindentation "
    "value.",
    status="assumed",
)
#: Young's modulus of tungsten-carbide/carbon (WC-C, a-C:H:W) tappet coatings.
WCC_MODULUS = TypicalValue(
    160e9,
    120e9,
    200e9,
    "Pa",
    "ASSUMED magnitude of sputtered WC/C (a-C:H:W) coatings",
    "ASSUMED: no source giving the number was found here. Replace it by the supplier's "
    "or a nanoindentation value.",
    status="assumed",
)
#: Poisson's ratio of the carbon-based coatings.
COATING_POISSON = TypicalValue(
    0.25,
    0.2,
    0.3,
    "-",
    "convention",
    "ASSUMED: the film's ν is rarely measured; it changes E/(1−ν²) by a few per cent.",
    status="assumed",
)


# ----------------------------------------------------------------------------- valvetrain
# The masses, the spring rate and the preload decide the cam–tappet contact force. These
# are the values a case without them runs on (with a warning naming each one); they are
# magnitudes of passenger-car direct-acting (bucket tappet) valvetrains, not of one engine.
_SAAB = (
    "Saab 9-5 (2000) V6 workshop data, valve gear: valve spring 252–288 N at 34 mm, "
    "630–680 N at 24 mm"
)
#: Valve with retainer and collets of a passenger-car intake or exhaust valve.
VALVE_MASS = TypicalValue(
    0.060,
    0.035,
    0.100,
    "kg",
    "ASSUMED magnitude of passenger-car poppet valves (5–7 mm stem) with retainer and collets",
    "ASSUMED: no source giving the number was found here. Replace it by the weighed "
    "valve, retainer and collets of the engine.",
    status="assumed",
)
#: Flat (bucket) tappet with its shim.
TAPPET_MASS = TypicalValue(
    0.040,
    0.020,
    0.060,
    "kg",
    "ASSUMED magnitude of 28–35 mm steel bucket tappets",
    "ASSUMED: no source giving the number was found here. Replace it by the weighed tappet.",
    status="assumed",
)
#: Active mass of the valve spring (the whole wire between the dead coils).
SPRING_MASS = TypicalValue(
    0.030,
    0.015,
    0.050,
    "kg",
    "ASSUMED magnitude of single passenger-car valve springs (wire 3–4.5 mm, mean "
    "diameter 20–25 mm, 5–7 active coils)",
    "ASSUMED: no source giving the number was found here. It sets the surge frequency "
    "½√(k/m_s); replace it by the spring's data.",
    status="assumed",
)
#: Valve-spring rate k.
SPRING_RATE = TypicalValue(
    35000.0,
    20000.0,
    60000.0,
    "N/m",
    _SAAB,
    "The cited data give (655 − 270) N over 10 mm ≈ 38 N/mm for one engine; 35 N/mm and "
    "the 20–60 N/mm range are ASSUMED magnitudes of single passenger-car valve springs.",
    status="qualitative",
)
#: Installed spring load F₀ with the valve closed.
SPRING_PRELOAD = TypicalValue(
    250.0,
    100.0,
    350.0,
    "N",
    _SAAB + "; Suzuki Jimny (SN413) service manual: preload 107–125 N at 31.5 mm",
    "The cited data span ≈ 110 N (a small four-valve engine) to ≈ 270 N; 250 N is "
    "ASSUMED. With the rate it decides the contact force at the nose.",
    status="qualitative",
)
#: The typical values of the ``[valvetrain]`` keys that decide the contact force.
VALVETRAIN = {
    "valve_mass": VALVE_MASS,
    "tappet_mass": TAPPET_MASS,
    "spring_mass": SPRING_MASS,
    "spring_rate": SPRING_RATE,
    "spring_preload": SPRING_PRELOAD,
}


# ----------------------------------------------------------------------------- cam
# The default cam of a case without [cam]: an acceleration-domain design
# (tribodyn.valvetrain.AccelerationCam) with these sizes of a passenger-car intake cam for
# a direct-acting bucket tappet. Replace them by the engine's cam (a lift table: [cam]
# type = "table").
#: Engine (crank) speed of a case without [engine]: a mid-range operating point.
ENGINE_SPEED = TypicalValue(
    3000.0,
    800.0,
    7000.0,
    "rpm",
    "convention: a mid-range speed of passenger-car engines (idle to rated speed)",
    "ASSUMED operating point; set the engine's speeds ([engine] speed_rpm, a sweep).",
    status="assumed",
)
#: Base-circle radius of the cam.
CAM_BASE_RADIUS = TypicalValue(
    0.015,
    0.0125,
    0.020,
    "m",
    "ASSUMED magnitude of passenger-car overhead camshafts (base circles of 25–40 mm)",
    "ASSUMED: no source giving the number was found here.",
    status="assumed",
)
#: Maximum valve lift (at the tappet, incl. the ramp) of a direct-acting cam.
CAM_MAX_LIFT = TypicalValue(
    0.009,
    0.006,
    0.013,
    "m",
    "ASSUMED magnitude of passenger-car intake and exhaust valve lifts",
    "ASSUMED: no source giving the number was found here.",
    status="assumed",
)
#: Axial width of the cam lobe, the length of the line contact.
CAM_WIDTH = TypicalValue(
    0.014,
    0.010,
    0.020,
    "m",
    "ASSUMED magnitude of passenger-car cam lobes for bucket tappets",
    "ASSUMED: no source giving the number was found here. The contact force per length, "
    "and so the film and the pressure, scale with it.",
    status="assumed",
)

#: every typical value and table above
__all__ = typical_names(dict(globals()))
