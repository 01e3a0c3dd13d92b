"""python3 -m barimpact plot DIR [--out FIGURES] (what `barimpact plot` runs)."""
import argparse
import sys

from .plot import load, mark_figures, plot


def main(argv=None):
    parser = argparse.ArgumentParser(prog="barimpact")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="draw the figures of a run directory")
    p.add_argument("dir")
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
        data = load(args.dir)
    except (OSError, ValueError) as e:
        print(f"barimpact: error: plot: {e}", file=sys.stderr)
        return 2
    for path in plot(data, args.out if args.out else f"{args.dir}/figures"):
        print(path)
    if not args.out:
        mark_figures(args.dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
