"""Real instrument files with the default options: read back point by point, analysed
on the first try (band clipped to the measurement, dropouts filled), profiles included.

The files in tests/data/topography were written byte by byte from the formats' published
layouts by tests/data/topography/make_files.py (see the README there), not by
SurfaceTopography's writers; the surface they hold is known, so every value is checked.
"""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from SurfaceTopography import Topography, UniformLineScan
from typer.testing import CliRunner

from tribodyn.cli import app
from tribodyn.topography import analyse_surface, read_topography, synthetic_surface
from tribodyn.topography.profile import ProfileAnalysis, analyse_profile

pytestmark = pytest.mark.filterwarnings("ignore:`axes` should not be `None`:DeprecationWarning")

DATA = Path(__file__).resolve().parent / "data" / "topography"
sys.path.insert(0, str(DATA))
import make_files as M  # noqa: E402  (the generator documents what the files hold)

#: file → (SurfaceTopography format, y axis as read, height tolerance [m])
#: "up": row index = y upward, as written; "rows": the file's row order, which for camera
#: formats starts at the top of the image, so y points down (a mirror image in y that
#: changes no statistic); tolerance: the format's quantisation
AREAL = {
    "surface.x3p": ("x3p", "up", 1e-13),  # float32 [m]
    "surface.sdf": ("sdf", "up", 6e-12),  # text, 5 decimals of µm
    "surface.sur": ("sur", "up", 6e-11),  # int32, 0.1 nm per count (+ offset)
    "surface.dat": ("metropro", "rows", 4e-11),  # int32 phase, 77 pm per count
    "surface.opd": ("opd", "rows", 1e-13),  # float32 waves
    "surface.plu": ("plu", "rows", 1e-13),  # float32 [µm]
}
PROFILES = {"profile.sdf": "sdf", "profile.sur": "sur"}
runner = CliRunner()


def expected(orientation):
    h, m = M.surface(), M.dropouts()
    return (h, m) if orientation == "up" else (h[:, ::-1], m[:, ::-1])


@pytest.mark.parametrize("name", AREAL)
def test_areal_file_values_orientation_and_dropouts(name):
    fmt, orient, tol = AREAL[name]
    t = read_topography(DATA / name)
    assert t.info["source"]["format"] == fmt
    assert t.nb_grid_pts == (M.NX, M.NY)  # x is the fast axis
    assert np.allclose(t.pixel_size, (M.DX, M.DX), rtol=1e-6)
    assert np.allclose(t.physical_sizes, (M.NX * M.DX, M.NY * M.DX), rtol=1e-6)
    h, m = expected(orient)
    got = t.heights()
    assert np.array_equal(np.ma.getmaskarray(got), m)  # dropouts where written
    diff = (np.ma.getdata(got) - h)[~m]
    if name == "surface.sur":
        # SurfaceTopography leaves out the header's z offset: a constant shift
        assert diff.mean() == pytest.approx(-math.floor(h.min() * 1e6) * 1e-6, abs=1e-10)
        diff = diff - diff.mean()
    assert np.max(np.abs(diff)) < tol
    # the tilt plane of the written surface shows the axes: the slope along x keeps its
    # sign in every file; along y it keeps it ("up") or changes it ("rows", mirrored)
    x = np.arange(M.NX)[:, None] * M.DX
    y = np.arange(M.NY)[None, :] * M.DX
    A = np.stack(
        [np.broadcast_to(x, h.shape)[~m], np.broadcast_to(y, h.shape)[~m], np.ones((~m).sum())],
        axis=1,
    )
    sx, sy, _ = np.linalg.lstsq(A, np.ma.getdata(got)[~m], rcond=None)[0]
    assert sx > 1e-3
    assert (sy < -5e-4) if orient == "up" else (sy > 5e-4)


@pytest.fixture(scope="module")
def reference():
    """The written surface (with the same dropouts) analysed in memory in
    :data:`CHECK_BAND`."""
    h, m = M.surface(), M.dropouts()
    t = Topography(np.ma.masked_array(h, mask=m), (M.NX * M.DX, M.NY * M.DX), unit="m")
    return analyse_surface(t, band=CHECK_BAND, clip_band=True)


#: band of the file-vs-memory comparison, clipped to each map: λ_s = 2Δ, whatever the
#: rounding of the pixel size a format stores (the edge margin of the analysis is whole
#: pixels of λ_s), λ_L = the field (the paper's band, 0.25–250 µm)
CHECK_BAND = (0.25e-6, 250e-6)


@pytest.mark.parametrize("name", AREAL)
def test_default_cli_run_works_and_matches_the_written_surface(name, reference):
    res = runner.invoke(app, ["topography", str(DATA / name), "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    # the band actually used, and why; the dropouts filled, with their share
    assert out["band"]["short_wavelength"] == pytest.approx(2.5e-6)  # typical (> 2Δ = 1 µm)
    assert out["band"]["long_wavelength"] == pytest.approx(55e-6)  # 60 − 2λ_s
    assert out["band"]["requested"] == pytest.approx([2.5e-6, 0.8e-3])
    assert "field of view" in out["band"]["clipped_because"]
    assert out["filled_fraction"] == pytest.approx(M.dropouts().mean(), abs=1e-9)
    assert any("band 2.5–55 µm used instead" in w for w in out["warnings"])
    assert any("28.0% of the points were not measured" in w for w in out["warnings"])
    assert "warning" in res.stderr
    # same numbers as the known surface analysed in memory (quantisation aside; files
    # whose rows run top-down hold its mirror image, which changes no statistic)
    band = [str(v) for v in CHECK_BAND]
    res = runner.invoke(
        app, ["topography", str(DATA / name), "--json", "--band", *band, "--clip-band"]
    )
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    ref = reference
    assert out["heights"]["rms"] == pytest.approx(ref.rms, rel=1e-4)
    assert out["spectral"]["asperity_density"] == pytest.approx(
        ref.spectral.asperity_density, rel=1e-3
    )
    assert out["spectral"]["summit_radius"] == pytest.approx(ref.spectral.summit_radius, rel=1e-3)
    assert abs(out["summit_count"] - ref.summit_stats.count) <= 2
    assert out["summits"]["summit_radius"] == pytest.approx(ref.summits.summit_radius, rel=0.03)


def test_table_output_shows_band_and_filled_share():
    res = runner.invoke(app, ["topography", str(DATA / "surface.dat")])
    assert res.exit_code == 0, res.output
    text = " ".join(res.stdout.split())
    assert "filled: 28.0% of the points" in text
    assert "warning: band 2.5–55 µm used instead of the requested 2.5–800 µm" in text
    assert "[surface_sets.roughness]" in text


def test_dropout_filling_recovers_the_complete_surface():
    """28 % dropouts (clusters and single pixels) on a known isotropic Gaussian surface:
    σ, η and β from the measured points agree with those of the complete surface. Tested
    within a few standard errors of the summit counts (≈ 1/√N)."""
    dx = 0.1e-6
    t = synthetic_surface(
        (1024, 1024), dx, rms=0.3e-6, short_cutoff=8 * dx, long_cutoff=128 * dx, seed=5
    )
    h = t.heights()[:900, :800]
    size = (900 * dx, 800 * dx)
    band = (8 * dx, 128 * dx)
    full = analyse_surface(Topography(h, size, unit="m"), band=band)
    rng = np.random.default_rng(3)
    from scipy.ndimage import gaussian_filter

    blobs = gaussian_filter(rng.standard_normal(h.shape), 6.0)
    mask = (blobs > np.quantile(blobs, 0.80)) | (rng.random(h.shape) < 0.10)
    holed = analyse_surface(Topography(np.ma.masked_array(h, mask=mask), size, unit="m"), band=band)
    assert holed.sampling.undefined_fraction == pytest.approx(0.28, abs=0.01)
    n = holed.summit_stats.count
    assert n > 300
    assert holed.rms == pytest.approx(full.rms, rel=0.02)
    assert holed.summits.asperity_density == pytest.approx(
        full.summits.asperity_density, rel=3 / math.sqrt(n)
    )
    assert holed.summits.summit_radius == pytest.approx(full.summits.summit_radius, rel=0.03)
    assert holed.spectral.asperity_density == pytest.approx(
        full.spectral.asperity_density, rel=0.05
    )
    assert holed.spectral.summit_radius == pytest.approx(full.spectral.summit_radius, rel=0.03)


# --- profiles ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", PROFILES)
def test_profile_file_values(name):
    t = read_topography(DATA / name)
    assert t.dim == 1 and t.info["source"]["format"] == PROFILES[name]
    assert t.nb_grid_pts == (M.NP,)
    assert t.physical_sizes[0] == pytest.approx(M.NP * M.DXP, rel=1e-6)
    h, m = M.profile(), M.profile_dropouts()
    got = t.heights()
    assert np.array_equal(np.ma.getmaskarray(got), m)
    diff = (np.ma.getdata(got) - h)[~m]
    assert np.max(np.abs(diff - (diff.mean() if name.endswith(".sur") else 0.0))) < 6e-11


def test_profile_cli_gives_what_a_profile_can_give():
    outs = []
    paper_band = ["--band", "0.25e-6", "250e-6", "--clip-band"]  # the band of the moments
    for name in PROFILES:
        res = runner.invoke(app, ["topography", str(DATA / name), "--json", *paper_band])
        assert res.exit_code == 0, res.output
        outs.append(json.loads(res.stdout))
    a, b = outs
    assert a["kind"] == "profile" and a["summits"] is None
    assert "isotropic" in a["isotropic_estimate"]["label"]
    assert "ISOTROPIC-SURFACE ESTIMATE" in a["roughness_toml"]
    assert a["filled_fraction"] == pytest.approx(M.profile_dropouts().mean())
    for key in ("m0", "m2", "m4"):
        assert a["moments"][key] == pytest.approx(b["moments"][key], rel=1e-5)
    # reference: the moments of the written rough profile (flat spectrum 4–30 µm), summed
    # over its discrete Fourier spectrum. Complete profile: only the Gaussian band
    # 0.5–250 µm differs (it passes > 97.8 % of the power at 4 µm); from the file, the
    # moments are averages over the measured points (85 % of the profile, a sample of it)
    rough = M._rough((M.NP,), M.DXP, seed=99)
    q = 2 * math.pi * np.fft.fftfreq(M.NP, M.DXP)
    power = np.abs(np.fft.fft(rough)) ** 2 / M.NP**2
    ref = [float(np.sum(power * q**k)) for k in (0, 2, 4)]
    complete = analyse_profile(
        UniformLineScan(M.profile(), M.NP * M.DXP, unit="m"),
        band=(0.25e-6, 250e-6),
        clip_band=True,
    )
    for got, want in zip((complete.moments.m0, complete.moments.m2, complete.moments.m4), ref):
        assert got == pytest.approx(want, rel=0.02)
    m = a["moments"]
    assert m["m0"] == pytest.approx(ref[0], rel=0.02)
    assert m["m2"] == pytest.approx(ref[1], rel=0.07)
    assert m["m4"] == pytest.approx(ref[2], rel=0.07)
    res = runner.invoke(app, ["topography", str(DATA / "profile.sdf")])
    assert res.exit_code == 0 and "isotropic estimate" in res.stdout


def test_profile_of_an_isotropic_surface_estimates_its_summits():
    """Rows of an isotropic Gaussian surface: the isotropic-surface estimates from the
    profile moments agree with the areal McCool values (Nayak 1971), and the counted peak
    density with Longuet-Higgins' (1/2π)√(m4/m2)."""
    dx = 0.1e-6
    t = synthetic_surface(
        (1024, 1024), dx, rms=0.3e-6, short_cutoff=8 * dx, long_cutoff=64 * dx, seed=21
    )
    area = analyse_surface(t, band=None)
    h = t.heights()
    eta, beta, dens, dens_g = [], [], [], []
    for row in range(0, 1024, 8):
        line = UniformLineScan(h[:, row], 1024 * dx, periodic=True, unit="m")
        p = analyse_profile(line, band=None)
        assert isinstance(p, ProfileAnalysis)
        eta.append(p.spectral.asperity_density)
        beta.append(p.spectral.summit_radius)
        dens.append(p.peak_density)
        dens_g.append(p.peak_density_gaussian)
    assert np.mean(eta) == pytest.approx(area.spectral.asperity_density, rel=0.04)
    assert np.mean(beta) == pytest.approx(area.spectral.summit_radius, rel=0.02)
    assert np.mean(dens) == pytest.approx(np.mean(dens_g), rel=0.04)


def test_profile_with_too_few_peaks_is_refused(tmp_path):
    from tribodyn.topography import InsufficientDataError

    line = UniformLineScan(np.sin(np.arange(256) * 2 * np.pi / 32) * 1e-7, 25.6e-6, unit="m")
    with pytest.raises(InsufficientDataError, match="peaks"):
        analyse_surface(line, band=None)


def test_damaged_files_are_refused_with_a_message(tmp_path):
    """Truncated copies of the instrument files, and a text SDF that lost its last line:
    an error naming the file, never a traceback or silently shortened data."""
    for name in list(AREAL) + list(PROFILES):
        raw = (DATA / name).read_bytes()
        for cut in (40, 600, len(raw) // 2, len(raw) - 5):
            bad = tmp_path / f"cut{cut}_{name}"
            bad.write_bytes(raw[:cut])
            res = runner.invoke(app, ["topography", str(bad)])
            assert res.exit_code == 2, (name, cut, res.output)
            assert res.exception is None or isinstance(res.exception, SystemExit)
    res = runner.invoke(app, ["topography", str(tmp_path / f"cut{len(raw) - 5}_{name}")])
    assert "truncated" in res.stderr or "cannot read" in res.stderr


def test_figure_path_must_be_an_image_file(tmp_path):
    good = str(DATA / "surface.x3p")
    for bad in (str(tmp_path), str(tmp_path / "fig.tmp")):
        res = runner.invoke(app, ["topography", good, "--figure", bad])
        assert res.exit_code == 2 and "--figure" in res.stderr


def test_cli_pairs_an_areal_map_with_a_profile():
    """A cam measured as a profile and a tappet as an areal map: the pair's composite
    parameters from the map and the profile's isotropic-surface estimates (exit 0)."""
    r = CliRunner().invoke(
        app, ["topography", str(DATA / "surface.x3p"), str(DATA / "profile.sur"), "--json"]
    )
    assert r.exit_code == 0, r.output


# ----------------------------------------------------------------------------- size limits
def test_map_larger_than_the_limit_is_refused_before_its_heights_are_read(monkeypatch):
    """A map beyond MAX_MAP_POINTS (4096²) is refused from its header, saying what to
    do; before, any size was read and analysed (memory of ~10 copies of the map). The
    limit is lowered here so that a small test file exceeds it."""
    import tribodyn.topography.filtering as F
    from tribodyn.topography.errors import TopographyReadError

    f = DATA / "surface.x3p"
    n = math.prod(read_topography(f).nb_grid_pts)
    monkeypatch.setattr(F, "MAX_MAP_POINTS", n - 1)
    with pytest.raises(TopographyReadError, match=f"= {n} points, more than the {n - 1}") as e:
        read_topography(f)
    assert "crop it or subsample it" in str(e.value)
    r = CliRunner().invoke(app, ["topography", str(f)])
    assert r.exit_code == 2 and "crop it or subsample it" in " ".join(r.output.split())


@pytest.mark.parametrize("grid", [4097, 10**6, 10**400])
def test_synthetic_map_beyond_the_limit_is_an_input_error(grid):
    from tribodyn import InputError

    with pytest.raises(InputError, match="^nb_grid_pts must"):
        synthetic_surface((grid, grid))


def test_synthetic_map_beyond_the_limit_from_the_cli(tmp_path):
    r = CliRunner().invoke(
        app, ["topography", str(tmp_path / "s.x3p"), "--synthetic", "--grid", "100000"]
    )
    assert r.exit_code == 2 and "nb_grid_pts must give at most" in " ".join(r.output.split())
    assert not (tmp_path / "s.x3p").exists()


def test_an_unknown_unit_is_an_input_error(tmp_path):
    # a bare matrix needs --unit; a unit SurfaceTopography does not know was a traceback
    np.save(tmp_path / "m.npy", np.random.default_rng(1).normal(size=(16, 16)))
    from tribodyn.topography import TopographyReadError

    t = read_topography(tmp_path / "m.npy", unit="µm", physical_sizes=(16.0, 16.0))
    assert np.allclose(t.physical_sizes, (16e-6, 16e-6))
    with pytest.raises(TopographyReadError, match=r"unit must be a length unit \(.*µm.*'furlong'"):
        read_topography(tmp_path / "m.npy", unit="furlong", physical_sizes=(16.0, 16.0))
    r = CliRunner().invoke(
        app, ["topography", str(tmp_path / "m.npy"), "--unit", "furlong", "--size", "16", "16"]
    )
    assert r.exit_code == 2 and "unit must be a length unit" in " ".join(r.output.split())
