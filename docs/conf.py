# Sphinx configuration of the camdyn documentation site; built by scripts/docs.sh
# (sphinx-build -W --keep-going docs build/docs/html), also in the test suite (ctest docs_site).
#
# Why Sphinx (Debian: python3-sphinx, python3-myst-parser, python3-breathe, doxygen):
#   * Breathe renders the C++ API from Doxygen's XML of the `///` comments in include/camdyn,
#   * autodoc renders the Python API from the docstrings of the built package,
#   * MyST keeps every page in Markdown, so the pages read the same on GitHub and on the site.
# MkDocs (Debian: mkdocs) has neither a C++ nor a Python API generator packaged.
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BUILD = os.environ.get("CAMDYN_BUILD_DIR", os.path.join(ROOT, "build"))
# The built extension camdyn._camdyn lives in BUILD/python (autodoc imports it).
sys.path.insert(0, os.path.join(BUILD, "python"))

project = "camdyn"
author = "the camdyn project"
copyright = "the camdyn project"
release = version = os.environ.get("CAMDYN_VERSION", "0.1.0")

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.mathjax", "breathe"]
source_suffix = {".md": "markdown"}
myst_enable_extensions = ["colon_fence", "dollarmath"]
myst_heading_anchors = 3

# Data directories with Markdown that are outputs of tools, not pages.
# Generated fragments (scripts/docs.sh) are included by their pages, not pages themselves.
exclude_patterns = ["_build", "bench/tol_sweep/*/*.md", "**/README.md", "_generated", "reference/generated",
                    "bench/generated_full/**"]

breathe_projects = {"camdyn": os.environ.get("CAMDYN_DOXYGEN_XML", os.path.join(BUILD, "docs", "doxygen", "xml"))}
breathe_default_project = "camdyn"
breathe_default_members = ("members",)

autodoc_member_order = "bysource"
napoleon_use_ivar = True  # "Attributes:" as fields, not as a second description of the members
autodoc_typehints = "none"

html_theme = "alabaster"
html_title = "camdyn"
html_static_path = []
html_theme_options = {"description": "cam–follower dynamics with impact, separation and elastic deformation",
                      "page_width": "1100px", "sidebar_width": "260px"}
pygments_style = "sphinx"


def _link_to_repository_file(app, env, node, contnode):
    """Pages are Markdown that also reads on GitHub, so they may link to files of the
    repository outside the site (`[scene](../examples/ohc_bucket_tappet.toml)`,
    `[README](../README.md)`). Such a link renders as its text when the file exists; a link
    to a file or page that does not exist still fails the build (warnings are errors)."""
    target = node.get("reftarget", "")
    if node.get("reftype") != "any" or "://" in target or target.startswith("#"):
        return None
    source = env.doc2path(node.get("refdoc", env.docname))
    path = os.path.normpath(os.path.join(os.path.dirname(source), target.split("#")[0]))
    inside_site = path.startswith(os.path.abspath(app.srcdir) + os.sep)
    if os.path.isfile(path) and not (inside_site and path.endswith(".md")):
        return contnode
    return None


def setup(app):
    app.connect("missing-reference", _link_to_repository_file)
