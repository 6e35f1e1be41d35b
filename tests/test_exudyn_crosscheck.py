"""Cross-check of the flexible valvetrain against an established multibody code, Exudyn
(J. Gerstmayr, "Exudyn – a C++-based Python package for flexible multibody systems",
Multibody System Dynamics 60 (2024) 533–561).

The same tappet–valve–spring system (bundled andreou2023_flexible case, rigid camshaft,
no friction) is built in Exudyn from the *unreduced* finite-element bodies: each body's
full mass and stiffness matrices in an ``ObjectGenericODE2`` on 1-D nodes, Rayleigh
damping C = (2ζ/ω₁)K with ω₁ its first fixed-interface frequency, and every joint (cam
contact with the Palmgren law and the prescribed cam lift, tappet–valve, valve seat,
spring seat and support, and coil clash on *every* spring element) as a
``ObjectConnectorCoordinateSpringDamper`` with a force law written here. Exudyn
integrates it with its implicit generalised-α solver at a fixed step. tribodyn runs its
Craig–Bampton-reduced model (modes up to 5 kHz, clash only on the coils that can close)
with LSODA. The comparison therefore checks the reduction, the assembly of the bodies and
joints (incl. the static preload) and the time integration against an independent code.

Exudyn's Hurty–Craig–Bampton interface (``FEMinterface.ComputeHurtyCraigBamptonModes``)
builds rigid RBE2/RBE3 interfaces on 3-D solid meshes and cannot take 1-D bar bodies, so
the reference here is the unreduced FE model integrated by Exudyn.

One engine cycle from static equilibrium at 3000 rpm. Measured: peak contact force
512.9 N (tribodyn) vs 514.7 N (Exudyn); difference 1.3 N RMS over the cycle (0.26 % of the
peak) and 17.6 N at worst (3.4 %), at the valve-closing seat impact (a 5e8 N/m seat
stiffness struck at a fixed step: 27 N at an 8 µs step, 17.6 N at 5 µs, 15 N at 4 µs),
with a ±7 N ringing of the ramp-end impact in between (the spring's higher modes, which
the reduction drops and Rayleigh damps more than the modal ζ). Tolerance: peak within
1 %, RMS within 0.75 % and worst within 5 % of the peak. Skipped when Exudyn cannot be
imported (``pip install "tribodyn[crosscheck]"``).
"""

import math
from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sla

from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.valvetrain import simulate_valvetrain

exu = pytest.importorskip("exudyn", reason="Exudyn not installed: pip install tribodyn[crosscheck]")
from exudyn import itemInterface as ei  # noqa: E402

PALMGREN_EXP = 0.9  # δ = C P^0.9 (Palmgren 1959), as the case's contact law
RPM = 3000.0
DT = 5e-6  # Exudyn step [s]: the seat impact converges at this step (see above)


def _step(F, ramp):
    """Cubic phase-in 3r² − 2r³ of the joint damping, r = min(F/ramp, 1)."""
    if F <= 0.0:
        return 0.0
    r = min(F / ramp, 1.0)
    return r * r * (3.0 - 2.0 * r)


def _first_fixed_interface_frequency(M, K, boundary):
    i = [j for j in range(M.shape[0]) if j not in set(boundary)]
    if not i:
        return None
    w2 = sla.eigh(K[np.ix_(i, i)], M[np.ix_(i, i)], eigvals_only=True)
    return math.sqrt(w2[0])


@pytest.fixture(scope="module")
def system():
    case = load_case("andreou2023_flexible")
    flex = replace(build(case).valvetrain, camshaft=None)
    return build(case).cam, flex


def _exudyn_contact_force(cam, flex, t_out):
    p = flex.joints
    w = RPM / 2.0 * 2.0 * math.pi / 60.0
    sp, v, tp = flex.spring, flex.valve, flex.tappet
    F0 = sp.preload
    comp = sp.statics(sp.installed_compression).compressions
    kel, _, gaps, _ = sp._elements()
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddNode(ei.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    mg = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    markers = {}
    for name, fe, zeta, bnd in (
        ("valve", v.fe_model(), v.damping_ratio, ("seat", "retainer")),
        ("tappet", tp.fe_model(), tp.damping_ratio, ("face",)),
        ("spring", sp.fe_model(), sp.damping_ratio, None),
    ):
        M, K = np.asarray(fe.M), np.asarray(fe.K)
        b = [0, fe.n - 1] if bnd is None else [fe.labels[x] for x in bnd]
        w1 = _first_fixed_interface_frequency(M, K, b)
        C = (2.0 * zeta / w1) * K if w1 else np.zeros_like(K)
        nodes = [
            mbs.AddNode(ei.Node1D(referenceCoordinates=[0.0], initialCoordinates=[0.0]))
            for _ in range(fe.n)
        ]
        mats = []
        for A in (M, K, C):
            mc = exu.MatrixContainer()
            mc.SetWithDenseMatrix(A, useDenseMatrix=True)
            mats.append(mc)
        mbs.AddObject(
            ei.ObjectGenericODE2(
                nodeNumbers=nodes,
                massMatrix=mats[0],
                stiffnessMatrix=mats[1],
                dampingMatrix=mats[2],
            )
        )
        markers[name] = [
            mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=n, coordinate=0)) for n in nodes
        ]
        if name == "spring":
            beta_s = 2.0 * zeta / w1
        else:
            markers[name + "_labels"] = fe.labels
    vl, tl = markers["valve_labels"], markers["tappet_labels"]
    face = markers["tappet"][tl["face"]]
    seat = markers["valve"][vl["seat"]]
    groove = markers["valve"][vl["retainer"]]
    top, bottom = markers["spring"][0], markers["spring"][-1]
    ramp = p.damping_force_ramp
    Cc = p.contact_compliance_coefficient

    def joint(mb, ma, d0, k, c, static, law=None):
        """Compressive joint: node a pushed −x, node b pushed +x, deformation d0 + q_a − q_b."""

        def uf(mbs, t, item, u, du, *_):
            d = d0(t) + u if callable(d0) else d0 + u
            dd = du + (d0.rate(t) if callable(d0) else 0.0)
            E = (law(d) if law else k * d) if d > 0.0 else 0.0
            F = max(E + c * _step(E, ramp) * dd, 0.0)
            return F - static

        return mbs.AddObject(
            ei.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[mb, ma], springForceUserFunction=uf
            )
        )

    class CamLift:  # d0(t) = s(ωt), with its rate ω s'
        def __call__(self, t):
            return cam.scalar_derivatives(w * t)[0]

        def rate(self, t):
            return w * cam.scalar_derivatives(w * t)[1]

    def palmgren(d):
        return (d / Cc) ** (1.0 / PALMGREN_EXP)

    o_cam = joint(face, mg, CamLift(), 0.0, p.contact_damping, 0.0, palmgren)
    joint(groove, face, -p.lash, flex.tappet_valve_stiffness, p.tappet_valve_damping, 0.0)
    ks = v.seat_stiffness
    joint(seat, mg, F0 / ks, ks, p.seat_damping, F0)
    kss, ksp = p.spring_seat_stiffness, p.spring_support_stiffness
    joint(top, groove, F0 / kss, kss, beta_s * kss, F0)
    joint(mg, bottom, F0 / ksp, ksp, beta_s * ksp, F0)
    for j in range(kel.size):  # coil clash on every element (wire overlap, Palmgren)
        Qs = sp.clash_force(comp[j] - gaps[j])[0]
        joint(
            markers["spring"][j + 1],
            markers["spring"][j],
            comp[j] - gaps[j],
            0.0,
            sp.clash_damping,
            Qs,
            lambda d: sp.clash_force(d)[0],
        )
    sens = mbs.AddSensor(
        ei.SensorObject(
            objectNumber=o_cam, outputVariableType=exu.OutputVariableType.Force, storeInternal=True
        )
    )
    mbs.Assemble()
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = float(t_out[-1])
    ti.numberOfSteps = int(round(ti.endTime / DT))
    ti.generalizedAlpha.spectralRadius = 0.9
    ti.newton.useModifiedNewton = False
    ti.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = DT
    s.show.statistics = False
    exu.SolveDynamic(mbs, s)
    data = mbs.GetSensorStoredData(sens)
    return np.interp(t_out, data[:, 0], data[:, 1])


def test_contact_force_against_exudyn(system):
    cam, flex = system
    r = simulate_valvetrain(cam, flex, engine_speed=RPM, tribology=None, cycles=1)
    assert r.converged, r.message
    F_exu = _exudyn_contact_force(cam, flex, r.time)
    F = r.contact_force
    peak = F.max()
    d = F - F_exu
    rms, worst = float(np.sqrt(np.mean(d * d))), float(np.abs(d).max())
    assert abs(F_exu.max() / peak - 1.0) < 0.01
    assert rms < 0.0075 * peak, (rms, worst, peak)
    assert worst < 0.05 * peak, (rms, worst, peak)
