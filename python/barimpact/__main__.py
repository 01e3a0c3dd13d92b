"""python3 -m barimpact plot DIR [DIR ...] [--out FIGURES] [--force] (what `barimpact plot` runs).

DIR is a run directory (history.csv or results.h5: the run's figures) or a sweep
directory (sweep.csv: each output against the swept keys, and the runs'
U(t) and R(t) overlaid); several run directories draw one comparison. The
figures go by the output rule of `barimpact run --out` (--force as its)."""
import argparse
import sys
from pathlib import Path

from .plot import compare, is_run_directory, plot


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
    raise ValueError(f"{d}: no history.csv, results.h5 or sweep.csv (not a directory written by barimpact run or "
                     "sweep)")


def _study_plot(command, directory):
    """The figures of a converge, bearing or hopkinson directory, drawn into it."""
    if command == "bearing-plot":
        from .bearing import plot_bearing as draw
    elif command == "hopkinson-plot":
        from .hopkinson import plot_hopkinson as draw
    else:
        from .convergence import plot_study as draw
    written = draw(directory)
    return [] if command == "hopkinson-plot" else written  # into the staging directory: its paths would mislead


def _parser():
    parser = argparse.ArgumentParser(prog="barimpact")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="draw the figures of a run or sweep directory, or compare runs")
    p.add_argument("dir", nargs="+")
    p.add_argument("--out", default=None, help="where the figures go (default: DIR/figures)")
    p.add_argument("--force", action="store_true", help="write the figures beside other files (as run's --force)")
    for command, what in (("converge-plot", "draw the plots of a barimpact converge directory"),
                          ("bearing-plot", "draw bearing.png of a barimpact bearing directory"),
                          ("hopkinson-plot", "draw the figures of a barimpact hopkinson directory")):
        sub.add_parser(command, help=what).add_argument("dir")
    return parser


def main(argv=None):
    args = _parser().parse_args(argv)
    try:
        if args.command == "plot":
            written = _plot(args.dir, args.out, args.force)
        else:
            written = _study_plot(args.command, args.dir)
    except (OSError, ValueError, ImportError) as e:  # ImportError: results.h5 without h5py
        print(f"barimpact: error: {args.command}: {e}", file=sys.stderr)
        return 2
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
