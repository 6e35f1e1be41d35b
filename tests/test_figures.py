"""Report figures: every PNG is written from a small synthetic results Dataset."""

import json

import numpy as np
import pytest
import xarray as xr

from tribodyn.output.figures import FIGURES, make_figures

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
EXPLICIT_IMPLICIT = (
    "fig08_tappet_velocity.png",
    "fig09_contact_force.png",
    "fig10_tappet_acceleration.png",
)


def _hertz(x, b, ph):
    return ph * np.sqrt(np.clip(1.0 - (x / b) ** 2, 0.0, None))


def _add_regime_map(ds) -> None:
    """The Greenwood chart's regime map, written as a study writes it (its variables of
    the study table, from the map of the Dataset's g_V, g_E)."""
    from types import SimpleNamespace

    from tribodyn.workflow.regime_map import regime_map
    from tribodyn.workflow.variables_study import REGIME

    m = regime_map(ds["gV"].values, ds["gE"].values)
    source = SimpleNamespace(analysis=SimpleNamespace(regime_map=m))
    for v in REGIME:
        if v.name in ("chart_gE", "chart_gV", "regime_map"):
            target = ds.coords if v.coord else ds
            target[v.name] = v.make(source)


def synthetic_dataset(implicit=True, failed_step=True) -> xr.Dataset:
    """A coarse stand-in for study_to_dataset's output (same names and dims)."""
    rpm, width = 3000.0, 0.012
    omega = rpm / 2 * 2 * np.pi / 60  # cam speed [rad/s]
    ca = np.arange(720.0, 1440.5, 1.0)
    ev = (ca > 900) & (ca < 1260)
    phase = np.where(ev, (ca - 900) / 360, 0.0)  # 0…1 over the event
    lift = 9.3e-3 * np.sin(np.pi * phase) ** 2
    dt = 120.0 / rpm / 720.0  # s per crank degree
    vel = np.gradient(lift, dt)
    acc = np.gradient(vel, dt)
    force = np.where(ev, 250 + 250 * np.sin(np.pi * phase) ** 2, 4 + 4 * np.sin(ca / 7.0))
    ring = np.where(ev, 30 * np.exp(-np.abs(ca - 905) / 5) * np.sin(ca * 3), 0.0)
    base = 0.015
    ue = np.where(
        ev, omega * (base + lift) / 2 - 5.0 * np.sin(np.pi * phase) ** 4, omega * base / 2
    )
    us = omega * (base + lift)
    R = np.where(ev, base + lift + 0.05 * np.sin(np.pi * phase) ** 8 + 0.002, base)
    R = np.clip(R - 0.012 * np.sin(np.pi * phase) ** 6, 0.002, None)

    ds = xr.Dataset(coords={"crank_angle": ("crank_angle", ca, {"units": "deg"})})
    for name, v in dict(
        contact_force=force,
        tappet_velocity=vel,
        tappet_acceleration=acc,
        valve_lift=lift,
        cam_lift=lift,
        entrainment_speed=ue,
        sliding_speed=us,
        radius_of_curvature=R,
        contact_offset=np.gradient(lift, np.deg2rad(ca / 2)),
    ).items():
        ds[name] = ("crank_angle", v)
    if implicit:
        ds["contact_force_implicit"] = ("crank_angle", force + ring)
        ds["tappet_velocity_implicit"] = ("crank_angle", vel + 1e-3 * ring)
        ds["tappet_acceleration_implicit"] = ("crank_angle", acc + 5 * ring)
        ds["valve_lift_implicit"] = ("crank_angle", lift)

    e = ca[::4]
    ie = np.searchsorted(ca, e)
    names = ["uncoated", "dlc_4um", "wcc_4um"]
    labels = ["uncoated", "DLC 4 µm", "WC-C 4 µm"]
    ds = ds.assign_coords(ehl_crank=("ehl_crank", e), surface_set=("surface_set", names))
    ds["surface_label"] = ("surface_set", labels)
    F, U, Rr, Us = force[ie], ue[ie], R[ie], us[ie]
    ds["ehl_contact_force"] = ("ehl_crank", F)
    ds["ehl_entrainment_speed"] = ("ehl_crank", U)
    ds["ehl_sliding_speed"] = ("ehl_crank", Us)
    ds["ehl_radius"] = ("ehl_crank", Rr)
    loaded = F > 5.0
    W = F / width / (2.3e11 * Rr)
    Ug = 0.055 * np.maximum(np.abs(U), 1e-3) / (2.3e11 * Rr)
    gV = 2415 * W**1.5 / np.sqrt(Ug)
    gE = W / np.sqrt(Ug)
    ds["gV"] = ("ehl_crank", np.where(loaded, gV, np.nan))
    ds["gE"] = ("ehl_crank", np.where(loaded, gE, np.nan))
    ds["regime"] = ("ehl_crank", np.where(loaded, 3, -1).astype(np.int8))
    _add_regime_map(ds)
    S = len(names)
    L = np.repeat(loaded[None], S, axis=0)
    ds["loaded"] = (("surface_set", "ehl_crank"), L.astype(np.int8))
    conv = np.ones_like(L, dtype=np.int8)
    if failed_step:
        conv[2, np.flatnonzero(loaded)[len(np.flatnonzero(loaded)) // 2]] = 0
    ds["converged"] = (("surface_set", "ehl_crank"), conv)
    ds["iterations"] = (("surface_set", "ehl_crank"), np.full(L.shape, 5, np.int32))
    gain = np.array([1.0, 1.004, 1.005])[:, None]
    hc = 2.9e-6 * np.maximum(np.abs(U), 0.05) ** 0.7 * (Rr / 0.01) ** 0.4 * gain
    hc = np.where(L, hc, np.nan)
    hm = 0.85 * hc
    wa = np.where(L, np.array([1.0, 0.05, 0.01])[:, None] * F * np.exp(-hc / 2e-7), np.nan)
    fv = np.where(L, 0.012 * F * np.array([1.0, 1.003, 1.002])[:, None], np.nan)
    fb = np.where(L, np.array([0.185, 0.44, 0.54])[:, None] * wa, np.nan)
    sigma = np.array([4.1e-7, 3.6e-7, 3.5e-7])[:, None]
    for name, v in dict(
        central_film=hc,
        min_film=hm,
        max_pressure=np.where(L, 5e8, np.nan),
        hydrodynamic_load=np.where(L, F - wa, np.nan),
        asperity_load=wa,
        viscous_friction=fv,
        boundary_friction=fb,
        rolling_friction=np.where(L, 0.0, np.nan),
        friction_power=(fv + fb) * Us,
        lambda_ratio=hm / sigma,
    ).items():
        ds[name] = (("surface_set", "ehl_crank"), v)
    # a thermal study's temperatures and isothermal comparison (Figs. 21, 22)
    rise = np.where(L, 40.0 * (F / F.max()) * np.array([1.0, 1.4, 1.3])[:, None], np.nan)
    for name, k in (
        ("max_temperature", 1.0),
        ("mid_film_temperature", 0.9),
        ("surface_temperature_cam", 0.7),
        ("surface_temperature_tappet", 0.8),
        ("mean_film_temperature", 0.85),
    ):
        ds[name] = (("surface_set", "ehl_crank"), 363.15 + k * rise)
    ds["central_film_isothermal"] = (("surface_set", "ehl_crank"), hc * 1.03)
    ds["viscous_friction_isothermal"] = (("surface_set", "ehl_crank"), fv * 1.1)
    ds.attrs["inlet_temperature_K"] = 363.15
    x = np.linspace(-4e-4, 4e-4, 81)
    b = np.sqrt(8 * (F / width) * Rr / (np.pi * 2.3e11))
    ph = np.sqrt((F / width) * 2.3e11 / (2 * np.pi * Rr))
    p = _hertz(x[None, :], b[:, None], ph[:, None])
    outside = np.abs(x) > b[:, None]
    h = hc[:, :, None] + np.where(outside, (x**2 - b[:, None] ** 2) / (2 * Rr[:, None]), 0.0)[None]
    ds["profile_x"] = (
        ("surface_set", "ehl_crank", "k"),
        np.where(L[..., None], np.broadcast_to(x, L.shape + x.shape), np.nan),
    )
    ds["pressure"] = (
        ("surface_set", "ehl_crank", "k"),
        np.where(L[..., None], p[None] * gain[..., None] ** -0.1, np.nan),
    )
    ds["film"] = (("surface_set", "ehl_crank", "k"), np.where(L[..., None], h, np.nan))
    ev_e = e[loaded & (F > 0.05 * F.max())]
    ds = ds.assign_coords(point=("point", np.arange(1, 7)))
    ds["point_crank"] = ("point", ev_e[np.linspace(3, ev_e.size - 4, 6).astype(int)])

    ratios = np.array([0.5, 1.0, 2.0])
    xd = np.linspace(-1.0e-4, 1.0e-4, 101)
    bd = 7.6e-5 * ratios**-0.04
    pd = 4.4e8 * ratios**0.01
    ds = ds.assign_coords(dry_ratio=("dry_ratio", ratios), dry_x=("dry_x", xd))
    ds["dry_pressure"] = (("dry_ratio", "dry_x"), _hertz(xd[None], bd[:, None], pd[:, None]))
    ds["dry_half_width"] = ("dry_ratio", bd)
    ds["dry_max_pressure"] = ("dry_ratio", pd)
    xe = np.linspace(-8e-4, 3.5e-4, 121)
    pairs = ["steel (uncoated)", "DLC 4 µm", "WC-C 4 µm"]
    ds = ds.assign_coords(
        ehl_x=("ehl_x", xe), ehl_ratio=("ehl_ratio", ratios), ehl_pair=("ehl_pair", pairs)
    )
    for dim, k in (("ehl_ratio", ratios), ("ehl_pair", np.array([1.0, 0.9, 0.85]))):
        pe = 2.6e8 * np.exp(-(((xe[None] + 4e-5) / 6e-5) ** 2)) * k[:, None] ** 0.01
        he = 1.6e-6 * k[:, None] ** -0.01 + xe[None] ** 2 / 2e-2
        ds[f"{dim}_pressure"] = ((dim, "ehl_x"), pe)
        ds[f"{dim}_film"] = ((dim, "ehl_x"), he)
        ds[f"{dim}_central_film"] = (dim, he[:, np.argmin(np.abs(xe))])
        ds[f"{dim}_min_film"] = (dim, he.min(axis=1))
        ds[f"{dim}_converged"] = (dim, np.ones(k.size, np.int8))
    # engineering outputs: torque, pressure, kinematics, surge
    two = ("surface_set", "ehl_crank")
    lift_e, off_e = lift[ie], np.gradient(lift, np.deg2rad(ca / 2))[ie]
    tf = np.where(L, 0.02 * (1 + np.arange(3)[:, None]) * (base + lift_e), 0.0)
    ds["camshaft_friction_torque"] = (two, tf)
    ds["camshaft_drive_torque"] = (two, F * off_e + tf)
    ds["hertz_pressure"] = (
        two,
        np.where(L, np.sqrt(F / width * 2.3e11 / (2 * np.pi * Rr)), np.nan),
    )
    th = np.arange(0.0, 360.0, 0.5)
    ds = ds.assign_coords(cam_angle_deg=("cam_angle_deg", th))
    s_th = 9.3e-3 * np.clip(np.cos(np.radians(th - 180) * 1.05), 0, None) ** 3
    ds["kinematic_lift"] = ("cam_angle_deg", s_th)
    ds["kinematic_velocity"] = ("cam_angle_deg", np.gradient(s_th, np.radians(th)) * omega)
    ds["kinematic_acceleration"] = (
        "cam_angle_deg",
        np.gradient(np.gradient(s_th, np.radians(th)), np.radians(th)) * omega**2,
    )
    ds["kinematic_radius"] = ("cam_angle_deg", base + s_th + 0.003)
    ds = ds.assign_coords(table_angle_deg=("table_angle_deg", th[::4]))
    ds["table_lift"] = ("table_angle_deg", s_th[::4])
    ds["table_fit_residual"] = ("table_angle_deg", 1e-8 * np.sin(th[::4]))
    n_h = np.arange(1, 41)
    ds = ds.assign_coords(harmonic=("harmonic", n_h), surge_mode=("surge_mode", [1, 2, 3]))
    ds["harmonic_frequency"] = ("harmonic", n_h * 25.0)
    ds["harmonic_amplitude"] = ("harmonic", 3e-3 * n_h**-3.0)
    ds["surge_frequency"] = ("surge_mode", 484.0 * np.array([1, 2, 3]))
    ds.attrs.update(
        engine_speed_rpm=rpm,
        cam_width_m=width,
        ehl_coating_conditions=json.dumps(
            dict(
                load_total=633.0,
                width=width,
                radius=0.01,
                thickness=5e-6,
                entrainment_speed=15.31,
                pair_thickness=4e-6,
            )
        ),
    )
    return ds


def _check_pngs(paths, out):
    for name, path in paths.items():
        assert path == out / name
        data = path.read_bytes()
        assert len(data) > 10_000, name
        assert data[:8] == PNG_MAGIC, name
    assert not [p for p in out.iterdir() if ".tmp" in p.name]  # atomic writes


@pytest.fixture(scope="module")
def every_png(tmp_path_factory):
    """Every figure of :func:`synthetic_dataset` drawn in turn in this process: (folder,
    ``make_figures``' answer). The tests read it and change nothing."""
    out = tmp_path_factory.mktemp("serial")
    return out, make_figures(synthetic_dataset(), out)


def test_make_figures_writes_every_png(every_png):
    out, paths = every_png
    # the stress map needs the maps a study stores (drawn in test_stress_cycle.py)
    assert set(paths) == set(FIGURES) - {"fig27_stress_map.png"}
    assert all(name.startswith("fig") and name.endswith(".png") for name in FIGURES)
    _check_pngs(paths, out)


def test_a_case_other_than_the_papers_gets_figures_named_by_content(tmp_path):
    """compare_paper = 0: no figNN_ names, no paper figure numbers in the titles; the
    paper's single-contact figures only where their data are."""
    from tribodyn.output.figures import content_name

    ds = synthetic_dataset()
    ds.attrs["compare_paper"] = 0
    paths = make_figures(ds, tmp_path, only=["camshaft_torque.png", "fig25_cam_kinematics.png"])
    assert set(paths) == {"camshaft_torque.png", "cam_kinematics.png"}
    _check_pngs(paths, tmp_path)
    assert content_name("fig23_camshaft_torque.png") == "camshaft_torque.png"
    for name in FIGURES:
        assert "paper Fig" not in FIGURES[content_name(name)]


def test_figures_drawn_in_processes_match_serial(every_png, tmp_path):
    """Two processes write the same files, in the same order, as drawing in turn."""
    ds = synthetic_dataset()
    only = [*EXPLICIT_IMPLICIT, "fig12_greenwood_chart.png", "fig15_central_film.png"]
    serial = {name: path for name, path in every_png[1].items() if name in only}
    assert len(serial) == len(only)
    parallel = make_figures(ds, tmp_path / "parallel", only=only, workers=2)
    assert list(parallel) == list(serial)
    assert all(p.parent == tmp_path / "parallel" for p in parallel.values())
    _check_pngs(parallel, tmp_path / "parallel")
    # same drawing: PNG sizes agree closely (pixel-identical up to compression details)
    for name in serial:
        a, b = serial[name].stat().st_size, parallel[name].stat().st_size
        assert abs(a - b) <= 0.01 * a, name


def test_missing_implicit_run_plots_explicit_only(tmp_path):
    ds = synthetic_dataset(implicit=False, failed_step=False)
    assert not [v for v in ds.data_vars if v.endswith("_implicit")]
    paths = make_figures(ds, tmp_path, only=EXPLICIT_IMPLICIT)
    assert set(paths) == set(EXPLICIT_IMPLICIT)
    _check_pngs(paths, tmp_path)


def test_missing_optional_parts_are_skipped(tmp_path):
    ds = synthetic_dataset().drop_vars(
        ["dry_pressure", "dry_half_width", "dry_max_pressure", "dry_x", "dry_ratio"]
    )
    paths = make_figures(ds, tmp_path, only=["fig05_dry_pressure.png", "fig15_central_film.png"])
    assert set(paths) == {"fig15_central_film.png"}
    _check_pngs(paths, tmp_path)


def test_unknown_names_are_an_error(tmp_path):
    from tribodyn import InputError

    with pytest.raises(InputError, match="fig99_unknown.png"):
        make_figures(synthetic_dataset(), tmp_path, only=["fig99_unknown.png"])
    assert not list(tmp_path.iterdir())


# ----------------------------------------------------------------------------- content
@pytest.fixture
def drawn(monkeypatch, tmp_path):
    """Draw figures but keep the matplotlib Figure objects instead of only the PNGs."""
    from tribodyn.output.figures import common

    figs = {}
    save = common.save_figure

    def keep(fig, path):
        figs[path.name] = fig
        fig.canvas.draw()  # what the PNG shows, laid out
        return save(fig, path)

    monkeypatch.setattr(common, "save_figure", keep)
    monkeypatch.setattr(common.plt, "close", lambda fig=None: None)

    def draw(ds, name):
        make_figures(ds, tmp_path, only=[name])
        return figs[name]

    return draw


def _lines_by_label(ax):
    return {ln.get_label(): ln for ln in ax.get_lines()}


def test_central_film_figure_shows_the_films_and_their_differences(drawn):
    """Fig. 15: each set's h_c in µm over the event, and the change against the reference
    in % in the lower panel; the failed step is marked where it is."""
    ds = synthetic_dataset()
    fig = drawn(ds, "fig15_central_film.png")
    top, bottom = fig.axes[0], fig.axes[1]
    e = ds["ehl_crank"].values
    hc = ds["central_film"].values
    for i, label in enumerate(ds["surface_label"].values):
        ln = _lines_by_label(top)[str(label)]
        x, y = ln.get_data()
        np.testing.assert_allclose(y, np.interp(x, e, hc[i]) * 1e6, rtol=1e-9)
    ref = hc[0]
    wcc = next(ln for lab, ln in _lines_by_label(bottom).items() if lab.startswith("WC-C"))
    x, y = wcc.get_data()
    ok = np.isfinite(y)
    np.testing.assert_allclose(y[ok], (np.interp(x[ok], e, hc[2] / ref) - 1) * 100, rtol=1e-6)
    assert "h_c" in top.get_ylabel() and "µm" in top.get_ylabel()
    failed = np.flatnonzero((ds["converged"].values[2] == 0) & (ds["loaded"].values[2] == 1))
    crosses = [ln for ln in top.get_lines() if ln.get_marker() == "x"]
    assert crosses and crosses[0].get_xdata()[0] == pytest.approx(e[failed[0]])


def test_contact_force_figure_shows_explicit_and_implicit(drawn):
    ds = synthetic_dataset()
    fig = drawn(ds, "fig09_contact_force.png")
    ax = fig.axes[0]
    lines = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 100]
    ys = [np.asarray(ln.get_ydata()) for ln in lines]
    ca = ds["crank_angle"].values
    for name in ("contact_force", "contact_force_implicit"):
        v = ds[name].values
        assert any(
            np.allclose(y, np.interp(ln.get_xdata(), ca, v), rtol=1e-9) for ln, y in zip(lines, ys)
        ), name


def test_greenwood_chart_places_the_representative_points(drawn):
    """Fig. 12: the six points sit at their (g_E, g_V) on logarithmic axes."""
    ds = synthetic_dataset()
    fig = drawn(ds, "fig12_greenwood_chart.png")
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    e = ds["ehl_crank"].values
    idx = [int(np.argmin(np.abs(e - c))) for c in ds["point_crank"].values]
    marks = np.vstack(
        [np.column_stack(ln.get_data()) for ln in ax.get_lines() if ln.get_marker() == "o"]
    )
    for i in idx:
        gE, gV = ds["gE"].values[i], ds["gV"].values[i]
        assert np.min(np.hypot(np.log(marks[:, 0] / gE), np.log(marks[:, 1] / gV))) < 1e-9
