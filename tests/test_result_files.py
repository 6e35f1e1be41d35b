"""Safe with files tribodyn did not write: no writing through planted links, no private
file in a shared report, modes and groups kept on a re-run, no other study's results
replaced, only tribodyn's own stale folders removed, a link given as ``-o`` kept, clear
messages (no tracebacks) for foreign or undecodable files, any depth of nesting."""

import base64
import json
import os
import stat
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from tribodyn import InputError
from tribodyn._safe_write import atomic_write, make_dirs, remove_tree
from tribodyn.cli import app
from tribodyn.output import writer as W
from tribodyn.output.result_folder import MARKER

runner = CliRunner()


def dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


@pytest.fixture
def fake_run(monkeypatch):
    """``tribodyn run`` without the computation: a stand-in study written by the real
    writer (no figures drawn: the Dataset has no figure's variables)."""
    import tribodyn.output.report as report
    import tribodyn.workflow.cycle as cycle

    ds = xr.Dataset({"central_film": ("crank", [1e-7, 2e-7])}, coords={"crank": [0.0, 1.0]})
    monkeypatch.setattr(W, "study_to_dataset", lambda study: ds)
    monkeypatch.setattr(
        report, "write_report", lambda study, ds, figs, path: Path(path).write_text("report")
    )
    calls = []

    def study(case, **kw):
        calls.append(case)
        summary = {
            "surface_sets": {},
            "implicit_vs_explicit": {},
            "warnings": [],
            "runtime_s": 1.0,
        }
        return SimpleNamespace(case=case, analyse=lambda: SimpleNamespace(summary=summary))

    monkeypatch.setattr(cycle, "run_cycle_study", study)
    return calls


def _run(*args):
    return runner.invoke(app, ["run", *map(str, args), "-q"])


def _results(folder: Path) -> Path:
    """A small result folder for ``tribodyn export``: results.nc of a cycle study's shape
    (crank angles, one surface set), report.md showing fig05_dry_pressure.png."""
    folder.mkdir(parents=True)
    ds = xr.Dataset(
        {
            "ehl_contact_force": ("ehl_crank", [0.0, 100.0], {"units": "N"}),
            "central_film": (("surface_set", "ehl_crank"), [[1e-7, 2e-7]], {"units": "m"}),
            "cam_lift": ("crank_angle", [0.0, 1e-3, 0.0], {"units": "m"}),
        },
        coords={
            "ehl_crank": [0.0, 1.0],
            "crank_angle": [0.0, 1.0, 2.0],
            "surface_set": ["uncoated"],
        },
    )
    ds.to_netcdf(folder / "results.nc", engine="h5netcdf")
    (folder / "report.md").write_text("# report\n\n![f](fig05_dry_pressure.png)\n")
    (folder / "fig05_dry_pressure.png").write_bytes(b"\x89PNG figure")
    return folder


def _export(results, *more):
    return runner.invoke(app, ["export", str(results), *map(str, more)])


# ----------------------------------------------------------------------------- the helper
def test_the_safe_write_replaces_a_link_and_never_writes_through_it(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    link = tmp_path / "out.txt"
    link.symlink_to(victim)
    atomic_write(link, "new")
    assert victim.read_text() == "precious"
    assert not link.is_symlink() and link.read_text() == "new"
    with pytest.raises(FileExistsError):
        atomic_write(link, "again", replace=False)
    assert link.read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt", "victim.txt"]


def test_deep_folders_are_made_and_removed_without_recursion(tmp_path):
    deep = tmp_path / "top" / Path(*["d"] * 1100)
    make_dirs(deep)
    (deep / "f").write_text("x")
    remove_tree(tmp_path / "top")
    assert not (tmp_path / "top").exists()


# ----------------------------------------------------------------------------- export
def test_export_does_not_write_through_planted_links(tmp_path):
    """A result folder from someone else with ``traces.csv.tmp -> ../victim``: the export
    used that fixed temporary name and overwrote the victim; a user's report.html.tmp was
    overwritten and renamed away."""
    res = _results(tmp_path / "res")
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    (res / "traces.csv.tmp").symlink_to("../victim.txt")
    (res / "report.html.tmp").write_text("my own file")
    r = _export(res)
    assert r.exit_code == 0, r.output
    assert victim.read_text() == "precious"
    assert (res / "report.html.tmp").read_text() == "my own file"
    assert (res / "traces.csv.tmp").is_symlink()
    assert (res / "traces.csv").read_text().startswith("crank_angle [deg]")


def test_export_embeds_no_file_from_outside_the_folder(tmp_path):
    """A figure named in report.md that is a link to a private file is not embedded in
    the shareable report.html; the export says so."""
    res = _results(tmp_path / "res")
    secret = tmp_path / "secret.png"
    secret.write_bytes(b"my private data " * 8)
    (res / "fig05_dry_pressure.png").unlink()
    (res / "fig05_dry_pressure.png").symlink_to(secret)
    r = _export(res)
    assert r.exit_code == 0, r.output
    page = (res / "report.html").read_text()
    assert base64.b64encode(secret.read_bytes()).decode()[:40] not in page
    assert "missing figure fig05_dry_pressure.png" in page
    assert "fig05_dry_pressure.png" in r.output and "warning" in r.output


def test_export_of_a_report_that_is_not_utf8(tmp_path):
    res = _results(tmp_path / "res")
    (res / "report.md").write_bytes("# Bericht\n\nÖl: 5W-30\n".encode("latin-1"))
    r = _export(res)
    assert r.exit_code == 0, r.output
    assert "UTF-8" in r.output and "Traceback" not in r.output
    assert "l: 5W-30" in (res / "report.html").read_text()


def test_export_into_a_folder_it_cannot_write(tmp_path):
    res = _results(tmp_path / "res")
    out = Path("/proc/tribodyn-export")  # no folder can be made there, even by root
    r = _export(res, "-o", out)
    assert r.exit_code == 1, r.output
    assert "cannot write" in r.output and "Traceback" not in r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)


def test_export_of_a_netcdf_from_elsewhere(tmp_path):
    res = tmp_path / "res"
    res.mkdir()
    xr.Dataset(
        {"x": ("ehl_crank", np.zeros(2))}, coords={"ehl_crank": [0.0, 1.0], "crank_angle": [0.0]}
    ).to_netcdf(res / "results.nc", engine="h5netcdf")
    r = _export(res)
    assert r.exit_code == 2, r.output
    assert "not a tribodyn results file" in r.output and "surface_set" in r.output
    assert not isinstance(r.exception, KeyError)


# ----------------------------------------------------------------------------- re-run
@pytest.mark.skipif(not hasattr(os, "getgroups"), reason="POSIX groups")
def test_a_rerun_keeps_the_modes_and_group_of_what_it_keeps(tmp_path, fake_run):
    out = tmp_path / "res"
    assert _run("-o", out).exit_code == 0
    private = out / "private"
    private.mkdir()
    (private / "notes.txt").write_text("mine")
    os.chmod(private, 0o700)
    groups = [g for g in os.getgroups() if g != os.getegid()] or [os.getegid()]
    gid = groups[0] if os.geteuid() != 0 else 4242  # root may give any group
    uid = os.geteuid() if os.geteuid() != 0 else 4321  # and any owner
    os.chown(out, uid, gid)
    os.chmod(out, 0o2770)
    r = _run("-o", out)
    assert r.exit_code == 0, r.output
    st = os.stat(out)
    assert stat.S_IMODE(st.st_mode) == 0o2770 and (st.st_uid, st.st_gid) == (uid, gid)
    assert stat.S_IMODE(os.stat(out / "private").st_mode) == 0o700
    assert (out / "private" / "notes.txt").read_text() == "mine"
    assert os.stat(out / "summary.json").st_gid == gid  # new files: the folder's group
    os.chmod(out, 0o700)
    assert _run("-o", out).exit_code == 0
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o700


def test_a_folder_of_someone_else_is_updated_in_place(tmp_path, monkeypatch):
    """A run that is not the folder owner's cannot replace the folder without changing
    its owner: the folder stays (same inode, owner, mode), the user's files stay, the new
    files move in, tribodyn's files it no longer writes go."""
    out = W.write_atomic(tmp_path / "res", lambda d: (d / "results.nc").write_text("1"))
    (out / "old.txt").write_text("x")
    W.mark_folder(
        out, {"results.nc": W._sha256(out / "results.nc"), "old.txt": W._sha256(out / "old.txt")}
    )
    (out / "notes.txt").write_text("mine")
    os.chmod(out, 0o750)
    before = os.stat(out)
    monkeypatch.setattr(os, "geteuid", lambda: before.st_uid + 1)  # not the owner, not root

    def writer(d):
        (d / "results.nc").write_text("2")
        (d / "inputs").mkdir()
        (d / "inputs" / "cam.csv").write_text("0,0\n")

    W.write_atomic(out, writer)
    after = os.stat(out)
    assert (after.st_ino, after.st_uid, after.st_mode) == (
        before.st_ino,
        before.st_uid,
        before.st_mode,
    )
    assert (out / "results.nc").read_text() == "2" and not (out / "old.txt").exists()
    assert (out / "notes.txt").read_text() == "mine"
    info = json.loads((out / MARKER).read_text())
    assert sorted(info["files"]) == ["inputs/cam.csv", "results.nc"] and "previous" not in info
    assert sorted(p.name for p in tmp_path.iterdir()) == ["res"]
    (out / "results.nc").write_text("edited")  # the user's now: in the way of a new one
    with pytest.raises(InputError, match="results.nc"):
        W.write_atomic(out, writer)
    assert (out / "results.nc").read_text() == "edited"


def test_run_refuses_the_folder_of_a_sweep_before_computing(tmp_path, fake_run):
    sw = tmp_path / "sw"
    (sw / "points").mkdir(parents=True)
    (sw / "points" / "0a1b.nc").write_bytes(b"point")
    (sw / "sweep.nc").write_bytes(b"sweep")
    W.mark_folder(sw, {"sweep.nc": W._sha256(sw / "sweep.nc")}, {"kind": "sweep"})
    r = _run("-o", sw)
    assert r.exit_code == 2 and "tribodyn sweep" in r.output, r.output
    assert not fake_run
    assert (sw / "points" / "0a1b.nc").read_bytes() == b"point"
    assert (sw / "sweep.nc").read_bytes() == b"sweep"
    run_dir = tmp_path / "run"
    assert _run("-o", run_dir).exit_code == 0
    r = runner.invoke(app, ["sweep", "andreou2023_dynamics", "-o", str(run_dir), "-q"])
    assert r.exit_code == 2 and "tribodyn run" in r.output, r.output


def test_resume_with_another_sweep_is_refused(tmp_path, monkeypatch):
    import tribodyn.workflow.sweep as sweep

    monkeypatch.setattr(sweep, "run_sweep", lambda *a, **k: pytest.fail("must not run"))
    out = tmp_path / "sw"
    (out / "points").mkdir(parents=True)
    (out / "sweep.nc").write_bytes(b"the speed sweep")
    info = {"kind": "sweep", "sweep": "andreou2023_speed", "sweep_mode": "study"}
    W.mark_folder(out, {"sweep.nc": W._sha256(out / "sweep.nc")}, info)
    r = runner.invoke(app, ["sweep", "andreou2023_dynamics", "-o", str(out), "--resume", "-q"])
    assert r.exit_code == 2 and "another sweep" in r.output, r.output
    assert (out / "sweep.nc").read_bytes() == b"the speed sweep"


def test_stale_looking_folders_of_someone_else_are_kept(tmp_path, fake_run):
    mine = tmp_path / f".res.tmp-{dead_pid()}-mine"
    mine.mkdir()
    (mine / "data.txt").write_text("mine")
    backup = tmp_path / ".res.tmp-backup"
    backup.mkdir()
    old = os.stat(backup).st_mtime - 7200
    os.utime(backup, (old, old))
    lookalike = tmp_path / f".res.old-{dead_pid()}-0123abcd"  # the form, not the proof
    lookalike.mkdir()
    assert _run("-o", tmp_path / "res").exit_code == 0
    assert (mine / "data.txt").read_text() == "mine"
    assert backup.is_dir() and lookalike.is_dir()


def test_a_link_given_as_output_is_kept_and_its_folder_written(tmp_path, fake_run):
    real = tmp_path / "real"
    assert _run("-o", real).exit_code == 0
    (real / "notes.txt").write_text("keep")
    link = tmp_path / "link"
    link.symlink_to(real)
    r = _run("-o", link)
    assert r.exit_code == 0, r.output
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert (real / "notes.txt").read_text() == "keep"
    assert len(fake_run) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "real"]


def test_a_folder_named_like_the_marker_is_refused_before_computing(tmp_path, fake_run):
    out = tmp_path / "res"
    out.mkdir()
    for f in ("results.nc", "summary.json", "case.toml"):  # a 0.1 result folder
        (out / f).write_text("x")
    (out / MARKER).mkdir()
    (out / MARKER / "mine.txt").write_text("mine")
    r = _run("-o", out)
    assert r.exit_code == 2 and MARKER in r.output, r.output
    assert not fake_run and (out / MARKER / "mine.txt").read_text() == "mine"


def test_a_home_folder_with_a_stray_marker_is_refused(tmp_path, fake_run, monkeypatch):
    home = tmp_path / "home"
    assert _run("-o", home).exit_code == 0  # as if `cp -r results/. ~`
    (home / ".bashrc").write_text("mine")
    monkeypatch.setenv("HOME", str(home))
    r = _run("-o", home)
    assert r.exit_code == 2 and "home folder" in r.output, r.output
    assert len(fake_run) == 1 and (home / ".bashrc").read_text() == "mine"


def test_a_deeply_nested_folder_of_the_user_is_kept(tmp_path, fake_run):
    out = tmp_path / "res"
    assert _run("-o", out).exit_code == 0
    deep = out / Path(*["d"] * 1100)
    make_dirs(deep)
    (deep / "note.txt").write_text("deep")
    try:
        r = _run("-o", out)
        assert r.exit_code == 0, r.output[-500:]
        assert (deep / "note.txt").read_text() == "deep"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["res"]
    finally:  # pytest removes its old folders recursively: not this deep
        for p in tmp_path.iterdir():
            remove_tree(p, ignore_errors=True)


def test_a_foreign_temporary_marker_file_is_not_removed(tmp_path):
    """The proof of origin must match the folder's name: a copied or forged one does not
    make a folder tribodyn's."""
    from tribodyn.output.result_folder import ORIGIN
    from tribodyn.output.work_folder import clean_stale

    pid = dead_pid()
    p = tmp_path / f".res.tmp-{pid}-0123abcd"
    p.mkdir()
    proof = {"tool": "tribodyn", "kind": "tmp", "pid": pid, "token": "ffffffff"}
    (p / ORIGIN).write_text(json.dumps(proof))  # another folder's token
    assert clean_stale(tmp_path / "res") == [] and p.is_dir()


def test_only_a_proven_replaced_folder_is_moved_back(tmp_path):
    """A kill between the two renames leaves ``.NAME.old-PID-TOKEN`` with its proof (it
    is written before the rename): moved back. A folder of that form without the proof,
    even holding results, is left where it is."""
    from tribodyn.output.work_folder import clean_stale, prove_origin

    pid = dead_pid()
    foreign = tmp_path / f".res.old-{pid}-0123abcd"
    foreign.mkdir()
    W.mark_folder(foreign, {})
    assert clean_stale(tmp_path / "res") == [] and foreign.is_dir()
    proven = tmp_path / f".res.old-{pid}-89abcdef"
    proven.mkdir()
    W.mark_folder(proven, {})
    prove_origin(proven)
    assert clean_stale(tmp_path / "res") == [proven]
    assert (tmp_path / "res" / MARKER).is_file() and foreign.is_dir()
    assert not (tmp_path / "res" / ".tribodyn-origin").exists()
