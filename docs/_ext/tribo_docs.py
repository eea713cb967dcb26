"""Sphinx directives and roles of tribo's documentation site, generated from the code so that the pages
cannot drift from it:

* ``cli-help``: the help of ``tribo`` and of each of its commands (``tribo.cli.build_parser``);
* ``solver-settings``: every solver setting with its kind and default (the core's table);
* the role ``rust``: a link into the crate documentation that ``cargo doc -p tribo --no-deps`` builds and
  that is copied into ``rust/`` of the site once it is written (``{rust}`label <tribo/index.html>```);
* Rust examples shown as rustdoc shows them: the lines a doctest hides (``# Ok::<(), tribo::Error>(())``, which
  the crate compiles the guide's example with) are left out of the page.
"""

from __future__ import annotations

import re
from typing import Any

from docutils import nodes
from docutils.parsers.rst import Directive
from sphinx.application import Sphinx


def _table(header: list[str], rows: list[list[str]]) -> nodes.table:
    table = nodes.table()
    group = nodes.tgroup(cols=len(header))
    table += group
    for _ in header:
        group += nodes.colspec(colwidth=1)
    head = nodes.thead()
    group += head
    body = nodes.tbody()
    group += body
    for target, cells in ((head, [header]), (body, rows)):
        for cells_row in cells:
            row = nodes.row()
            for text in cells_row:
                entry = nodes.entry()
                entry += nodes.paragraph(text=text)
                row += entry
            target += row
    return table


class SolverSettings(Directive):
    """Every solver setting: name, kind, default."""

    def run(self) -> list[nodes.Node]:
        import tribo

        defaults = tribo.solver_defaults()
        rows = []
        for name, spec in tribo.solver_settings().items():
            kind = spec["kind"] + (f" ({', '.join(spec['options'])})" if "options" in spec else "")
            rows.append([name, kind, repr(defaults.get(name))])
        return [_table(["setting", "kind", "default"], rows)]


class CliHelp(Directive):
    """``tribo --help`` and the help of each command, as literal blocks."""

    def run(self) -> list[nodes.Node]:
        import argparse

        from tribo.cli import build_parser

        parser = build_parser()
        out: list[nodes.Node] = [nodes.literal_block(text=parser.format_help())]
        for action in parser._actions:  # noqa: SLF001 - argparse keeps its subparsers here
            if isinstance(action, argparse._SubParsersAction):  # noqa: SLF001
                for name, sub in action.choices.items():
                    section = nodes.section(ids=[f"tribo-{name}"])
                    section += nodes.title(text=f"tribo {name}")
                    section += nodes.literal_block(text=sub.format_help())
                    out.append(section)
        return out


def rust_role(name: str, rawtext: str, text: str, lineno: int, inliner: Any, options: Any = None,
              content: Any = None) -> tuple[list[nodes.Node], list[nodes.Node]]:
    """``{rust}`label <path>``` or ``{rust}`path```: a link to the crate documentation copied into the site."""
    label, _, target = text.partition(" <")
    target = target.rstrip(">") if target else label
    env = inliner.document.settings.env
    # Checked once the crate documentation is in place (``copy_rust_doc``): a link that breaks fails the build.
    env.tribo_rust_links = {*getattr(env, "tribo_rust_links", set()), (env.docname, target.split("#")[0])}
    # Relative to the page: the site root holds the crate documentation.
    docname = env.docname
    prefix = "../" * docname.count("/") + "rust/"
    return [nodes.reference(rawtext, label, refuri=prefix + target)], []


def purge_rust_links(app: Sphinx, env: Any, docname: str) -> None:
    """Forgets the ``rust`` links of a page read again (an incremental build)."""
    env.tribo_rust_links = {link for link in getattr(env, "tribo_rust_links", set()) if link[0] != docname}


def merge_rust_links(app: Sphinx, env: Any, docnames: Any, other: Any) -> None:
    """Keeps the ``rust`` links a parallel reader found."""
    env.tribo_rust_links = getattr(env, "tribo_rust_links", set()) | getattr(other, "tribo_rust_links", set())


def copy_rust_doc(app: Sphinx, exception: Exception | None) -> None:
    """Copies the crate documentation into ``rust/`` of an HTML build, running ``cargo doc -p tribo --no-deps``
    first when it has not been built; fails the build when it cannot be made or a ``rust`` link points at no
    page of it (the links used to break silently when ``cargo doc`` had not run before Sphinx)."""
    import shutil
    import subprocess
    from pathlib import Path

    from sphinx.errors import ExtensionError

    if exception is not None or app.builder.format != "html":
        return
    source = Path(app.config.tribo_rust_doc)
    if not (source / "tribo" / "index.html").is_file():
        root = source.parent.parent  # <repository>/target/doc
        try:
            subprocess.run(["cargo", "doc", "-p", "tribo", "--no-deps"], cwd=root, check=True, capture_output=True)
        except (OSError, subprocess.CalledProcessError) as e:
            raise ExtensionError(f"the crate documentation is not in {source} and cargo doc failed: {e}") from e
        if not (source / "tribo" / "index.html").is_file():  # CARGO_TARGET_DIR elsewhere, say
            raise ExtensionError(f"cargo doc ran, but the crate documentation is not in {source}")
    shutil.copytree(source, Path(app.outdir) / "rust", dirs_exist_ok=True)
    links = getattr(app.env, "tribo_rust_links", set())
    broken = sorted(f"{page}: {target}" for page, target in links if not (source / target).is_file())
    if broken:
        raise ExtensionError(f"rust links to no page of the crate documentation: {broken}")


RUST_BLOCK = re.compile(r"^```rust[^\n]*\n.*?^```", re.M | re.S)


def hide_rust_lines(text: str) -> str:
    """The Markdown ``text`` with the lines rustdoc hides in its ``rust`` fences left out: ``# `` followed by
    code, or a lone ``#`` (``##`` stands for a shown ``#``)."""

    def block(m: re.Match[str]) -> str:
        lines = m[0].split("\n")
        kept = [line.replace("##", "#", 1) if line.lstrip().startswith("##") else line for line in lines[1:-1]
                if not (line.lstrip() == "#" or line.lstrip().startswith("# "))]
        return "\n".join([lines[0], *kept, lines[-1]])

    return RUST_BLOCK.sub(block, text)


def source_read(app: Sphinx, docname: str, source: list[str]) -> None:
    if app.env.doc2path(docname).suffix == ".md":
        source[0] = hide_rust_lines(source[0])


def setup(app: Sphinx) -> dict[str, Any]:
    app.add_directive("solver-settings", SolverSettings)
    app.add_directive("cli-help", CliHelp)
    app.add_role("rust", rust_role)
    app.add_config_value("tribo_rust_doc", "", "html")
    app.connect("build-finished", copy_rust_doc)
    app.connect("source-read", source_read)
    app.connect("env-purge-doc", purge_rust_links)
    app.connect("env-merge-info", merge_rust_links)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
