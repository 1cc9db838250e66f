"""`pip install` of the wheel, then `rolling serve`, serves the whole explorer (issue 9).

The wheel is built from a copy of the checkout (setuptools without build isolation: no
network), installed into a fresh venv in a temporary directory outside the checkout, and
started from another temporary directory. Its dependencies are taken from the project's
environment through a plain path entry (a `.pth` line, which does not run that
environment's own `.pth` hooks, so the project's editable install cannot leak in); the test
checks that `app`, `solvers` and `catalogue` are imported from the new venv.

Then it fetches every page, every script, stylesheet and font they reference (following
ES module imports and CSS url()), the work-precision results and /api/health.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import sysconfig
import time
from pathlib import Path
from urllib.parse import urljoin

import httpx
import pytest

from app.testing import free_port

ROOT = Path(__file__).resolve().parents[1]
PAGES = ["/", "/case/plane/chaplygin-ball", "/poincare", "/scenes", "/work-precision", "/docs"]
_SKIP = {".git", ".venv", "build", "dist", "node_modules", "__pycache__", ".pytest_cache",
         ".ruff_cache", "tests", "bench"}

pytestmark = pytest.mark.slow


def _copy_source(dst: Path) -> Path:
    src = dst / "src"
    shutil.copytree(ROOT, src, ignore=lambda d, names: [
        n for n in names if n in _SKIP or n.endswith(".egg-info")
        or n.endswith((".nbi", ".nbc", ".pyc"))])
    return src


# the checkout must not be importable in the subprocesses (PYTHONPATH of the test run)
_ENV = {k: v for k, v in os.environ.items() if not k.startswith(("ROLLING_", "PYTHON"))}


def _run(cmd: list[str], **kw) -> subprocess.CompletedProcess:
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=_ENV, **kw)
    assert out.returncode == 0, f"{cmd}:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return out


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """The venv with the wheel installed (its bin/ holds `rolling`)."""
    tmp = tmp_path_factory.mktemp("wheel")
    src = _copy_source(tmp)
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
          "-w", str(tmp / "dist"), str(src)], cwd=tmp)
    wheel = next((tmp / "dist").glob("rolling_hierarchy-*.whl"))
    venv = tmp / "venv"
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)])
    _run([sys.executable, "-m", "pip", "--python", str(venv / "bin" / "python"), "install",
          "--no-deps", "--no-index", "--ignore-installed", "-q", str(wheel)], cwd=tmp)
    site = next((venv / "lib").glob("python3*/site-packages"))
    # the dependencies (numpy, fastapi, ...) from the project's environment, after the
    # venv's own site-packages: a path line only, so no editable-install hook runs
    (site / "zz_project_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    return venv


def test_the_installed_package_is_the_one_imported(installed, tmp_path):
    code = ("import app, solvers, catalogue, json; print(json.dumps("
            "[app.__file__, solvers.__file__, catalogue.__file__]))")
    out = _run([str(installed / "bin" / "python"), "-c", code], cwd=tmp_path)
    for f in json.loads(out.stdout):
        assert Path(f).resolve().is_relative_to(installed.resolve()), f


def _refs(base: str, text: str, kind: str) -> set[str]:
    if kind == "html":
        found = re.findall(r'(?:src|href)="([^"#]+)"', text)
        found += re.findall(r'from\s+"([^"]+)"', text)   # inline module scripts
    elif kind == "js":
        found = re.findall(r'(?:from|import)\s*\(?\s*"(\.{1,2}/[^"]+)"', text)
    else:   # css; KaTeX lists woff2 first, then woff and ttf fallbacks that every browser
        # able to run the pages skips (only the woff2 files are vendored)
        found = [u for u in re.findall(r'url\(["\']?([^)"\']+)["\']?\)', text)
                 if not u.endswith((".woff", ".ttf"))]
    return {urljoin(base, f) for f in found
            if not f.startswith(("data:", "http:", "https:", "mailto:"))}


def test_rolling_serve_from_the_wheel_serves_the_explorer(installed, tmp_path):
    port = free_port()
    env = dict(_ENV)
    # no background verification and no worker warm-up: the pages and their assets are
    # what is checked here, on a machine the other tests share
    env.update(ROLLING_VERIFY_ON_START="0", ROLLING_WARM_WORKERS="0",
               ROLLING_CACHE_DIR=str(tmp_path / "cache"), ROLLING_LOG_LEVEL="warning")
    proc = subprocess.Popen([str(installed / "bin" / "rolling"), "serve", "--port", str(port)],
                            cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    base = f"http://127.0.0.1:{port}"
    try:
        with httpx.Client(base_url=base, timeout=30.0) as client:
            deadline = time.monotonic() + 120
            while True:
                assert proc.poll() is None, proc.stdout.read()[-3000:]
                try:
                    if client.get("/api/health").status_code == 200:
                        break
                except httpx.HTTPError:
                    pass
                assert time.monotonic() < deadline, "rolling serve did not answer in 120 s"
                time.sleep(0.3)
            health = client.get("/api/health").json()
            assert health["status"] == "ok"
            todo = [(base + p, "html") for p in PAGES]
            seen: set[str] = set()
            while todo:
                url, kind = todo.pop()
                if url in seen or not url.startswith(base):
                    continue
                seen.add(url)
                r = client.get(url)
                assert r.status_code == 200, f"{url}: {r.status_code} {r.text[:200]}"
                path = url.split("?")[0]
                if kind == "html" or path.endswith((".js", ".css")):
                    k = kind if kind == "html" else ("js" if path.endswith(".js") else "css")
                    for ref in _refs(url, r.text, k):
                        nxt = ("js" if ref.split("?")[0].endswith(".js") else
                               "css" if ref.split("?")[0].endswith(".css") else "other")
                        todo.append((ref, nxt))
            assert any(u.endswith("katex.min.js") for u in seen)
            assert any(u.endswith(".woff2") for u in seen)
            assert any(u.endswith("plotly.min.js") for u in seen)
            assert any(u.endswith("swagger-ui-bundle.js") for u in seen)
            wp = client.get("/api/work-precision")
            assert wp.status_code == 200 and wp.json()["runs"]
            figs = client.get("/static/data/paper_figures.json")
            assert figs.status_code == 200 and figs.json()
    finally:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
