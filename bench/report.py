#!/usr/bin/env python3
"""Runs the benchmarks and writes docs/benchmarks.md: the paper scheme's step
against the bare loop and four cases batched in SIMD registers (one Google
Benchmark run, repetitions interleaved at random so that the machine's noise
falls on all alike, medians), a sweep's throughput (bench/sweep_throughput.sh),
the bearing graph's wall time, whole processes' start-up and memory
(bench/whole_process.py) and the SciPy baseline (bench/scipy_baseline.py).
Every table and number in it comes from this run; rerunning replaces it, but
for the sections no benchmark here makes (each measured by the commands it
shows), which are kept from the file it replaces.

    python3 bench/report.py build/release/bench/barimpact_bench docs/benchmarks.md
"""
import os
import json
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import whole_process  # noqa: E402

# Each scheme's bare loop: its step's arithmetic written flat (bench/step_benchmark.cpp).
BARE_LOOPS = {
    "paper": "BM_BareLoop",
    "central-difference": "BM_BareCentralDifference",
    "characteristic": "BM_BareCharacteristic",
    "newmark": "BM_BareNewmark",
    "moreau-jean": "BM_BareMoreauJean",
    "paoli-schatzman": "BM_BarePaoliSchatzman",
    "mass-redistribution": "BM_BareMassRedistribution",
}


def machine():
    model = "unknown processor"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    cores = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
    cxx = subprocess.run(["c++", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    return f"{model}, {cores} cores, {platform.system()} {platform.release()}, {cxx}"


# The line benchmarks (BM_Line, BM_RigidLine) against the same scheme's single bar.
LINE_ROWS = [
    ("central-difference, 3-bar line (rigid links)", "BM_Line/central-difference", "BM_BareCentralDifference"),
    ("newmark, 3-bar line (elastic links; the near end pushing)", "BM_Line/newmark", "BM_BareNewmark"),
    ("paper, 3-bar line (elastic links; the near end pushing)", "BM_Line/paper", "BM_SchemeSequential/paper/elastic"),
    ("characteristic, 3-bar line (rigid links), dt = h/c", "BM_Line/characteristic", "BM_BareCharacteristic"),
] + [(f"{s}, 3-bar line, links {state}", f"BM_RigidLine/{s}/{key}", f"BM_RigidBar/{s}")
     for s in ("moreau-jean", "paoli-schatzman", "mass-redistribution")
     for state, key in (("idle", "idle"), ("pushing", "active"))]


def line_section(samples):
    sizes = sorted({m for n, m in samples if n.startswith("BM_Line/")})
    med = {k: statistics.median(v) for k, v in samples.items()}
    rows, above, overhead = [], [], []
    for label, name, base in LINE_ROWS:
        cells, ratios = [], []
        for m in sizes:
            if (name, m) in med:
                cells.append(f"{med[(name, m)]:.2f}")
                ratio = med[(name, m)] / med[(base, m)]
                ratios.append(f"{ratio:.2f}")
                if ratio > 1.25:
                    above.append(f"{label.split(',')[0]} at M = {m:,} ({ratio:.2f})")
            else:
                cells.append("")
        rows.append(f"| {label} | " + " | ".join(cells) + " | " + " / ".join(ratios) + " |")
        m0 = sizes[0]
        if (name, m0) in med:  # what a step costs beyond its single bar's at the smallest M
            overhead.append(f"{label.split(',')[0]} {(med[(name, m0)] - med[(base, m0)]) * m0:.0f} ns")
    for name in ("BM_BareCentralDifference", "BM_BareNewmark", "BM_PaperStep", "BM_BareCharacteristic"):
        rows.append(f"| single bar: {name[3:]} | " + " | ".join(f"{med[(name, m)]:.2f}" for m in sizes) + " | |")
    for s in ("moreau-jean", "paoli-schatzman", "mass-redistribution"):
        rows.append(f"| single bar: {s}, obstacle idle | " +
                    " | ".join(f"{med[(f'BM_RigidBar/{s}', m)]:.2f}" if (f"BM_RigidBar/{s}", m) in med else ""
                               for m in sizes) + " | |")
    return f"""## A line of bodies against the single bar

Nanoseconds per node-step, same run. A line is three bars of M elements in
all (M/3, M/3, the rest) joined by a unilateral joint and a welded one,
with a law at x = 0: rigid for central differences, characteristic and the
rigid-contact schemes, elastic (k = 100) for Newmark and paper. The ratio is
to the single bar of M elements in the same scheme: its bare loop for
central differences, Newmark and characteristic, its own step with the
two-ended solve (BM_SchemeSequential/paper/elastic: the line engine has no
partitioned solve yet) for paper, its own step with the obstacle idle for
the rigid-contact schemes. Target: <= 1.25 (above it in this run:
{", ".join(above) if above else "none"}).

| step | {" | ".join(f"M = {m:,}" for m in sizes)} | ratio to the single bar |
|---|{"---:|" * len(sizes)}---|
{chr(10).join(rows)}

At M = {sizes[0]:,} a step costs a few hundred nanoseconds and what it does
besides its sweeps shows (beyond the single bar's step: {", ".join(overhead)}):
links, ends, statuses and the few general rows. Central differences and
characteristic run each uniform stretch of a body as the single bar's
vectorised pass; the rigid-contact schemes store a link's response on the
bodies it touches only; Newmark runs the single bar's two passes, A
factored from the far end, the links' free accelerations known between the
sweeps and their forces entering the back substitution (docs/methods.md,
"Lines of bodies: newmark"); paper runs the single bar's two-ended solve
with its right-hand side formed in blocks of row pairs whose stencils are a
uniform stretch's constants.

"""


def plastic_section(samples):
    sizes = sorted({m for n, m in samples if n.startswith("BM_PlasticLine/")})
    if not sizes:
        return ""
    med = {k: statistics.median(v) for k, v in samples.items()}
    rows = []
    bare = "BM_BareCentralDifference"
    if all((bare, m) in med for m in sizes):
        rows.append(f"| bare central differences (single bar) | {' | '.join(f'{med[(bare, m)]:.2f}' for m in sizes)} |  |")
    schemes = [s for s in ("central-difference", "paper", "newmark", "moreau-jean", "mass-redistribution")
               if (f"BM_PlasticLine/{s}/elastic", sizes[0]) in med]
    for scheme in schemes:
        elastic = f"BM_PlasticLine/{scheme}/elastic"
        for label, material in (("elastic", "elastic"), ("plastic, never yielding", "unyielded"),
                                ("plastic, yielding from the wall on", "yielding")):
            name = f"BM_PlasticLine/{scheme}/{material}"
            cells = " | ".join(f"{med[(name, m)]:.2f}" for m in sizes)
            ratio = "" if material == "elastic" else " / ".join(
                f"{med[(name, m)] / med[(elastic, m)]:.2f}" for m in sizes)
            rows.append(f"| {scheme}, {label} | {cells} | {ratio} |")
    return f"""## Elastic-plastic bars

Nanoseconds per node-step, same run. Two welded bars of M elements in all
moving at -1 onto a rigid wall (paper and Newmark: elastic, k = 100), dt = h/2
(BM_PlasticLineStep): elastic; elastic-plastic with a yield stress never
reached; elastic-plastic with sigma_y = 0.05 and E_t = 0.1, yielding from
the wall on. The ratio is to the same scheme's elastic line; the target
for an elastic bar through the plastic code path is 1.3.

| step | {" | ".join(f"M = {m:,}" for m in sizes)} | ratio to the elastic step |
|---|{"---:|" * len(sizes)}---|
{chr(10).join(rows)}

{plastic_notes(med, sizes, schemes)}
"""


def ratio_range(med, scheme, material, sizes):
    """The smallest and largest ratio of a plastic row to its elastic step."""
    r = [med[(f"BM_PlasticLine/{scheme}/{material}", m)] / med[(f"BM_PlasticLine/{scheme}/elastic", m)] for m in sizes]
    return f"{min(r):.2f} to {max(r):.2f}"


def plastic_notes(med, sizes, schemes):
    implicit = [s for s in schemes if s != "central-difference"]
    never = ", ".join(f"{s} {ratio_range(med, s, 'unyielded', sizes)}" for s in implicit)
    over = [s for s in implicit for m in sizes
            if med[(f"BM_PlasticLine/{s}/unyielded", m)] / med[(f"BM_PlasticLine/{s}/elastic", m)] > 1.3]
    verdict = ("the target is met" if not over else
               "above the target: " + ", ".join(sorted(set(over))))
    # Where every level yields (M = 1,000 to 10,000: the penalty wall of paper
    # and Newmark is soft enough at 10^6 elements that nothing yields in time).
    mid = [m for m in sizes if 1000 <= m <= 10000] or sizes
    yielding = ", ".join(f"{s} {ratio_range(med, s, 'yielding', mid)}" for s in implicit)
    text = f"""**Implicit schemes** (target 1.3x for an elastic bar through the plastic
code path), never yielding, times the elastic step: {never}; {verdict}.
Their iteration (include/barimpact/schemes/plastic_iteration.hpp) stops when
the return map at the step's u^{{n+1}} moves no plastic strain by more than
1e-10 sigma_y / E from the strains the step was loaded with, at most 30
steps per level (then the run stops as failed). A level where nothing
yields is one step plus a read-only yield check (vectorised, compiled for
AVX2 beside the portable path: src/schemes/yield_check.cpp); the level is
kept for a possible return at intervals doubling to 32 steps while nothing
yields, so the copy costs 1/32 of a pass.

A level that yields costs {yielding} times the elastic step at M = 1,000
to 10,000, where every level yields from the first step on: a few steps of
the scheme per level, each with a tangent factorisation and solve (its
division per row, a latency chain), the return map after every step, and
the copies back to level n, all over the whole line however few elements
flow. Reusing the elastic factors outside the flowing elements would remove
most of the tangent's cost; not done. paper's and Newmark's wall is the
penalty law k = 100, soft against elements of E A / h = 10^6 at M =
1,000,000: the benchmark's steps end before the bar reaches the yield
stress there, and those cells do not yield.
"""
    if "central-difference" in schemes:
        elastic = [med[("BM_PlasticLine/central-difference/elastic", m)] for m in sizes]
        text += f"""
**Central differences**, never yielding: {ratio_range(med, "central-difference", "unyielded", sizes)} times the
elastic step (target 1.3x: {"met" if max(med[("BM_PlasticLine/central-difference/unyielded", m)] / e for m, e in zip(sizes, elastic)) <= 1.3 else "not met"}); yielding: {ratio_range(med, "central-difference", "yielding", sizes)}. Until an
element first yields the plastic strains are all 0: the elastic stencil
runs, and one read-only pass over u^{{n+1}} checks |u_{{j+1}} - u_j| against
h sigma_y / E (vectorised): u streamed once more against an elastic step of
{min(elastic):.2f} to {max(elastic):.2f} ns per node. Fusing the check into the stencil's pass is what
remains. Once a bar has yielded, a step whose elements all stay elastic,
after one where they did too, writes nothing; a yielding step runs the
return map's pass over every element.
"""
    return text


# The steps with a partitioned solve (issue 30): (label, sequential and
# partitioned benchmarks, bytes a node-step moves through memory in the
# partitioned step, counted from its loops: 8 per double read or written;
# a uniform bar's chunk factors sit at their fixed point in registers).
#   the solve alone: elimination reads and writes x (16); back
#     substitution reads and writes x (16): 32;
#   newmark (unloaded): the predictor reads u, v, a, writes u, v (40); r
#     reads u and the bond's stiffness, writes r (24); the solve (32); the
#     update reads r, u, v, writes u, v, a (48): 144;
#   paper: r from two levels, written over the third (24); the solve (32): 56.
PARTITIONED = [
    ("the solve alone", "BM_TridiagonalSolve/sequential", "BM_TridiagonalSolve/partitioned", 32),
    ("newmark's step", "BM_NewmarkStep/sequential", "BM_NewmarkStep/partitioned", 144),
    ("paper's step", "BM_SchemeSequential/paper/elastic", "BM_Scheme/paper/elastic", 56),
]
TARGET_GAIN = 2.5  # issue 30: every implicit scheme 2.5x its sequential solve at M = 10^4..10^6


def partitioned_rows(med, triad, memory):
    """The table's rows, and per step the gains at M >= 10^4."""
    rows, gains = [], {}
    for label, seq, part, moved in PARTITIONED:
        for m in sorted({m for (n, m) in med if n == part and m >= 10_000 and (seq, m) in med}):
            s, p = med[(seq, m)], med[(part, m)]
            gains.setdefault(label, []).append(s / p)
            limit = ""
            if triad:
                bandwidth = triad.get(m, memory)
                limit = f" {bandwidth:.0f} | {moved / bandwidth:.2f} | {p / (moved / bandwidth):.1f} |"
            rows.append(f"| {label} | {m:>9,} | {s:.2f} | {p:.2f} | {s / p:.2f}x | {moved} |{limit}")
    return rows, gains


def partitioned_section(samples):
    med = {k: statistics.median(v) for k, v in samples.items()}
    triad = {m: 24.0 / med[("BM_Triad", m)] for (n, m) in med if n == "BM_Triad"}  # GB/s: 24 bytes per element
    memory = triad[max(triad)] if triad else None  # the largest triad, past the last-level cache
    rows, gains = partitioned_rows(med, triad, memory)
    if not rows:
        return ""
    met = [label for label, g in gains.items() if min(g) >= TARGET_GAIN]
    missed = [f"{label} ({min(g):.2f}x at worst)" for label, g in gains.items() if min(g) < TARGET_GAIN]
    small = sorted(m for (n, m) in med if n == "BM_NewmarkStep/partitioned" and ("BM_NewmarkStep/sequential", m) in med)
    pays = [m for m in small if med[("BM_NewmarkStep/partitioned", m)] < med[("BM_NewmarkStep/sequential", m)]]
    newmark_small = "; ".join(f"{m:,}: {med[('BM_NewmarkStep/sequential', m)]:.2f} against "
                              f"{med[('BM_NewmarkStep/partitioned', m)]:.2f}" for m in small if m < 10_000)
    widths = sorted({int(n.rsplit("/P", 1)[1]) for (n, _) in med if n.startswith("BM_TridiagonalSolve/partitioned/P")})
    sweep = []
    for m in sorted({m for (n, m) in med if n == "BM_TridiagonalSolve/partitioned"}):
        cells = {int(n.rsplit("/P", 1)[1]): v for (n, mm), v in med.items()
                 if mm == m and n.startswith("BM_TridiagonalSolve/partitioned/P")}
        cells[8] = med[("BM_TridiagonalSolve/partitioned", m)]
        sweep.append(f"| {m:>9,} | " + " | ".join(f"{cells[w]:.2f}" if w in cells else "" for w in sorted(set(widths) | {8}))
                     + " |")
    widths = sorted(set(widths) | {8})
    limit_head = " triad (GB/s) | limit (ns) | partitioned / limit |" if triad else ""
    limit_rule = "---:|---:|---:|" if triad else ""
    bandwidth = (f"the limit is the bytes a node-step moves through memory (counted from the loops,\n"
                 f"bench/report.py) over the triad's bandwidth at the same M (BM_Triad; {memory:.0f} GB/s at\n"
                 f"{max(triad):,} elements, past the last-level cache); below 1 where the step's arrays stay in a\n"
                 f"cache level the triad's three overflow.") if triad else "no triad was measured in this run."
    return f"""## The partitioned solve: past the recurrence's latency

The implicit schemes' prefactored tridiagonal solve runs one chain of
multiply-subtracts from node to node: its latency, not the machine's
arithmetic or memory, sets their speed. Wang's partition method
(model/partitioned_tridiagonal.hpp) cuts the line into P chunks whose
chains run side by side (eight at a time, in registers), joined by a
reduced system of the P - 1 separators. Nanoseconds per node-step, same
run; {bandwidth}

| step | M | sequential (ns) | partitioned (ns) | gain | bytes |{limit_head}
|---|---:|---:|---:|---:|---:|{limit_rule}
{chr(10).join(rows)}

Target (issue 30): {TARGET_GAIN}x the sequential step at M = 10^4..10^6 for every
implicit scheme. In this run: {", ".join(met) if met else "none"} met it;
{", ".join(missed) if missed else "none"} did not. The paper scheme's one-bar kernel
and Newmark take the partitioned solve from 2000 nodes on runs of 32 steps
or more (8 chunks; `time.partitions` sets them, 1 the sequential solve); the line engine's
paper and the rigid-contact schemes keep the sequential one. The
threshold keeps the pinned examples on the sequential solve, bit for bit;
Newmark's partitioned step is faster from M = {f"{pays[0]:,}" if pays else "(none measured)"} (ns per
node-step, sequential against partitioned, M = {newmark_small}). Results are
the sequential solve's to rounding (tests/unit/partitioned_tridiagonal_test.cpp,
line_newmark_test.cpp, paper_scheme_test.cpp bound them).

The solve alone against P, ns per node (P = 8 is the default):

| M | {" | ".join(f"P = {w}" for w in widths)} |
|---:|{"---:|" * len(widths)}
{chr(10).join(sweep)}

"""


def pile_section(samples, bearing):
    sizes = sorted({m for n, m in samples if n == "BM_Pile/smith-soil"})
    if not sizes:
        return ""
    med = {k: statistics.median(v) for k, v in samples.items()}
    rows, above = [], []
    soil = []
    for m in sizes:
        cells = [med.get((n, m)) for n in ("BM_Pile/no-soil", "BM_BareCentralDifference", "BM_Pile/smith-soil",
                                           "BM_BareSmithPile")]
        ratio = "" if cells[3] is None else f"{cells[2] / cells[3]:.2f}"
        if ratio and cells[2] / cells[3] > 1.25:
            above.append(f"M = {m:,} ({ratio})")
        if cells[0] is not None:
            soil.append(cells[2] / cells[0])
        rows.append(f"| {m:,} | " + " | ".join("" if c is None else f"{c:.2f}" for c in cells) + f" | {ratio} |")
    soil = soil or [float("nan")]
    return f"""## Pile driving: Smith's soil and the bearing graph

Nanoseconds per node-step, same run. One step of central differences on a
20 m pile of M elements moving into Smith's soil, with a side spring on
every node and a Smith toe (`BM_Pile/smith-soil`), against the same pile
without soil (`BM_Pile/no-soil`) and against the bare loop of the same
arithmetic, one fused pass of stencil and side springs with slip, Smith
damping and the work of both (`BM_BareSmithPile`). Target: <= 1.25 (above
it in this run: {", ".join(above) if above else "none"}).

| M (elements) | no soil | bare central differences | Smith soil | bare Smith loop | ratio to its bare loop |
|---:|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

The soil makes a step {min(soil):.1f} to {max(soil):.1f} times the pile's without it: the two sums
it carries for the budget, slip work and damping work, are chains from node
to node that the compiler does not vectorise. The line's fused stretch
costs what the bare loop costs per node; at 100 elements what the line
engine adds around it shows (the toe's link and its node, the head's row,
the ends' forces and the budget of the level).

{bearing}
"""


def bearing_time(binary):
    """The bearing graph of 20 capacities, wall time, median of 5 whole
    processes (start-up and every run's files included, no figure), beside
    the same graph of the example's weightless 0.12 s blows, run in turn."""
    import tempfile
    import time
    here = os.path.dirname(os.path.abspath(__file__))
    case = os.path.join(here, "..", "examples", "pile", "steel-pipe-sand.toml")
    weightless = ["--set", "load.gravity=0", "--set", "time.end=0.12"]
    times = {"as shipped": [], "weightless": []}
    for _ in range(5):
        for name, extra in (("as shipped", []), ("weightless", weightless)):
            with tempfile.TemporaryDirectory() as work:
                start = time.perf_counter()
                subprocess.run([binary, "bearing", case, "--out", os.path.join(work, "b"), "--capacity",
                                "0.5e6:4e6:20", "--no-plot", *extra], capture_output=True, check=True)
                times[name].append(time.perf_counter() - start)
    shipped, light = (statistics.median(times[k]) for k in ("as shipped", "weightless"))
    return f"""The bearing graph of 20 capacities of examples/pile/steel-pipe-sand.toml
takes {shipped:.3f} s wall time, median of 5 whole processes into fresh
directories, with bearing.csv and every run's files written and no figure
(target: 0.5 s). The example runs 0.6 s under gravity (the ram falls back
at 0.39 s, and every capacity's blow must finish); the same graph of its
weightless 0.12 s blows takes {light:.3f} s, run in turn:

    build/release/barimpact bearing examples/pile/steel-pipe-sand.toml --out /tmp/b --capacity 0.5e6:4e6:20 --no-plot
    build/release/barimpact bearing examples/pile/steel-pipe-sand.toml --out /tmp/b0 --capacity 0.5e6:4e6:20 --no-plot \\
        --set load.gravity=0 --set time.end=0.12
"""


def large_run_section(binary, python_dir):
    """The README's large case (20,000 elements, 80,000 steps, a history row
    every step, 101 snapshots) in both formats: run, plot and load times
    (one each, whole processes) and the files' sizes."""
    import tempfile
    import time
    here = os.path.dirname(os.path.abspath(__file__))
    case = os.path.join(here, "..", "examples", "paper-example1.toml")
    env = dict(os.environ, PYTHONPATH=python_dir, MPLBACKEND="Agg")

    def timed(args):
        start = time.perf_counter()
        subprocess.run(args, capture_output=True, check=True, env=env)
        return time.perf_counter() - start

    def megabytes(path):
        if os.path.isfile(path):
            return os.path.getsize(path) / 1e6
        return sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(path) for f in fs) / 1e6

    rows = []
    with tempfile.TemporaryDirectory() as work:
        for format, files in (("csv", ("history.csv", "fields.csv")), ("hdf5", ("results.h5",))):
            out = os.path.join(work, format)
            run = timed([binary, "run", case, "--out", out, "--set", f"output.format={format}", "--set",
                         "bar.elements=20000", "--set", "time.step=5e-5"])
            plot = timed([binary, "plot", out])
            load = timed(["/usr/bin/python3", "-c", f"import barimpact; barimpact.load({out!r})"])
            size = sum(megabytes(os.path.join(out, f)) for f in files)
            rows.append(f"| {format} | {size:.1f} | {run:.1f} | {plot:.1f} | {megabytes(os.path.join(out, 'figures')):.2f} "
                        f"| {load:.2f} |")
    return f"""## A large run: CSV or HDF5, and its figures

The README's large case: Example 1 on 20,000 elements for 80,000 steps,
a history row every step and 101 snapshots. Wall seconds of whole
processes (one each; `load` includes Python's start-up and the import),
sizes in MB. Targets: `barimpact plot` under 15 s and under 5 MB.

    build/release/barimpact run examples/paper-example1.toml --out out/big --set output.format=hdf5 --set bar.elements=20000 --set time.step=5e-5
    build/release/barimpact plot out/big
    python3 -c "import barimpact; barimpact.load('out/big')"

| output.format | results (MB) | run (s) | plot (s) | figures (MB) | load (s) |
|---|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

"""


def reading_section(reading):
    """Reading a long line's case text, and building its line (bench/read_benchmark.cpp)."""
    sizes = sorted({b for n, b in reading if n == "BM_ReadLine"})
    rows = [f"| {b:>7,} | {statistics.median(reading[('BM_ReadLine', b)]):.3f} | "
            f"{statistics.median(reading[('BM_BuildLine', b)]):.4f} |" for b in sizes]
    return f"""
## Reading a long line

N point masses joined by springs (bench/read_benchmark.cpp): reading and
checking the case's text, and building its line, in seconds for the whole
line (medians of 7). Target: 10^5 bodies read in under a second.

| bodies | read (s) | build the line (s) |
|---:|---:|---:|
{chr(10).join(rows)}
"""


def match_wall(binary, jobs):
    """Median wall seconds of `barimpact match` of the steel pipe, --no-plot, as a user runs it."""
    record = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "pda", "steel-pipe.toml")
    times = []
    with tempfile.TemporaryDirectory() as work:
        for _ in range(5):
            args = [binary, "match", record, "--out", os.path.join(work, "m"), "--force", "--no-plot"]
            args += ["--jobs", str(jobs)] if jobs else []
            start = time.perf_counter()
            subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times.append(time.perf_counter() - start)
    return statistics.median(times)


def matching_section(matching, binary):
    """Signal matching's fit against one forward blow (bench/match_benchmark.cpp), and whole processes."""
    if "BM_MatchForwardBlow" not in matching:
        return ""
    blow_s = statistics.median(t for t, _, _ in matching["BM_MatchForwardBlow"])
    rows = [f"| one forward blow of the match's model | 1 | {blow_s * 1e3:.3f} ms | {1 / blow_s:,.0f} | 1 |"]
    for threads, what in ((1, "the fit, 1 thread"), (2, "the fit, 2 threads (the starts over the cores)")):
        runs = matching.get(f"BM_Match/{threads}", [])
        if runs:
            wall = statistics.median(t for t, _, _ in runs)
            rate = statistics.median(r for _, r, _ in runs)
            blows = statistics.median(n for _, _, n in runs)
            rows.append(f"| {what} | {blows:,.0f} | {wall:.3f} s | {rate:,.0f} | {rate * blow_s:.2f} |")
    both, one = match_wall(binary, None), match_wall(binary, 1)
    cores = os.cpu_count()
    return f"""
## Signal matching

The steel pipe's record (examples/pda/steel-pipe.toml: 19.2 m below the
gauges, 100 elements, 10 shaft segments, the toe, two quakes and two
dampings, 4 starts; from the foot to t2 + 20 ms) on this {cores}-core machine
(bench/match_benchmark.cpp, medians of 7 in the run above; the whole
process, `barimpact match ... --no-plot`, wall time, medians of 5 runs one
after the other, the files in the page cache):

| what | blows | wall time | blows per second | against one blow alone |
|---|---:|---:|---:|---:|
{chr(10).join(rows)}
| `barimpact match --no-plot`, whole process, every core | | {both:.2f} s | | |
| the same, `--jobs 1` | | {one:.2f} s | | |

The target, a match of a 20 m pile with its quakes and dampings on a 40 ms
record in under 5 s, is {"met" if both < 5.0 else "not met"}: {both:.2f} s. A blow of the
fit costs about what a blow alone costs: Ceres Solver's own work (its QR of
the Jacobian an iteration), the line's copy and the scheme's set-up per
blow are the rest. A forward blow is the line engine's central-difference
step, vectorised along the pile's stretches of nodes; the fit's blows are
spread over cores, not over SIMD lanes (the batched SIMD kernel is the
paper scheme's, without Smith's soil). Ceres Solver is loaded only by a
process that matches (the fitting module), so a match pays its loading,
and no other run does.
"""


def sections(text):
    """The text's "## " sections in order: (heading, the section's text)."""
    out, heading, lines = [], None, []
    for line in text.splitlines(keepends=True):
        if line.startswith("## "):
            out.append((heading, "".join(lines)))
            heading, lines = line.strip(), []
        lines.append(line)
    out.append((heading, "".join(lines)))
    return out


# The sections no benchmark here makes, each measured by the commands it shows.
MEASURED_APART = ("## Field snapshots' memory", "## Figures: a pile blow and a long Hopkinson record",
                  "## Drivability: a pile driven through its profile")


def keep_measured_apart(text, previous):
    """The previous report's MEASURED_APART sections, kept where they were:
    before the next section both have."""
    if not os.path.exists(previous):
        return text
    with open(previous) as f:
        old = sections(f.read())
    new = sections(text)
    made = {h for h, _ in new}
    for i, (heading, body) in enumerate(old):
        if heading not in MEASURED_APART or heading in made:
            continue
        following = next((h for h, _ in old[i + 1:] if h in made), None)
        at = next((k for k, (h, _) in enumerate(new) if h == following), len(new))
        new.insert(at, (heading, body))
        made.add(heading)
    return "".join(body for _, body in new)


def main():
    binary, out = sys.argv[1], sys.argv[2]
    build = os.path.dirname(os.path.dirname(os.path.abspath(binary)))
    here = os.path.dirname(os.path.abspath(__file__))
    args = [binary, "--benchmark_format=json", "--benchmark_repetitions=7",
            "--benchmark_enable_random_interleaving=true", "--benchmark_min_time=0.2"]
    data = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    samples = defaultdict(list)
    reading = defaultdict(list)  # (name, bodies): seconds per read or build of the whole line
    matching = defaultdict(list)  # BM_Match*: (seconds, blows per second, blows) per repetition
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        if b["run_name"].startswith("BM_Match"):
            seconds = b["real_time"] * {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]]
            matching[b["run_name"].removesuffix("/real_time")].append((seconds, b["blows_per_s"], b.get("blows", 1.0)))
            continue
        parts = b["run_name"].split("/")
        name, size = "/".join(parts[:-1]), parts[-1]
        if "per_body" in b:
            reading[(name, int(size))].append(b["real_time"] * {"ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]])
            continue
        samples[(name, int(size))].append(b["per_node_step"] * 1e9)
    sizes = sorted({s for n, s in samples if n == "BM_PaperStep"})
    rows = []
    for s in sizes:
        paper = statistics.median(samples[("BM_PaperStep", s)])
        bare = statistics.median(samples[("BM_BareLoop", s)])
        batch = statistics.median(samples[("BM_PaperBatch", s)])
        rows.append(f"| {s:>9,} | {paper:6.2f} | {bare:6.2f} | {paper / bare:5.2f} | {batch:6.2f} | {paper / batch:4.1f}x |")
    simd_rows = []
    for path in ("scalar", "sse2", "avx2"):
        name = f"BM_PaperBatchPath/{path}"
        cells = [(m, statistics.median(v)) for (n, m), v in sorted(samples.items()) if n == name]
        if cells:
            simd_rows.append(f"| {path} | " + " | ".join(
                f"{t:.2f} ({statistics.median(samples[('BM_PaperStep', m)]) / t:.1f}x)" for m, t in cells) + " |")
    simd_sizes = sorted({m for (n, m) in samples if n.startswith("BM_PaperBatchPath/")})
    scheme_names = sorted({n for n, _ in samples if n.startswith("BM_Scheme/")}, key=lambda n: n)
    scheme_sizes = sorted({s for n, s in samples if n.startswith("BM_Scheme/")})
    scheme_rows = []
    worst = 0.0
    above = []  # (label, M, ratio) over the target
    for n in scheme_names:
        cells = [statistics.median(samples[(n, m)]) for m in scheme_sizes]
        label = n[len("BM_Scheme/"):]
        bare_name = BARE_LOOPS[label.split("/")[0]]
        bare = [statistics.median(samples[(bare_name, m)]) for m in scheme_sizes]
        ratio = " / ".join(f"{c / b:.2f}" for c, b in zip(cells, bare))
        worst = max(worst, max(c / b for c, b in zip(cells, bare)))
        above += [f"{label} at M = {m:,} ({c / b:.2f})" for m, c, b in zip(scheme_sizes, cells, bare) if c / b > 1.25]
        scheme_rows.append(f"| {label} | " + " | ".join(f"{c:.2f}" for c in cells) + f" | {ratio} |")
    bare_rows = []
    for name in sorted(set(BARE_LOOPS.values())):
        cells = " | ".join(f"{statistics.median(samples[(name, m)]):.2f}" for m in scheme_sizes)
        bare_rows.append(f"| {name[3:]} | {cells} | |")
    sweep = subprocess.run(["bash", os.path.join(here, "sweep_throughput.sh"), os.path.join(build, "barimpact")],
                           capture_output=True, text=True, check=True).stdout.strip()
    bearing = bearing_time(os.path.join(build, "barimpact")) if any(n == "BM_Pile/smith-soil" for n, _ in samples) else ""
    large = large_run_section(os.path.join(build, "barimpact"), os.path.join(build, "python"))
    bare_ns = {m: statistics.median(samples[("BM_BareLoop", m)]) for (n, m) in samples if n == "BM_BareLoop"}
    whole = whole_process.section(os.path.join(build, "barimpact"), bare_ns)
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"))
    scipy = subprocess.run(["/usr/bin/python3", os.path.join(here, "scipy_baseline.py"), "100", "1000", "10000"],
                           capture_output=True, text=True, check=True, env=env).stdout.strip()
    text = f"""# Benchmarks

## One time step of `paper` against the bare loop

Nanoseconds per node-step (median of 7 repetitions, interleaved at random in
one run). `paper` is `PaperScheme::advance()` on Example 1's data with M
elements and dt = h: the library's step with its contact term, load
dispatch and finiteness check. The bare loop is the same arithmetic written
flat: the stencil right-hand side fused into the first sweep of the
prefactored two-ended tridiagonal solve (inwards from both ends), then the
sweep back outwards from the middle row. Target: ratio <= 1.25.

| M (elements) | paper (ns) | bare loop (ns) | ratio | batch of 4 (ns per case) | batch gain |
|---:|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

Machine: {machine()}.

Produced by `make bench`, that is

    cmake --preset release && cmake --build --preset release
    python3 bench/report.py build/release/bench/barimpact_bench docs/benchmarks.md

"batch of 4" is `PaperBatch::advance()` on four different cases, one per
lane of an AVX2 register (the same arithmetic lane by lane, the same bits as
the single runs: tests/unit/paper_batch_test.cpp), per node-step per case.

### The batch kernel's SIMD paths

The release build runs on any x86-64 processor: the batch kernel is
compiled once per path and the widest one the processor runs is taken at
run time (`BARIMPACT_SIMD=scalar|sse2|avx2` forces one; `barimpact
--version` names them). Nanoseconds per node-step per case, and the gain
over a single `paper` step of the same M, same run:

| path | {" | ".join(f"M = {m:,}" for m in simd_sizes)} |
|---|{"---:|" * len(simd_sizes)}
{chr(10).join(simd_rows)}

Every path gives the same bits (tests/unit/paper_batch_test.cpp forces each
in turn; tests/cli/cli_test.sh compares a sweep's files on each).

## Every scheme's step against its bare loop

Nanoseconds per node-step, same run, Example 1 (rigid obstacle for the
rigid schemes, k = 100 otherwise), dt = h/2 (h for characteristic). Each
scheme's bare loop (bench/step_benchmark.cpp) is its step's arithmetic
written flat, without the scheme object, contact, energy budget or checks.
Target: ratio <= 1.25 at every M; the largest ratio in this run is {worst:.2f}
(above the target: {", ".join(above) if above else "none"}).

| scheme / obstacle | {" | ".join(f"M = {m:,}" for m in scheme_sizes)} | ratio to its bare loop |
|---|{"---:|" * len(scheme_sizes)}---|
{chr(10).join(scheme_rows)}
{chr(10).join(bare_rows)}

The explicit lumped schemes (central-difference, characteristic) run one
fused pass that the compiler vectorises (a third to half a nanosecond per
node-step), so at M = 100 a whole step takes 35-50 ns and what a step does
besides its pass shows: the virtual call, the contact law, the budget's
checks, and for characteristic its end advanced in characteristic variables
through a virtual call (about 15 ns in all; this machine's noise moves such
short steps by 10-20% from run to run). From M = 1000 on, that is noise.
The others fuse their right-hand side into the
sweep of a prefactored tridiagonal solve towards x = 0 and their update
into the sweep back: the factors are eliminated from the far end, so node
0's unknown is known between the two sweeps and the obstacle (Newmark's
penalty force, Moreau-Jean's impulse, Paoli-Schatzman's projection, mass
redistribution's status) is decided there and enters the solve as a force
at node 0, with no third pass; paper, whose contact term is explicit,
solves from both ends at once (two independent chains). Interior rows use
the uniform mesh's constant stencils, so a step streams only its state and
two factor arrays.

{line_section(samples)}{plastic_section(samples)}{partitioned_section(samples)}{pile_section(samples, bearing)}{large}{whole}## Sweeps: SIMD batches, threads, MPI

{sweep}

Produced by `bash bench/sweep_throughput.sh build/release/barimpact` (part of
`make bench`): the configurations alternate over five rounds and each row
is the median. Wall times include everything a sweep does besides stepping:
start-up, planning, observers (the energies of every 100th row are computed
lane by lane, 5-6% of a batched sweep) and writing runs/<id>/, which is
why the sweep's batch gain is below the kernel's (first table). The
`mpirun` line includes Open MPI's start-up (about 0.4 s); both ranks run
cases (rank 0 also hands them out, from its main thread, between short
sleeps).

## Against the SciPy script a user would write (bench/scipy_baseline.py)

{scipy}

The same scheme on Example 1 scaled to M elements: NumPy stencil right-hand
side and `scipy.linalg.cho_solve_banded` with the matrix factored once by
`cholesky_banded`, timed in the same process as barimpact's Python module.
The target of 100x is **not** met at M = 10^3 and 10^4: LAPACK's banded
solve is compiled code too, and SciPy's per-step overhead (about 20 us) only
dominates on small meshes (M = 100). barimpact's advantage comes from fusing
the right-hand side into the sweeps and from the two-ended solve's two
chains, and grows by the batch gain above (about 3x) in a sweep.

The implicit loops are latency-bound: each sweep carries a multiply and a
subtract from node to node (no fused multiply-add: everything is built with
-ffp-contract=off so that batches reproduce single runs bit for bit), about
12 cycles, 3.4 ns, per node-step for a one-ended solve at any size; the
paper scheme's two-ended solve runs two such chains side by side (first
table). 100x against SciPy at M = 10^4 would be about 0.25 ns, under one cycle,
per node-step for a stencil and two recurrences: beyond what one core does
with this scheme, batched or not. Debian's Google
Benchmark prints "Library was built as DEBUG": that concerns the harness,
not the code measured.
"""
    text += reading_section(reading)
    text += matching_section(matching, os.path.join(build, "barimpact"))
    text = keep_measured_apart(text, out)
    with open(out, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
