"""The `sympathy-help` directive: a command's `--help`, run at build time from the executable
(SYMPATHY_CLI), so the reference cannot drift from what the command prints.

    ```{sympathy-help} orbit
    ```
"""
import os
import subprocess

from docutils import nodes
from docutils.parsers.rst import Directive
from sphinx.errors import ExtensionError


class SympathyHelp(Directive):
    required_arguments = 0
    optional_arguments = 1

    def run(self):
        cli = os.environ.get("SYMPATHY_CLI")
        if not cli:
            raise self.error("SYMPATHY_CLI is not set (scripts/docs sets it to the built "
                             "executable)")
        command = [cli] + ([self.arguments[0]] if self.arguments else []) + ["--help"]
        env = dict(os.environ, COLUMNS="100")
        done = subprocess.run(command, capture_output=True, text=True, env=env)
        if done.returncode != 0:
            raise self.error(f"{' '.join(command)} exited {done.returncode}: {done.stderr}")
        block = nodes.literal_block(done.stdout, done.stdout)
        block["language"] = "text"
        return [block]


def setup(app):
    if not hasattr(app, "add_directive"):
        raise ExtensionError("sympathy_help needs Sphinx")
    app.add_directive("sympathy-help", SympathyHelp)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
