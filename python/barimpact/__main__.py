"""python3 -m barimpact plot DIR [DIR ...] [--out FIGURES] (what `barimpact plot` runs).

DIR is a run directory (history.csv or results.h5: the run's figures) or a sweep
directory (sweep.csv: each output against the swept keys, and the runs'
U(t) and R(t) overlaid); several run directories draw one comparison."""
import argparse
import sys
from pathlib import Path

from .plot import compare, is_run_directory, load, mark_figures, plot


def _plot(dirs, out):
    """The figures of one run or sweep directory, or the comparison of several runs."""
    if len(dirs) > 1:
        if out is None:
            raise ValueError("several directories: give --out for their comparison")
        return compare([load(d) for d in dirs], out)
    d = Path(dirs[0])
    target = Path(out) if out else d / "figures"
    if is_run_directory(d):
        written = plot(load(d), target)
    elif (d / "sweep.csv").is_file():
        from .convergence import plot_sweep
        written = plot_sweep(d, target)
    else:
        raise ValueError(f"{d}: no history.csv, results.h5 or sweep.csv (not a directory written by barimpact run or "
                         "sweep)")
    if not out:
        mark_figures(d)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(prog="barimpact")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="draw the figures of a run or sweep directory, or compare runs")
    p.add_argument("dir", nargs="+")
    p.add_argument("--out", default=None, help="where the figures go (default: DIR/figures)")
    c = sub.add_parser("converge-plot", help="draw the plots of a barimpact converge directory")
    c.add_argument("dir")
    b = sub.add_parser("bearing-plot", help="draw bearing.png of a barimpact bearing directory")
    b.add_argument("dir")
    h = sub.add_parser("hopkinson-plot", help="draw the figures of a barimpact hopkinson directory")
    h.add_argument("dir")
    args = parser.parse_args(argv)
    if args.command == "bearing-plot":
        from .bearing import plot_bearing
        for path in plot_bearing(args.dir):
            print(path)
        return 0
    if args.command == "hopkinson-plot":
        from .hopkinson import plot_hopkinson
        plot_hopkinson(args.dir)  # into the staging directory: its paths would mislead
        return 0
    if args.command == "converge-plot":
        from .convergence import plot_study
        for path in plot_study(args.dir):
            print(path)
        return 0
    try:
        written = _plot(args.dir, args.out)
    except (OSError, ValueError, ImportError) as e:  # ImportError: results.h5 without h5py
        print(f"barimpact: error: plot: {e}", file=sys.stderr)
        return 2
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
