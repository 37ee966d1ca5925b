"""Reproduce the paper's figures (docs/figures/*.png) with symtmm's own commands.

Every figure is one ``symtmm`` command line, the same one docs/figures.md
shows; this script only runs them in turn and reports the time each took::

    python scripts/make_figures.py            # all figures
    python scripts/make_figures.py fig09 fig13   # some of them

Run it from the repository root.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from symtmm.cli import main

OUT = Path("docs/figures")
EX1 = "examples/paper_ex1_ff_cc.toml"
EX2 = "examples/paper_ex2_three_pp.toml"
EX3 = "examples/paper_ex3_three_pp_coupled.toml"
EX4 = "examples/paper_ex4_damped.toml"

#: name -> the command line (without the leading ``symtmm``)
FIGURES = {
    "fig09": ["scan", EX1, "--omega-max", "225", "--points", "6000",
              "--title", ("Paper fig. 9 - example 1 (free-free over clamped-clamped, K = 100, "
                         "x1 = 0.3)"),
              "--plot", str(OUT / "fig09_ex1_scan.png")],
    "fig10": ["sweep", EX1, "--param", "x1", "--from", "0", "--to", "0.5", "--steps", "51",
              "--count", "10", "--no-progress", "--panels",
              "--title", ("Paper fig. 10 - example 1: the first ten frequency parameters "
                         "against the spring position, K = 100"),
              "--x-label", "spring position x1 [m]",
              "--plot", str(OUT / "fig10_ex1_sweep_K100.png")],
    "fig10b": ["sweep", EX1, "--set", "K=1000", "--param", "x1", "--from", "0", "--to", "0.5",
               "--steps", "51", "--count", "10", "--no-progress", "--panels",
               "--title", ("Paper fig. 10 - example 1: the first ten frequency parameters "
                          "against the spring position, K = 1000"),
               "--x-label", "spring position x1 [m]",
               "--plot", str(OUT / "fig10_ex1_sweep_K1000.png")],
    "fig12": ["scan", EX2, "--omega-max", "175", "--points", "4000",
              "--title", ("Paper fig. 12 - example 2: three uncoupled pinned-pinned beams "
                         "(every root triple)"),
              "--plot", str(OUT / "fig12_ex2_scan.png")],
    "fig13": ["sweep", EX3, "--param", "x1", "--from", "0", "--to", "0.5", "--steps", "51",
              "--count", "12", "--no-progress", "--panels",
              "--title", ("Paper fig. 13 - example 3: three pinned-pinned beams in a chain, "
                         "K = 25"),
              "--x-label", "spring position x1 [m]",
              "--plot", str(OUT / "fig13_ex3_sweep.png")],
    "fig14": ["scan", EX4, "--omega-max", "1500", "--points", "3000",
              "--title", "Paper fig. 14 - example 4: example 3 with dashpots, C = 5",
              "--plot", str(OUT / "fig14_ex4_scan.png")],
    "modes": ["modes", EX1, "--count", "4", "--points", "201",
              "--title", "Example 1: the first four mode shapes (K = 100, x1 = 0.3)",
              "--plot", str(OUT / "modes_ex1.png")],
}


def run(names) -> int:
    OUT.mkdir(parents=True, exist_ok=True)
    for name in names:
        argv = FIGURES[name]
        print(f"$ symtmm {' '.join(repr(a) if ' ' in a else a for a in argv)}", flush=True)
        start = time.perf_counter()
        code = main(argv)
        print(f"[{name}: exit {code}, {time.perf_counter() - start:.1f} s]", flush=True)
        if code:
            return code
    return 0


if __name__ == "__main__":          # the sweeps' worker processes import this module
    wanted = sys.argv[1:] or list(FIGURES)
    unknown = [n for n in wanted if n not in FIGURES]
    if unknown:
        sys.exit(f"unknown figure(s) {', '.join(unknown)}; known: {', '.join(FIGURES)}")
    sys.exit(run(wanted))
