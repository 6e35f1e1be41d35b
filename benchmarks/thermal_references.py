"""Thermal EHL against published thermal corrections and the traction curve (prints JSON).

    python benchmarks/thermal_references.py

Steel on steel line contact, w = 500 kN/m, R = 20 mm (p_h ≈ 0.96 GPa), SAE 5W-30 at
40 °C (bundled datasheet oil), u_e = 5 m/s:

* central film h_T/h_iso against Murch & Wilson (1975) φ = 3.94/(3.94 + L^0.62)
  (rolling) and Gupta et al. (1992) φ = (1 − 13.2 (p_h/E') L^0.42)/(1 + 0.213 (1 + 2.23
  SRR^0.83) L^0.64), L = βμ₀u_e²/k, for SRR = u_s/u_e = 0, 0.5, 1, 1.5; beside it the
  same with the walls held at the bulk temperature (solids of conductivity 1e6 W/(m K), the
  assumption of those inlet analyses) and the Couette heat of the inlet, mid-film
  μ₀u_s²/(8k) between walls at the bulk temperature;
* pure rolling under all of Murch & Wilson's assumptions (walls at the bulk temperature,
  k independent of pressure, no compression heating, Barus, incompressible; 21 film nodes):
  the film reduction against theirs and against the independent thermal Grubin inlet of
  tests/independent_inlet.py (docs/validation.md, *Thermal inlet*);
* viscous traction coefficient, thermal and isothermal, over SRR = 0.005 … 1.2.
Not a timing; the tests check the rolling point and the traction curve's shape.
"""

import json
import math
import sys
from pathlib import Path

from timing import steel_5w30
from tribodyn import solve_ehl
from tribodyn.contact.ehl.thermal import ThermalOptions, solve_thermal_ehl
from tribodyn.physics import thermal_oil
from tribodyn.physics.heat_conduction import ThermalBody, ThermalProperties

W, R, UE = 5e5, 0.02, 5.0


def main():
    oil, pair, tb = steel_5w30()
    cold = ThermalProperties(1e6, 7850.0, 470.0)
    tb_cold = (ThermalBody(cold), ThermalBody(cold))
    e = 210e9 / 0.91
    L = (
        oil.temperature_viscosity_coefficient()
        * oil.inlet_viscosity
        * UE**2
        / float(oil.conductivity(0.0, oil.inlet_temperature))
    )
    ph = math.sqrt(W * e / (2 * math.pi * R))
    iso = solve_ehl(W, R, UE, 0.0, pair, oil.isothermal())
    film = []
    for srr in (0.0, 0.5, 1.0, 1.5):
        r = solve_thermal_ehl(W, R, UE, srr * UE, pair, oil, tb)
        rc = solve_thermal_ehl(W, R, UE, srr * UE, pair, oil, tb_cold)
        k0 = float(oil.conductivity(0.0, oil.inlet_temperature))
        gupta = (1 - 13.2 * ph / e * L**0.42) / (1 + 0.213 * (1 + 2.23 * srr**0.83) * L**0.64)
        film.append(
            {
                "srr": srr,
                "h_thermal_over_isothermal": r.central_film / iso.central_film,
                "h_over_isothermal_walls_at_bulk_temperature": rc.central_film / iso.central_film,
                "inlet_couette_mid_film_rise_K": oil.inlet_viscosity * (srr * UE) ** 2 / (8 * k0),
                "gupta_1992": gupta,
                "murch_wilson_1975": 3.94 / (3.94 + L**0.62) if srr == 0 else None,
                "max_temperature_rise_K": r.max_temperature - r.inlet_temperature,
                "converged": bool(r.converged and rc.converged),
            }
        )
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from ehl_cases import murch_wilson_oil
    from independent_inlet import grubin_inlet, roelands_thinning

    mw_oil, fluid = murch_wilson_oil(oil)
    saved = thermal_oil.CONDUCTIVITY_PRESSURE
    thermal_oil.CONDUCTIVITY_PRESSURE = (0.0, saved[1])  # k independent of pressure
    try:
        mw_iso = solve_ehl(W, R, UE, 0.0, pair, mw_oil.isothermal())
        mw = solve_thermal_ehl(
            W,
            R,
            UE,
            0.0,
            pair,
            mw_oil,
            tb_cold,
            thermal_options=ThermalOptions(film_nodes=21, compression_heating=False),
        )
    finally:
        thermal_oil.CONDUCTIVITY_PRESSURE = saved
    thinning = roelands_thinning(fluid["mu0"], mw_oil.inlet_temperature, fluid["beta"])
    kw = dict(load=W, radius=R, e_prime=e, speed=UE, **fluid, thinning=thinning)
    grubin = grubin_inlet(**kw)["h0"] / grubin_inlet(**kw, heating=False)["h0"]
    inlet_analysis = {
        "h_over_isothermal": mw.central_film / mw_iso.central_film,
        "independent_thermal_grubin_inlet": grubin,
        "murch_wilson_1975": 3.94 / (3.94 + L**0.62),
        "converged": bool(mw.converged),
    }
    traction = []
    for srr in (0.005, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8, 1.2):
        r = solve_thermal_ehl(W, R, UE, srr * UE, pair, oil, tb)
        i = solve_ehl(W, R, UE, srr * UE, pair, oil.isothermal())
        traction.append(
            {
                "srr": srr,
                "mu_thermal": r.viscous_friction / W,
                "mu_isothermal": i.viscous_friction / W,
                "max_temperature_rise_K": r.max_temperature - r.inlet_temperature,
                "converged": bool(r.converged),
            }
        )
    print(
        json.dumps(
            {
                "thermal_loading_L": L,
                "hertz_pressure_Pa": ph,
                "film": film,
                "rolling_under_inlet_analysis_assumptions": inlet_analysis,
                "traction": traction,
            },
            indent=2,
        )
    )


if __name__ == "__main__":
    main()
