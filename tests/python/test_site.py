"""The documentation site (``docs/``, ``pip install ".[docs]"``): it builds with warnings as errors (broken
references, docstrings that do not parse, a gallery script that fails), every internal link and image of
its pages resolves, the pages open in a real headless browser (Chromium from the distribution's packages)
and render, and every gallery script runs on its own."""

from __future__ import annotations

import os
import runpy
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
GALLERY = sorted((DOCS / "gallery").glob("plot_*.py"))
# In CI the docs extra and Chromium are installed by the test command: nothing here may be skipped there.
REQUIRED = bool(os.environ.get("CI"))


def _require(module: str) -> None:
    if REQUIRED:
        __import__(module)
    else:
        pytest.importorskip(module)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site, built once into a temporary folder with warnings as errors."""
    for module in ("sphinx", "myst_parser", "sphinx_gallery", "furo"):
        _require(module)
    out = tmp_path_factory.mktemp("site")
    env = {**os.environ, "MPLBACKEND": "Agg"}
    r = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS),
                        str(out), "-d", str(tmp_path_factory.mktemp("doctrees"))],
                       capture_output=True, text=True, env=env, timeout=900)
    assert r.returncode == 0, r.stderr[-4000:]
    return out


def test_rust_examples_show_what_rustdoc_shows(site: Path) -> None:
    """The Rust guide's example is the crate's doctest: the line that doctest hides (its ``Ok``) is not shown."""
    import html
    import re

    text = html.unescape(re.sub(r"<[^>]+>", "", (site / "guide" / "rust.html").read_text(encoding="utf-8")))
    assert "let problem = Problem::new(mesh, spec)?;" in text
    assert "Ok::<(), tribo::Error>(())" not in text and "Ok::<(), tribo::Error>(())" in (DOCS / "guide" / "rust.md").read_text(
        encoding="utf-8")


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(str(a["id"]))
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script", "source"):
                self.links.append(str(a[key]))


def _parse(path: Path) -> _Links:
    p = _Links()
    p.feed(path.read_text(encoding="utf-8"))
    return p


def test_the_site_has_every_part(site: Path) -> None:
    for page in ("index", "getting-started", "guide/index", "guide/scene-files", "guide/solver", "method", "api",
                 "cli", "measured", "STUDIES", "adaptive", "two_bodies", "auto_gallery/index"):
        assert (site / f"{page}.html").is_file(), page
    assert len(list((site / "auto_gallery").glob("plot_*.html"))) == len(GALLERY)
    # The generated references: every scene table, every command, every public name.
    keys = (site / "guide" / "scene-files.html").read_text(encoding="utf-8")
    assert all(f"[{t}]" in keys for t in ("body", "obstacle", "history", "adapt", "solver")) and "[[bodies]]" in keys
    cli = (site / "cli.html").read_text(encoding="utf-8")
    assert all(f"tribo {c}" in cli for c in ("run", "sweep", "demo"))
    api = (site / "api.html").read_text(encoding="utf-8")
    import tribo

    # Issue 38: each public name has its own anchor (they were documented under :no-index:, unreachable).
    ids = _parse(site / "api.html").ids
    missing = [n for n in tribo.__all__ if n != "__version__" and f"tribo.{n}" not in ids]
    assert not missing, missing
    assert "tribo.tribo.STATE_NAMES" not in ids and "tribo.Solution.lambda_n" in ids
    # The guide links to them (the links themselves are checked below).
    guide = _parse(site / "guide" / "python.html").links
    assert {"../api.html#tribo.Problem.solve", "../api.html#tribo.Solution"} <= set(guide)


def test_every_internal_link_and_image_resolves(site: Path) -> None:
    pages = [p for p in site.rglob("*.html") if "rust" not in p.relative_to(site).parts[:1]
             and "_modules" not in p.parts]
    assert len(pages) > 30
    broken = []
    ids: dict[Path, set[str]] = {}  # each target parsed once (api.html is the target of hundreds of links)
    for page in pages:
        for link in _parse(page).links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "javascript:", "data:")):
                continue
            target = page if not parts.path else (page.parent / unquote(parts.path)).resolve()
            if not target.exists():
                broken.append(f"{page.relative_to(site)} -> {link}")
            elif parts.fragment and target.suffix == ".html" and "rust" not in target.relative_to(site).parts[:1]:
                if target not in ids:
                    ids[target] = _parse(target).ids
                if unquote(parts.fragment) not in ids[target]:
                    broken.append(f"{page.relative_to(site)} -> {link} (no such anchor)")
    assert not broken, broken[:20]


def _chromium() -> str:
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        if REQUIRED:
            pytest.fail("Chromium is not installed (the test command installs Debian's chromium)")
        pytest.skip("no Chromium")
    return exe


@pytest.mark.parametrize("page", ["index.html", "auto_gallery/plot_hertz.html"])
def test_the_pages_render_in_a_headless_browser(site: Path, page: str, tmp_path: Path) -> None:
    """Chromium loads the page from disk, runs its scripts and draws it: the screenshot is a page of text
    and figures (many colours, not blank), and the rendered DOM holds its title and its images."""
    exe = _chromium()
    shot = tmp_path / "page.png"
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--window-size=1280,1600"]
    url = (site / page).as_uri()
    r = subprocess.run([exe, *flags, f"--screenshot={shot}", url], capture_output=True, text=True, timeout=120)
    assert shot.is_file() and shot.stat().st_size > 10_000, r.stderr[-2000:]
    import matplotlib.image

    pixels = matplotlib.image.imread(shot)[..., :3]
    colours = np.unique((pixels * 255).astype(np.uint8).reshape(-1, 3), axis=0)
    assert len(colours) > 100 and pixels.std() > 0.05, (len(colours), pixels.std())
    dom = subprocess.run([exe, *flags, "--dump-dom", url], capture_output=True, text=True, timeout=120).stdout
    assert "tribo" in dom and "<img" in dom
    if os.environ.get("TRIBO_KEEP_SCREENSHOTS"):
        shutil.copy(shot, Path(os.environ["TRIBO_KEEP_SCREENSHOTS"]) / page.replace("/", "_").replace(".html", ".png"))


@pytest.mark.parametrize("script", GALLERY, ids=[s.stem for s in GALLERY])
def test_each_gallery_script_runs(script: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(script), run_name="__main__")
    import matplotlib.pyplot as plt

    assert plt.get_fignums(), "a gallery script draws its figure"
    plt.close("all")
