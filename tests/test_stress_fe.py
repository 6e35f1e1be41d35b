"""Layered subsurface stress (physics.stress) against an independent plane-strain
finite-element model (scikit-fem, quadratic triangles) of a coating bonded to a substrate
under a Hertz pressure with sliding traction μp: a stiff layer (E_c/E_s = 4, h = b/4) and
a compliant one (E_c/E_s = 1/4, h = b/2).

The FE domain is a graded rectangle (element b/20 near the contact, growing by 1.3 to
L = 80b); on its far sides and bottom McEwen's homogeneous tractions are imposed (the
layered field differs from the homogeneous one there by O(h b/L²)). The truncation is
checked: L = 40b changes the compared stresses by < 0.5 % p0."""

from functools import lru_cache

import numpy as np
import pytest

skfem = pytest.importorskip("skfem")
from skfem import (  # noqa: E402
    Basis,
    BilinearForm,
    ElementTriP2,
    ElementVector,
    FacetBasis,
    LinearForm,
    MeshTri,
    asm,
    condense,
    solve,
)
from skfem.helpers import ddot, sym_grad, trace  # noqa: E402

from test_stress import mcewen  # noqa: E402
from tribodyn import Body, Coating, Material, subsurface_stress  # noqa: E402


def _graded(fine, span, length, growth=1.3):
    pts = list(np.arange(0.0, span, fine)) + [span]
    d = fine
    while pts[-1] < length:
        d *= growth
        pts.append(min(pts[-1] + d, length))
    return np.array(pts)


@lru_cache(maxsize=4)
def fe_model(ec, nuc, h, mu, es=1.0, nus=0.3, length=80.0, fine=0.05):
    """Displacement solution (lengths /b, stresses /p0); y = −z."""
    xr = _graded(fine, 1.6, length)
    xs = np.unique(np.concatenate([-xr[::-1], xr, [-1.0, 1.0]]))
    zs = _graded(fine, 1.6, length)
    zs = np.unique(np.concatenate([zs, np.linspace(0.0, h, int(np.ceil(h / fine)) + 1)]))
    mesh = MeshTri.init_tensor(xs, -zs[::-1])
    e = ElementVector(ElementTriP2())
    basis = Basis(mesh, e, intorder=4)

    def lame(y):
        inside = -y < h
        E, nu = np.where(inside, ec, es), np.where(inside, nuc, nus)
        return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))

    @BilinearForm
    def stiffness(u, v, w):
        lam, g = lame(w.x[1])
        eu, ev = sym_grad(u), sym_grad(v)
        return lam * trace(eu) * trace(ev) + 2 * g * ddot(eu, ev)

    @LinearForm
    def surface(v, w):
        p = np.sqrt(np.clip(1 - w.x[0] ** 2, 0, None))
        return -p * v[1] + mu * p * v[0]

    @LinearForm
    def far(v, w):
        sx, sz, txz = mcewen(w.x[0], -w.x[1], mu)
        sxy = -txz
        n = w.n
        return (sx * n[0] + sxy * n[1]) * v[0] + (sxy * n[0] + sz * n[1]) * v[1]

    top = mesh.facets_satisfying(lambda x: np.isclose(x[1], 0.0))
    outer = mesh.facets_satisfying(
        lambda x: np.isclose(x[1], -zs[-1]) | np.isclose(np.abs(x[0]), xs[-1])
    )
    K = asm(stiffness, basis)
    f = asm(surface, FacetBasis(mesh, e, facets=top, intorder=6)) + asm(
        far, FacetBasis(mesh, e, facets=outer, intorder=6)
    )
    # rigid-body modes: pin one bottom corner, and the other's vertical displacement
    c1 = basis.get_dofs(lambda x: np.isclose(x[1], -zs[-1]) & np.isclose(x[0], xs[0])).all()
    c2 = basis.get_dofs(lambda x: np.isclose(x[1], -zs[-1]) & np.isclose(x[0], xs[-1]))
    u = solve(*condense(K, f, D=np.concatenate([c1, c2.nodal["u^2"]])))
    return mesh, basis, u, lame


def fe_stress(model, x, z):
    """(σ_xx, σ_zz, σ_xz) at points from the P2 displacement gradient (z into the body;
    a point on the interface is taken on the side given by the sign of its offset)."""
    mesh, basis, u, lame = model
    pts = np.vstack([x, -np.asarray(z, float)])
    cells = mesh.element_finder()(pts[0], pts[1])
    out = np.zeros((3, pts.shape[1]))
    for k, c in enumerate(cells):
        X = basis.mapping.invF(pts[:, k : k + 1][:, :, None], tind=np.array([c]))
        grad = np.zeros((2, 2))
        for j in range(basis.Nbfun):
            phi = basis.elem.gbasis(basis.mapping, X, j, tind=np.array([c]))[0]
            grad += u[basis.element_dofs[j, c]] * phi.grad[:, :, 0, 0]
        eps = 0.5 * (grad + grad.T)
        lam, g = lame(np.array([pts[1, k]]))
        s = lam * np.trace(eps) * np.eye(2) + 2 * g * eps
        out[:, k] = s[0, 0], s[1, 1], -s[0, 1]
    return out


CASES = [(4.0, 0.25, 0.3), (0.25, 0.5, 0.3)]  # E_c/E_s, h/b, μ


def _points(h):
    xs = np.array([-0.5, 0.0, 0.5, 0.8])
    zs = np.array([0.02, h / 2, h * (1 - 1e-6), h * (1 + 1e-6), 0.7])
    return xs, zs


def _analytic(ec, h, mu, xs, zs):
    b = 1e-4
    x = np.linspace(-3, 3, 1201)
    p = np.sqrt(np.clip(1 - x * x, 0, None))
    body = Body(Material(1e9, 0.3), Coating(ec * 1e9, 0.25, h * b))
    r = subsurface_stress(x * b, p, mu * p, body, zs * b)
    ix = [int(np.argmin(abs(x - v))) for v in xs]
    return np.array([r.sxx[:, ix], r.szz[:, ix], r.sxz[:, ix]]), r


@pytest.mark.parametrize("ec, h, mu", CASES)
def test_layered_stress_matches_finite_elements(ec, h, mu):
    xs, zs = _points(h)
    X, Z = np.meshgrid(xs, zs)
    fe = fe_stress(fe_model(ec, 0.25, h, mu), X.ravel(), Z.ravel()).reshape(3, *X.shape)
    an, _ = _analytic(ec, h, mu, xs, zs)
    # layer, both sides of the interface, substrate: within 1.5 % of p0
    assert np.abs(fe - an).max() < 0.015, np.abs(fe - an).max()


def test_fe_truncation_is_small():
    """Halving the FE domain (80b → 40b) moves the compared stresses by < 0.5 % p0, so
    the FE reference's own truncation error is below the tolerance above."""
    ec, h, mu = CASES[0]
    xs, zs = _points(h)
    X, Z = np.meshgrid(xs, zs)
    big = fe_stress(fe_model(ec, 0.25, h, mu), X.ravel(), Z.ravel())
    small = fe_stress(fe_model(ec, 0.25, h, mu, length=40.0), X.ravel(), Z.ravel())
    assert np.abs(big - small).max() < 0.005
