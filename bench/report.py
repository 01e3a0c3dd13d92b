#!/usr/bin/env python3
"""Runs the benchmarks and writes docs/benchmarks.md: the paper scheme's step
against the bare loop and four cases batched in SIMD registers (one Google
Benchmark run, repetitions interleaved at random so that the machine's noise
falls on all alike, medians), a sweep's throughput (bench/sweep_throughput.sh)
and the SciPy baseline (bench/scipy_baseline.py).

    python3 bench/report.py build/release/bench/barimpact_bench docs/benchmarks.md
"""
import os
import json
import platform
import statistics
import subprocess
import sys
from collections import defaultdict


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


def main():
    binary, out = sys.argv[1], sys.argv[2]
    build = os.path.dirname(os.path.dirname(os.path.abspath(binary)))
    here = os.path.dirname(os.path.abspath(__file__))
    args = [binary, "--benchmark_format=json", "--benchmark_repetitions=7",
            "--benchmark_enable_random_interleaving=true", "--benchmark_min_time=0.2"]
    data = json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout)
    samples = defaultdict(list)
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        parts = b["run_name"].split("/")
        name, size = "/".join(parts[:-1]), parts[-1]
        samples[(name, int(size))].append(b["per_node_step"] * 1e9)
    sizes = sorted({s for n, s in samples if n == "BM_PaperStep"})
    rows = []
    for s in sizes:
        paper = statistics.median(samples[("BM_PaperStep", s)])
        bare = statistics.median(samples[("BM_BareLoop", s)])
        batch = statistics.median(samples[("BM_PaperBatch4", s)])
        rows.append(f"| {s:>9,} | {paper:6.2f} | {bare:6.2f} | {paper / bare:5.2f} | {batch:6.2f} | {paper / batch:4.1f}x |")
    scheme_names = sorted({n for n, _ in samples if n.startswith("BM_Scheme/")}, key=lambda n: n)
    scheme_sizes = sorted({s for n, s in samples if n.startswith("BM_Scheme/")})
    scheme_rows = []
    for n in scheme_names:
        cells = [statistics.median(samples[(n, m)]) for m in scheme_sizes]
        label = n[len("BM_Scheme/"):]
        ratio = ""
        bare_name = None
        if label.startswith("central-difference") or label.startswith("characteristic"):
            bare_name = "BM_BareCentralDifference"
        if label.split("/")[0] in ("paper", "paoli-schatzman", "moreau-jean", "newmark"):
            bare_name = "BM_BareLoop"  # stencil fused into a prefactored tridiagonal solve
        if bare_name:
            bare = [statistics.median(samples[(bare_name, m)]) for m in scheme_sizes]
            ratio = " / ".join(f"{c / b:.2f}" for c, b in zip(cells, bare))
        scheme_rows.append(f"| {label} | " + " | ".join(f"{c:.2f}" for c in cells) + f" | {ratio} |")
    bare_cd = " | ".join(f"{statistics.median(samples[('BM_BareCentralDifference', m)]):.2f}" for m in scheme_sizes)
    sweep = subprocess.run(["bash", os.path.join(here, "sweep_throughput.sh"), os.path.join(build, "barimpact")],
                           capture_output=True, text=True, check=True).stdout.strip()
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"))
    scipy = subprocess.run(["/usr/bin/python3", os.path.join(here, "scipy_baseline.py"), "100", "1000", "10000"],
                           capture_output=True, text=True, check=True, env=env).stdout.strip()
    text = f"""# Benchmarks

## One time step of `paper` against the bare loop

Nanoseconds per node-step (median of 7 repetitions, interleaved at random in
one run). `paper` is `PaperScheme::advance()` on Example 1's data with M
elements and dt = h: the library's step with its contact term, load
dispatch and finiteness check. The bare loop is the same arithmetic written
flat (stencil right-hand side fused into the forward sweep of the
prefactored tridiagonal solve, then the backward sweep). Target: ratio <= 1.25.

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

## Every scheme's step

Nanoseconds per node-step, same run, Example 1 (rigid obstacle for the
rigid schemes, k = 100 otherwise), dt = h/2 (h for characteristic):

| scheme / obstacle | {" | ".join(f"M = {m:,}" for m in scheme_sizes)} | ratio to the bare loop |
|---|{"---:|" * len(scheme_sizes)}---|
{chr(10).join(scheme_rows)}
| bare central-difference loop | {bare_cd} | |

The explicit lumped schemes (central-difference, characteristic) run one
fused pass that the compiler vectorises, about 0.65 ns per node-step: at or
near 1.25x of their bare loop at M = 100, where the per-step work (contact,
checks, observers' bookkeeping) shows, and at par above (memory-bound at 10^6).
paper, paoli-schatzman, moreau-jean and newmark fuse their right-hand side
into a prefactored tridiagonal solve (the one-step schemes also their update
into the backward sweep; newmark adds a predictor pass): their ratio is to
the bare loop of that (first table); at 10^6 nodes the extra arrays they
stream (stencils, factors, loads) cost memory bandwidth. mass-redistribution
still makes several passes per step (8-15 ns per node-step); fusing it is
open work.

## Sweeps: SIMD batches, threads, MPI

{sweep}

Produced by `bash bench/sweep_throughput.sh build/release/barimpact` (part of
`make bench`): per core, batching four cases per register runs a sweep
about 3 times faster than running its cases one by one; the `mpirun` line
includes Open MPI's start-up (about 0.4 s) and uses one worker rank.

## Against the SciPy script a user would write (bench/scipy_baseline.py)

{scipy}

The same scheme on Example 1 scaled to M elements: NumPy stencil right-hand
side and `scipy.linalg.cho_solve_banded` with the matrix factored once by
`cholesky_banded`, timed in the same process as barimpact's Python module.
The target of 100x is **not** met at M = 10^3 and 10^4: LAPACK's banded
solve is compiled code too, and SciPy's per-step overhead (about 20 us) only
dominates on small meshes (M = 100). barimpact's advantage there comes from
fusing the right-hand side into the sweep, and grows with batching (3x more).

Both loops are latency-bound: each sweep carries one fused multiply-add from
node to node (about 4 cycles), so about 8 cycles, 3 ns, per node-step at any
size; memory bandwidth is not the limit even at M = 10^6. Debian's Google
Benchmark prints "Library was built as DEBUG": that concerns the harness,
not the code measured.
"""
    with open(out, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
