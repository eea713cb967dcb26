"""Sphinx configuration of tribo's documentation site (``pip install ".[docs]"``, then
``python -m sphinx -W -b html docs docs/_build/html``).

The source is this folder: the user guide (``guide/``), the method, the API and command-line reference, the
gallery (``gallery/``, run by sphinx-gallery) and every study page (``*.md`` beside this file, with their
charts). The Rust crate documentation (``cargo doc -p tribo --no-deps``, which the build runs when it is
missing) is copied to ``rust/`` of the site; a ``rust`` link to no page of it fails the build.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))

import tribo  # noqa: E402

project = "tribo"
author = "the tribo developers"
release = tribo.__version__
extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "tribo_docs",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "gallery/README.rst", "auto_gallery/*.md5", "auto_gallery/*.json"]
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
# Single backticks in the docstrings are code, as in the crate's documentation.
default_role = "code"
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
html_theme = "furo"
html_title = f"tribo {release}"
html_static_path: list[str] = []
# The crate documentation (``cargo doc -p tribo --no-deps``, run by ``tribo_docs`` when it is missing), copied
# into ``rust/`` of the site once the HTML is written; the ``rust`` role links into it (a broken link fails).
tribo_rust_doc = str(ROOT / "target" / "doc")
sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_gallery",
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "download_all_examples": False,
    "remove_config_comments": True,
}
nitpicky = False
suppress_warnings: list[str] = []
napoleon_use_ivar = True
