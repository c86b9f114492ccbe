"""Sphinx configuration of the flexbeam documentation.

Build (warnings are errors, as in CI)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Pages are MyST Markdown (``docs/*.md``); the API reference comes from the NumPy-style
docstrings (autodoc + numpydoc); the gallery runs the scripts of ``examples/``
(sphinx-gallery); the case-file reference is generated from the pydantic schema by the
local extension ``_ext/case_schema.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import flexbeam

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

project = "flexbeam"
author = "the flexbeam developers"
copyright = "2026, the flexbeam developers"
version = release = flexbeam.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "case_schema",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = [
    "_build",
    "auto_examples/*.ipynb",
    "auto_examples/*.py",
    "auto_examples/*.zip",
    "auto_examples/*.md5",
    "auto_examples/*.codeobj.json",
]
root_doc = "index"

# --- MyST: GitHub-style heading anchors, so validation.md's links to its own sections resolve
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath", "colon_fence"]

# --- API reference
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the NumPy-style docstrings carry the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

intersphinx_mapping = {}  # no network in CI: references to other projects stay plain text

# --- gallery: the examples run here (a few seconds each on the compiled kernels)
sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r".*\.py$",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "plot_gallery": "True",
}

# --- HTML
html_theme = "pydata_sphinx_theme"
html_title = f"flexbeam {release}"
html_static_path = ["_static"]
html_css_files = ["flexbeam.css"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_show_sourcelink = False
html_sidebars = {"**": []}  # the navigation bar lists the pages; no left sidebar
