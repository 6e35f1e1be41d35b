"""Mixed elastohydrodynamic line contact: steady and transient (paper Section 2.4, Eqs. 1–9).

Modules: :mod:`.options` (options, inputs, result) · :mod:`.grid` (domain and grid) ·
:mod:`.reynolds` (discrete system and linearisation) · :mod:`.newton` (semismooth Newton,
GMRES, two-grid) · :mod:`.postprocess` (friction, loads, checks) · :mod:`.validity`
(film > 0, the model's assumptions) · :mod:`.steady` · :mod:`.transient`; thermal EHL:
:mod:`.energy` (film + solids energy equation) · :mod:`.thermal` (steady) ·
:mod:`.thermal_transient`.

Equations (x in the frame of the contact point, u_e the mean entraining speed):

* Reynolds (Eq. 1)      ∂/∂x(ρh³/(12μ) ∂p/∂x) − u_e ∂(ρh)/∂x − ∂(ρh)/∂t = 0
* cavitation            p ≥ 0, Reynolds residual ≤ 0, p·residual = 0 (complementarity;
                        the Reynolds exit condition p = dp/dx = 0, Eq. 4, emerges)
* film (Eq. 9)          h = h₀ + x²/(2R) + V(x),  V = K (p + p_a)   (DC-FFT, coated or not)
* asperities (Eq. 6)    p_a = (8√2/15)π(ηβσ)²√(σ/β) E' F_5/2(h/σ), local, load-carrying
* load balance (Eq. 8)  ∫(p + p_a) dx = w
* rheology              Roelands (or Barus) μ(p), Dowson–Higginson ρ(p)

Discretisation: uniform grid (needed by DC-FFT), finite volumes with arithmetic-mean
face coefficients, second-order upwind Couette term (first order next to the inlet),
backward-difference (BDF1/BDF2) time derivative. Unknowns: the total pressure
q = p + p_a at the nodes and h₀, found by a semismooth Newton method on
min(p_i, −c_i R_i) = 0 and the load balance (the film is explicit in q, so the Newton
matrix J = A_P + (A_H − A_P D_a) K needs no inverse), with a non-monotone Armijo line
search. Cold starts go through load continuation when the direct iteration fails.

Scaling: a = max(b, √(2R h_est)) (b: Hertz half-width; h_est: Moes central film) so
that both elastic and rigid (inlet-dominated) contacts get a sufficient domain;
P = p a/w, H = h R/a², X = x/a.
"""

from .options import EHLOptions, EHLResult
from .steady import solve_ehl
from .thermal import ThermalEHLResult, ThermalOptions, solve_thermal_ehl
from .thermal_transient import ThermalTransientEHL
from .transient import TransientEHL

__all__ = [
    "EHLOptions",
    "EHLResult",
    "solve_ehl",
    "TransientEHL",
    "ThermalOptions",
    "ThermalEHLResult",
    "solve_thermal_ehl",
    "ThermalTransientEHL",
]
