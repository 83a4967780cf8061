"""Benchmark: the wear run's stages before and after, and the time a run cannot go below.

`fewear run` of each rod over FEWEAR_BENCH_CYCLES cycles (default 20,000), in one process each,
run by this source tree and by a baseline tree (FEWEAR_BASELINE_SOURCE, default /work/main, the
lead's checkout of main; a commit's tree by `git archive <commit> fewear | tar -x -C <dir>`;
skipped if absent), one after the other on the same machine, each with its kernels compiled
before. Each run counts its stages' work (:data:`COUNTER`: contact solves, their Newton
iterations and nodes in contact, dynamics steps, Newton iterations and factorisations, ALE
moves, re-meshes, the wear step's matrix exponentials). The benchmark prints the stages' times
side by side and a floor for each stage: the arithmetic its counts need (:func:`floor_flops`,
the operation counts of the algorithms on the run's sizes) over the rate of a large matrix
product on one core (this machine's best case), for the contact at least the bytes of the
compliance it reads (:func:`contact_bytes`) at the rate of a cached read: times no
implementation of these algorithms can beat. Prints, never asserts times.
"""

import json
import os
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "20000"))
BASELINE = os.environ.get("FEWEAR_BASELINE_SOURCE", "/work/main")
HERE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Run in the measured tree's process: wraps the stages' entry points (present in both trees) to
# count their work, runs `fewear run`, writes the counts beside summary.json.
COUNTER = textwrap.dedent('''
    import json, sys
    import numpy as np
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.mbd.integrator import GeneralizedAlpha
    from fewear.mesh.ale import BoreMotion
    from fewear.wear import archard

    counts = dict(contact_solves=0, contact_iterations=0, active_nodes=0, bore_nodes=0,
                  dynamics_steps=0, dynamics_iterations=0, factorizations=0, dynamics_size=0,
                  ale_moves=0, ale_nonzeros=0, elastic_dofs=0, exponential_flops=0)
    def count(self, result):
        counts["contact_solves"] += 1
        counts["contact_iterations"] += result.newton_iterations
        counts["active_nodes"] += int(np.count_nonzero(result.pressure_Pa))
        counts["bore_nodes"] = result.pressure_Pa.size
        counts["elastic_dofs"] = self.solver.V.dofmap.index_map.size_global * 2
    solve = CondensedBushingContact.solve
    def counted_solve(self, *args, **kwargs):
        result = solve(self, *args, **kwargs)
        count(self, result)
        return result
    CondensedBushingContact.solve = counted_solve
    solve_run = getattr(CondensedBushingContact, "solve_run", None)
    if solve_run is not None:  # a tree that solves a cycle's load steps in one call
        def counted_solve_run(self, *args, **kwargs):
            results, refusal = solve_run(self, *args, **kwargs)
            for result in results:
                count(self, result)
            return results, refusal
        CondensedBushingContact.solve_run = counted_solve_run
    run = GeneralizedAlpha._run
    def counted_run(self, *args, **kwargs):
        before = self._counts.copy()
        out = run(self, *args, **kwargs)
        steps, _, iterations, factorizations, _ = self._counts - before
        counts["dynamics_steps"] += int(steps)
        counts["dynamics_iterations"] += int(iterations)
        counts["factorizations"] += int(factorizations)
        counts["dynamics_size"] = self.system.n_coordinates + self.system.n_constraints
        return out
    GeneralizedAlpha._run = counted_run
    move = BoreMotion._move
    def counted_move(self, bore):
        counts["ale_moves"] += 1
        counts["ale_nonzeros"] = int(self._operator.getInfo()["nz_used"])
        return move(self, bore)
    BoreMotion._move = counted_move
    expm = archard.expm
    def counted_expm(matrix):
        counts["exponential_flops"] += 7 * 2 * matrix.shape[0] ** 3
        return expm(matrix)
    archard.expm = counted_expm
    from fewear.cli import main
    status = main(sys.argv[1:])
    out = sys.argv[sys.argv.index("--out") + 1]
    with open(out + "/counts.json", "w") as file:
        json.dump(counts, file)
    sys.exit(status)
''')


# The kernels compiled (or loaded) before the timed run, wherever the tree keeps compile_kernels.
COMPILE = textwrap.dedent('''
    try:
        from fewear.kernels import compile_kernels
    except ImportError:
        from fewear.jit import compile_kernels
    compile_kernels()
''')


def run_rod(source: str, rod: str, tmp_path) -> dict:
    """summary.json's case of ``rod`` and the counts of a `fewear run` by the tree ``source``."""
    tag = "baseline" if source != HERE else "this"
    config = tmp_path / f"{rod}.toml"
    config.write_text(f'[wear_loop]\ntotal_cycles = {CYCLES}\nrod_models = ["{rod}"]\n')
    out = tmp_path / f"{tag}_{rod}"
    env = dict(os.environ, PYTHONPATH=source, OPENBLAS_NUM_THREADS="1")
    subprocess.run([sys.executable, "-c", COMPILE], env=env, check=True, cwd=tmp_path)
    subprocess.run([sys.executable, "-c", COUNTER, "run", "--config", str(config), "--out",
                    str(out), "--jobs", "1"], env=env, check=True, cwd=tmp_path,
                   stdout=subprocess.DEVNULL)
    case = json.loads((out / "summary.json").read_text())["cases"][rod]
    if "joints" in case:  # a summary by joint: the slider-crank's one worn joint
        (case,) = case["joints"].values()
    return dict(case, counts=json.loads((out / "counts.json").read_text()))


def matrix_product_rate() -> float:
    """flop/s of a 600 x 600 matrix product on one core (the best of five)."""
    a, b = np.random.default_rng(0).random((2, 600, 600))
    best = np.inf
    for _ in range(5):
        start = time.perf_counter()
        a @ b
        best = min(best, time.perf_counter() - start)
    return 2.0 * 600**3 / best


def read_rate() -> float:
    """bytes/s of reading a 2 MB array held in the caches (the best of twenty sums)."""
    values = np.random.default_rng(0).random(262144)
    best = np.inf
    for _ in range(20):
        start = time.perf_counter()
        values.sum()
        best = min(best, time.perf_counter() - start)
    return values.nbytes / best


def contact_bytes(case: dict) -> float:
    """The bytes of the bore compliance G each contact Newton iteration reads: the rows of the
    support (4 m rows of 2 n values: the displacement update) and the active block (2 m x 2 m,
    the bordered step), 8 bytes a value; G (2n x 2n) does not fit a core's L2."""
    c = case["counts"]
    n, m = c["bore_nodes"], c["active_nodes"] / max(c["contact_solves"], 1)
    return c["contact_iterations"] * 8 * (4 * m * 2 * n + (2 * m) ** 2)


def floor_flops(case: dict) -> dict:
    """The arithmetic (flop) of each counted stage. Contact: per Newton iteration on n bore
    nodes with m in contact, the nodal forces and normals (25 n), the bordered step's blocks
    (30 m^2) and LU ((2/3)(m + 2)^3), the displacement update from 4 m rows of G (16 m n), two
    line-search trials and the state's updates (36 n); per solve, the result's forces (25 n)
    and the pressure sensitivity's solve ((2/3) m^3). Dynamics: per Newton iteration the
    triangular solves (2 N^2) and a residual (at least 10 N), per factorisation (2/3) N^3 and
    the matrix (4 N^2), N unknowns and multipliers. ALE: per move one pass over the operator
    (2 nnz). Re-mesh: the stiffness's factorisation, nested dissection's N^1.5 for N
    elastic dofs on a 2D mesh. Wear: the linearised block step's matrix exponentials, six
    products and a solve of their size n (14 n^3, Pade 13 without squaring)."""
    c = case["counts"]
    solves = max(c["contact_solves"], 1)
    n, m = c["bore_nodes"], c["active_nodes"] / solves
    per_iteration = 25 * n + 30 * m**2 + (2 / 3) * (m + 2) ** 3 + 16 * m * n + 36 * n
    N = c["dynamics_size"]
    return {
        "contact": c["contact_iterations"] * per_iteration
        + c["contact_solves"] * (25 * n + (2 / 3) * m**3),
        "dynamics": c["dynamics_iterations"] * (2 * N**2 + 10 * N)
        + c["factorizations"] * ((2 / 3) * N**3 + 4 * N**2),
        "mesh": c["ale_moves"] * 2 * c["ale_nonzeros"]
        + case["remeshes"] * c["elastic_dofs"] ** 1.5,
        "wear": c["exponential_flops"],
    }


def test_stages_before_and_after_beside_the_floor(tmp_path):
    trees = {"this": HERE}
    if os.path.isdir(BASELINE) and os.path.realpath(BASELINE) != os.path.realpath(HERE):
        trees = {"baseline": BASELINE, **trees}
    rate, bandwidth = matrix_product_rate(), read_rate()
    print(f"\nfewear run, {CYCLES:,} cycles per rod, one process; floor at "
          f"{rate / 1e9:.1f} Gflop/s (a matrix product on one core) or, for the contact where "
          f"it is more, G's bytes at {bandwidth / 1e9:.1f} GB/s (a cached array's sum)")
    for rod in ("rigid", "flexible"):
        cases = {name: run_rod(source, rod, tmp_path) for name, source in trees.items()}
        this = cases["this"]
        floor = {stage: flops / rate for stage, flops in floor_flops(this).items()}
        floor["contact"] = max(floor["contact"], contact_bytes(this) / bandwidth)
        print(f"\n{rod} rod: stage      " + "".join(f"{name:>10s}" for name in cases)
              + "     floor")
        for stage in ("contact", "dynamics", "mesh", "wear"):
            times = "".join(f"{case['stage_wall_time_s'][stage]:9.1f}s" for case in
                            cases.values())
            print(f"  {stage:18s}{times}{floor[stage]:9.2f}s")
        print(f"  {'whole run':18s}" + "".join(f"{case['wall_time_s']:9.1f}s"
                                              for case in cases.values())
              + f"{sum(floor.values()):9.2f}s")
        for name, case in cases.items():
            c = case["counts"]
            print(f"  {name}: {c['contact_solves']:,} contact solves, "
                  f"{c['contact_iterations'] / max(c['contact_solves'], 1):.2f} Newton "
                  f"iterations and {c['active_nodes'] / max(c['contact_solves'], 1):.1f} of "
                  f"{c['bore_nodes']} nodes in contact per solve; {c['dynamics_steps']:,} "
                  f"dynamics steps, {c['dynamics_iterations']:,} Newton iterations, "
                  f"{c['factorizations']:,} factorisations (N = {c['dynamics_size']}); "
                  f"{c['ale_moves']} ALE moves, {case['remeshes']} re-meshes; max depth "
                  f"{case['max_wear_depth_m']:.4e} m")
