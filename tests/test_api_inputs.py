"""Bad types and values at every public constructor and solver give InputError naming the
argument (never TypeError, ValueError, OverflowError, … from deep inside), and the
constructors and the case file share one set of limits (tribodyn.physics.limits)."""

import math
import re

import numpy as np
import pytest
from scipy import integrate

from ehl_cases import OIL_055 as OIL
from ehl_cases import PAIR, STEEL
from tribodyn import (
    Body,
    Coating,
    EHLOptions,
    InputError,
    Lubricant,
    Material,
    Roughness,
    TransientEHL,
    greenwood_tripp,
    hertz_line_contact,
    reduced_modulus,
    solve_dry_contact,
    solve_ehl,
)
from tribodyn.config import Case
from tribodyn.physics import limits as L
from tribodyn.valvetrain import ValvetrainParameters

#: values of the wrong type for a number
WRONG_TYPES = [None, "1", "a", [1.0, 2.0], {}, 1j, object(), True]
#: non-finite numbers
NON_FINITE = [float("nan"), float("inf"), -float("inf")]


# ----------------------------------------------------------------------------- the reported problems
@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: solve_ehl(1e4, 0.01, 1.0, 0.0, None, OIL), "bodies"),
        (lambda: greenwood_tripp(1e6, 1.0), "n"),
        (lambda: greenwood_tripp(2.5, "1"), "lam"),
        (lambda: TransientEHL(PAIR, OIL, max_substeps="a"), "max_substeps"),
        (lambda: TransientEHL(PAIR, OIL, max_substeps=-1), "max_substeps"),
        (lambda: Lubricant(0.055, 1e-8, compressible="no"), "compressible"),
        (lambda: Material(E=1e-30, nu=0.3), "E"),
        (lambda: Roughness(asperity_density=1e9, rms=1.0, summit_radius=1e-6), "rms"),
    ],
)
def test_reported_raw_exceptions_are_input_errors(call, name):
    with pytest.raises(InputError, match=rf"^{name} must"):
        call()


# ----------------------------------------------------------------------------- every constructor
VALID = {
    "Material": (Material, dict(E=210e9, nu=0.3)),
    "Coating": (Coating, dict(E=175e9, nu=0.3, thickness=4e-6)),
    "Lubricant": (
        Lubricant,
        dict(
            viscosity=0.055,
            pressure_viscosity=1e-8,
            density=850.0,
            eyring_stress=2e6,
            limiting_shear_coefficient=0.08,
            limiting_shear_stress=0.0,
        ),
    ),
    "Roughness": (Roughness, dict(asperity_density=1e10, rms=0.3e-6, summit_radius=1e-6)),
    "EHLOptions": (
        EHLOptions,
        dict(
            n=256,
            inlet=4.0,
            outlet=1.75,
            inlet_truncation=0.005,
            inlet_rigid=4.0,
            outlet_rigid=2.0,
            tol=1e-9,
            max_iter=60,
            boundary_shear_strength=2e6,
            boundary_shear_coefficient=0.185,
        ),
    ),
    "ValvetrainParameters": (
        ValvetrainParameters,
        dict(
            valve_mass=0.07,
            tappet_mass=0.04,
            spring_rate=33750.0,
            spring_preload=250.0,
            contact_stiffness=4e8,
            seat_stiffness=5e7,
            lash=0.0,
            tappet_radius=0.0165,
        ),
    ),
    "solve_dry_contact": (
        lambda **k: solve_dry_contact(bodies=PAIR, n=64, **k),
        dict(load=1e4, radius=0.01),
    ),
    "hertz_line_contact": (hertz_line_contact, dict(load=1e4, radius=0.01, reduced_modulus=2.3e11)),
}
#: arguments for which None is a documented value (automatic grid, Palmgren contact law)
NONE_ALLOWED = {("EHLOptions", "n"), ("ValvetrainParameters", "contact_stiffness")}
CASES = [
    (cls, arg, bad)
    for cls, (_, kw) in VALID.items()
    for arg in kw
    for bad in WRONG_TYPES + NON_FINITE
    if not (bad is None and (cls, arg) in NONE_ALLOWED)
]


@pytest.mark.parametrize(
    "cls, arg, bad", CASES, ids=[f"{c}-{a}-{type(b).__name__}{b!r:.6}" for c, a, b in CASES]
)
def test_constructors_reject_wrong_types_and_non_finite_numbers(cls, arg, bad):
    build, kw = VALID[cls]
    with pytest.raises(InputError, match=arg):
        build(**{**kw, arg: bad})


#: numbers a float cannot hold, numpy bools and complex scalars (OverflowError before)
UNCONVERTIBLE = [10**400, -(10**400), 10**5000, np.True_, np.complex128(1.0)]
EXTREME_CASES = [
    (cls, arg, bad)
    for cls, (_, kw) in VALID.items()
    for arg in kw
    for bad in UNCONVERTIBLE
    if not (cls == "EHLOptions" and arg == "n" and isinstance(bad, int) and bad < 0)
]


@pytest.mark.parametrize(
    "cls, arg, bad",
    EXTREME_CASES,
    ids=[f"{c}-{a}-{type(b).__name__}{i}" for i, (c, a, b) in enumerate(EXTREME_CASES)],
)
def test_constructors_convert_huge_ints_and_numpy_scalars_safely(cls, arg, bad):
    build, kw = VALID[cls]
    with pytest.raises(InputError, match=arg) as err:
        build(**{**kw, arg: bad})
    assert len(str(err.value)) < 300  # a 5000-digit number is not printed in full


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: greenwood_tripp(2.5, 10**5000), "lam"),
        (lambda: greenwood_tripp(2.5, [1.0, 10**400]), "lam"),
        (lambda: Material(10**400, 0.3), "E"),
    ],
)
def test_huge_ints_give_input_errors(call, name):
    with pytest.raises(InputError, match=rf"^{name} must"):
        call()


def test_check_array_rejects_strings_complex_and_huge_ints():
    from tribodyn._validation import check_array

    for bad in (["1", "2"], [1j, 2.0], [1.0, 10**400], [True, False]):
        with pytest.raises(InputError, match="^x must be an array of real numbers"):
            check_array("x", bad)


@pytest.mark.parametrize(
    "kw, name",
    [
        # wrong types
        (dict(elastic="yes"), "elastic"),
        (dict(limiting_shear=1), "limiting_shear"),
        (dict(viscous_model=3), "viscous_model"),
        (dict(time_order="2"), "time_order"),
        (dict(n=100.5), "n"),
        (dict(n=True), "n"),
        (dict(max_iter=2.5), "max_iter"),
        # values out of range
        (dict(n=8), "n"),
        (dict(inlet=0.5), "inlet"),
        (dict(outlet=-1.0), "outlet"),
        (dict(viscous_model="bingham"), "viscous_model"),
        (dict(time_order=3), "time_order"),
        (dict(max_iter=0), "max_iter"),
        (dict(tol=0.0), "tol"),
    ],
)
def test_bad_ehl_options_name_the_option(kw, name):
    """Option flags and integers are typed, and values out of range are refused."""
    with pytest.raises(InputError, match=name):
        EHLOptions(**kw)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: Body(None), "material"),
        (lambda: Body(STEEL, coating="dlc"), "coating"),
        (lambda: reduced_modulus(42), "bodies"),
        (lambda: reduced_modulus([PAIR[0]]), "bodies"),
        (lambda: Lubricant(0.055, 1e-8, viscosity_model=None), "viscosity_model"),
        (lambda: Roughness(1e10, 3e-7, 1e-6, method=1), "method"),
        (lambda: greenwood_tripp(2.5, [1.0, float("nan")]), "lam"),
        (lambda: greenwood_tripp(2.5, np.array(["a"])), "lam"),
        (lambda: greenwood_tripp(2.5, 1.0, method=None), "method"),
        (lambda: greenwood_tripp(None, 1.0), "n"),
        (lambda: TransientEHL(PAIR, OIL, max_substeps=2.5), "max_substeps"),
        (lambda: TransientEHL(PAIR, OIL, max_substeps=11), "max_substeps"),
        (lambda: TransientEHL(PAIR, OIL, n=8192), "n"),
        (lambda: TransientEHL(None, OIL), "bodies"),
        (lambda: solve_ehl(1e4, 0.01, 1.0, 0.0, PAIR, OIL, n="a"), "n"),
        (lambda: solve_ehl(1e4, 0.01, 1.0, 0.0, PAIR, OIL, bogus=1), "bogus"),
        (lambda: solve_ehl("1e4", 0.01, 1.0, 0.0, PAIR, OIL), "load"),
        (lambda: solve_dry_contact(1e4, 0.01, PAIR, n="a"), "n"),
        (lambda: solve_dry_contact(1e4, 0.01, PAIR, max_iter=None), "max_iter"),
        (lambda: ValvetrainParameters(spring_masses=1.5), "spring_masses"),
        (lambda: ValvetrainParameters().replace(bogus=1), "bogus"),
    ],
)
def test_other_bad_arguments(call, name):
    with pytest.raises(InputError, match=name):
        call()


# ----------------------------------------------------------------------------- shared limits
#: (case-file section dict key, schema model, {case key: (constructor, its kwarg, limit)})
SHARED = [
    (
        "materials",
        "steel",
        {
            "E": (lambda v: Material(E=v, nu=0.3), "E", L.YOUNGS_MODULUS),
            "nu": (lambda v: Material(E=210e9, nu=v), "nu", L.POISSON_RATIO),
        },
    ),
    (
        "lubricant",
        None,
        {
            "viscosity": (lambda v: Lubricant(v, 1e-8), "viscosity", L.VISCOSITY),
            "pressure_viscosity": (
                lambda v: Lubricant(0.05, v),
                "pressure_viscosity",
                L.PRESSURE_VISCOSITY,
            ),
            "density": (lambda v: Lubricant(0.05, 1e-8, density=v), "density", L.DENSITY),
            "eyring_stress": (
                lambda v: Lubricant(0.05, 1e-8, eyring_stress=v),
                "eyring_stress",
                L.EYRING_STRESS,
            ),
        },
    ),
    (
        "valvetrain",
        None,
        {
            "valve_mass": (lambda v: ValvetrainParameters(valve_mass=v), "valve_mass", L.MASS),
            "contact_stiffness": (
                lambda v: ValvetrainParameters(contact_stiffness=v),
                "contact_stiffness",
                L.STIFFNESS,
            ),
            "spring_rate": (
                lambda v: ValvetrainParameters(spring_rate=v),
                "spring_rate",
                L.SPRING_RATE,
            ),
            "seat_damping": (
                lambda v: ValvetrainParameters(seat_damping=v),
                "seat_damping",
                L.DAMPING,
            ),
        },
    ),
    (
        "roughness",
        None,
        {
            "rms": (lambda v: Roughness(1e10, v, 1e-6), "rms", L.ROUGHNESS_RMS),
            "asperity_density": (
                lambda v: Roughness(v, 3e-7, 1e-6),
                "asperity_density",
                L.ASPERITY_DENSITY,
            ),
            "summit_radius": (lambda v: Roughness(1e10, 3e-7, v), "summit_radius", L.SUMMIT_RADIUS),
        },
    ),
]


def _outside(limit):
    """Values just outside each bound of a limit."""
    out = []
    if limit.gt is not None:
        out.append(limit.gt)
    if limit.ge is not None:
        out.append(limit.ge - max(abs(limit.ge) * 1e-3, 1e-3))
    if limit.lt is not None:
        out.append(limit.lt)
    if limit.le is not None:
        out.append(limit.le * 1.001 if limit.le > 0 else limit.le + 1e-3)
    return out


def _case_with(section, sub, key, value):
    rough = {"asperity_density": 1e10, "rms": 3e-7, "summit_radius": 1e-6}
    if section == "materials":
        data = {
            "materials": {
                "steel": {"E": 210e9, "nu": 0.3, "boundary_shear_coefficient": 0.185, key: value}
            }
        }
        return data, f"materials.steel.{key}"
    if section == "roughness":
        data = {"surface_sets": [{"name": "a", "roughness": {**rough, key: value}}]}
        return data, f"surface_sets[0].roughness.{key}"
    return {section: {key: value}}, f"{section}.{key}"


LIMIT_CASES = [
    (sec, sub, key, v)
    for sec, sub, keys in SHARED
    for key, (_, _, lim) in keys.items()
    for v in _outside(lim)
]


@pytest.mark.parametrize(
    "section, sub, key, value", LIMIT_CASES, ids=[f"{s}.{k}={v:g}" for s, _, k, v in LIMIT_CASES]
)
def test_case_file_and_constructor_reject_the_same_values(section, sub, key, value):
    build, arg, limit = dict((k, t) for s, _, ks in SHARED for k, t in ks.items() if s == section)[
        key
    ]
    with pytest.raises(InputError, match=rf"^{arg} must"):
        build(value)
    data, path = _case_with(section, sub, key, value)
    with pytest.raises(InputError, match=re.escape(path)):
        Case.from_dict(data)


def test_schema_ranges_are_the_shared_limits():
    """The range a key records (docs, messages; checked by the constructor it is given
    to) is the constructor's limit."""
    from tribodyn.config import schema
    from tribodyn.valvetrain.parameters import _LIMITS

    def bounds(model, name):
        extra = model.model_fields[name].json_schema_extra
        return extra.get("range") if isinstance(extra, dict) else None

    for name, limit in _LIMITS.items():
        if name == "cam_width":
            assert bounds(schema._CamBase, "width") == limit.constraints()
        else:
            assert bounds(schema.Valvetrain, name) == limit.constraints(), name
    for model, pairs in (
        (schema.MaterialConfig, {"E": L.YOUNGS_MODULUS, "nu": L.POISSON_RATIO}),
        (
            schema.RoughnessConfig,
            {
                "rms": L.ROUGHNESS_RMS,
                "asperity_density": L.ASPERITY_DENSITY,
                "summit_radius": L.SUMMIT_RADIUS,
            },
        ),
        (
            schema.LubricantConfig,
            {"viscosity": L.VISCOSITY, "density": L.DENSITY, "eyring_stress": L.EYRING_STRESS},
        ),
    ):
        for name, limit in pairs.items():
            assert bounds(model, name) == limit.constraints(), name


def test_case_file_names_the_key_of_absurd_valvetrain_values():
    for key, value in (("contact_stiffness", 1e30), ("valve_mass", 1e6)):
        with pytest.raises(InputError, match=rf"valvetrain\.{key}: must be .* \(got 1e\+"):
            Case.from_toml_string(f"[valvetrain]\n{key} = {value:g}\n")


# ----------------------------------------------------------------------------- Greenwood–Tripp
@pytest.mark.parametrize("n", [0.5, 3.5, 6.0, 10.0])
@pytest.mark.parametrize("lam", [-3.0, 0.0, 2.0, 5.0])
def test_greenwood_tripp_orders_up_to_the_limit_match_quadrature(n, lam):
    """F_n(λ) = (1/√2π) ∫_λ^∞ (s − λ)^n e^(−s²/2) ds (Greenwood & Tripp 1970) for every
    order the limit allows, by adaptive quadrature."""
    ref, _ = integrate.quad(
        lambda s: (s - lam) ** n * math.exp(-0.5 * s * s),
        lam,
        np.inf,
        epsabs=0,
        epsrel=1e-12,
        limit=200,
    )
    assert greenwood_tripp(n, lam) == pytest.approx(ref / math.sqrt(2 * math.pi), rel=1e-8)


@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(x_nodes=float("nan")), "x_nodes"),  # ValueError from int(nan) before
        (dict(film_nodes=10**400), "film_nodes"),
        (dict(max_iter=float("inf")), "max_iter"),
        (dict(step_iter=2.5), "step_iter"),
        (dict(solid_nodes="8"), "solid_nodes"),
        (dict(shear_heating="no"), "shear_heating"),
        (dict(compression_heating=1), "compression_heating"),
    ],
)
def test_thermal_options_convert_safely(kw, name):
    from tribodyn.contact.ehl.thermal import ThermalOptions

    with pytest.raises(InputError, match=rf"^{name} must"):
        ThermalOptions(**kw)


@pytest.mark.parametrize("cls", sorted(VALID))
def test_zero_d_arrays_count_as_their_scalars(cls):
    """``np.array(2.5)`` (a 0-d array, what ``a.sum()`` of an array-like or ``np.asarray``
    of a scalar gives) is a number: every constructor takes it as the scalar (it used to
    be refused as 'not a finite real number'); a 0-d NaN is still refused."""
    from tribodyn._validation import check_int, check_real

    build, kw = VALID[cls]
    build(**{k: np.asarray(v) if isinstance(v, (int, float)) else v for k, v in kw.items()})
    assert check_real("x", np.array(2.5)) == 2.5 and check_int("n", np.array(4)) == 4
    with pytest.raises(InputError, match="x must be a finite real number"):
        check_real("x", np.array(np.nan))
