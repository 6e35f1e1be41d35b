"""Lumped vs flexible valvetrain for a flexible case (the study's "lumped vs flexible").

The lumped companion has the same masses, spring rate, preload and static compliances
(:meth:`tribodyn.valvetrain.flexible.FlexibleValvetrain.lumped_equivalent`), so the
differences come from the bodies' flexibility (stem, spring continuum and coil clash,
skirt), the camshaft's torsion and the joints' placement. Both run with the same cam,
explicit tribology and numerics. The jump speed of each (lowest engine speed with contact
loss during the lift) is located by :func:`~tribodyn.valvetrain.sweep.locate_jump_speed`:
a quasi-static estimate corrected by the case-speed run, then secant steps on the minimum
contact force against n², bracketed, until the bracket is narrower than
:data:`JUMP_SPEED_TOLERANCE` (typically 5–8 dynamics runs per model, all near the jump).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..config.build import as_built
from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from ..valvetrain.sweep import locate_jump_speed

__all__ = ["ModelComparison", "compare_lumped_flexible", "JUMP_SPEED_TOLERANCE"]

#: width of the final jump-speed bracket [rpm] (the speed is its midpoint, ± half of it)
JUMP_SPEED_TOLERANCE = 100.0


@dataclass
class ModelComparison:
    """Key numbers of both models: ``rows[model][quantity]`` (SI; speeds in rpm)."""

    rows: dict = field(default_factory=dict)
    messages: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"rows": self.rows, "messages": self.messages}


def _row(r: ValvetrainResult) -> dict:
    s = r.summary()
    return {
        "peak_contact_force_N": s["peak_contact_force_N"],
        "min_contact_force_in_event_N": s["min_contact_force_in_event_N"],
        "seating_velocity_m_s": s["seating_velocity_m_s"],
        "friction_energy_per_cycle_J": s["friction_energy_per_cycle_J"],
        "jump_at_case_speed": s["jump"],
        "solver_time_s": r.stats.get("wall_time_s"),
    }


def compare_lumped_flexible(
    case,
    tribology,
    flexible: ValvetrainResult,
    *,
    high_factor: float = 3.0,
) -> ModelComparison:
    """Run the lumped companion of a flexible ``case`` (a Case or BuiltCase; same
    tribology and numerics) and collect both models' numbers; ``flexible`` is the case's
    own (flexible) run. The jump speed is searched up to ``high_factor`` × the case's
    engine speed (NaN with a message if there is no jump up to there)."""
    built = as_built(case)
    out = ModelComparison()
    opts = built.dynamics_options
    lumped = built.lumped
    runs = {  # model → (its parameters, its run at the case speed)
        "lumped": (lumped, simulate_valvetrain(built.cam, lumped, tribology=tribology, **opts)),
        "flexible": (built.valvetrain, flexible),
    }
    for name, (_, r) in runs.items():
        if not r.converged:
            out.messages.append(f"{name} dynamics failed: {r.message}")
            continue
        out.rows[name] = _row(r)
    kw = {k: v for k, v in opts.items() if k != "engine_speed"}
    for name, (params, r) in runs.items():
        if name not in out.rows:
            continue
        row = out.rows[name]
        if r.jump:
            row["jump_speed_rpm"] = math.nan
            out.messages.append(f"{name} jump speed: the follower already jumps at the case speed")
            continue
        speed = built.case.engine_speed
        found = locate_jump_speed(
            built.cam,
            params,
            start=speed,
            start_result=r,
            high=high_factor * speed,
            tolerance=JUMP_SPEED_TOLERANCE,
            tribology=tribology,
            **kw,
        )
        row["jump_speed_rpm"] = found.speed
        row["jump_speed_bracket_rpm"] = list(found.bracket)
        row["quasi_static_jump_speed_rpm"] = found.quasi_static
        row["jump_speed_runs"] = len(found.runs) - 1  # the case-speed run is not extra
        if not found.converged:
            out.messages.append(f"{name} jump speed: {found.message}")
    return out
