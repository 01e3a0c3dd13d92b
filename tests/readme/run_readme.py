"""Runs every command the README shows, as written and in order, the way a
new user would after the build: from a scratch copy of the repository's
layout (its files linked in, build/release/ linked to the build, no out/),
so that a command that needs a file the README never made fails here.

    python3 tests/readme/run_readme.py README.md EXAMPLES_DIR BUILD_DIR

A command is a line of an indented code block whose first word runs
something (barimpact, python3, cmake, mkdir, cd or a subshell's cd, an
assignment before a command); `make` lines (the build itself) and sample output are not run.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

COMMAND = re.compile(r"^(\(?cd|\S*barimpact|mkdir|cmake|\S*python3|[A-Z_]+=\S+|\S+/bin/\S+)(\s|$)")


def readme_commands(text):
    """The commands of the README's indented blocks, continuation lines joined."""
    commands, in_fence = [], False
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if line.startswith("```"):
            in_fence = not in_fence
        if in_fence or not line.startswith("    ") or line.startswith("     "):
            continue
        command = line[4:]
        while command.endswith("\\") and i < len(lines):
            command = command[:-1] + " " + lines[i].strip()
            i += 1
        if COMMAND.match(command):
            commands.append(command)
    return commands


def main(readme, examples, build):
    commands = readme_commands(Path(readme).read_text())
    if not commands:
        print("no commands found in", readme)
        return 1
    source = Path(examples).resolve().parent
    with tempfile.TemporaryDirectory(prefix="barimpact-readme-") as root:
        # A clone after the build: the sources, and build/release.
        # examples/ is copied: a case's relative path (../../out/...) must
        # lead into this tree, as in a clone, not through a link into the source.
        for entry in source.iterdir():
            if entry.name == "examples":
                shutil.copytree(entry, os.path.join(root, entry.name))
            elif entry.name not in ("build", "out", ".git", "dist"):
                os.symlink(entry, os.path.join(root, entry.name))
        os.makedirs(os.path.join(root, "build"))
        os.symlink(os.path.abspath(build), os.path.join(root, "build", "release"))
        script = ["set -u"]
        for c in commands:
            quoted = shlex.quote(c)
            script.append(f"echo + {quoted}")
            # On lines of their own: a command may end in a comment.
            script.append(f"{{\n{c}\n}} > /dev/null || {{ echo \"README command failed (exit $?): \"{quoted}; exit 1; }}")
        # As on a Debian machine: python3 is Debian's.
        env = dict(os.environ, MPLBACKEND="Agg", PATH="/usr/bin:" + os.environ.get("PATH", ""))
        env.pop("PYTHONPATH", None)
        done = subprocess.run(["bash", "-c", "\n".join(script)], cwd=root, env=env)
        print(f"{len(commands)} README commands", "ran" if done.returncode == 0 else "did not all run")
        return done.returncode


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
