"""Results are never lost or misplaced: output checked before computing, only tribodyn's own
result folders replaced, results rescued when writing fails, SIGTERM handled like Ctrl-C,
temporary folders of killed runs cleaned up."""

import errno
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest
import xarray as xr
from typer.testing import CliRunner

from conftest import REDUCED
from tribodyn import InputError
from tribodyn.cli import app
from tribodyn.config import load_case
from tribodyn.output import (
    OutputWriteError,
    check_output_dir,
    clean_stale,
    is_result_folder,
    write_atomic,
    write_results,
)
from tribodyn.output import writer as W

runner = CliRunner()


def dead_pid() -> int:
    """A PID that belongs to no process (a child that has exited and been reaped)."""
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


# ----------------------------------------------------------------------------- before computing
def test_existing_file_is_refused_and_left_alone(tmp_path):
    f = tmp_path / "notes.txt"
    f.write_text("my notes")
    with pytest.raises(InputError, match="is an existing file"):
        check_output_dir(f)
    r = runner.invoke(app, ["run", "-o", str(f), "-q"])
    assert r.exit_code == 2 and "existing file" in r.output
    assert f.read_text() == "my notes"
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]


def test_foreign_folder_is_refused_empty_and_result_folders_accepted(tmp_path):
    foreign = tmp_path / "photos"
    foreign.mkdir()
    (foreign / "a.jpg").write_bytes(b"x")
    with pytest.raises(InputError, match="did not write"):
        check_output_dir(foreign)
    r = runner.invoke(app, ["run", "-o", str(foreign), "-q"])
    assert r.exit_code == 2 and (foreign / "a.jpg").exists()
    empty = tmp_path / "empty"
    empty.mkdir()
    assert check_output_dir(empty) == empty
    marked = tmp_path / "marked"
    marked.mkdir()
    (marked / W.MARKER).write_text("{}")
    (marked / "results.nc").write_bytes(b"old")
    assert is_result_folder(marked) and check_output_dir(marked) == marked
    legacy = tmp_path / "legacy"  # written by tribodyn 0.1
    legacy.mkdir()
    for name in ("results.nc", "summary.json", "case.toml"):
        (legacy / name).write_text("x")
    assert is_result_folder(legacy)


def test_parent_that_is_a_file_is_refused(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(InputError, match="is a file, not a folder"):
        check_output_dir(tmp_path / "f" / "sub" / "res")


def test_unwritable_location_is_refused(tmp_path):
    if os.geteuid() == 0:  # root writes anywhere: use a location no one can
        target = Path("/proc/tribodyn-results")
    else:
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o555)
        target = ro / "res"
    with pytest.raises(InputError, match="cannot write in"):
        check_output_dir(target)


def test_full_disk_is_detected_by_the_probe(tmp_path, monkeypatch):
    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(W.os, "fsync", full)
    with pytest.raises(InputError, match="No space left on device"):
        check_output_dir(tmp_path / "res")
    assert not list(tmp_path.iterdir())  # the probe is removed


def test_too_little_free_space_is_refused(tmp_path, monkeypatch):
    import shutil

    monkeypatch.setattr(
        shutil, "disk_usage", lambda p: SimpleNamespace(total=1 << 30, used=1 << 30, free=5 << 20)
    )
    with pytest.raises(InputError, match="only 5 MB free"):
        check_output_dir(tmp_path / "res")


def test_bad_output_is_refused_before_the_study_runs(tmp_path, monkeypatch):
    import tribodyn.workflow.cycle as cycle

    monkeypatch.setattr(
        cycle, "run_cycle_study", lambda *a, **k: pytest.fail("the study must not start")
    )
    (tmp_path / "f").write_text("x")
    r = runner.invoke(app, ["run", "-o", str(tmp_path / "f" / "res"), "-q"])
    assert r.exit_code == 2 and "-o/--out" in r.output
    r = runner.invoke(app, ["run", "-j", "-3", "-o", str(tmp_path / "res"), "-q"])
    assert r.exit_code == 2 and "-j/--workers" in r.output


# ----------------------------------------------------------------------------- atomic writing
def test_results_folders_are_marked(tmp_path):
    out = write_atomic(
        tmp_path / "res", lambda d: (d / "x.txt").write_text("1"), meta={"case": "c"}
    )
    info = json.loads((out / W.MARKER).read_text())
    assert info["tool"] == "tribodyn" and info["case"] == "c"
    out = write_atomic(tmp_path / "res", lambda d: (d / "y.txt").write_text("2"))
    assert (out / "y.txt").exists() and not (out / "x.txt").exists()
    with pytest.raises(InputError, match="did not write"):
        (tmp_path / "other").mkdir()
        (tmp_path / "other" / "keep").write_text("k")
        write_atomic(tmp_path / "other", lambda d: None)
    assert (tmp_path / "other" / "keep").read_text() == "k"


def test_interrupt_while_writing_leaves_no_trace(tmp_path):
    def interrupted(d):
        (d / "results.nc").write_text("half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_atomic(tmp_path / "res", interrupted)
    assert not list(tmp_path.iterdir())


def test_stale_temporary_folders_are_cleaned(tmp_path):
    """Only folders with tribodyn's proof of origin (the PID and token of their name) are
    removed; folders of someone else's named alike are kept (test_result_files.py)."""
    from tribodyn.output.work_folder import prove_origin

    dead = dead_pid()
    stale = tmp_path / f".res.tmp-{dead}-abc12345"  # killed run (process gone)
    stale.mkdir()
    prove_origin(stale)
    (stale / "results.nc").write_text("x")
    alive = tmp_path / f".res.tmp-{os.getppid()}-0123abcd"  # a running process: kept
    alive.mkdir()
    prove_origin(alive)
    legacy = tmp_path / ".res.tmp-k3j2h1g0"  # 0.1 name, an hour old: no proof, kept
    legacy.mkdir()
    old = time.time() - 2 * 3600
    os.utime(legacy, (old, old))
    other = tmp_path / ".other.tmp-1-abc"  # another target: kept
    other.mkdir()
    write_atomic(tmp_path / "res", lambda d: (d / "new").write_text("1"))
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == sorted(["res", alive.name, legacy.name, other.name])


def test_previous_results_are_restored_after_a_kill_between_renames(tmp_path):
    old = tmp_path / f".res.old-{dead_pid()}"
    old.mkdir()
    (old / W.MARKER).write_text("{}")
    (old / "summary.json").write_text("previous")
    restored = clean_stale(tmp_path / "res")
    assert restored == [old]
    assert (tmp_path / "res" / "summary.json").read_text() == "previous"


# ----------------------------------------------------------------------------- rescue
@pytest.fixture
def fake_study(monkeypatch):
    """A stand-in for a computed study: write_results needs its Dataset, summary and case."""
    ds = xr.Dataset({"central_film": ("crank", [1e-7, 2e-7])}, coords={"crank": [0.0, 1.0]})
    monkeypatch.setattr(W, "study_to_dataset", lambda study: ds)
    case = load_case()
    return SimpleNamespace(case=case, analyse=lambda: SimpleNamespace(summary={"a": 1}))


def test_results_are_rescued_when_writing_fails(tmp_path, monkeypatch, fake_study):
    target = tmp_path / "res"
    original = W.write_netcdf  # what writes results.nc

    def disk_full(ds, path, *a, **k):
        if ".res.tmp-" in str(path):
            raise OSError(errno.ENOSPC, "No space left on device")
        return original(ds, path, *a, **k)

    monkeypatch.setattr(W, "write_netcdf", disk_full)
    monkeypatch.setattr(W.tempfile, "gettempdir", lambda: str(tmp_path / "rescue-area"))
    with pytest.raises(OutputWriteError) as info:
        write_results(fake_study, target, figures=False, report=False)
    err = info.value
    assert "no space left on the device" in str(err) and str(err.rescued) in str(err)
    assert err.rescued.parent == tmp_path / "rescue-area"
    with xr.open_dataset(err.rescued / "results.nc", engine="h5netcdf") as ds:
        assert ds["central_film"].values.tolist() == [1e-7, 2e-7]
    assert json.loads((err.rescued / "summary.json").read_text()) == {"a": 1}
    assert (err.rescued / "case.toml").is_file()
    assert not target.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".res")]


def test_a_target_taken_meanwhile_is_rescued_too(tmp_path, monkeypatch, fake_study):
    target = tmp_path / "res"
    target.write_text("someone else's file")  # appeared after the check
    monkeypatch.setattr(W.tempfile, "gettempdir", lambda: str(tmp_path / "rescue-area"))
    with pytest.raises(OutputWriteError, match="existing file") as info:
        write_results(fake_study, target, figures=False, report=False)
    assert (info.value.rescued / "results.nc").is_file()
    assert target.read_text() == "someone else's file"


# ----------------------------------------------------------------------------- SIGTERM
# ``tribodyn run`` that prints the phase it reaches to stderr: the dynamics begun (the
# study's progress event), the EHL, drawing or results.nc-writing processes running (the
# first submission to the study's, the drawing or the writing pool returned: their
# processes are started, so the signal does not meet a fork).
MARKED_RUN = """\
import sys
from concurrent.futures import ProcessPoolExecutor
import tribodyn.output.figures as figures
import tribodyn.output.writer as writer
import tribodyn.workflow.cycle as cycle
from tribodyn.cli import app

study, draw, submit = cycle.run_cycle_study, figures.make_figures, ProcessPoolExecutor.submit
to_dataset = writer.study_to_dataset
phase = ["ehl"]

def marked_study(case, progress=None, **kw):
    def mark(event, **info):
        progress(event, **info)
        if event == "dynamics":
            print("phase dynamics", file=sys.stderr, flush=True)
    return study(case, progress=mark, **kw)

def marked_draw(*args, **kw):
    phase[0] = "writing"
    return draw(*args, **kw)

def marked_dataset(*args, **kw):
    phase[0] = "writing"
    return to_dataset(*args, **kw)

def marked_submit(pool, *args, **kw):
    future = submit(pool, *args, **kw)
    if not getattr(pool, "marked", False):
        pool.marked = True
        print("phase", phase[0], file=sys.stderr, flush=True)
    return future

cycle.run_cycle_study, figures.make_figures = marked_study, marked_draw
writer.study_to_dataset = marked_dataset
ProcessPoolExecutor.submit = marked_submit
app(prog_name="tribodyn", args=sys.argv[1:])
"""


@pytest.mark.parametrize(
    "phase, draw", [("dynamics", True), ("ehl", True), ("writing", True), ("writing", False)]
)
def test_sigterm_stops_a_run_cleanly(tmp_path, phase, draw):
    """SIGTERM during the computation or while the results are written: workers (EHL,
    drawing or results.nc-writing processes) stopped, nothing written, no temporary
    folder, exit code 143, a message instead of a traceback. The signal is sent when the
    run reports the phase (the dynamics begun, the EHL, drawing or results.nc-writing
    processes running), so the test does not depend on the machine's speed; two sets of
    the paper case at coarse resolution keep it short."""
    case = tmp_path / "c.toml"
    base = load_case()
    small = {
        "surface_sets": base.to_dict()["surface_sets"][:2],
        "numerics.crank_step_deg": 5.0,
        "numerics.n": 128,
        "numerics.implicit_coupling": False,
        "numerics.workers": 2,
    }
    base.updated({**REDUCED, **small}).write_toml(case)
    out = tmp_path / "out"
    rescue_area = tmp_path / "tmp"  # a rescue folder, if any, stays inside the test's folder
    rescue_area.mkdir()
    (rescue_area / "marked_run.py").write_text(MARKED_RUN)
    proc = subprocess.Popen(
        [sys.executable, "-m", "marked_run", "run", str(case), "-o", str(out), "-q"]
        + (["--figures"] if draw else []),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "TMPDIR": str(rescue_area)},
        cwd=rescue_area,  # the rescue's fallbacks (temporary folder, then the working one)
    )
    seen = []
    for line in proc.stderr:  # the phases, in order, until the one to stop in
        seen.append(line.strip())
        if line.strip() == f"phase {phase}":
            break
    assert f"phase {phase}" in seen, seen
    assert proc.poll() is None, "the run ended before the signal"
    proc.send_signal(signal.SIGTERM)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 143, stdout + stderr
    assert "interrupted" in stdout and "Traceback" not in stdout + stderr
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".out")]


class _RaisesWhenCollected:
    def __del__(self):
        raise KeyboardInterrupt


@pytest.mark.filterwarnings("error::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("where", ["study", "writing"])
def test_a_signal_lost_in_a_callback_still_ends_as_interrupted(tmp_path, monkeypatch, capfd, where):
    """SIGTERM whose KeyboardInterrupt is raised inside a callback (a weakref's) is lost
    there; the stopped workers then fail the study or the drawing. That failure is the
    signal's, so the run ends as interrupted (143) with the rescue folder named, and the
    lost interrupt prints no traceback."""
    import tribodyn.cli.run as R
    from tribodyn.output import OutputWriteError
    from tribodyn.workflow.cycle import StudyError

    monkeypatch.setattr(R, "_terminated", False)  # restored afterwards
    rescued = tmp_path / "rescue"

    def signal_then_fail(*args, **kwargs):
        R._terminated = True  # what the handler sets before its interrupt is lost
        lost = _RaisesWhenCollected()  # an interrupt raised where Python cannot pass it on
        del lost
        if where == "study":
            raise StudyError("BrokenProcessPool: a process was terminated abruptly")
        raise OutputWriteError(
            "cannot write: BrokenProcessPool", tmp_path / "out", rescued, OSError()
        )

    if where == "study":
        monkeypatch.setattr("tribodyn.workflow.cycle.run_cycle_study", signal_then_fail)
    else:
        monkeypatch.setattr("tribodyn.output.write_results", signal_then_fail)
        monkeypatch.setattr(
            "tribodyn.workflow.cycle.run_cycle_study", lambda c, **kw: SimpleNamespace(case=c)
        )
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["run", "-o", str(out), "-q"])
    assert r.exit_code == 143, r.output
    assert "interrupted" in r.output and "ignored" not in r.output + capfd.readouterr().err
    assert (str(rescued) in r.output.replace("\n", "")) == (where == "writing")
    assert not out.exists()


@pytest.mark.filterwarnings("error::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("event_after_signal", [True, False])
def test_a_signal_lost_while_forking_stops_the_run_before_writing(
    tmp_path, monkeypatch, event_after_signal
):
    """SIGTERM during a fork: the handler cannot stop the worker being forked, and its
    interrupt is lost in the after-fork hook, so the study goes on and would complete.
    The run stops at its next progress event, or when the study returns: nothing is
    written, and it ends as interrupted (143)."""
    import tribodyn.cli.run as R

    monkeypatch.setattr(R, "_terminated", False)  # restored afterwards
    wrote, went_on = [], []
    monkeypatch.setattr("tribodyn.output.write_results", lambda *a, **k: wrote.append(1))

    def signal_lost_then_complete(c, progress=None, **kwargs):
        progress("dynamics")
        R._terminated = True  # what the handler sets before its interrupt is lost
        lost = _RaisesWhenCollected()
        del lost
        if event_after_signal:
            progress("set", name="x", done=0, total=1)
            went_on.append(1)  # the run went on after the signal's next event
        return SimpleNamespace(case=c)

    monkeypatch.setattr("tribodyn.workflow.cycle.run_cycle_study", signal_lost_then_complete)
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["run", "-o", str(out), "-q"])
    assert r.exit_code == 143, r.output
    assert "interrupted" in r.output and not wrote and not went_on
    assert not out.exists()


@pytest.mark.parametrize("terminated", [False, True])
def test_an_interrupt_through_exec_keeps_the_exit_code(tmp_path, terminated):
    """``python -m``: an interrupt that passed through ``exec`` of source text (as in a
    dataclass's creation) left CPython's unhandled-interrupt flag set, and the process
    ended as killed by SIGINT (-2) instead of with 130 or 143."""
    (tmp_path / "interrupted_run.py").write_text(
        "import sys\n"
        "import tribodyn.cli.run as R\n"
        "from tribodyn.cli import app\n"
        "def _run(*args, **kwargs):\n"
        f"    R._terminated = {terminated}\n"
        "    exec('raise KeyboardInterrupt')\n"
        "R._run = _run\n"
        "app(prog_name='tribodyn', args=['run', '-o', sys.argv[1], '-q'])\n"
    )
    proc = subprocess.run(
        [sys.executable, "-m", "interrupted_run", str(tmp_path / "out")],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == (143 if terminated else 130), proc.stdout + proc.stderr
    assert "interrupted" in proc.stdout and "Traceback" not in proc.stdout + proc.stderr


def test_the_interrupted_message_shows_the_folder_as_given(tmp_path, monkeypatch):
    """Ctrl-C during a run: the message prints the output folder literally (a bracket
    in its name is not taken for rich markup)."""
    import tribodyn.cli.run as R

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(R, "_run", interrupt)
    out = tmp_path / "res[bold]"
    r = CliRunner().invoke(app, ["run", "-o", str(out), "-q"])
    assert r.exit_code == 130, r.output
    assert "interrupted" in r.output and "res[bold]" in r.output.replace("\n", "")
    assert not out.exists()


HALF_OPEN = """
import os, signal, sys
from tribodyn.cli import run

class HalfOpen:  # a finaliser that fails on an object the interrupt cut short
    def __del__(self):
        raise AttributeError("'File' object has no attribute '_closed'")

kept = []
try:
    with run._terminate_as_interrupt():
        kept.append(HalfOpen())
        os.kill(os.getpid(), signal.SIGTERM)
        signal.pause()
except KeyboardInterrupt:
    print("interrupted")
sys.exit(143)
"""


def test_sigterm_leaves_no_traceback_of_a_half_built_object(tmp_path):
    """A SIGTERM that cuts an object's construction short (e.g. the results.nc file
    being opened) makes its finaliser fail later, when the process ends; the run still
    ends with the one message, no traceback."""
    script = tmp_path / "half_open.py"
    script.write_text(HALF_OPEN)
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 143 and r.stdout == "interrupted\n", r.stdout + r.stderr
    assert "Traceback" not in r.stderr and "Exception ignored" not in r.stderr, r.stderr
