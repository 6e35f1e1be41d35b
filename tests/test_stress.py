"""Subsurface stress of homogeneous and coated half-planes (physics.stress) against closed
forms: McEwen's field of a Hertz pressure with sliding traction (Johnson, Contact Mechanics,
1985, §7.2), its published maxima, the surface Hilbert transform, and the layer limits."""

import math

import numpy as np
import pytest

from tribodyn import Body, Coating, InputError, Material, subsurface_stress

STEEL = Material(E=210e9, nu=0.3)
B = 1e-4  # half-width [m]
P0 = 1e9  # peak pressure [Pa]


def mcewen(x, z, mu):
    """McEwen (1949) / Johnson Eqs. 7.18-7.20: stresses /p0 of p = p0√(1−x²) with q = μp
    in +x on the body (lengths /b), z into the body, compression negative."""
    a = 1.0 - x * x + z * z
    r = np.sqrt(a * a + 4.0 * x * x * z * z)
    m = np.sqrt(0.5 * (r + a))
    n = np.sqrt(np.maximum(0.5 * (r - a), 0.0)) * np.sign(x)
    d = m * m + n * n
    sx = -(m * (1 + (z * z + n * n) / d) - 2 * z) + mu * (n * (2 - (z * z - m * m) / d) - 2 * x)
    sz = -m * (1 - (z * z + n * n) / d) - mu * n * (m * m - z * z) / d
    txz = -n * (m * m - z * z) / d - mu * (m * (1 + (z * z + n * n) / d) - 2 * z)
    return sx, sz, txz


def hertz(n=401, half=2.0):
    x = np.linspace(-half, half, n)
    return x, np.sqrt(np.clip(1.0 - x * x, 0.0, None))


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_mcewen_field_at_points(mu):
    x, p = hertz()
    pts = [(-0.5, 0.3), (0.0, 0.5), (0.5, 0.78), (1.2, 0.4), (-1.1, 0.2), (0.3, 1.5)]
    z = np.array(sorted({zz for _, zz in pts}))
    r = subsurface_stress(x * B, p * P0, mu * p * P0, Body(STEEL), z * B)
    for xx, zz in pts:
        i, j = int(np.argmin(abs(z - zz))), int(np.argmin(abs(x - xx)))
        ref = mcewen(np.array(x[j]), np.array(zz), mu)
        got = (r.sxx[i, j] / P0, r.szz[i, j] / P0, r.sxz[i, j] / P0)
        assert np.allclose(got, ref, atol=3e-3), (xx, zz, got, ref)
        assert r.syy[i, j] == pytest.approx(0.3 * (r.sxx[i, j] + r.szz[i, j]))


def test_johnson_maxima_frictionless():
    """μ = 0: max von Mises 0.557 p0 at z ≈ 0.70b; max principal shear 0.300 p0 at
    z ≈ 0.79b on the axis (Johnson §7.2, ν = 0.3)."""
    x, p = hertz()
    z = np.linspace(0.0, 1.5, 151)
    r = subsurface_stress(x * B, p * P0, 0 * p, Body(STEEL), z * B)
    pk = r.max_von_mises_substrate
    assert pk.value / P0 == pytest.approx(0.557, rel=0.01)
    assert pk.z / B == pytest.approx(0.70, abs=0.02)
    assert abs(pk.x) < 0.011 * B
    tau = np.hypot(0.5 * (r.sxx - r.szz), r.sxz)  # in-plane principal shear stress
    i, j = np.unravel_index(np.argmax(tau), tau.shape)
    assert tau[i, j] / P0 == pytest.approx(0.300, rel=0.01)
    assert z[i] == pytest.approx(0.79, abs=0.02)
    assert r.max_tension_coating.value != r.max_tension_coating.value  # NaN: no coating


def test_traction_moves_the_maximum_towards_the_surface():
    """μ = 0.25: the von Mises maximum is shallower than 0.70b; μ = 0.3 (past ≈ 0.27) it
    is on the surface."""
    x, p = hertz()
    z = np.linspace(0.0, 1.0, 101)
    z25 = subsurface_stress(x * B, p, 0.25 * p, Body(STEEL), z * B).max_von_mises_substrate.z
    z30 = subsurface_stress(x * B, p, 0.30 * p, Body(STEEL), z * B).max_von_mises_substrate.z
    assert 0.2 * B < z25 < 0.6 * B
    assert z30 == 0.0


def test_trailing_edge_tension_is_two_mu_p0():
    """Surface σ_xx = −p − (2/π)∫q/(x − s)ds: at the trailing edge x = −b it is +2μp0. The
    piecewise-linear load converges like √Δ at the edge (the slope of √(1−x²) is
    infinite there): within 1.2 % at Δ = b/1600, half the error at 4× finer."""
    mu = 0.25
    errs = []
    for n in (1601, 6401):
        x, p = hertz(n)
        r = subsurface_stress(x * B, p * P0, mu * p * P0, Body(STEEL), [0.0])
        pk = r.max_tension_surface
        assert pk.x == pytest.approx(-B, abs=2e-3 * B)
        errs.append(abs(pk.value / P0 - 2 * mu) / (2 * mu))
    assert errs[1] < 0.012
    assert errs[1] == pytest.approx(errs[0] / 2, rel=0.15)


def test_coating_of_the_substrate_material_changes_nothing():
    x, p = hertz(301, 3.0)
    z = np.array([0.0, 0.1, 0.25, 0.5, 1.0]) * B
    ref = subsurface_stress(x * B, p * P0, 0.2 * p * P0, Body(STEEL), z)
    for h in (1e-6, 25e-6, 5e-5):
        r = subsurface_stress(
            x * B, p * P0, 0.2 * p * P0, Body(STEEL, Coating(STEEL.E, STEEL.nu, h)), z
        )
        for k in ("sxx", "szz", "sxz", "syy", "von_mises"):
            assert np.abs(getattr(r, k) - getattr(ref, k)).max() < 1e-9 * P0


def test_vanishing_coating_gives_the_substrate():
    """A stiff coating (800 GPa) of thickness h → 0: substrate stresses converge like h."""
    x, p = hertz(301, 3.0)
    z = np.array([0.1, 0.5, 1.0]) * B
    ref = subsurface_stress(x * B, p * P0, 0.2 * p * P0, Body(STEEL), z)
    errs = []
    for h in (1e-9, 1e-8):
        body = Body(STEEL, Coating(800e9, 0.2, h))
        r = subsurface_stress(x * B, p * P0, 0.2 * p * P0, body, z)
        errs.append(max(np.abs(getattr(r, k) - getattr(ref, k)).max() for k in ("sxx", "szz")))
    assert errs[1] < 1e-3 * P0
    assert errs[1] == pytest.approx(10 * errs[0], rel=0.1)


def test_thick_coating_gives_the_coating_material():
    """h ≫ b: near the surface the field is the homogeneous one (independent of E): the
    σ_zz, σ_xz of the coated body equal it within 1e-4 p0, σ_xx (bending of the layer
    over the far interface) within O(b/h)."""
    x, p = hertz(301, 3.0)
    z = np.array([0.0, 0.1, 0.5, 1.0]) * B
    coat = Material(800e9, 0.2)
    ref = subsurface_stress(x * B, p * P0, 0.2 * p * P0, Body(coat), z)
    dev = []
    for h in (1e-3, 3e-3):  # 10b, 30b
        r = subsurface_stress(x * B, p * P0, 0.2 * p * P0, Body(STEEL, Coating(800e9, 0.2, h)), z)
        assert np.abs(r.szz - ref.szz).max() < 1e-3 * P0
        assert np.abs(r.sxz - ref.sxz).max() < 6e-3 * P0
        dev.append(np.abs(r.sxx - ref.sxx).max() / P0)
    assert dev[1] < 0.04
    assert dev[0] / dev[1] == pytest.approx(3.0, rel=0.15)  # ∝ b/h


def test_thin_stiff_layer_takes_the_substrate_strain():
    """Long-wave limit: under a load much wider than the layer the coating's ε_xx is the
    substrate surface's, so at the centre σ_xx,c = −p [(G_c/G_s)(1 − 2ν_s) + ν_c]/(1 − ν_c)
    (plane strain, σ_zz = −p, homogeneous σ_xx = −p beneath)."""
    x, p = hertz(801, 2.0)
    errs = []
    for h in (2e-7, 2e-8):  # b/500, b/5000: the bending correction falls like h/b
        coat = Coating(4 * 210e9, 0.25, h)
        r = subsurface_stress(x * B, p * P0, 0 * p, Body(STEEL, coat), [h / 2])
        g = coat.shear_modulus / STEEL.shear_modulus
        expect = -((g * (1 - 2 * STEEL.nu) + coat.nu) / (1 - coat.nu))
        errs.append(abs(r.sxx[0, 400] / P0 / expect - 1))
    assert errs[1] < 2e-3
    assert errs[0] == pytest.approx(10 * errs[1], rel=0.1)


def test_coated_peaks_and_interface():
    x, p = hertz(301, 3.0)
    h = 10e-6
    body = Body(STEEL, Coating(400e9, 0.22, h))
    r = subsurface_stress(x * B, p * P0, 0.1 * p * P0, body, np.linspace(0, 1.2 * B, 61))
    assert r.max_von_mises_coating.z <= h < r.max_von_mises_substrate.z
    assert r.max_interface_shear.z == h
    assert r.max_interface_shear.value == pytest.approx(np.abs(r.interface_sxz).max())
    assert r.max_tension_surface.z == 0.0
    assert set(r.peaks()) == {
        "max_von_mises_coating",
        "max_von_mises_substrate",
        "max_tension_surface",
        "max_tension_coating",
        "max_interface_shear",
        "max_interface_tension",
    }
    # σ_yy uses each layer's own ν
    i = 1  # z = 0.02b < h
    assert r.syy[i] == pytest.approx(0.22 * (r.sxx[i] + r.szz[i]))
    assert r.syy[-1] == pytest.approx(0.3 * (r.sxx[-1] + r.szz[-1]))


@pytest.mark.parametrize(
    "kwargs, word",
    [
        ({"x": [0.0, 1e-6, 3e-6, 4e-6]}, "x"),
        ({"x": [0.0, 1e-6]}, "x"),
        ({"pressure": [1.0, 2.0]}, "pressure"),
        ({"traction": [0.0, math.nan, 0.0, 0.0]}, "traction"),
        ({"depths": [-1e-6]}, "depths"),
        ({"body": STEEL}, "body"),
    ],
)
def test_bad_input_names_the_argument(kwargs, word):
    args = {
        "x": [0.0, 1e-6, 2e-6, 3e-6],
        "pressure": [0.0, 1.0, 1.0, 0.0],
        "traction": [0.0, 0.0, 0.0, 0.0],
        "body": Body(STEEL),
        "depths": [0.0, 1e-6],
    }
    args.update(kwargs)
    with pytest.raises(InputError, match=word):
        subsurface_stress(**args)


@pytest.mark.parametrize(
    "kwargs, expected",
    [
        ({"pressure": [0.0, 1e300, 1e300, 0.0]}, r"pressure must be >= -1e\+11 and <= 1e\+11"),
        ({"traction": [0.0, -1e12, 0.0, 0.0]}, r"traction must be >= -1e\+11 and <= 1e\+11"),
        ({"depths": [1e300]}, r"depths must be >= 0 and < 1 \[m\]"),
    ],
)
def test_loads_and_depths_beyond_physics_are_refused(kwargs, expected):
    """A pressure of 1e300 Pa used to give inf stresses, a depth of 1e300 m NaN."""
    args = {
        "x": [0.0, 1e-6, 2e-6, 3e-6],
        "pressure": [0.0, 1.0, 1.0, 0.0],
        "traction": [0.0, 0.0, 0.0, 0.0],
        "body": Body(STEEL),
        "depths": [0.0, 1e-6],
    }
    args.update(kwargs)
    with pytest.raises(InputError, match=expected):
        subsurface_stress(**args)


def test_sizes_are_refused_before_allocating():
    """A 1e-15 m spacing on a 4 µm coating needs a periodic length of 1.3e11 nodes (tens of
    TiB); a million nodes or 1e5 depths are refused likewise, naming the argument and its
    limit (the check runs before anything of that size is allocated)."""
    from tribodyn.physics.stress import StressOperator

    coated = Body(STEEL, Coating(E=175e9, nu=0.3, thickness=4e-6))
    with pytest.raises(InputError, match=r"spacing of x \(dx\) must be >= .* m for this coating"):
        StressOperator(201, 1e-15, coated, [1e-6])
    with pytest.raises(InputError, match=r"n \(nodes of x\) must be .*<= 65536"):
        StressOperator(1_000_000, 1e-6, Body(STEEL), [1e-6])
    with pytest.raises(InputError, match=r"len\(depths\) must be .*<= 2000"):
        StressOperator(201, 1e-5, Body(STEEL), np.linspace(0.0, 1e-3, 100_000))
    with pytest.raises(InputError, match=r"len\(depths\) × n .* GiB"):
        StressOperator(60_000, 1e-7, Body(STEEL), np.linspace(0.0, 1e-4, 1500))


def test_float32_grid_is_uniform():
    """A float32 linspace is uniform to its own precision (it used to be refused as 'not
    uniformly spaced'); the field equals the float64 grid's to float32 rounding."""
    x64 = np.linspace(-1e-3, 1e-3, 201)
    x32 = x64.astype(np.float32)
    p = np.maximum(1e9 * (1.0 - (x64 / 5e-4) ** 2), 0.0)
    a = subsurface_stress(x32, p, 0.0 * p, Body(STEEL), [2e-4])
    b = subsurface_stress(x64, p, 0.0 * p, Body(STEEL), [2e-4])
    assert a.max_von_mises_substrate.value == pytest.approx(
        b.max_von_mises_substrate.value, rel=1e-5
    )
    with pytest.raises(InputError, match="uniformly spaced"):  # still a real check
        subsurface_stress(x64 * (1 + 1e-3 * (x64 > 0)), p, 0.0 * p, Body(STEEL), [2e-4])
