"""Boundary-element contact of rough surfaces and the load–separation law that replaces
Greenwood–Tripp: closed forms (Westergaard/Johnson–Greenwood–Higginson wavy surface,
rigid–plastic bearing area), a published numerical range (κ of the area–load law) and
the solver plumbing (a law tabulated from F_5/2 reproduces Greenwood–Tripp)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import asperity_pressure_derivative
from tribodyn import InputError, Roughness, greenwood_tripp
from tribodyn.config.build import build
from tribodyn.physics.asperity_law import LoadSeparationLaw
from tribodyn.physics.rough_contact import solve_rough_contact
from tribodyn.topography.load_separation import load_separation_law
from tribodyn.topography.synthetic import synthetic_surface

E_STAR = 1e11


def _wavy(n=512, ell=1e-4, amp=1e-6):
    x = (np.arange(n) + 0.5) * ell / n
    z = np.tile(amp * np.cos(2 * math.pi * x / ell)[:, None], (1, 4))
    return z, ell / n


@pytest.mark.parametrize("sep", [0.9e-6, 0.6e-6, 0.3e-6, 0.1e-6, 0.02e-6])
def test_wavy_surface_contact_width_matches_westergaard(sep):
    # Johnson, Greenwood & Higginson (1985), plane strain: p̄ = p* sin²(πa/ℓ), p* = πE*Δ/ℓ
    z, dx = _wavy()
    ell, amp = 1e-4, 1e-6
    r = solve_rough_contact(z, dx, E_STAR, sep)
    assert r.converged, r.message
    p_star = math.pi * E_STAR * amp / ell
    assert 0.0 < r.mean_pressure < p_star
    a_exact = ell / math.pi * math.asin(math.sqrt(r.mean_pressure / p_star))
    a_bem = 0.5 * r.area_fraction * ell
    assert abs(a_bem - a_exact) <= 1.0 * dx  # the contact edge is resolved to a node


def test_wavy_surface_full_contact_pressure():
    # heavy load: the contact closes as p̄ → p* (contact width → ℓ)
    z, dx = _wavy(n=256)
    r = solve_rough_contact(z, dx, E_STAR, 0.002e-6)
    p_star = math.pi * E_STAR * 1e-6 / 1e-4
    assert r.converged
    assert 0.93 < r.mean_pressure / p_star < 1.0
    a_exact = 1e-4 / math.pi * math.asin(math.sqrt(r.mean_pressure / p_star))
    assert abs(0.5 * r.area_fraction * 1e-4 - a_exact) <= 1.0 * dx


def test_rigid_plastic_limit_is_the_bearing_area():
    # H ≪ elastic pressures: no elastic deflection, every contact flows at H, so
    # A/A₀ = fraction of heights above ū and p̄ = H A/A₀
    t = synthetic_surface(
        (32, 32), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=6.4e-6, seed=3
    )
    z = t.heights() - t.heights().mean()
    hard = 1e4
    for lam in (0.0, 0.5, 1.0):
        r = solve_rough_contact(z, 0.4e-6, E_STAR, lam * 0.2e-6, hardness=hard)
        assert r.converged, r.message
        bearing = float(np.mean(z > lam * 0.2e-6))
        assert abs(r.area_fraction - bearing) <= 2.0 / z.size
        assert r.plastic_fraction == pytest.approx(r.area_fraction, abs=2.0 / z.size)
        assert r.mean_pressure == pytest.approx(hard * r.area_fraction, rel=1e-6)


@pytest.fixture(scope="module")
def light_load():
    """Elastic contact of a 128² self-affine surface (σ 0.2 µm, H 0.8) at light loads."""
    n, dx = 128, 0.4e-6
    t = synthetic_surface(
        (n, n), dx, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=25.6e-6, seed=1
    )
    z = t.heights()
    q = 2 * np.pi * np.fft.fftfreq(n, dx)
    zq = np.fft.fft2(z - z.mean())
    slope = math.sqrt(float(np.sum((q[:, None] ** 2 + q[None, :] ** 2) * abs(zq) ** 2)) / n**4)
    init, out = None, {}
    for lam in (2.0, 1.75, 1.5, 1.25, 1.0):
        r = solve_rough_contact(z, dx, E_STAR, lam * 0.2e-6, initial=init)
        init = r.pressure
        assert r.converged, r.message
        out[lam] = r
    return slope, out


def test_light_load_area_coefficient_in_published_range(light_load):
    # A/A₀ = κ p̄/(E* ∇z_rms) at light load; numerical κ lies between Persson's √(8/π) ≈ 1.60
    # and Bush–Gibson–Thomas' √(2π) ≈ 2.51 (Paggi & Ciavarella, Wear 268 (2010) 1020)
    slope, res = light_load
    for lam in (2.0, 1.5, 1.0):
        r = res[lam]
        kappa = r.area_fraction * E_STAR * slope / r.mean_pressure
        assert 0.005 < r.area_fraction < 0.12
        assert math.sqrt(8 / math.pi) <= kappa <= math.sqrt(2 * math.pi), (lam, kappa)


def test_light_load_pressure_is_exponential_in_separation(light_load):
    # Persson, PRL 99 (2007) 125502: at small pressure p ∝ exp(−ū/u₀), u₀ of the order of
    # the RMS roughness (Lorenz & Persson 2009: u₀ "a constant of order the rms roughness")
    _, res = light_load
    lam = np.array(sorted(res))
    lnp = np.log([res[k].mean_pressure for k in lam])
    slope, icpt = np.polyfit(lam, lnp, 1)
    assert np.max(np.abs(lnp - (icpt + slope * lam))) < 0.1  # within 10 % of the exponential
    u0 = -1.0 / slope  # in units of σ
    assert 0.2 < u0 < 1.0, u0


def test_contact_reports_non_convergence():
    z, dx = _wavy(n=128)
    r = solve_rough_contact(z, dx, E_STAR, 0.3e-6, max_iter=2)
    assert not r.converged and "not converged" in r.message


def test_contact_input_errors():
    z, dx = _wavy(n=32)
    with pytest.raises(InputError, match="separation > 0"):
        solve_rough_contact(z, dx, E_STAR, 0.0)
    with pytest.raises(InputError, match="hardness"):
        solve_rough_contact(z, dx, E_STAR, 1e-7, hardness=-1.0)
    with pytest.raises(InputError, match="2-D"):
        solve_rough_contact(np.ones(5), dx, E_STAR, 1e-7)


def _gt_law(e_prime, rough):
    lam = np.linspace(-1.0, 6.0, 141)
    p = rough.pressure_scale(e_prime) * greenwood_tripp(2.5, lam)
    a = rough.contact_area_fraction(lam * rough.rms)
    return LoadSeparationLaw(lam, p, a, e_prime, source="Greenwood–Tripp table")


def test_law_tabulated_from_greenwood_tripp_reproduces_it():
    e_prime = 2.31e11
    gt = Roughness(1e9, 0.2e-6, 200e-6)
    law = Roughness(1e9, 0.2e-6, 200e-6, law=_gt_law(e_prime, gt))
    h = np.linspace(-0.1e-6, 1.1e-6, 97)
    assert law.asperity_model == "measured" and gt.asperity_model == "greenwood_tripp"
    np.testing.assert_allclose(
        law.asperity_pressure(h, e_prime), gt.asperity_pressure(h, e_prime), rtol=2e-4
    )
    np.testing.assert_allclose(
        asperity_pressure_derivative(law, h, e_prime),
        asperity_pressure_derivative(gt, h, e_prime),
        rtol=5e-3,
    )
    np.testing.assert_allclose(law.contact_area_fraction(h), gt.contact_area_fraction(h), rtol=2e-4)


def test_ehl_with_a_law_uses_it():
    # one code path: the EHL solver with a law tabulated from F_5/2 gives the
    # Greenwood–Tripp result; scaled ×50 it carries more asperity load
    from tribodyn import Body, Lubricant, Material, solve_ehl
    from tribodyn.physics.materials import reduced_modulus

    steel = Body(Material(E=210e9, nu=0.3))
    oil = Lubricant(viscosity=0.01, pressure_viscosity=1.5e-8)
    e_s = reduced_modulus((steel, steel), surface=True)
    gt = Roughness(1e10, 0.2e-6, 20e-6)
    base = _gt_law(e_s, gt)
    tab = Roughness(1e10, 0.2e-6, 20e-6, law=base)
    big = Roughness(
        1e10,
        0.2e-6,
        20e-6,
        law=LoadSeparationLaw(base.lam, 50 * base.pressure, base.area, e_s),
    )
    kw = dict(
        load=1e5,
        radius=0.01,
        entrainment_speed=0.3,
        sliding_speed=1.0,
        bodies=(steel, steel),
        lubricant=oil,
    )
    r_gt, r_tab, r_big = (solve_ehl(roughness=r, **kw) for r in (gt, tab, big))
    assert r_gt.converged and r_tab.converged and r_big.converged
    assert r_gt.asperity_load > 0.005 * 1e5
    assert r_tab.asperity_load == pytest.approx(r_gt.asperity_load, rel=2e-3)
    assert r_big.asperity_load > 3 * r_gt.asperity_load


def test_law_from_elastic_plastic_contact_is_monotone_and_capped():
    t = synthetic_surface(
        (64, 64), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=12.8e-6, seed=2
    )
    e_prime, hard = 2.31e11, 7e9
    law = load_separation_law(
        t.heights(), 0.4e-6, e_prime, hard, separations=(2.0, 1.5, 1.0, 0.6, 0.3, 0.0)
    )
    rough = Roughness(1e9, 0.2e-6, 200e-6, law=law)
    h = np.linspace(-2e-6, 1e-6, 200)
    p = rough.asperity_pressure(h, e_prime)
    assert np.all(np.diff(p) <= 0.0) and p.max() <= hard * (1 + 1e-9)
    assert np.all(asperity_pressure_derivative(rough, h, e_prime) <= 0.0)
    a = rough.contact_area_fraction(h)
    assert np.all((a >= 0) & (a <= 1))


# ----------------------------------------------------------------------------- case file
_SET = """
[[surface_sets]]
name = "m"
roughness = {{ asperity_density = 1e9, rms = 0.2e-6, summit_radius = 200e-6 }}
{extra}
"""


def _case(extra):
    from tribodyn.config import Case

    return Case.from_toml_string(_SET.format(extra=extra))


@pytest.mark.parametrize(
    "extra, match",
    [
        ('asperity_model = "measured"', "measured_surface"),
        (
            'asperity_model = "greenwood_tripp"\nmeasured_surface = { topography = "x.sdf" }',
            "asperity_model",
        ),
        ("measured_surface = { topography = 'x.sdf' }", "measured_surface.topography"),
        ('asperity_model = "measured"\nmeasured_surface = { hurst = 0.8 }', "short_cutoff"),
        (
            'asperity_model = "measured"\nmeasured_surface = { topography = "x.sdf", hurst = 0.8 }',
            "topography",
        ),
        (
            'asperity_model = "measured"\nmeasured_surface = { hurst = 0.8, '
            "short_cutoff = 1e-7, long_cutoff = 25e-6 }",
            "4 pixels",
        ),
        ('asperity_model = "persson"', "asperity_model"),
    ],
)
def test_case_asperity_model_errors_name_the_field(extra, match):
    with pytest.raises(InputError, match=match):
        _case(extra)


def test_default_asperity_law_is_the_surface_law_of_the_typical_spectrum():
    """A set without asperity keys (a 0.2 case file) gets the boundary-element law of a
    self-affine surface with its σ and the typical spectrum of physics.typical; the
    same surface at the same E' gives the same (cached) law object."""
    from tribodyn.config import Case
    from tribodyn.physics import typical
    from tribodyn.physics.materials import reduced_modulus
    from tribodyn.topography.load_separation import synthetic_load_separation

    s = build(_case("")).set("m").surface
    assert s.roughness.asperity_model == "measured"
    assert "typical spectrum" in s.asperity_law and "H 0.85" in s.asperity_law
    law = synthetic_load_separation(
        0.2e-6,
        typical.SURFACE_HURST.value,
        typical.SURFACE_SHORT_CUTOFF.value,
        typical.SURFACE_LONG_CUTOFF.value,
        reduced_modulus(s.bodies, surface=True),
        7e9,
    )
    assert s.roughness.law is law
    # Greenwood–Tripp only where the case asks for it
    gt = build(_case('asperity_model = "greenwood_tripp"')).set("m").surface
    assert gt.roughness.law is None and "asks for it" in gt.asperity_law
    # the library's default sets follow the default; the paper's sets keep Table 4 GT
    assert all(x.roughness.law is not None for x in build(Case()).surface_sets)
    from tribodyn.config import load_case

    assert all(x.roughness.law is None for x in build(load_case("andreou2023")).surface_sets)


def test_greenwood_tripp_defaults_imply_a_small_rms_slope():
    """Nayak/McCool: η, β, σ of a surface's own spectral moments give back its √m₂
    (an identity of the relations), and the typical ηβσ 0.04, σ/β 1e-3 give ≈ 0.018."""
    from tribodyn.topography.spectral_moments import mccool_parameters
    from tribodyn.topography.synthetic import synthetic_moments

    m = synthetic_moments(0.2e-6, 0.85, 3.2e-6, 25.6e-6)
    mc = mccool_parameters(m)
    r = Roughness(mc.asperity_density, 0.2e-6, mc.summit_radius)
    assert r.implied_rms_slope == pytest.approx(np.sqrt(m.m2), rel=1e-9)
    # m₂ = 3 (σ/β) / (128 √3 ηβσ) = 3e-3/(128·√3·0.04) by hand
    assert Roughness(1e9, 0.2e-6, 200e-6).implied_rms_slope == pytest.approx(
        np.sqrt(3e-3 / (128 * np.sqrt(3) * 0.04)), rel=1e-12
    )


def test_case_measured_surface_builds_a_law(tmp_path):
    case = _case(
        'asperity_model = "measured"\nmeasured_surface = { hurst = 0.8, short_cutoff = 3.2e-6,'
        " long_cutoff = 6.4e-6, grid = 32, hardness = 7e9 }"
    )
    rough = build(case).set("m").surface.roughness
    assert rough.asperity_model == "measured" and rough.law.hardness == 7e9
    assert rough.rms == 0.2e-6
    assert rough.asperity_pressure(0.3 * 0.2e-6, 2.3e11) > 100 * Roughness(
        1e9, 0.2e-6, 200e-6
    ).asperity_pressure(0.3 * 0.2e-6, 2.3e11)
    with pytest.raises(InputError, match="measured_surface.*no such file"):
        _case('asperity_model = "measured"\nmeasured_surface = { topography = "no.sdf" }')


def test_calibration_refuses_greenwood_tripp_parameter_with_a_law():
    from tribodyn.physics.lubricant import Lubricant
    from tribodyn.workflow.calibration import CalibrationSetup, FrictionData, calibrate_friction

    gt = Roughness(1e9, 0.2e-6, 200e-6)
    setup = CalibrationSetup(
        radius=0.01,
        lubricant=Lubricant(0.02, 2e-8),
        roughness=Roughness(1e9, 0.2e-6, 200e-6, law=_gt_law(2.31e11, gt)),
    )
    ue = np.geomspace(0.01, 1.0, 8)
    data = FrictionData(ue, 0.2 * ue, np.full(8, 2e5), np.full(8, 0.1))
    with pytest.raises(InputError, match="roughness_parameter"):
        calibrate_friction(data, setup, free=("roughness_parameter",))


def test_case_measured_map_file(tmp_path):
    # a measured map file: read, made periodic (mirrored), σ checked against roughness.rms
    from tribodyn.config import Case
    from tribodyn.topography import write_topography

    t = synthetic_surface(
        (48, 48), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=9.6e-6, seed=4
    )
    write_topography(t, tmp_path / "pair.nc")
    text = _SET.format(
        extra='asperity_model = "measured"\nmeasured_surface = { topography = "pair.nc" }'
    )
    case = Case.from_toml_string(text, base_dir=tmp_path)
    rough = build(case).set("m").surface.roughness
    assert rough.law is not None and rough.rms == pytest.approx(0.2e-6, rel=0.1)
    assert rough.asperity_pressure(0.0, 2.3e11) > 1e8
    d = case.to_dict(resolve_paths=True)
    assert d["surface_sets"][0]["measured_surface"]["topography"] == str(tmp_path / "pair.nc")
    with pytest.raises(InputError, match=r"topography.*RMS height"):
        Case.from_toml_string(text.replace("rms = 0.2e-6", "rms = 0.4e-6"), base_dir=tmp_path)
    with pytest.raises(InputError, match=r"measured_surface.topography.*no such file"):
        Case.from_toml_string(text.replace("pair.nc", "other.nc"), base_dir=tmp_path)


def test_report_method_names_the_asperity_model_of_the_sets():
    from types import SimpleNamespace

    from tribodyn.output.report import _asperity_models
    from tribodyn.workflow.inputs_as_used import surface_as_used

    e_prime = 2.31e11
    gt = Roughness(1e9, 0.2e-6, 200e-6)
    law = Roughness(1e9, 0.2e-6, 200e-6, law=_gt_law(e_prime, gt))

    def case(*roughs):
        """The surface sets as used (what the report reads) of sets with ``roughs``."""
        sets = [
            SimpleNamespace(
                name=f"s{i}",
                roughness=r,
                coating_label=f"s{i}",
                coating_material=None,
                coating=None,
                asperity_law="",
                boundary_shear_coefficient=0.1,
            )
            for i, r in enumerate(roughs)
        ]
        return {s.name: surface_as_used(s) for s in sets}

    assert _asperity_models(case(gt, gt)) == "Greenwood–Tripp asperities"
    assert "Greenwood" not in _asperity_models(case(law, law))
    mixed = _asperity_models(case(gt, law))
    assert "s1" in mixed and "Greenwood–Tripp for the other sets" in mixed


def test_law_hands_the_pair_modulus_to_the_contact_as_e_star():
    """The law takes E' (paper convention, E' = 2E*) and must solve the contact with
    E* = E'/2: on the wavy surface each tabulated point obeys Westergaard's
    p̄ = p* sin²(πa/ℓ), p* = π(E'/2)Δ/ℓ, with 2a/ℓ the law's contact fraction (a factor 2
    in the hand-off would put every point off by 2×)."""
    z, dx = _wavy(n=256)
    ell, amp, e_prime = 1e-4, 1e-6, 2e11
    sigma = float(np.sqrt(np.mean(z**2)))
    law = load_separation_law(z, dx, e_prime, separations=(1.2, 0.9, 0.6, 0.3, 0.1))
    p_star = math.pi * 0.5 * e_prime * amp / ell
    for lam, p, area in zip(law.lam, law.pressure, law.area, strict=True):
        assert 0.0 < area < 1.0, lam
        a_exact = ell / math.pi * math.asin(math.sqrt(p / p_star))
        assert abs(0.5 * area * ell - a_exact) <= 1.0 * dx, (lam, sigma)


def _write_map(path, seed=4, scale=1.0):
    from tribodyn.topography import write_topography

    t = synthetic_surface(
        (48, 48), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=9.6e-6, seed=seed
    )
    write_topography(t, path)
    return t.heights()


def test_case_measured_map_without_calibration_takes_unit_and_physical_sizes(tmp_path):
    """A bare height matrix (.npy, plain text) stores neither lateral size nor unit: the
    case gives them (measured_surface.unit, physical_sizes) and the law equals that of
    the same heights in a calibrated file (netCDF, metres)."""
    from SurfaceTopography import Topography

    from tribodyn.config import Case
    from tribodyn.topography import write_topography

    z = _write_map(tmp_path / "periodic.nc")
    # a measured map: not periodic (detrended and mirrored, as a bare matrix is)
    write_topography(
        Topography(z, (19.2e-6, 19.2e-6), periodic=False, unit="m"), tmp_path / "pair.nc"
    )
    np.save(tmp_path / "pair.npy", z * 1e6)  # µm, 48 × 0.4 µm = 19.2 µm
    np.savetxt(tmp_path / "pair.txt", z * 1e9)  # nm

    def case(ms):
        text = _SET.format(extra=f'asperity_model = "measured"\nmeasured_surface = {{ {ms} }}')
        return Case.from_toml_string(text, base_dir=tmp_path)

    ref = build(case('topography = "pair.nc"')).set("m").surface.roughness.law
    for ms in (
        'topography = "pair.npy", unit = "µm", physical_sizes = [19.2, 19.2]',
        'topography = "pair.txt", unit = "nm", physical_sizes = [19200.0]',
    ):
        law = build(case(ms)).set("m").surface.roughness.law
        assert law is not ref
        np.testing.assert_allclose(law.lam, ref.lam)
        # heights differ by rounding only: equal to the contact solver's tolerance
        np.testing.assert_allclose(law.pressure, ref.pressure, rtol=1e-6)
        np.testing.assert_allclose(law.area, ref.area, rtol=1e-6, atol=1e-9)
    # the size matters: twice the pixel halves the slopes (not the same law)
    wide = case('topography = "pair.npy", unit = "µm", physical_sizes = [38.4]')
    wide_p = build(wide).set("m").surface.roughness.law.pressure
    assert np.max(np.abs(wide_p - ref.pressure) / ref.pressure.max()) > 0.05


_MAP_ERRORS = [
    ('topography = "pair.npy"', r"topography.*no lateral calibration.*physical_sizes"),
    (
        'topography = "pair.npy", unit = "furlong", physical_sizes = [19.2]',
        r"measured_surface\.unit: must be 'm', 'mm'",
    ),
    (
        'topography = "pair.npy", unit = "µm", physical_sizes = [19.2, 0.0]',
        r"measured_surface\.physical_sizes: lengths must be > 0",
    ),
    (
        'topography = "pair.npy", unit = "µm", physical_sizes = 19.2',
        r"measured_surface\.physical_sizes: must be an array \(",
    ),
    (
        'topography = "pair.npy", unit = "µm", physical_sizes = [1.0, 2.0, 3.0]',
        r"measured_surface\.physical_sizes.*at most 2",
    ),
    (
        'topography = "periodic.nc", physical_sizes = [19.2]',
        r"topography.*already stores its lateral size",
    ),
    (
        'hurst = 0.8, short_cutoff = 3.2e-6, long_cutoff = 25.6e-6, unit = "µm"',
        r"measured_surface\.unit: only with a topography",
    ),
]


@pytest.mark.parametrize("ms, match", _MAP_ERRORS)
def test_case_measured_map_calibration_errors_name_the_field(tmp_path, ms, match):
    """A map's lateral calibration given wrongly, or where it does not belong, is refused
    with the field named."""
    from tribodyn.config import Case

    z = _write_map(tmp_path / "periodic.nc")
    np.save(tmp_path / "pair.npy", z * 1e6)
    text = _SET.format(extra=f'asperity_model = "measured"\nmeasured_surface = {{ {ms} }}')
    with pytest.raises(InputError, match=match):
        Case.from_toml_string(text, base_dir=tmp_path)


def test_measured_map_law_is_computed_once_per_file_and_pair(tmp_path, monkeypatch):
    """Validating the case again (Case.updated, the points of a sweep) reuses the law of
    an unchanged map; a changed file, another hardness or another E' compute it anew."""
    import os

    from tribodyn.config import load_case
    from tribodyn.config.sweep import SweepSpec
    from tribodyn.topography import load_separation as ls
    from tribodyn.topography import reading

    calls = {"law": 0, "read": 0}
    law_fn, read_fn = ls.load_separation_law, reading.read_topography

    def counted_law(*a, **k):
        calls["law"] += 1
        return law_fn(*a, **k)

    def counted_read(*a, **k):
        calls["read"] += 1
        return read_fn(*a, **k)

    monkeypatch.setattr(ls, "load_separation_law", counted_law)
    monkeypatch.setattr(reading, "read_topography", counted_read)
    _write_map(tmp_path / "pair.nc")
    text = _SET.format(
        extra='asperity_model = "measured"\nmeasured_surface = { topography = "pair.nc" }'
    )
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    case = load_case(tmp_path / "case.toml")
    law = build(case).set("m").surface.roughness.law
    assert calls == {"law": 1, "read": 1}
    for change in ({"engine.speed_rpm": 2000.0}, {"numerics.tol": 1e-8}):
        assert build(case.updated(change)).set("m").surface.roughness.law is law
    sweep = SweepSpec.from_toml_string(
        '[sweep]\ncase = "case.toml"\n[[axes]]\npath = "engine.speed_rpm"\n'
        "values = [1000.0, 1500.0, 2500.0]",
        base_dir=tmp_path,
    )
    assert all(build(p.case).set("m").surface.roughness.law is law for p in sweep.points())
    assert calls == {"law": 1, "read": 1}
    harder = case.updated({"surface_sets[0].measured_surface.hardness": 9e9})
    assert build(harder).set("m").surface.roughness.law is not law and calls["law"] == 2
    stiffer = case.updated({"materials.steel.E": 2.5e11})
    assert build(stiffer).set("m").surface.roughness.law is not law and calls["law"] == 3
    st = os.stat(tmp_path / "pair.nc")
    _write_map(tmp_path / "pair.nc", seed=5)  # the map measured again
    os.utime(tmp_path / "pair.nc", ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    again = build(case.updated({"engine.speed_rpm": 2000.0})).set("m").surface.roughness.law
    assert again is not law and calls == {"law": 4, "read": 2}
    assert not np.allclose(again.pressure, law.pressure)
