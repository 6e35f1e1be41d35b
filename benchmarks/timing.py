"""Helpers shared by the benchmark scripts: best-of-n wall time and the steel pair with
the 5W-30 oil of the thermal benchmarks."""

import time

from tribodyn import Body, Material
from tribodyn.physics.heat_conduction import ThermalBody, ThermalProperties
from tribodyn.physics.oils import OILS
from tribodyn.physics.thermal_oil import ThermalLubricant


def best_of(fn, repeat):
    """(shortest wall time [s] of ``repeat`` calls of ``fn``, the last call's result)."""
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def steel_5w30():
    """(5W-30 at a 40 °C inlet, steel–steel elastic pair, steel–steel thermal bodies:
    k = 46 W/(m·K), ρ = 7850 kg/m³, c = 470 J/(kg·K))."""
    sheet = {k: v for k, v in OILS["5W-30"].items() if k != "description"}
    oil = ThermalLubricant(313.15, **sheet)
    steel = Material(210e9, 0.3)
    ts = ThermalProperties(46.0, 7850.0, 470.0)
    return oil, (Body(steel), Body(steel)), (ThermalBody(ts), ThermalBody(ts))
