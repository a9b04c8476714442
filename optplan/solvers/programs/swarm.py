"""Every registered metaheuristic as a program solver: the program's batched view,
the feasibility rule (or a penalty) and the engine's exact evaluation budget."""
from __future__ import annotations

import time

import numpy as np

from ...checks import anything, choice, integer, number, seed
from ...formulations.program import Option, ProgramSolver
from ..metaheuristics import get_algorithm, optimize
from .common import INIT_OPTION, result_of, start_vector

DEFAULT_ITERS = 500


class SwarmSolver(ProgramSolver):
    """A population metaheuristic on the program's batched view."""

    capabilities = frozenset({"stochastic", "population"})
    options = {
        "pop": Option(30, integer(2), "population size"),
        "iters": Option(None, integer(0, optional=True), f"iteration budget (default {DEFAULT_ITERS} when "
                                                          "max_evals is not given)"),
        "max_evals": Option(None, integer(1, optional=True), "evaluation budget: exactly this many rows evaluated"),
        "seed": Option(0, seed, "int, None or numpy Generator"),
        "constraint": Option("feasibility", choice("feasibility", "penalty"),
                             "feasibility rule (feasible first, then violation, then cost) or cost + penalty * violation "
                             "(a constraint's own paper penalty where it has one)"),
        "penalty": Option(1000.0, number(0.0), "weight of the violation in penalty mode"),
        "init": INIT_OPTION,
        "progress": Option(False, choice(False, True), "print progress to stderr"),
        "stagnation": Option(None, integer(1, optional=True), "stop after this many iterations without improvement"),
        "start": Option("variables", choice("variables", "algorithm"),
                        "first population: the variables' own starts (e.g. collision-free column nodes) or the "
                        "algorithm's own initialiser (e.g. MISSA's chaotic map)"),
        "archive_every": Option(None, integer(1, optional=True),
                                "keep the population every that many iterations (OptimizeResult.archive)"),
        "target": Option(None, number(optional=True), "stop once the best feasible cost is <= target"),
        "callback": Option(None, anything, "callback(state) after each iteration; return False to stop"),
        "budget": Option(None, anything, "an optplan Budget (iterations, evaluations, stagnation, target) instead "
                                         "of iters/max_evals/stagnation/target"),
    }

    def __init__(self, algorithm: str, **settings) -> None:
        self.algorithm = get_algorithm(algorithm)
        self.name = self.algorithm.name
        super().__init__(**settings)

    def all_options(self):
        out = dict(self.options)
        for k, v in self.algorithm.defaults().items():
            out.setdefault(k, Option(v, anything, f"{self.name}'s own parameter (its class lists the paper default)"))
        return out

    def search(self, program, **options):
        """The engine's run on the program (options checked like :meth:`solve`): the raw
        :class:`~optplan.results.OptimizeResult`, archive included. ``op.plan`` uses it."""
        opts = {k: o.default for k, o in self.all_options().items()}
        opts.update(self.settings)
        opts.update(self.check_options(options))
        return self._search(program, opts)

    def run(self, program, **o):
        t0 = time.perf_counter()
        opt = self._search(program, o)
        return result_of(program, program.variables, opt.x, self.name, opt.status, opt.message, opt.nfev, t0,
                         seed=o["seed"], history=opt.history)

    def _search(self, program, o):
        variables = program.variables
        own = {k: o[k] for k in self.algorithm.defaults() if k in o}
        iters, max_evals = o["iters"], o["max_evals"]
        if iters is None and max_evals is None and o["budget"] is None:
            iters = DEFAULT_ITERS
        x0 = start_vector(program, variables, o["init"])
        clearance = program.clearance

        def initial(n, rng):
            X = variables.initial_population(n, rng, clearance)
            if X is None:
                X = variables.lower + rng.random((n, variables.dim)) * (variables.upper - variables.lower)
            if x0 is not None:
                X[0] = x0
            return X

        penalty = o["penalty"]
        if o["constraint"] == "feasibility":
            f = program.population
        else:  # the program's penalty: the paper's where a constraint carries one, else penalty * violation
            def f(X):
                return program.penalised(X, penalty)
        init = initial if o["start"] == "variables" or x0 is not None else None
        return optimize(f, np.stack([variables.lower, variables.upper], axis=1), algorithm=self.name, pop=o["pop"],
                        iters=iters, max_evals=max_evals, seed=o["seed"], init=init, repair=variables.repair,
                        progress=o["progress"], stagnation=o["stagnation"], archive_every=o["archive_every"],
                        target=o["target"], callback=o["callback"], budget=o["budget"], **own)
