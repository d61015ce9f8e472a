# Sphinx configuration of rotgen's documentation site (issue 47).
#
# Built by `cmake --build build --target docs` (docs/CMakeLists.txt), which runs Doxygen over the
# runtime headers and one emitted header, then
#   sphinx-build -W --keep-going -n -b html docs build/docs/html
# with ROTGEN_DOXYGEN_XML (Doxygen's XML folder, for breathe) and ROTGEN_PYTHON_PATH (where the
# built `rotgen` package is, for autodoc) in the environment. Every warning fails the build.
import os
import sys

project = "rotgen"
author = "the rotgen authors"
copyright = "the rotgen authors"
version = release = os.environ.get("ROTGEN_VERSION", "")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "_ext"))
extensions = [
    "rotgen_cpp",  # docs/_ext: the directive rotgen-header, one header's C++ reference
    "myst_parser",
    "breathe",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
]

# The pages are Markdown (MyST), readable as they are on a forge; index.md holds the table of
# contents. The README is the repository's front page, not a page of the site.
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "Doxyfile.in", "CMakeLists.txt"]
myst_heading_anchors = 3  # [text](page.md#a-heading) links, as a forge renders them
myst_enable_extensions = ["dollarmath"]
suppress_warnings = []

# Python: the module as built (PYTHONPATH=build/python), imported by autodoc.
sys.path.insert(0, os.environ.get("ROTGEN_PYTHON_PATH",
                                  os.path.join(os.path.dirname(__file__), "..", "build", "python")))
autodoc_member_order = "bysource"
autodoc_typehints = "none"
napoleon_google_docstring = True
napoleon_numpy_docstring = True
# "str or os.PathLike, optional", "{'json', 'text'}", "ndarray, shape (n,)": types, not prose
napoleon_preprocess_types = True
napoleon_type_aliases = {"ndarray": "numpy.ndarray", "DataFrame": "pandas.DataFrame",
                         "array": "numpy.ndarray", "PathLike": "os.PathLike"}

# C++: breathe over Doxygen's XML.
breathe_projects = {"rotgen": os.environ.get("ROTGEN_DOXYGEN_XML",
                                             os.path.join(os.path.dirname(__file__), "..", "build",
                                                          "docs", "doxygen", "xml"))}
breathe_default_project = "rotgen"
breathe_domain_by_extension = {"hpp": "cpp"}
cpp_index_common_prefix = ["rotgen::"]

# Every cross-reference must resolve, but for names in other projects' namespaces (no intersphinx:
# the build reads nothing from the network) and rotgen's own `detail` namespaces, which the
# Doxyfile leaves out of the reference on purpose (EXCLUDE_SYMBOLS) though signatures name them.
nitpicky = True
nitpick_ignore_regex = [
    (r"cpp:.*", r"(std|Eigen|xsimd|boost)(::.*)?"),
    (r"cpp:.*", r"(rotgen::)?(.*::)?detail(::.*)?"),
    (r"py:.*", r"(numpy|pandas|os)(\..*)?"),
]

html_theme = "alabaster"
html_title = "rotgen"
# A page wide enough for the 100-column transcripts, headers and tables (the theme's default, 940
# px, hides their ends behind a scroll bar and shrinks the pipeline picture past reading).
html_theme_options = {"description": "rigid-body rotational dynamics, derived and generated",
                      "fixed_sidebar": True, "page_width": "1240px", "sidebar_width": "230px"}
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}
html_static_path = ["_ext/static"]  # rotgen.css: spacing of API entries, code font size
html_css_files = ["rotgen.css"]
html_show_sourcelink = False
html_copy_source = False
