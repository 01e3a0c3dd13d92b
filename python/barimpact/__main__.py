"""python3 -m barimpact plot DIR [DIR ...] [--out FIGURES] [--force] (what `barimpact plot` runs).

DIR is a run directory (history.csv or results.h5: the run's figures) or a sweep
directory (sweep.csv: each output against the swept keys, and the runs'
U(t) and R(t) overlaid); several run directories draw one comparison. The
figures go by the output rule of `barimpact run --out` (--force as its). A
hopkinson, pda or match directory (written with --no-plot) gets its figures
drawn where the command draws them (hopkinson's into DIR/figures, pda's and
match's into DIR)."""
import argparse
import importlib
import sys
from pathlib import Path

from . import _core
from .plot import REDRAWN, compare, is_run_directory, plot, redraw

# The commands whose figures go into the staging directory of their results
# (COMMAND-plot STAGING --as OUT): each module's plot_COMMAND_into draws them.
STAGED = ("hopkinson", "pda", "match")



def _plot(dirs, out, force):
    """The figures of one run or sweep directory, or the comparison of several runs."""
    if len(dirs) > 1:
        if out is None:
            raise ValueError("several directories: give --out for their comparison")
        return compare(dirs, out, force=force)
    d = Path(dirs[0])
    if is_run_directory(d):
        return plot(d, out, force=force)
    if (d / "sweep.csv").is_file():
        from .convergence import plot_sweep
        return plot_sweep(d, out, force=force)
    written = redraw(d, out)  # a study's or analysis's figures, where the command draws them
    if written is None:
        raise ValueError(f"{d}: no history.csv, results.h5, sweep.csv or a study's table ({', '.join(REDRAWN)}): "
                         "not a directory written by barimpact")
    return written


def _run(args):
    """The subcommand's work: the paths it wrote, to print."""
    if args.command == "bearing-plot":
        from .bearing import plot_bearing
        return plot_bearing(args.dir)
    if args.command == "drive-plot":
        from .drive import plot_drive
        return plot_drive(args.dir)
    if args.command == "inspector-plot":
        from .drive import plot_inspector
        return plot_inspector(args.dir)
    command = args.command.removesuffix("-plot")
    if command in STAGED:
        module = importlib.import_module(f".{command}", __package__)
        getattr(module, f"plot_{command}_into")(args.dir, args.shown or args.dir)
        return []  # into the staging directory: its paths would mislead
    if args.command == "converge-plot":
        from .convergence import plot_study
        return plot_study(args.dir)
    return _plot(args.dir, args.out, args.force)


def _message(e):
    """One line: a file's error as PATH: REASON (a full disk names the figure)."""
    if isinstance(e, OSError) and e.filename is not None and e.strerror:
        return f"{e.filename}: {e.strerror}"
    return str(e)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="barimpact")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="draw the figures of a run or sweep directory, or compare runs")
    p.add_argument("dir", nargs="+")
    p.add_argument("--out", default=None, help="where the figures go (default: DIR/figures)")
    p.add_argument("--force", action="store_true", help="write the figures beside other files (as run's --force)")
    c = sub.add_parser("converge-plot", help="draw the plots of a barimpact converge directory")
    c.add_argument("dir")
    b = sub.add_parser("bearing-plot", help="draw bearing.png of a barimpact bearing directory")
    b.add_argument("dir")
    v = sub.add_parser("drive-plot", help="draw drive.png of a barimpact drive directory")
    v.add_argument("dir")
    i = sub.add_parser("inspector-plot", help="draw inspector.png of a barimpact inspector directory")
    i.add_argument("dir")
    for command in STAGED:
        s = sub.add_parser(f"{command}-plot", help=f"draw the figures of a barimpact {command} directory")
        s.add_argument("dir")
        s.add_argument("--as", dest="shown", default=None,
                       help="the directory the figures are moved to (DIR is its staging), which errors name")
    args = parser.parse_args(argv)
    try:
        written = _run(args)
    except (OSError, ValueError, ImportError) as e:  # ImportError: results.h5 without h5py
        # The command the user gave: plot, converge, bearing, drive, inspector, hopkinson, pda, match.
        # Exit 2, as the command's own refusals.
        print(f"barimpact: error: {args.command.removesuffix('-plot')}: {_message(e)}", file=sys.stderr)
        return 2
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
