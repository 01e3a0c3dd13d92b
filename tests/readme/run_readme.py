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


def readme_notes(text):
    """Per command (as readme_commands gives them), what the README says of
    it: its line's comment and the deeper-indented comment lines under it."""
    notes, lines, at = [], text.splitlines(), -1
    for command in readme_commands(text):
        flat = " ".join(command.split())
        at = next(k for k in range(at + 1, len(lines)) if lines[k].startswith("    ") and
                  flat.startswith(" ".join(lines[k].rstrip("\\").split())))
        note = command.partition("#")[2]
        while at + 1 < len(lines) and lines[at + 1].startswith("     ") and lines[at + 1].lstrip().startswith("#"):
            at += 1
            note += " " + lines[at].strip()
        notes.append(note)
    return notes


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
        errors = Path(root) / ".stderr"
        errors.mkdir()
        for k, c in enumerate(commands):
            quoted = shlex.quote(c)
            script.append(f"echo + {quoted}")
            # On lines of their own: a command may end in a comment. Its
            # stderr kept (and shown) to look for health warnings.
            err = shlex.quote(str(errors / f"{k}.txt"))
            script.append(f"{{\n{c}\n}} > /dev/null 2> {err} || {{ s=$?; cat {err} >&2; "
                          f"echo \"README command failed (exit $s): \"{quoted}; exit 1; }}")
            script.append(f"cat {err} >&2")
        # As on a Debian machine: python3 is Debian's.
        env = dict(os.environ, MPLBACKEND="Agg", PATH="/usr/bin:" + os.environ.get("PATH", ""))
        env.pop("PYTHONPATH", None)
        done = subprocess.run(["bash", "-c", "\n".join(script)], cwd=root, env=env)
        print(f"{len(commands)} README commands", "ran" if done.returncode == 0 else "did not all run")
        warned = unexpected_warnings(commands, readme_notes(Path(readme).read_text()), errors)
        for c, w in warned:
            print(f"README command warned ({w}), and its line does not say it will: {c}")
        return done.returncode or (1 if warned else 0)


def unexpected_warnings(commands, notes, errors):
    """The commands that printed a health warning ("barimpact: warning: CODE")
    without the README saying so (a comment on its line or under it naming
    the code): a README snippet runs clean, or says why not."""
    out = []
    for k, (c, note) in enumerate(zip(commands, notes)):
        path = errors / f"{k}.txt"
        text = path.read_text(errors="replace") if path.exists() else ""
        codes = sorted(set(re.findall(r"barimpact: warning: (?:\d+: )?([a-z][a-z-]*)", text)))
        unsaid = [code for code in codes if code not in note]
        if unsaid:
            out.append((c, ", ".join(unsaid)))
    return out


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
