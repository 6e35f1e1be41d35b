"""Measured topography → Greenwood–Tripp roughness (tribodyn.topography).

Synthetic isotropic Gaussian surfaces with known spectra check the two estimators of
summit density η and mean summit radius β against each other (8-neighbour summits vs
McCool's spectral moments). The synthetic spectra keep their shortest wavelength ≥ 16
pixels, where the discrete summit statistics have converged to the continuous ones; one
test documents the divergence when the sampling is too coarse.
"""

import json
import math
import tomllib

import numpy as np
import pytest
from SurfaceTopography import Topography, UniformLineScan
from typer.testing import CliRunner

from tribodyn import InputError, Roughness
from tribodyn.cli import app
from tribodyn.config.build import build
from tribodyn.output.figures.topography import plot_height_distribution
from tribodyn.paper import TOPOGRAPHY_BAND as PAPER_BAND
from tribodyn.topography import (
    TYPICAL_BAND,
    BandLimitError,
    InsufficientDataError,
    PairAnalysis,
    SpectralMoments,
    TopographyReadError,
    analyse_pair,
    analyse_surface,
    composite_roughness,
    mccool_parameters,
    read_topography,
    summit_statistics,
    synthetic_moments,
    synthetic_surface,
    write_topography,
)

# SurfaceTopography's Fourier filter calls numpy.fft.irfftn in a form NumPy 2 deprecates.
pytestmark = pytest.mark.filterwarnings("ignore:`axes` should not be `None`:DeprecationWarning")

DX = 0.1e-6  # pixel [m]
SIGMA = 0.3e-6  # RMS height [m]
TOL = 0.05  # summits vs McCool


def deviations(r):
    return (
        r.summits.asperity_density / r.spectral.asperity_density - 1,
        r.summits.summit_radius / r.spectral.summit_radius - 1,
    )


def surface(n=1024, spectrum=(16, 64), seed=0, hurst=0.8):
    """Periodic synthetic surface; spectrum cutoffs in pixels."""
    return synthetic_surface(
        (n, n),
        DX,
        rms=SIGMA,
        hurst=hurst,
        short_cutoff=spectrum[0] * DX,
        long_cutoff=spectrum[1] * DX,
        seed=seed,
    )


@pytest.fixture(scope="module")
def narrow_band():
    """Two 1024² surfaces, wavelengths 16–64 pixels (≈ 1250 summits each)."""
    return [surface(seed=s) for s in (11, 12)]


# --- McCool / Nayak formulas ------------------------------------------------------------


def test_mccool_formulas_unit_moments():
    p = mccool_parameters(SpectralMoments(1.0, 1.0, 1.0))
    assert p.asperity_density == pytest.approx(1 / (6 * math.pi * math.sqrt(3)), rel=1e-14)
    assert p.summit_radius == pytest.approx(0.375 * math.sqrt(math.pi), rel=1e-14)
    assert p.alpha == 1.0
    assert p.summit_height_std == pytest.approx(math.sqrt(1 - 0.8968), rel=1e-14)
    assert p.summit_height_mean == pytest.approx(4 / math.sqrt(math.pi), rel=1e-14)


def test_eta_beta_sigma_depends_on_bandwidth_only():
    # ηβσ = 0.375/(6√(3π)) √α for any moments
    m = SpectralMoments(2.3e-13, 0.04, 7.0e10)
    p = mccool_parameters(m)
    assert p.asperity_density * p.summit_radius * p.rms == pytest.approx(
        0.375 / (6 * math.sqrt(3 * math.pi)) * math.sqrt(m.alpha), rel=1e-12
    )


def test_mccool_rejects_inconsistent_moments():
    with pytest.raises(InputError, match="bandwidth"):
        mccool_parameters(SpectralMoments(1.0, 10.0, 1.0))


def test_direction_averaged_profile_moments(narrow_band):
    # m2 = M2/2 and m4 = 3M4/8 equal the x-profile moments of an isotropic surface
    t = narrow_band[0]
    r = analyse_surface(t, band=None)
    m2x = t.integrate_psd_from_profile(lambda q: q**2, reliable=False)
    m4x = t.integrate_psd_from_profile(lambda q: q**4, reliable=False)
    assert r.moments.m2 == pytest.approx(m2x, rel=0.05)
    assert r.moments.m4 == pytest.approx(m4x, rel=0.05)


# --- summits vs McCool on isotropic Gaussian surfaces ------------------------------------


@pytest.mark.parametrize("index", [0, 1])
def test_summits_agree_with_mccool_band_limited(narrow_band, index):
    r = analyse_surface(narrow_band[index], band=None)
    d_eta, d_beta = deviations(r)
    assert abs(d_eta) < TOL and abs(d_beta) < TOL
    assert r.summit_stats.count > 1000
    # σ is exact: real-space RMS = √m0 (Parseval) = the prescribed σ
    assert r.summits.rms == pytest.approx(SIGMA, rel=1e-12)
    assert r.spectral.rms == pytest.approx(SIGMA, rel=1e-12)
    assert r.sampling.periodic and r.slope_anisotropy < 1.1
    assert abs(r.heights.skewness) < 0.1 and abs(r.heights.kurtosis - 3) < 0.2


def test_realised_spectrum_matches_prescribed(narrow_band):
    expected = mccool_parameters(synthetic_moments(SIGMA, 0.8, 16 * DX, 64 * DX))
    r = analyse_surface(narrow_band[0], band=None)
    assert r.spectral.asperity_density == pytest.approx(expected.asperity_density, rel=TOL)
    assert r.spectral.summit_radius == pytest.approx(expected.summit_radius, rel=TOL)


def test_summits_agree_with_mccool_broadband_gaussian_filter():
    # wavelengths 2–1024 px, Gaussian band-pass 16–256 px: α ≈ 13, ≈ 3700 summits
    r = analyse_surface(surface(2048, (2, 1024), seed=5), band=(16 * DX, 256 * DX))
    d_eta, d_beta = deviations(r)
    assert abs(d_eta) < TOL and abs(d_beta) < TOL
    assert r.summits.rms == pytest.approx(r.spectral.rms, rel=1e-12)
    assert r.moments.alpha > 8
    assert r.band.kind == "gaussian" and not r.band.clipped


def test_summits_agree_with_mccool_step_filter():
    r = analyse_surface(surface(1024, (2, 512), seed=6), band=(16 * DX, 64 * DX), kind="step")
    d_eta, d_beta = deviations(r)
    assert abs(d_eta) < TOL and abs(d_beta) < TOL


def test_under_resolved_summits_diverge_and_are_flagged():
    # λ_s = 4 px: the 8-neighbour test misses summits; the spectral values do not care
    r = analyse_surface(surface(1024, (2, 512), seed=7), band=(4 * DX, 256 * DX))
    d_eta, d_beta = deviations(r)
    assert d_eta < -0.15 and d_beta > 0.05
    assert any("λ_s spans 4 pixels (< 16)" in n for n in r.notes)


def test_summit_statistics_of_a_lattice_of_bumps():
    # h = cos(kx) + cos(ky): one summit per period², curvature −(h_xx + h_yy)/2 = k²
    n, per = 240, 24
    x = np.arange(n) * DX
    k = 2 * np.pi / (per * DX)
    h = np.cos(k * x)[:, None] + np.cos(k * x)[None, :]
    kappa = np.full(h.shape, k**2)
    s = summit_statistics(h * 1e-7, kappa, (DX, DX), periodic=True)
    assert s.count == (n // per) ** 2
    assert s.asperity_density == pytest.approx(1 / (per * DX) ** 2, rel=1e-12)
    assert s.summit_radius == pytest.approx(1 / k**2, rel=1e-12)


# --- instrument files --------------------------------------------------------------------


@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    """A non-periodic 1000 × 900 map in µm (like an instrument file), with a tilt."""
    t = surface(1024, (2, 512), seed=8)
    h = t.heights()[:1000, :900] * 1e6 + 0.05 * np.linspace(0, 1, 1000)[:, None]
    return Topography(h, (100.0, 90.0), periodic=False, unit="µm")


@pytest.mark.parametrize("suffix", [".x3p", ".nc", ".gwy"])
def test_read_written_instrument_formats(measured, tmp_path, suffix):
    path = write_topography(measured, tmp_path / f"map{suffix}")
    t = read_topography(path)
    assert t.unit == "m"
    assert t.nb_grid_pts == (1000, 900)
    assert np.allclose(t.physical_sizes, (100e-6, 90e-6), rtol=1e-6)
    assert np.allclose(t.pixel_size, (0.1e-6, 0.1e-6), rtol=1e-6)
    h, h0 = t.heights(), measured.heights() * 1e-6
    assert np.std(h) == pytest.approx(np.std(h0), rel=1e-6)
    assert not t.is_periodic
    assert t.info["source"]["file"] == str(path)


def test_file_analysis_equals_in_memory_and_summits_agree(measured, tmp_path):
    path = write_topography(measured, tmp_path / "map.x3p")
    band = (1.6e-6, 6.4e-6)
    r_file = analyse_surface(path, band=band)
    r_mem = analyse_surface(measured, band=band)
    assert r_file.name == "map.x3p" and r_file.source["format"] == "x3p"
    assert r_file.summits.asperity_density == pytest.approx(
        r_mem.summits.asperity_density, rel=1e-9
    )
    assert r_file.spectral.summit_radius == pytest.approx(r_mem.spectral.summit_radius, rel=1e-9)
    # non-periodic map: filtered via mirror stitching, one-λ_s margin excluded
    assert not r_file.sampling.periodic
    assert r_file.summits.rms == pytest.approx(r_file.spectral.rms, rel=1e-12)
    d_eta, d_beta = deviations(r_file)
    assert abs(d_eta) < TOL and abs(d_beta) < TOL


def test_undefined_points_are_filled(measured):
    h = measured.heights().copy()
    rng = np.random.default_rng(0)
    h[rng.random(h.shape) < 0.05] = np.nan
    t = Topography(h, measured.physical_sizes, periodic=False, unit="µm")
    r = analyse_surface(t, band=(1.6e-6, 6.4e-6))
    assert r.sampling.undefined_fraction == pytest.approx(0.05, abs=0.005)
    assert "undefined points filled" in r.sampling.describe()
    assert np.all(np.isfinite(r.topography.heights()))


# --- errors ------------------------------------------------------------------------------


def small_map(n=64, periodic=False):
    return Topography(
        surface(n, (4, 32), seed=1).heights(), (n * DX, n * DX), periodic=periodic, unit="m"
    )


def test_band_below_nyquist_raises():
    with pytest.raises(BandLimitError, match=r"below the Nyquist wavelength 2Δ = 0\.2 µm"):
        analyse_surface(small_map(), band=(0.15e-6, 3e-6))


def test_explicit_band_beyond_scan_raises():
    # the paper's 250 µm limit exceeds a 6.4 µm (or the paper's own ≈ 55 µm) scan: given
    # explicitly, the band stays an error
    with pytest.raises(BandLimitError, match=r"250 µm exceeds the measured length 6\.4 µm"):
        analyse_surface(small_map(), band=PAPER_BAND)


def test_default_band_is_the_typical_one_clipped_to_the_measurement():
    # the ISO roughness band of a ground surface: λ_s 2.5 µm, λ_c 0.8 mm
    assert TYPICAL_BAND == (2.5e-6, 0.8e-3)
    # pixel 0.5 µm: Nyquist 1 µm < 2.5 µm stays; field 64 µm less one λ_s per edge
    coarse = Topography(small_map(128).heights(), (64e-6, 64e-6), unit="m")
    r = analyse_surface(coarse)
    assert r.band.short_wavelength == pytest.approx(2.5e-6)
    assert r.band.long_wavelength == pytest.approx(64e-6 - 2 * 2.5e-6)
    assert r.band.requested == TYPICAL_BAND and r.band.clipped
    assert len(r.warnings) == 1 and "λ_L lowered to the field of view 64 µm" in r.warnings[0]
    # pixels of 2 µm: λ_s raised to the Nyquist wavelength 4 µm
    wide = Topography(small_map(128).heights(), (256e-6, 256e-6), unit="m")
    r = analyse_surface(wide)
    assert r.band.short_wavelength == pytest.approx(4e-6)
    assert r.band.long_wavelength == pytest.approx(256e-6 - 2 * 4e-6)
    assert "Nyquist wavelength 2Δ = 4 µm" in r.warnings[0]
    # a field too small for the band is refused (6.4 µm leaves 1.4 µm < 4 λ_s) …
    with pytest.raises(InsufficientDataError, match=r"too small for any band"):
        analyse_surface(small_map())
    # … and so is a map too small for summit statistics, not analysed on nothing
    tiny = Topography(
        np.random.default_rng(0).standard_normal((16, 16)) * 1e-7, (1.6e-6, 1.6e-6), unit="m"
    )
    with pytest.raises(InsufficientDataError, match=r"only 8 summits .* at least 25"):
        analyse_surface(tiny, band=(0.25e-6, 1.1e-6))


def test_band_limits_in_wrong_order_raise():
    with pytest.raises(BandLimitError, match="short < long"):
        analyse_surface(small_map(), band=(3e-6, 1e-6))


def test_clip_band_narrows_to_measurement_range():
    r = analyse_surface(small_map(), band=PAPER_BAND, clip_band=True)
    assert r.band.clipped and r.band.requested == (0.25e-6, 250e-6)
    assert r.band.short_wavelength == pytest.approx(0.25e-6)
    assert r.band.long_wavelength == pytest.approx(64 * DX)
    assert any("used instead of the requested 0.25–250 µm" in w for w in r.warnings)


def test_band_errors_are_input_errors():
    assert issubclass(BandLimitError, InputError)
    assert issubclass(TopographyReadError, InputError)
    assert issubclass(InsufficientDataError, InputError)


def test_unreadable_file_raises(tmp_path):
    bad = tmp_path / "scan.opd"
    bad.write_bytes(b"this is not a Wyko file\x00\x01\x02" * 8)
    with pytest.raises(TopographyReadError, match="not a surface-topography format"):
        analyse_surface(bad)
    with pytest.raises(TopographyReadError, match="no such file"):
        read_topography(tmp_path / "missing.x3p")


def test_file_without_calibration_or_as_line_scan_raises(tmp_path):
    np.save(tmp_path / "bare.npy", np.zeros((32, 32)))
    with pytest.raises(TopographyReadError, match="no lateral calibration"):
        read_topography(tmp_path / "bare.npy")
    t = read_topography(tmp_path / "bare.npy", physical_sizes=(3.2, 3.2), unit="µm")
    assert t.physical_sizes == pytest.approx((3.2e-6, 3.2e-6))
    line = UniformLineScan(np.sin(np.arange(128.0)), 12.8, unit="µm")
    line.to_netcdf(str(tmp_path / "profile.nc"))
    prof = read_topography(tmp_path / "profile.nc")  # a profile, read as one
    assert prof.dim == 1 and prof.physical_sizes[0] == pytest.approx(12.8e-6)


def test_too_little_left_is_refused():
    t = small_map()
    h = t.heights().copy()
    h[:, :32] = np.nan  # half of the map undefined
    half = Topography(h, t.physical_sizes, unit="m")
    # a share rule only when asked for
    with pytest.raises(InsufficientDataError, match=r"2048 of 4096 points \(50\.0%\) are measured"):
        analyse_surface(half, band=(0.4e-6, 3e-6), min_defined_fraction=0.9)
    # by default: refused only because too few summits remain for η and β
    with pytest.raises(InsufficientDataError, match=r"only \d+ summits .* at least 25"):
        analyse_surface(half, band=(0.4e-6, 3e-6))
    big = small_map(128).heights().copy()
    big[:, :64] = np.nan
    r = analyse_surface(Topography(big, (12.8e-6, 12.8e-6), unit="m"), band=(0.4e-6, 3e-6))
    assert r.sampling.undefined_fraction == pytest.approx(0.5)  # enough summits: analysed
    assert r.summit_stats.count >= 25 and any("50.0% of the points" in w for w in r.warnings)
    with pytest.raises(InsufficientDataError, match="at least 16 per side"):
        analyse_surface(Topography(np.ones((8, 8)), (1e-6, 1e-6), unit="m"), band=None)


# --- composite pair, TOML block, CLI, figure ---------------------------------------------


def test_composite_pair(narrow_band):
    a, b = (analyse_surface(t, band=None, name=n) for t, n in zip(narrow_band, ("cam", "tappet")))
    p = composite_roughness(a, b)
    assert p.rms == pytest.approx(math.hypot(a.rms, b.rms), rel=1e-14)
    assert p.moments.m4 == pytest.approx(a.moments.m4 + b.moments.m4, rel=1e-14)
    assert p.summit_stats is not None
    d_eta = p.summits.asperity_density / p.spectral.asperity_density - 1
    d_beta = p.summits.summit_radius / p.spectral.summit_radius - 1
    assert abs(d_eta) < TOL and abs(d_beta) < TOL
    rough = p.to_roughness("spectral")
    assert isinstance(rough, Roughness)
    assert rough.asperity_density == p.spectral.asperity_density
    assert rough.rms == p.rms and rough.summit_radius == p.spectral.summit_radius


def test_composite_of_differently_sampled_maps_falls_back_to_spectral():
    a = analyse_surface(surface(256, (16, 64), seed=1), band=None)
    b = analyse_surface(
        synthetic_surface(
            (256, 256), 0.8 * DX, rms=SIGMA, short_cutoff=16 * DX, long_cutoff=64 * DX, seed=2
        ),
        band=None,
    )
    p = composite_roughness(a, b)
    assert p.summits is None and any("pixel sizes" in n for n in p.notes)
    with pytest.raises(InputError, match="method='spectral'"):
        p.to_roughness("summits")
    assert p.to_roughness("spectral").rms == pytest.approx(p.rms)


def test_toml_block_round_trip(narrow_band):
    r = analyse_surface(narrow_band[0], band=(1.6e-6, 51.2e-6))
    block = r.toml_block()
    data = tomllib.loads(block)["surface_sets"]["roughness"]
    assert set(data) == {"asperity_density", "rms", "summit_radius"}
    assert data["asperity_density"] == pytest.approx(r.summits.asperity_density, rel=1e-5)
    assert data["rms"] == pytest.approx(r.rms, rel=1e-5)
    assert data["summit_radius"] == pytest.approx(r.summits.summit_radius, rel=1e-5)
    assert "# band 1.6–51.2 µm (Gaussian" in block
    assert "# sampling 1024 × 1024 points, pixel 0.1 × 0.1 µm" in block
    Roughness(**data)  # accepted by the physics layer


@pytest.fixture(scope="module")
def pair_files(tmp_path_factory):
    d = tmp_path_factory.mktemp("pair")
    paths = []
    for i, suffix in enumerate((".x3p", ".nc")):
        t = synthetic_surface(
            (256, 256), DX, rms=0.2e-6, short_cutoff=1.6e-6, long_cutoff=12.8e-6, seed=20 + i
        )
        paths.append(write_topography(t, d / f"surface{i}{suffix}"))
    return paths


def test_cli_json_and_figure(pair_files, tmp_path):
    fig = tmp_path / "heights.png"
    res = CliRunner().invoke(
        app,
        [
            "topography",
            *map(str, pair_files),
            "--band",
            "1.6e-6",
            "12.8e-6",
            "--json",
            "--figure",
            str(fig),
        ],
    )
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    comp = out["composite"]
    assert comp["summits"]["units"]["asperity_density"] == "1/m²"
    assert out["first"]["band"]["short_wavelength"] == pytest.approx(1.6e-6)
    assert out["first"]["sampling"]["nb_grid_pts"] == [256, 256]
    assert tomllib.loads(out["roughness_toml"])["surface_sets"]["roughness"][
        "rms"
    ] == pytest.approx(comp["rms"], rel=1e-5)
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and fig.stat().st_size > 20_000


def test_cli_table_and_errors(pair_files, tmp_path):
    runner = CliRunner()
    res = runner.invoke(
        app,
        ["topography", str(pair_files[0]), "--band", "1.6e-6", "12.8e-6", "--method", "spectral"],
    )
    assert res.exit_code == 0, res.output
    assert "[surface_sets.roughness]" in res.stdout and "summit density" in res.stdout
    assert "band 1.6–12.8 µm" in res.stdout and "converge" in res.stdout
    res = runner.invoke(
        app, ["topography", str(pair_files[0]), "--band", "0.25e-6", "250e-6"]
    )  # the paper's band, given: must fit
    assert res.exit_code == 2 and "exceeds the measured length" in res.stderr
    # default: the typical band, clipped to the 25.6 µm field: too few summits remain
    res = runner.invoke(app, ["topography", str(pair_files[0])])
    assert res.exit_code == 2 and "shorter band" in res.stderr
    res = runner.invoke(  # the paper's band, clipped to the measurement
        app, ["topography", str(pair_files[0]), "--band", "0.25e-6", "250e-6", "--clip-band"]
    )
    assert res.exit_code == 0, res.output
    assert "warning: band 0.25–25.6 µm used instead of the requested 0.25–250 µm" in " ".join(
        res.stdout.split()
    )
    res = runner.invoke(app, ["topography", str(tmp_path / "missing.opd")])
    assert res.exit_code == 2 and "no such file" in res.stderr


def test_cli_synthetic(tmp_path):
    path = tmp_path / "synthetic.x3p"
    res = CliRunner().invoke(
        app,
        [
            "topography",
            str(path),
            "--synthetic",
            "--grid",
            "256",
            "--band",
            "1e-6",
            "12.8e-6",
            "--json",
        ],
    )
    assert res.exit_code == 0, res.output
    assert path.is_file()
    assert json.loads(res.stdout)["sampling"]["pixel_size"] == pytest.approx([1e-7, 1e-7])


def test_height_distribution_figure(narrow_band, tmp_path):
    pair = analyse_pair(narrow_band[0], narrow_band[1], band=None)
    assert isinstance(pair, PairAnalysis)
    path = plot_height_distribution(pair, tmp_path / "fig7.png")
    assert path.read_bytes()[:4] == b"\x89PNG" and path.stat().st_size > 20_000


def test_pair_carries_its_sum_surface(narrow_band):
    """The figure reads the sum surface h₁ + h₂ from the analysis (same grid: a plain sum),
    and the Gaussian with σ beside each surface's heights: the normal density on a
    400-point grid about the mean over ±max(4.5σ, largest deviation)."""
    pair = analyse_pair(narrow_band[0], narrow_band[1], band=None)
    h = pair.first.topography.heights() + pair.second.topography.heights()
    assert np.array_equal(pair.sum_surface, np.ravel(h))
    assert pair.sum_heights.rms == pytest.approx(np.std(h), rel=1e-12)
    for g, z in (
        (pair.sum_gaussian, np.ravel(h)),
        (pair.first.gaussian, np.ravel(pair.first.topography.heights())),
    ):
        d, sigma = z - z.mean(), np.std(z)
        span = max(4.5 * sigma, np.abs(d).max())
        assert g.z.size == 400 and g.span == pytest.approx(span, rel=1e-9)
        np.testing.assert_allclose(np.diff(g.z), 2 * span / 399, rtol=1e-9)
        expected = np.exp(-0.5 * (g.z / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))
        np.testing.assert_allclose(g.pdf, expected, rtol=1e-9)


def test_roughness_block_pastes_into_a_case_file(narrow_band):
    from tribodyn.config import Case

    r = analyse_surface(narrow_band[0], band=None)
    text = (
        '[[surface_sets]]\nname = "measured"\ncoating = "wcc"\n'
        "coating_thickness = 4e-6\n\n" + r.toml_block()
    )
    case = Case.from_toml_string(text)
    rough = build(case).set("measured").surface.roughness
    assert rough.rms == pytest.approx(r.rms, rel=1e-5)
