"""Sphinx directive `rotgen-header`: one header's C++ reference, from Doxygen's XML, via breathe.

    ```{rotgen-header} runtime/integrate/integrate.hpp
    ```

expands to a label named after Doxygen's id of the file (so that the comments' links to a header,
`stepper.hpp`, resolve), breathe's `doxygenfile` for the header's own functions, types, variables
and macros, declared in the header's namespace, and one `doxygenstruct`/`doxygenclass` for each
class the header defines. (A plain `doxygenfile` renders the header's namespace as a declaration of
its own, once per header: duplicate declarations of `rotgen`, which `-W` refuses.)

When the build ends, every header Doxygen read must have been shown by one `rotgen-header`: a new
header of the runtime without its entry on the C++ page is a warning, so an error under -W.
"""
import os
import xml.etree.ElementTree as ET

from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

logger = logging.getLogger(__name__)
SECTIONS = "briefdescription detaileddescription define typedef enum func var"


def xml_dir(config):
    return config.breathe_projects[config.breathe_default_project]


def file_compounds(config):
    """{location of the file as Doxygen names it: (refid, parsed compounddef)}"""
    found = {}
    root = xml_dir(config)
    index = ET.parse(os.path.join(root, "index.xml")).getroot()
    for compound in index.findall("compound"):
        if compound.get("kind") != "file":
            continue
        refid = compound.get("refid")
        definition = ET.parse(os.path.join(root, refid + ".xml")).getroot().find("compounddef")
        found[definition.find("location").get("file")] = (refid, definition)
    return found


class RotgenHeader(SphinxDirective):
    required_arguments = 1
    has_content = False
    option_spec = {"namespace": directives.unchanged}

    def run(self):
        env = self.env
        if not hasattr(env, "rotgen_files"):
            env.rotgen_files = file_compounds(env.config)
        path = self.arguments[0]
        matches = [k for k in env.rotgen_files if k == path or k.endswith("/" + path)]
        if len(matches) != 1:
            logger.warning(f"rotgen-header: {len(matches)} headers of Doxygen's XML match {path!r}",
                           location=self.get_location())
            return []
        location = matches[0]
        refid, definition = env.rotgen_files[location]
        env.rotgen_shown = getattr(env, "rotgen_shown", set()) | {location}
        spaces = [n.text for n in definition.findall("innernamespace")
                  if "detail" not in n.text.split("::")]
        namespace = self.options.get("namespace") or max(spaces, key=len, default="")
        classes = [(c.get("refid"), c.text) for c in definition.findall("innerclass")]
        names = {name for _, name in classes}
        # MyST syntax: the page that uses the directive is Markdown, and so is its nested parse.
        lines = [f"({refid})=", ""]
        if namespace:
            lines += [f"```{{cpp:namespace-push}} {namespace}", "```", ""]
        lines += [f"```{{doxygenfile}} {location}", f":sections: {SECTIONS}", "```", ""]
        if namespace:
            lines += ["```{cpp:namespace-pop}", "```", ""]
        for cid, name in classes:
            if name.rsplit("::", 1)[0] in names:
                continue  # a nested class: shown with the class around it
            kind = "struct" if cid.startswith("struct") else "class"
            lines += [f"```{{doxygen{kind}}} {name}", ":members:", "```", ""]
        content = StringList(lines, source=self.get_source_info()[0])
        holder = nodes.container()
        nested_parse_with_titles(self.state, content, holder)
        return holder.children


def check_every_header_shown(app, env):
    if not hasattr(env, "rotgen_files"):
        env.rotgen_files = file_compounds(env.config)
    missing = sorted(set(env.rotgen_files) - getattr(env, "rotgen_shown", set()))
    for location in missing:
        logger.warning(f"the C++ reference shows no entry for {location}: add "
                       f"```{{rotgen-header}} {location}``` to docs/cpp.md")


def purge(app, env, docname):
    if docname == "cpp":
        env.rotgen_shown = set()


def setup(app):
    app.add_directive("rotgen-header", RotgenHeader)
    app.connect("env-check-consistency", check_every_header_shown)
    app.connect("env-purge-doc", purge)
    return {"version": "1", "parallel_read_safe": False, "parallel_write_safe": True}
