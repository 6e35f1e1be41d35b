"""The ``tribodyn view`` page in a real browser (headless Chromium): every figure is
drawn, no script error is logged, and a screenshot is saved. Skipped where no Chromium
is installed (CI installs Debian's chromium-headless-shell)."""

import os
import re
import shutil
import subprocess
import time

import pytest

from tribodyn.output.explorer import build_page, write_page

BROWSERS = ("chromium-headless-shell", "chromium", "chromium-browser", "google-chrome")


def _browser():
    return next((p for p in map(shutil.which, BROWSERS) if p), None)


def _chromium(exe, *args, timeout=120):
    cmd = [exe, "--headless", "--disable-gpu", "--hide-scrollbars", "--no-first-run"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        cmd.append("--no-sandbox")  # Chromium refuses root without it (CI containers)
    return subprocess.run(
        cmd + list(args), capture_output=True, text=True, timeout=timeout, check=False
    )


@pytest.mark.skipif(_browser() is None, reason="no Chromium binary (chromium-headless-shell)")
def test_page_draws_every_figure_in_chromium(reduced_results, engine_results, tmp_path):
    exe = _browser()
    page, n = build_page(
        [reduced_results, reduced_results, engine_results], ["run A", "run B", "engine"]
    )
    path = write_page(page, tmp_path / "view.html")
    url = path.resolve().as_uri()
    t0 = time.perf_counter()
    r = _chromium(
        exe,
        "--enable-logging=stderr",
        "--v=0",
        "--virtual-time-budget=30000",
        "--dump-dom",
        url,
    )
    took = time.perf_counter() - t0
    assert r.returncode == 0, r.stderr[-2000:]
    body = re.findall(r"<body[^>]*>", r.stdout)  # the last: the library's text holds one
    assert body
    attrs = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', body[-1]))
    assert "error" not in attrs, attrs
    assert attrs.get("rendered") == str(n), (attrs, n)
    assert int(attrs["draw-ms"]) >= 0
    assert f"{n} figures drawn in" in r.stdout
    # the figures' targets hold their drawn roots
    assert r.stdout.count('class="fig"') == n
    errors = [
        ln
        for ln in r.stderr.splitlines()
        if "CONSOLE" in ln and re.search(r"Uncaught|error|Error", ln)
    ]
    assert not errors, errors
    shot = tmp_path / "view.png"
    _chromium(
        exe, "--virtual-time-budget=30000", "--window-size=1400,3000", f"--screenshot={shot}", url
    )
    assert shot.stat().st_size > 50_000  # drawn, not a blank page
    print(
        f"page {path.stat().st_size / 1e6:.2f} MB, {n} figures, browser {took:.1f} s, "
        f"draw {attrs['draw-ms']} ms; screenshot {shot}"
    )


def test_the_error_check_sees_a_script_error(tmp_path):
    """The checks above can fail: a page whose script throws is reported."""
    exe = _browser()
    if exe is None:
        pytest.skip("no Chromium binary (chromium-headless-shell)")
    p = tmp_path / "bad.html"
    p.write_text("<html><body><script>nosuchfunction()</script></body></html>", encoding="utf-8")
    r = _chromium(exe, "--enable-logging=stderr", "--v=0", "--dump-dom", p.resolve().as_uri())
    assert any("Uncaught" in ln for ln in r.stderr.splitlines() if "CONSOLE" in ln)
