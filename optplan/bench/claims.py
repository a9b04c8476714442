"""The papers' quantitative claims, judged against our runs.

Each :class:`Claim` quotes one statement of a paper with the table or figure it comes from,
names the shipped spec whose runs judge it, and says what is compared. The verdict is
computed from the stored runs, never written by hand:

* ``less`` — group ``better`` has a lower mean ``metric`` than group ``other`` (the paper's
  reduction ``claimed``, a fraction, or ``None`` for a direction only). Our figure is the
  reduction of the mean with a 95 % bootstrap interval (seeded, so it repeats) and the
  two-sided rank-sum p-value (a one-sample signed-rank test when ``other`` is a single
  deterministic run, e.g. A*). Verdict: ``not significant`` when p >= alpha; ``reversed``
  when significant the other way; ``weaker`` when the interval lies below the claimed
  reduction; else ``holds``.
* ``less_spread`` — group ``better`` has a smaller spread (variance / standard deviation)
  of ``metric``: our figure is the ratio of standard deviations and Levene's test
  (median-centred) p-value; verdicts as for ``less`` (no claimed size).
* ``fails`` — the share of ``better``'s runs that succeed is at most ``claimed`` (a method the
  paper shows failing): ``holds`` when the Wilson interval reaches down to it, ``weaker`` when
  some runs fail, ``reversed`` when none does.
* ``rate`` — the share of ``better``'s runs that succeed (feasible path; goal reached without
  collision) is at least ``claimed``. Our figure is the share with its Wilson 95 % interval.
  Verdict: ``holds`` when the interval reaches the claimed share, ``weaker`` when it lies
  below it but some runs succeed, ``reversed`` when none do.

* ``less_best`` / ``less_worst`` — the best (lowest) / worst (highest) run of ``better`` is lower
  than that of ``other`` (the papers' "best length 3.60 % below ACO's", "the longest path is 9.35 %
  shorter"; lower is better, as for ``less``: a claim that a larger value wins swaps the groups).
  Our figure is the reduction of the best (worst) values with a 95 % bootstrap interval (each group
  resampled, its minimum (maximum) taken), the lead, and the p-value of an exact precedence test.
  The lead counts the runs of the group that leads lying beyond the other group's extreme
  (``+k``: ``k`` runs of ``better`` below ``other``'s best, or ``k`` runs of ``other`` above
  ``better``'s worst; ``-k`` the other way). Under the null (both groups drawn from one
  distribution, the runs' labels exchangeable) the chance that the ``k`` most extreme of the
  ``N = n + m`` pooled runs all belong to one group is ``C(n, k) / C(N, k)``; the two-sided p adds
  both groups' terms. Why not the bootstrap alone: the minimum of a resample is one of the few
  lowest runs, so a bootstrap "support" only restates how many runs lead, with no calibrated null;
  the precedence test turns that same count into a p-value (with tied extremes the lead counts
  strictly beyond, which keeps the p conservative). Verdicts as for ``less`` (``weaker``: the
  interval lies below the claimed reduction).
* ``tie`` — the groups are equally good (chen2025 Table 7's "=", "equally accurate"): an
  equivalence test, two one-sided tests at ``alpha`` with the margin ``tol``, done as the
  ``1 - 2 alpha`` bootstrap interval of the difference of the means lying inside ``[-tol, tol]``.
  ``tie_best``: the same on the difference of the best values (the two groups "reach the same
  best"). The margin is never fitted to the data: for a benchmark function it is
  :data:`FUNCTION_TOL` (errors below 1e-8 count as the optimum, the convention of the CEC
  benchmark suites, the reporting standard for F1-F18-type functions); elsewhere the claim names
  it (:data:`PRINTED_LENGTH_TOL`: half a unit of the paper's last printed digit, so "the same value"
  is the same value as printed). Verdict: ``holds`` when the interval lies inside the margin;
  ``reversed`` (the groups differ) when the rank-sum test (the precedence test for ``tie_best``) is
  significant and the 95 % interval lies wholly outside the margin; else ``not significant``
  (neither equality nor a difference is shown). Chen2025's own "=" means the rank-sum test found no
  difference (p NaN: both samples the same); a failed test is no evidence of equality, hence the
  equivalence test.
* ``reaches`` — at least ``claimed`` of ``better``'s runs end within ``tol`` (default
  :data:`FUNCTION_TOL`) of the function's known optimum (``metric`` ``f_error``, the stored error):
  judged as ``rate`` is, on the runs that reach it.
* ``printed`` — group ``better``'s mean ``metric`` is the value the paper printed (chen2025 Tables 4-6:
  each algorithm's mean on each function, with its standard deviation over 20 runs; ``printed``
  holds them, :class:`Printed`). Both sides are samples, so the test is Welch's, from our runs and
  the printed mean, standard deviation and run count. It is an equivalence test as ``tie`` is, with
  the margin :func:`printed_margin`: the largest of :data:`FUNCTION_TOL` (both within it of each
  other count as the same value, the CEC convention), half a unit of the last printed digit (the
  printed value's own rounding) and :data:`PRINTED_REL` of the printed distance to the optimum (a
  reproduction that lands within a tenth of the paper's error). Verdict: ``holds`` when the 90 %
  Welch interval of the difference lies inside the margin; ``reversed`` (ours is another value;
  the figure says whether lower or higher) when Welch's p < alpha and the 95 % interval lies
  wholly outside it; else ``not significant``.
* ``misses`` — at most ``claimed`` (``None``: none) of ``better``'s runs end within ``tol`` of the
  function's optimum (a paper's "still clearly different from the theoretical optimum"): judged as
  ``fails`` is, on the runs that reach it, with the tolerance of ``reaches``.
* ``trend`` — the mean ``metric`` of group ``better`` grows along the claim's ordered ``targets``
  (the papers' "path length grows with the number of obstacles"; a claim that it shrinks lists the
  targets the other way round, as a claim that a larger value wins swaps the groups of ``less``).
  A spec runs the same seeds on every target, and a seed fixes the global path and the world's
  draws, so the runs are compared within their seed: the test is the rank correlation between each
  run's target position and its value, both ranked within the seed (Page's test for ordered
  alternatives; a seed that failed on some targets adds its others), with a two-sided permutation
  p-value, the targets dealt anew within each seed: exact over every deal when there are at most
  :data:`TREND_EXACT`, else from :data:`PERMUTATIONS` seeded random deals (so a verdict repeats).
  Why within seeds: the spread between seeds (another global path) can dwarf the change between
  targets that every seed shows. Why ranks: the targets are ordered categories (0-3 obstacles,
  2-5 movers) with no scale between them. Our figure: the mean per target in order, the relative
  change of the mean from the first target to the last with a 95 % bootstrap interval (seeds
  resampled), rho and p. Verdicts as for ``less``: ``reversed`` when significant the other way,
  ``weaker`` when the interval lies below the claimed change (``claimed``: the paper's relative
  change first to last, or ``None``).
* ``lead_trend`` — group ``better``'s lead over ``other`` grows along the claim's ordered ``targets``
  (li2023: "the gains over TGA grow with the map size"; a lead claimed to shrink lists the targets the
  other way round, as for ``trend``). The lead at a target is the reduction of the mean,
  ``1 - mean(better) / mean(other)`` (:func:`_drop`, ``less``'s figure). Our figure: the reduction per
  target in order, its change from the first target to the last (percentage points) with a 95 %
  bootstrap interval, and the p of a studentised bootstrap (bootstrap-t) of that change: the runs of
  each group at the first and the last target are resampled on their own (different maps: no seed pairs
  runs across targets), each resample's change is standardised by its delta-method standard error, and p
  is the share of resamples at least as far out as the observed change (the plain percentile bootstrap
  gave 7-9 % false positives at alpha 0.05 with 10-20 skewed runs a group, the bootstrap-t 4-7 %). A
  group with one run, or with identical repeats (A*, deterministic), resamples to itself and has no
  variance: its mean is exact and the spread comes from the stochastic group alone. (A permutation test
  of the group x target interaction is not sound there: it would deal A*'s one value, or its identical
  copies, as exchangeable draws; a rank test of the runs scaled by A* is not either: it compares the
  shapes of distributions whose spread changes with the map, not the means the lead is made of.) The
  middle targets are printed, not tested. Verdicts as for ``trend``: ``reversed`` when the lead
  significantly shrinks, ``weaker`` when the interval lies below ``claimed`` (the paper's change of the
  reduction first to last, a fraction), ``too few runs`` when the first or last target's comparison
  could never reach alpha in ``less``'s test.
* ``all`` / ``most`` / ``net`` — a statement that sums up others ("MISSA beats the other three in length,
  rotation and run time", "in most functions", a tally of wins and losses), judged as a combination of
  the claims that judge its parts (``parts``, claims of the same spec; build it with
  :func:`combined_claim`; the claims table prints the parts' verdicts counted, e.g. ``4/6 hold``). A part
  *supports* the combination when it holds or is weaker (significant in the claimed direction), *opposes*
  it when reversed, is *open* when not significant and *unknown* without a verdict (not run, too few
  runs). The verdict is what the parts prove whatever the open and unknown ones would turn out to be:
  ``all`` holds when every part holds and is reversed when any part is; ``most`` holds when more than
  half of the parts hold and is reversed when at least half are reversed (then at most half can hold);
  ``net``, the direction of a tally (chen2025 Table 7's wins / ties / losses, open parts being ties),
  holds when the supporting parts (wins) outnumber the reversed ones (losses) and the unknown ones
  together, and is reversed when the losses outnumber the wins and the unknown ones. A combination
  proved only by counting weaker parts as holding is ``weaker``; one left undecided is ``not
  significant``, or ``not run`` / ``too few runs`` when unknown parts leave it undecided. Parts on run
  time make a combination of their own (the docs' tables do not compare run-time rows).

When the numbers of runs could never give a p-value below alpha (a ``--quick`` run: 3 against 3
runs, the smallest rank-sum p is 0.1, as is the smallest precedence p; one seed on each of four
targets, the smallest trend p is 2/24), a ``less``, ``less_best``, ``less_worst``, ``tie``, ``tie_best``,
``trend`` or ``lead_trend`` claim gets ``too few runs``, not a verdict.
A claim whose groups or target the spec does not hold (a quick run on fewer maps, a missing
baseline) is listed as ``not run``, so every claim is always shown.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Mapping

import numpy as np

from ..local.presets import OUR_CHANGES, PRINTED
from .tables import Table

# "too few runs": the runs' sizes could never reach alpha (3 against 3: the smallest p is 0.1)
TOO_FEW_RUNS = "too few runs"
VERDICTS = ("holds", "weaker", "not significant", "reversed", "too few runs", "not run")
BOOTSTRAP = 2000
# a trend's p-value is exact (every way of dealing the runs to the targets) up to this many ways,
# else it is estimated from this many seeded random ones (resolution about 0.003 at p = 0.05)
TREND_EXACT = 20000
PERMUTATIONS = 20000
# an error to a benchmark function's known optimum below this counts as reaching it (the CEC
# benchmark suites' convention); the margin of ``tie`` claims on function values
FUNCTION_TOL = 1e-8
# chen2025 Tables 8-11 print lengths to 4 decimals: lengths closer than half the last digit print alike
PRINTED_LENGTH_TOL = 5e-5
# a reproduced mean counts as the printed one within this share of the printed distance to the optimum
PRINTED_REL = 0.1
# kinds judged on the share of one group's runs (their id names no other group and no metric)
SHARE_KINDS = ("rate", "fails", "reaches", "misses")
# kinds judged along several ordered targets (their id names the targets in order)
ORDERED_KINDS = ("trend", "lead_trend")
# kinds judged as a combination of other claims, their parts
COMBINED_KINDS = ("all", "most", "net")


@dataclass(frozen=True)
class Printed:
    """A paper's printed summary of one group's runs (kind ``printed``).

    Attributes:
        text: the mean as printed (its digits fix the rounding unit).
        sd: the printed standard deviation.
        runs: the number of runs the paper's statistics are over.
        optimum: the function's known optimum (the margin scales with the printed distance to it).
    """

    text: str
    sd: float
    runs: int
    optimum: float

    @property
    def mean(self) -> float:
        return float(self.text)

    @property
    def unit(self) -> float:
        """The unit of the last printed digit of the mean (0 for a printed exact 0)."""
        mantissa, _, exp = self.text.lower().partition("e")
        decimals = len(mantissa.partition(".")[2])
        return 0.0 if self.mean == 0 else 10.0 ** (int(exp or 0) - decimals)


@dataclass(frozen=True)
class Claim:
    """One quantitative statement of a paper.

    Attributes:
        spec: name of the shipped spec whose runs judge it.
        source: where the paper says it (table / figure / section).
        quote: the statement, in short.
        target: the map or scenario it is about.
        kind: ``less``, ``less_spread``, ``less_best``, ``less_worst``, ``tie``, ``tie_best``,
            ``rate``, ``fails``, ``reaches``, ``misses``, ``printed``, ``trend``, ``lead_trend``, or a
            combination ``all``,
            ``most``, ``net`` (module docstring).
        better: the group label the paper says is better (or that succeeds, for ``rate``).
        other: the group it is compared with (every kind but the shares).
        metric: the stored metric (``length``, ``runtime_s``, ``turn_angle_deg``, ``n_turns``,
            ``time_s``, ``f``, ``f_error``, ...); ``rate`` and ``fails`` ignore it.
        claimed: the paper's reduction (fraction) or success share; ``None``: direction only.
        note: what the reader should know (e.g. timings on a shared machine).
        tol: the margin of ``tie`` / ``tie_best`` and the distance to the optimum ``reaches``
            accepts; ``None``: :data:`FUNCTION_TOL` on a benchmark function (required elsewhere).
        targets: a ``trend``'s (``lead_trend``'s) targets in the order its metric (its lead) is claimed
            to grow along (``target`` is then the first of them, so that code reading one target still
            names a real one); empty for every other kind. Build a trend with :func:`trend_claim`, a lead
            trend with :func:`lead_trend_claim`.
        parts: a combination's claims (``all``, ``most``, ``net``), all of the same spec; empty for every
            other kind. Build one with :func:`combined_claim`, which labels its target, groups and
            metric after its parts.
        printed: a ``printed`` claim's printed mean and spread (:class:`Printed`); ``None`` for every
            other kind.
    """

    spec: str
    source: str
    quote: str
    target: str
    kind: str
    better: str
    other: str | None = None
    metric: str = "length"
    claimed: float | None = None
    note: str = ""
    tol: float | None = None
    targets: tuple[str, ...] = ()
    parts: tuple["Claim", ...] = ()
    printed: Printed | None = None

    def __post_init__(self) -> None:
        # a trend judges several targets, every other kind one: catch a half-built claim early
        if self.kind in ORDERED_KINDS:
            lead = self.kind == "lead_trend"
            if (len(self.targets) < 2 or len(set(self.targets)) != len(self.targets)
                    or self.target != self.targets[0] or (self.other is not None) != lead):
                raise ValueError(f"a {self.kind} claim needs two or more distinct targets, the first as its target, "
                                 f"and {'an' if lead else 'no'} other group: {self.targets!r}, {self.target!r}, "
                                 f"{self.other!r}")
        elif self.targets:
            raise ValueError(f"only a trend or lead_trend claim names several targets, not a {self.kind} claim")
        if (self.kind in COMBINED_KINDS) != bool(self.parts):
            raise ValueError(f"a combination ({', '.join(COMBINED_KINDS)}) and only a combination names parts: "
                             f"a {self.kind} claim with {len(self.parts)}")
        if (self.kind == "printed") != (self.printed is not None) or (self.printed and self.other is not None):
            raise ValueError(f"a printed claim and only a printed claim names the printed value, and no other group: "
                             f"a {self.kind} claim with {self.printed!r}, other {self.other!r}")
        if any(p.spec != self.spec for p in self.parts):
            raise ValueError(f"a combination's parts are judged on its own spec {self.spec}, not on "
                             f"{sorted({p.spec for p in self.parts} - {self.spec})}")

    @property
    def id(self) -> str:
        """The claim's stable name, made of what the verdict is computed from (spec, target, kind,
        groups, metric; never the quote or the claimed size): ``spec:target:kind:better`` for a
        share (``rate``, ``fails``, ``reaches``), ``spec:target:kind:better:other:metric`` for a
        comparison, ``spec:t1>t2>...:trend:better:metric`` for a trend (its targets in order),
        ``spec:t1>t2>...:lead_trend:better:other:metric`` for a lead trend; a combination's is a
        comparison's, made of the labels :func:`combined_claim` gives it after its parts. The
        inventory of the papers' statements (:mod:`.claim_inventory`) names claims by it."""
        if self.kind == "trend":
            return ":".join([self.spec, ">".join(self.targets), self.kind, self.better, self.metric])
        if self.kind == "lead_trend":
            return ":".join([self.spec, ">".join(self.targets), self.kind, self.better, str(self.other), self.metric])
        if self.kind == "printed":
            return ":".join([self.spec, self.target, self.kind, self.better, self.metric])
        parts = [self.spec, self.target, self.kind, self.better]
        if self.kind not in SHARE_KINDS:
            parts += [str(self.other), self.metric]
        return ":".join(parts)


def trend_claim(spec: str, source: str, quote: str, targets: Iterable[str], better: str, metric: str,
                claimed: float | None = None, note: str = "") -> Claim:
    """A ``trend`` claim: ``better``'s mean ``metric`` grows along ``targets`` (in that order);
    ``claimed`` is the paper's relative change from the first target to the last."""
    targets = tuple(targets)
    return Claim(spec, source, quote, targets[0] if targets else "", "trend", better, None, metric, claimed, note,
                 targets=targets)


def lead_trend_claim(spec: str, source: str, quote: str, targets: Iterable[str], better: str, other: str,
                     metric: str, claimed: float | None = None, note: str = "") -> Claim:
    """A ``lead_trend`` claim: ``better``'s lead over ``other`` (the reduction of the mean ``metric``)
    grows along ``targets`` (in that order); ``claimed`` is the paper's change of that reduction from
    the first target to the last (a fraction: 0.072 for 1.4 % -> 8.6 %)."""
    targets = tuple(targets)
    return Claim(spec, source, quote, targets[0] if targets else "", "lead_trend", better, other, metric, claimed,
                 note, targets=targets)


def _label(items: Iterable[str | None]) -> str:
    """The distinct non-empty ``items`` in their order, joined by ``+``."""
    return "+".join(dict.fromkeys(i for i in items if i))


def combined_claim(kind: str, source: str, quote: str, parts: Iterable[Claim], target: str | None = None,
                   note: str = "") -> Claim:
    """A combination (``all``, ``most`` or ``net``, module docstring) of the claims ``parts``, all of one
    spec. Its target, groups and metric are labels made of its parts' (their distinct values joined by
    ``+``; ``target`` overrides the target's, e.g. ``F1-F18``), so its id says what it combines. Parts on
    run time are not mixed with others: such a combination is a run-time row of its own, which the
    docs' tables do not compare."""
    parts = tuple(parts)
    if kind not in COMBINED_KINDS or not parts:
        raise ValueError(f"a combination is one of {', '.join(COMBINED_KINDS)} over one or more parts, "
                         f"not a {kind} claim of {len(parts)}")
    compared = [p for p in parts if p.kind not in SHARE_KINDS]
    if len({p.metric == "runtime_s" for p in compared}) > 1:
        raise ValueError(f"{quote!r}: parts on run time make a combination of their own (its row is not "
                         "compared in the docs' tables)")
    return Claim(parts[0].spec, source, quote, target or _label(t for p in parts for t in (p.targets or (p.target,))),
                 kind, _label(p.better for p in parts), _label(p.other for p in compared) or None,
                 _label(p.metric for p in compared) or "share", note=note, parts=parts)


def target_text(claim: Claim) -> str:
    """The claim's target as the tables show it: a trend's targets in order, ``a -> b -> c``; a
    combination's label."""
    return " -> ".join(claim.targets) if claim.targets else claim.target


def _drop(ma: float, mb: float) -> float:
    """How much lower ``ma`` is than ``mb``, relative to ``|mb|``: ``1 - ma / mb`` for positive
    values, and still positive when ``ma`` is lower for negative ones (functions whose optimum is
    below zero: F8, F17, F18)."""
    if ma == mb:   # equal, including both exactly 0 (every run at the optimum)
        return 0.0
    return float((mb - ma) / abs(mb)) if mb != 0 else float(np.sign(mb - ma) * np.inf)


def _reduction(a: np.ndarray, b: np.ndarray) -> float:
    """How much lower the mean of ``a`` is than that of ``b`` (:func:`_drop`)."""
    return _drop(a.mean(), b.mean())


def _bootstrap_reduction(a: np.ndarray, b: np.ndarray, seed: int = 0) -> tuple[float, float]:
    """95 % percentile interval of :func:`_reduction` (vectorised resampling)."""
    rng = np.random.default_rng(seed)
    ia = rng.integers(0, len(a), size=(BOOTSTRAP, len(a)))
    ib = rng.integers(0, len(b), size=(BOOTSTRAP, len(b)))
    ma, mb = a[ia].mean(axis=1), b[ib].mean(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(ma == mb, 0.0, (mb - ma) / np.abs(mb))
    return float(np.percentile(r, 2.5)), float(np.percentile(r, 97.5))


def _verdict(p: float, alpha: float, same_direction: bool, smaller_than_claimed: bool = False) -> str:
    """The verdict of a test with p-value ``p``: not significant, reversed (the effect goes the
    other way), weaker (the interval lies below the claimed size) or holds."""
    if not np.isfinite(p) or p >= alpha:
        return "not significant"
    if not same_direction:
        return "reversed"
    return "weaker" if smaller_than_claimed else "holds"


def judge_less(a, b, claimed: float | None, alpha: float = 0.05) -> tuple[str, str]:
    """``(our figure, verdict)`` of "``a`` is lower than ``b`` by ``claimed``" (see module doc)."""
    from scipy.stats import wilcoxon

    from .stats import ranksum_p, smallest_p

    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) < 2 or len(b) < 1:
        return f"{len(a)} and {len(b)} runs", "not run"
    red = _reduction(a, b)
    if len(b) == 1:   # a deterministic reference (A*): one-sample signed-rank test
        diff = a - b[0]
        p = 1.0 if np.all(diff == 0) else float(wilcoxon(diff, alternative="two-sided").pvalue)
        lo, hi = _bootstrap_reduction(a, np.repeat(b, 2))
        floor = 2.0 / 2 ** len(a)   # the smallest two-sided p of the signed-rank test
    else:
        p = ranksum_p(a, b)
        lo, hi = _bootstrap_reduction(a, b)
        floor = smallest_p(len(a), len(b))
    figure = f"{100 * red:+.1f} % [{100 * lo:+.1f}, {100 * hi:+.1f}], p={p:.2g}"
    if floor >= alpha:   # e.g. a --quick run: no outcome could be significant, so no verdict
        return figure, TOO_FEW_RUNS
    return figure, _verdict(p, alpha, red >= 0, claimed is not None and hi < claimed)


def judge_less_spread(a, b, alpha: float = 0.05) -> tuple[str, str]:
    """``(our figure, verdict)`` of "``a`` varies less than ``b``" (Levene's test)."""
    from scipy.stats import levene

    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) < 2 or len(b) < 2:
        return f"{len(a)} and {len(b)} runs", "not run"
    sa, sb = a.std(), b.std()
    p = 1.0 if sa == sb == 0 else float(levene(a, b, center="median").pvalue)
    ratio = sa / sb if sb > 0 else float("inf")
    figure = f"std {sa:.3g} vs {sb:.3g} (ratio {ratio:.2f}), p={p:.2g}"
    return figure, _verdict(p, alpha, sa < sb)


def judge_rate(successes: int, runs: int, claimed: float) -> tuple[str, str]:
    """``(our figure, verdict)`` of "at least ``claimed`` of the runs succeed"."""
    from .stats import wilson_interval

    if runs == 0:
        return "0 runs", "not run"
    lo, hi = wilson_interval(successes, runs)
    figure = f"{successes}/{runs} [{100 * lo:.0f}-{100 * hi:.0f} %]"
    if hi >= claimed - 1e-9:   # the interval's upper end is 1 up to rounding at all successes
        return figure, "holds"
    return figure, "weaker" if successes else "reversed"


def judge_fails(successes: int, runs: int, claimed: float) -> tuple[str, str]:
    """``(our figure, verdict)`` of "at most ``claimed`` of the runs succeed" (a method the paper
    shows failing): holds when the Wilson interval reaches down to ``claimed``, weaker when some
    runs fail but fewer than that, reversed when none fails."""
    from .stats import wilson_interval

    if runs == 0:
        return "0 runs", "not run"
    lo, hi = wilson_interval(successes, runs)
    figure = f"{successes}/{runs} succeed [{100 * lo:.0f}-{100 * hi:.0f} %]"
    if lo <= claimed + 1e-9:
        return figure, "holds"
    return figure, "weaker" if successes < runs else "reversed"


def _resampled(a: np.ndarray, b: np.ndarray, stat: str, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """``stat`` (``mean``, ``min`` or ``max``) of :data:`BOOTSTRAP` resamples of each group (seeded,
    so a verdict repeats)."""
    rng = np.random.default_rng(seed)
    ia = rng.integers(0, len(a), size=(BOOTSTRAP, len(a)))
    ib = rng.integers(0, len(b), size=(BOOTSTRAP, len(b)))
    f = getattr(np, stat)
    return f(a[ia], axis=1), f(b[ib], axis=1)


def precedence_p(a, b, worst: bool = False) -> tuple[float, int]:
    """``(p, lead)``: the exact two-sided precedence test of "the best (``worst``: the worst) run
    of ``a`` is lower than that of ``b``".

    ``lead`` is ``+k`` when ``k`` runs of ``a`` lie strictly below every run of ``b`` (``worst``:
    ``k`` runs of ``b`` strictly above every run of ``a``), ``-k`` when it goes the other way, 0
    when the extremes are equal. With the runs' group labels exchangeable (no difference), the
    ``k`` most extreme of the ``N`` pooled runs all fall in one group with chance
    ``(C(n, k) + C(m, k)) / C(N, k)`` summed over both groups, the p-value. Counting strictly
    beyond the other's extreme keeps it conservative when runs tie."""
    import math

    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) == 0 or len(b) == 0:
        return float("nan"), 0
    if worst:
        for_a, for_b = int((b > a.max()).sum()), int((a > b.max()).sum())
    else:
        for_a, for_b = int((a < b.min()).sum()), int((b < a.min()).sum())
    k = max(for_a, for_b)
    if k == 0:
        return 1.0, 0
    n, m = len(a), len(b)
    p = (math.comb(n, k) + math.comb(m, k)) / math.comb(n + m, k)
    return min(1.0, p), for_a - for_b


def smallest_precedence_p(n: int, m: int) -> float:
    """The smallest p :func:`precedence_p` can give with ``n`` against ``m`` runs (the larger group
    wholly beyond the other's extreme); 0.1 for 3 against 3, as for the rank-sum test."""
    import math

    if n <= 0 or m <= 0:
        return 1.0
    k = max(n, m)
    return min(1.0, (math.comb(n, k) + math.comb(m, k)) / math.comb(n + m, k))


def _lead_text(lead: int) -> str:
    return f"lead {lead:+d} run{'s' if abs(lead) != 1 else ''}"


def judge_less_extreme(a, b, claimed: float | None, alpha: float = 0.05, worst: bool = False) -> tuple[str, str]:
    """``(our figure, verdict)`` of "the best (``worst``: the worst) run of ``a`` is lower than
    that of ``b`` by ``claimed``" (kinds ``less_best`` / ``less_worst``, module docstring)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) < 2 or len(b) < 2:
        return f"{len(a)} and {len(b)} runs", "not run"
    stat = "max" if worst else "min"
    red = _drop(getattr(a, stat)(), getattr(b, stat)())
    sa, sb = _resampled(a, b, stat)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(sa == sb, 0.0, (sb - sa) / np.abs(sb))
    lo, hi = float(np.percentile(r, 2.5)), float(np.percentile(r, 97.5))
    p, lead = precedence_p(a, b, worst)
    figure = f"{100 * red:+.1f} % [{100 * lo:+.1f}, {100 * hi:+.1f}], {_lead_text(lead)}, p={p:.2g}"
    if smallest_precedence_p(len(a), len(b)) >= alpha:
        return figure, TOO_FEW_RUNS
    return figure, _verdict(p, alpha, lead > 0, claimed is not None and hi < claimed)


def judge_tie(a, b, tol: float, alpha: float = 0.05, best: bool = False) -> tuple[str, str]:
    """``(our figure, verdict)`` of "``a`` and ``b`` are equally good" (kind ``tie``: their means;
    ``best``: their best runs, kind ``tie_best``) within the margin ``tol`` (module docstring)."""
    from .stats import ranksum_p, smallest_p

    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) < 2 or len(b) < 2:
        return f"{len(a)} and {len(b)} runs", "not run"
    stat = "min" if best else "mean"
    diff = float(getattr(a, stat)() - getattr(b, stat)())
    sa, sb = _resampled(a, b, stat)
    d = sa - sb
    lo, hi = np.percentile(d, [100 * alpha, 100 * (1 - alpha)])                # the two one-sided tests
    lo2, hi2 = np.percentile(d, [100 * alpha / 2, 100 * (1 - alpha / 2)])      # the two-sided interval
    if best:
        p, floor = precedence_p(a, b)[0], smallest_precedence_p(len(a), len(b))
    else:
        p, floor = ranksum_p(a, b), smallest_p(len(a), len(b))
    figure = (f"{'best' if best else 'mean'} diff {diff:+.2g} [{100 * (1 - 2 * alpha):.0f} %: {lo:+.2g}, "
              f"{hi:+.2g}] vs margin {tol:.2g}, p={p:.2g}")
    if floor >= alpha:
        return figure, TOO_FEW_RUNS
    if -tol <= lo and hi <= tol:
        return figure, "holds"
    if np.isfinite(p) and p < alpha and (lo2 > tol or hi2 < -tol):
        return figure, "reversed"
    return figure, "not significant"


def printed_margin(printed: Printed) -> float:
    """The margin within which a reproduced mean is the printed one (module docstring, ``printed``)."""
    return max(FUNCTION_TOL, printed.unit / 2, PRINTED_REL * abs(printed.mean - printed.optimum))


def judge_printed(values, printed: Printed, alpha: float = 0.05) -> tuple[str, str]:
    """``(our figure, verdict)`` of "the mean of these runs is the printed one": Welch's equivalence
    test against the printed mean, standard deviation and run count (module docstring)."""
    from scipy.stats import t as student

    a = np.asarray(values, float)
    if len(a) < 2:
        return f"{len(a)} runs", "not run"
    margin = printed_margin(printed)
    diff = float(a.mean() - printed.mean)
    # Welch's degrees of freedom square the variances: in units of the largest value involved they
    # neither underflow (1e-130 squared twice) nor overflow
    scale = max(float(np.abs(a).max()), abs(printed.mean), printed.sd) or 1.0
    va, vp = (a / scale).var(ddof=1) / len(a), (printed.sd / scale) ** 2 / printed.runs
    se = float(np.sqrt(va + vp)) * scale
    if se > 0:
        df = (va + vp) ** 2 / (va ** 2 / (len(a) - 1) + vp ** 2 / (printed.runs - 1))
        lo, hi = diff + np.array([-1, 1]) * student.ppf(1 - alpha, df) * se
        lo2, hi2 = diff + np.array([-1, 1]) * student.ppf(1 - alpha / 2, df) * se
        p = float(2 * student.sf(abs(diff) / se, df))
    else:   # no spread on either side (or below what floats resolve): the difference is exact
        lo = lo2 = hi = hi2 = diff
        p = 1.0 if diff == 0 else 0.0
    side = "" if abs(diff) <= margin else (", ours lower" if diff < 0 else ", ours higher")
    figure = (f"mean {a.mean():.5g} vs {printed.text}: diff {diff:+.2g} [{100 * (1 - 2 * alpha):.0f} %: {lo:+.2g}, "
              f"{hi:+.2g}] vs margin {margin:.2g}, p={p:.2g}{side}")
    if -margin <= lo and hi <= margin:
        return figure, "holds"
    if p < alpha and (lo2 > margin or hi2 < -margin):
        return figure, "reversed"
    return figure, "not significant"


def judge_reaches(errors, runs: int, tol: float, claimed: float) -> tuple[str, str]:
    """``(our figure, verdict)`` of "at least ``claimed`` of the ``runs`` end within ``tol`` of the
    known optimum" (``errors``: the stored errors of the finished runs; a failed run does not
    reach it). Judged as :func:`judge_rate` on the runs that reach it."""
    errors = np.abs(np.asarray(errors, float))
    figure, verdict = judge_rate(int((errors <= tol).sum()), runs, claimed)
    if len(errors):
        figure += f" within {tol:.2g}, best error {errors.min():.2g}"
    return figure, verdict


def judge_misses(errors, runs: int, tol: float, claimed: float) -> tuple[str, str]:
    """``(our figure, verdict)`` of "at most ``claimed`` of the ``runs`` end within ``tol`` of the
    known optimum": judged as :func:`judge_fails` on the runs that reach it."""
    errors = np.abs(np.asarray(errors, float))
    figure, verdict = judge_fails(int((errors <= tol).sum()), runs, claimed)
    figure = figure.replace("succeed", f"within {tol:.2g} of the optimum")
    if len(errors):
        figure += f", best error {errors.min():.2g}"
    return figure, verdict


def _assignments(sizes: list[int]) -> np.ndarray:
    """Every way to deal ``sum(sizes)`` runs (positions) to targets holding ``sizes[i]`` runs each,
    as a ``(ways, runs)`` array of target indices."""
    import itertools

    n = sum(sizes)
    out: list[np.ndarray] = []

    def deal(free: list[int], g: int, labels: np.ndarray) -> None:
        if g == len(sizes) - 1:
            lab = labels.copy()
            lab[free] = g
            out.append(lab)
            return
        for chosen in itertools.combinations(free, sizes[g]):
            lab = labels.copy()
            lab[list(chosen)] = g
            taken = set(chosen)
            deal([i for i in free if i not in taken], g + 1, lab)

    deal(list(range(n)), 0, np.zeros(n, dtype=int))
    return np.array(out)


def _ways(sizes: Iterable[int]) -> int:
    """How many ways there are to deal the runs to targets of these sizes (a multinomial)."""
    import math

    sizes = list(sizes)
    ways, left = 1, sum(sizes)
    for k in sizes:
        ways *= math.comb(left, k)
        left -= k
    return ways


def smallest_trend_p(counts: Iterable[Iterable[int]]) -> float:
    """The smallest p :func:`trend_p` can give; ``counts``: per block (seed), its runs per target.
    Untied values dealt in order within every block, and the reverse, are the two most extreme deals:
    ``2 / ways``. One seed on four targets: 2/24; one block of 3 against 3 runs: 0.1."""
    ways = 1
    for block in counts:
        ways *= _ways([k for k in block if k])
    return 1.0 if ways < 2 else min(1.0, 2.0 / ways)


def _trend_blocks(groups, blocks) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(values, target positions, block ids)`` of every run, pooled."""
    vals = [np.asarray(g, float).ravel() for g in groups]
    if blocks is None:
        blocks = [np.zeros(len(v), dtype=int) for v in vals]
    blocks = [np.asarray(b).ravel() for b in blocks]
    if [len(b) for b in blocks] != [len(v) for v in vals]:
        raise ValueError("a trend's blocks must name the block of every run")
    x = np.concatenate(vals) if vals else np.zeros(0)
    pos = np.repeat(np.arange(len(vals)), [len(v) for v in vals])
    blk = np.concatenate(blocks) if blocks else np.zeros(0)
    return x, pos, blk


def trend_p(groups, blocks=None, seed: int = 0) -> tuple[float, float]:
    """``(rho, p)``: the rank correlation between the runs' target positions (``groups``: values per
    target, in the claimed order) and their values, and its two-sided permutation p-value.

    ``blocks`` (parallel to ``groups``: each run's block, e.g. its seed) pairs the runs: both ranks
    are taken within a block and the target labels are permuted within it (Page's test for ordered
    alternatives, with incomplete blocks allowed). ``None``: one block, i.e. Spearman's rho of all runs
    with a plain permutation test. Under the null (the target changes nothing) the values in a block
    are exchangeable across its targets, so every deal is equally likely and ``p`` is the share of
    deals whose statistic is at least as far from 0. Exact when there are at most
    :data:`TREND_EXACT` deals; else ``(1 + hits) / (1 + PERMUTATIONS)`` over seeded random ones.
    ``rho`` is the statistic over its largest possible value: Spearman's rho for one block, the mean
    of the blocks' rhos for complete untied blocks."""
    from functools import reduce

    from scipy.stats import rankdata

    x, pos, blk = _trend_blocks(groups, blocks)
    parts = []   # per block: (target index of each run, centred target ranks, centred value ranks)
    for b in np.unique(blk):
        i = np.flatnonzero(blk == b)
        if len(i) > 1:
            parts.append((pos[i], rankdata(pos[i]) - (len(i) + 1) / 2.0, rankdata(x[i]) - (len(i) + 1) / 2.0))
    denom = float(np.sqrt(sum((s ** 2).sum() for _, s, _ in parts) * sum((r ** 2).sum() for _, _, r in parts)))
    if denom == 0.0:   # every value tied within its block, or no block spans two targets
        return 0.0, 1.0
    t_obs = float(sum(s @ r for _, s, r in parts))
    counts = [[int(k) for k in np.unique(p, return_counts=True)[1]] for p, _, _ in parts]
    if np.prod([float(_ways(c)) for c in counts]) <= TREND_EXACT:
        sums = []
        for (p, s, r), c in zip(parts, counts):
            score = np.array([s[p == t][0] for t in np.unique(p)])   # the score of each target present
            sums.append(score[_assignments(c)] @ r)
        t = reduce(lambda acc, u: (acc[:, None] + u[None, :]).ravel(), sums, np.zeros(1))
        exact = True
    else:
        rng = np.random.default_rng(seed)
        t = np.zeros(PERMUTATIONS)
        for _, s, r in parts:
            t += rng.permuted(np.tile(s, (PERMUTATIONS, 1)), axis=1) @ r
        exact = False
    hits = int(np.count_nonzero(np.abs(t) >= abs(t_obs) - 1e-9 * max(1.0, abs(t_obs))))
    p = hits / len(t) if exact else (hits + 1) / (len(t) + 1)
    return t_obs / denom, float(min(1.0, p))


def _bootstrap_change(first: np.ndarray, last: np.ndarray, bf: np.ndarray | None, bl: np.ndarray | None,
                      seed: int = 0) -> tuple[float, float]:
    """95 % percentile interval of the relative change of the mean from ``first`` to ``last``;
    with blocks ``bf`` / ``bl`` the blocks are resampled, keeping each seed's pair together."""
    if bf is None or bl is None or len(np.unique(np.r_[bf, bl])) < 2:
        lo, hi = _bootstrap_reduction(last, first, seed)   # reduction of last against first
        return 0.0 - hi, 0.0 - lo
    ids = {b: k for k, b in enumerate(np.unique(np.r_[bf, bl]))}
    sums, ns = np.zeros((2, len(ids))), np.zeros((2, len(ids)))
    for row, (vals, bs) in enumerate(((first, bf), (last, bl))):
        for v, b in zip(vals, bs):
            sums[row, ids[b]] += v
            ns[row, ids[b]] += 1
    idx = np.random.default_rng(seed).integers(0, len(ids), size=(BOOTSTRAP, len(ids)))
    with np.errstate(divide="ignore", invalid="ignore"):
        mf = sums[0][idx].sum(axis=1) / ns[0][idx].sum(axis=1)
        ml = sums[1][idx].sum(axis=1) / ns[1][idx].sum(axis=1)
        ch = np.where(ml == mf, 0.0, (ml - mf) / np.abs(mf))
    ch = ch[np.isfinite(ch)]
    if not len(ch):
        return float("nan"), float("nan")
    return float(np.percentile(ch, 2.5)), float(np.percentile(ch, 97.5))


def judge_trend(groups, claimed: float | None, alpha: float = 0.05, blocks=None) -> tuple[str, str]:
    """``(our figure, verdict)`` of "the mean grows along ``groups``" (each the values of one target,
    in the claimed order; ``blocks``: each run's seed, see :func:`trend_p`; kind ``trend``, module
    docstring)."""
    x, pos, blk = _trend_blocks(groups, blocks)
    sizes = [int((pos == i).sum()) for i in range(len(groups))]
    if len(sizes) < 2 or min(sizes) < 1:
        return f"runs per target {'/'.join(map(str, sizes))}", "not run"
    first, last = x[pos == 0], x[pos == len(sizes) - 1]
    change = 0.0 - _drop(last.mean(), first.mean())        # (last - first) / |first|; 0.0 - keeps no "-0.0"
    paired = blocks is not None
    lo, hi = _bootstrap_change(first, last, blk[pos == 0] if paired else None,
                               blk[pos == len(sizes) - 1] if paired else None)
    rho, p = trend_p(groups, blocks)
    means = " -> ".join(f"{x[pos == i].mean():.4g}" for i in range(len(sizes)))
    figure = (f"means {means}; first to last {100 * change:+.1f} % [{100 * lo:+.1f}, {100 * hi:+.1f}], "
              f"rho={rho:+.2f}{' within seeds' if paired else ''}, p={p:.2g}")
    counts = [[int(((blk == b) & (pos == i)).sum()) for i in range(len(sizes))] for b in np.unique(blk)]
    if smallest_trend_p(counts) >= alpha:
        return figure, TOO_FEW_RUNS
    return figure, _verdict(p, alpha, rho > 0, claimed is not None and hi < claimed)


def _lead_variance(a: np.ndarray, b: np.ndarray, axis: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The reduction of the mean of ``a`` against ``b`` and its variance by the delta method,
    ``var(mean a) / mb^2 + ma^2 var(mean b) / mb^4`` (a single run of ``b`` counts as exact); with
    ``axis``, of every row of resampled groups at once."""
    ma, mb = a.mean(axis=axis), b.mean(axis=axis)
    n, m = a.shape[-1], b.shape[-1]
    va = a.var(axis=axis, ddof=1) / n if n > 1 else np.zeros_like(ma)
    vb = b.var(axis=axis, ddof=1) / m if m > 1 else np.zeros_like(mb)
    with np.errstate(divide="ignore", invalid="ignore"):
        red = np.where(ma == mb, 0.0, (mb - ma) / np.abs(mb))
        return red, va / mb ** 2 + ma ** 2 * vb / mb ** 4


def judge_lead_trend(pairs, claimed: float | None, alpha: float = 0.05, seed: int = 0) -> tuple[str, str]:
    """``(our figure, verdict)`` of "the lead of ``a`` over ``b`` grows along the targets" (``pairs``: the
    ``(a, b)`` values of each target, in the claimed order; kind ``lead_trend``, module docstring).

    The change of the lead from the first target to the last, ``D``, is tested with a studentised
    bootstrap (bootstrap-t): each group at both ends resampled on its own, ``t* = (D* - D) / se*``
    with the delta-method standard error of each resample, and ``p`` the share of ``|t*|`` at least the
    observed ``|D / se|`` (``(1 + k) / (1 + BOOTSTRAP)``). Unlike the percentile interval (shown) it keeps
    its false-positive rate near alpha with 10-20 skewed runs a group (tests/test_claim_summary_44.py)."""
    from .stats import smallest_p

    pairs = [(np.asarray(a, float), np.asarray(b, float)) for a, b in pairs]
    if len(pairs) < 2 or any(len(a) < 2 or len(b) < 1 for a, b in pairs):
        return "runs per target " + ", ".join(f"{len(a)} and {len(b)}" for a, b in pairs), "not run"
    # a reference whose runs are all alike (A*, deterministic, stored once or repeated) is one exact value
    pairs = [(a, b[:1] if np.all(b == b[0]) else b) for a, b in pairs]
    reds = [_reduction(a, b) for a, b in pairs]
    change = reds[-1] - reds[0]
    reductions = "reductions " + " -> ".join(f"{100 * r:+.1f} %" for r in reds)
    (af, bf), (al, bl) = pairs[0], pairs[-1]
    (_, vf), (_, vl) = _lead_variance(af, bf), _lead_variance(al, bl)
    if not np.isfinite(change) or not np.isfinite(vf + vl):
        return reductions, "not significant"
    rng = np.random.default_rng(seed)

    def resampled(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _lead_variance(a[rng.integers(0, len(a), size=(BOOTSTRAP, len(a)))],
                              b[rng.integers(0, len(b), size=(BOOTSTRAP, len(b)))], axis=1)

    (rf, wf), (rl, wl) = resampled(af, bf), resampled(al, bl)
    d, se = rl - rf, np.sqrt(wf + wl)
    keep = np.isfinite(d) & np.isfinite(se)
    d, se = d[keep], se[keep]
    lo, hi = (float(x) for x in np.percentile(d, [2.5, 97.5]))
    if vf + vl == 0:   # nothing varies at either end: the change is exact
        p = 1.0 if change == 0 else 0.0
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(se > 0, (d - change) / se, np.where(d == change, 0.0, np.inf))
        p = min(1.0, (1 + int(np.count_nonzero(np.abs(t) >= abs(change) / np.sqrt(vf + vl)))) / (1 + len(t)))
    figure = f"{reductions}; first to last {100 * change:+.1f} pp [{100 * lo:+.1f}, {100 * hi:+.1f}], p={p:.2g}"

    def less_floor(a: np.ndarray, b: np.ndarray) -> float:   # the smallest p of ``less`` at one target
        return 2.0 / 2 ** len(a) if len(b) == 1 else smallest_p(len(a), len(b))

    if max(less_floor(af, bf), less_floor(al, bl)) >= alpha:
        return figure, TOO_FEW_RUNS
    return figure, _verdict(p, alpha, change > 0, claimed is not None and hi < claimed)


# the verdicts a combination's parts count: supporting it, opposing it, open, unknown
_SUPPORT = ("holds", "weaker")
_UNKNOWN = ("not run", TOO_FEW_RUNS)


def judge_combined(kind: str, verdicts: Iterable[str], labels: Iterable[str] | None = None) -> tuple[str, str]:
    """``(our figure, verdict)`` of a combination ``all``, ``most`` or ``net`` (module docstring) whose
    parts got ``verdicts``; ``labels`` (parallel) name the parts in the figure's list of reversed ones."""
    verdicts = list(verdicts)
    labels = list(labels) if labels is not None else [str(i + 1) for i in range(len(verdicts))]
    n = len(verdicts)
    if not n:
        raise ValueError("a combination needs parts")
    count = {v: verdicts.count(v) for v in VERDICTS}
    unknown_ = [v for v in verdicts if v not in VERDICTS]
    if unknown_:
        raise ValueError(f"unknown verdicts {sorted(set(unknown_))}")
    holds, support = count["holds"], count["holds"] + count["weaker"]
    against, unknown = count["reversed"], sum(count[v] for v in _UNKNOWN)
    if kind == "all":
        def proved(k: int) -> bool:
            return k == n
        disproved = against > 0
    elif kind == "most":
        def proved(k: int) -> bool:
            return 2 * k > n
        disproved = 2 * against >= n
    elif kind == "net":
        def proved(k: int) -> bool:
            return k > against + unknown
        disproved = against > support + unknown
    else:
        raise ValueError(f"unknown combination kind {kind!r}; known: {', '.join(COMBINED_KINDS)}")
    if proved(holds):
        verdict = "holds"
    elif proved(support):
        verdict = "weaker"
    elif disproved:
        verdict = "reversed"
    elif unknown:
        verdict = TOO_FEW_RUNS if count[TOO_FEW_RUNS] else "not run"
    else:
        verdict = "not significant"
    figure = ", ".join([f"{holds}/{n} hold", *(f"{count[v]} {v}" for v in VERDICTS[1:] if count[v])])
    if kind == "net":
        figure += f"; wins/ties/losses {support}/{count['not significant']}/{against}"
    reversed_ = [lab for lab, v in zip(labels, verdicts) if v == "reversed"]
    if reversed_:
        figure += f" (reversed: {', '.join(reversed_[:6])}{', ...' if len(reversed_) > 6 else ''})"
    return figure, verdict


def part_labels(parts: Iterable[Claim]) -> list[str]:
    """Short names of a combination's parts: what varies between them (target, kind, groups, metric)."""
    parts = list(parts)
    words = {"less": "mean", "less_best": "best", "less_worst": "worst", "less_spread": "spread"}
    fields = (target_text, lambda c: words.get(c.kind, c.kind), lambda c: c.better, lambda c: c.other or "",
              lambda c: "" if c.kind in SHARE_KINDS else c.metric)
    varying = [f for f in fields if len({f(c) for c in parts} - {""}) > 1]
    return [" ".join(x for x in (f(c) for f in varying) if x) or c.quote for c in parts]


def _tol(claim: Claim, res) -> float:
    """The claim's margin: its own, else the benchmark tolerance on a function spec; never guessed."""
    if claim.tol is not None:
        return claim.tol
    if res.spec.kind == "optimize":
        return FUNCTION_TOL
    raise ValueError(f"claim {claim.id}: a {claim.kind} claim on a {res.spec.kind} spec must name its tol")


def _group(res, target: str, label: str):
    for (lab, refine, local), recs in res.groups(target).items():
        if res.group_name(lab, refine, local) == label or lab == label:
            return recs
    return None


def judge(claim: Claim, res) -> tuple[str, str]:
    """``(our figure, verdict)`` of one claim on the stored runs ``res`` of its spec."""
    if claim.kind in COMBINED_KINDS:
        return judge_combined(claim.kind, [judge(p, res)[1] for p in claim.parts], part_labels(claim.parts))
    if claim.kind == "lead_trend":
        if not set(claim.targets) <= {t.name for t in res.spec.targets}:
            return "target not in this run", "not run"
        pairs = []
        for t in claim.targets:
            a, b = _group(res, t, claim.better), _group(res, t, claim.other)
            if a is None or b is None:
                return "group not in this run", "not run"
            pairs.append((res.values(a, claim.metric), res.values(b, claim.metric)))
        return judge_lead_trend(pairs, claim.claimed, res.spec.alpha)
    if claim.kind == "trend":
        if not set(claim.targets) <= {t.name for t in res.spec.targets}:
            return "target not in this run", "not run"
        groups = [_group(res, t, claim.better) for t in claim.targets]
        if any(g is None for g in groups):
            return "group not in this run", "not run"
        # each run's value with its seed: a seed's runs on the targets are compared with each other
        runs = [[(r.seed, v) for r in recs for v in res.values([r], claim.metric)] for recs in groups]
        return judge_trend([[v for _, v in g] for g in runs], claim.claimed, res.spec.alpha,
                           blocks=[[s for s, _ in g] for g in runs])
    if claim.target not in {t.name for t in res.spec.targets}:
        return "target not in this run", "not run"
    a = _group(res, claim.target, claim.better)
    b = _group(res, claim.target, claim.other) if claim.other else None
    if a is None or (claim.other and b is None):
        return "group not in this run", "not run"
    if claim.kind == "printed":
        return judge_printed(res.values(a, claim.metric), claim.printed, res.spec.alpha)
    if claim.kind in SHARE_KINDS:
        stored, _, ok = res.counts(a)
        if claim.kind == "reaches":
            return judge_reaches(res.values(a, claim.metric), stored, _tol(claim, res),
                                 claim.claimed if claim.claimed is not None else 1.0)
        if claim.kind == "misses":
            return judge_misses(res.values(a, claim.metric), stored, _tol(claim, res),
                                claim.claimed if claim.claimed is not None else 0.0)
        judge_share = judge_rate if claim.kind == "rate" else judge_fails
        return judge_share(ok, stored, claim.claimed if claim.claimed is not None else
                           (1.0 if claim.kind == "rate" else 0.0))
    va, vb = res.values(a, claim.metric), res.values(b, claim.metric)
    if claim.kind == "less":
        return judge_less(va, vb, claim.claimed, res.spec.alpha)
    if claim.kind == "less_spread":
        return judge_less_spread(va, vb, res.spec.alpha)
    if claim.kind in ("less_best", "less_worst"):
        return judge_less_extreme(va, vb, claim.claimed, res.spec.alpha, worst=claim.kind == "less_worst")
    if claim.kind in ("tie", "tie_best"):
        return judge_tie(va, vb, _tol(claim, res), res.spec.alpha, best=claim.kind == "tie_best")
    raise ValueError(f"unknown claim kind {claim.kind!r}")


def _claimed_text(c: Claim) -> str:
    if c.kind == "printed":
        return f"{c.printed.text} (sd {c.printed.sd:.2g}, {c.printed.runs} runs)"
    if c.kind in ("tie", "tie_best"):
        return "equal"
    if c.kind == "trend":   # grows along the targets as listed; the size is first to last
        return "grows" if c.claimed is None else f"{100 * c.claimed:+.1f} %"
    if c.kind == "lead_trend":   # the lead grows; the size is the change of the reduction, first to last
        return "grows" if c.claimed is None else f"{100 * c.claimed:+.1f} pp"
    if c.kind in COMBINED_KINDS:
        return {"all": "all hold", "most": "most hold", "net": "more wins than losses"}[c.kind]
    if c.claimed is None:
        return ">= 100 %" if c.kind == "reaches" else "0 %" if c.kind == "misses" else "better"
    if c.kind in ("fails", "misses"):
        return f"<= {100 * c.claimed:.0f} %"
    if c.kind in ("less", "less_best", "less_worst"):
        return f"{100 * c.claimed:.1f} %"
    return f">= {100 * c.claimed:.0f} %" if c.kind in ("rate", "reaches") else ""


# what the compared column says before the groups, for the kinds that compare extremes or equality
# (a prefix, so that a run-time row still ends in "(runtime_s)", the mark doc_tables skips)
_COMPARED_PREFIX = {"less_best": "best: ", "less_worst": "worst: ", "tie": "equal: ", "tie_best": "equal best: ",
                    "reaches": "optimum: ", "misses": "off the optimum: ", "trend": "trend: ", "lead_trend": "lead trend: ",
                    "printed": "printed mean: "}


def _compared_text(c: Claim, shown: Claim) -> str:
    """The compared column: the kind's prefix (a combination's kind and number of parts), the groups of
    ``shown`` (``c`` or its printed twin) and the metric."""
    prefix = f"{c.kind} of {len(c.parts)}: " if c.parts else _COMPARED_PREFIX.get(c.kind, "")
    return prefix + shown.better + (f" vs {shown.other}" if shown.other else "") + \
        (f" ({c.metric})" if c.kind not in SHARE_KINDS else "")


def claims_of(spec_name: str) -> list[Claim]:
    """The claims judged by one shipped spec."""
    return [c for c in CLAIMS if c.spec == spec_name]


def claims_table(res) -> Table | None:
    """The claims table of one spec's runs (``None`` when the spec judges no claim); printed values
    have a table of their own (:func:`printed_table`)."""
    claims = [c for c in claims_of(res.spec.name) if c.kind != "printed"]
    if not claims:
        return None
    # a claim with a twin at the paper's printed setting is shown as printed, with our change beside it
    twins = {c.id: PRINTED_TWINS[c.id] for c in claims if c.id in PRINTED_TWINS}
    twin_ids = {t.id for t in twins.values()}
    claims = [c for c in claims if c.id not in twin_ids]
    header = ["source", "claim", "target", "compared", "claimed", "ours (95 % interval, p)", "verdict"]
    if twins:
        header += ["ours, with our change", f"verdict, with our change: {_changes_text(twins.values())}"]
    table = Table(header, caption=f"claims judged by {res.spec.name}")
    notes = []
    verdicts: dict[str, str] = {}
    for c in claims:
        shown = twins.get(c.id, c)
        figure, verdict = judge(shown, res)
        row = [c.source, c.quote, target_text(c), _compared_text(c, shown), _claimed_text(c), figure, verdict]
        if twins:
            ours = judge(c, res) if c.id in twins else ("-", "-")   # "-": nothing of ours in its groups
            row += list(ours)
            if c.id in twins:
                verdicts.update({shown.id: verdict, c.id: ours[1]})
        table.rows.append(row)
        if c.note and c.note not in notes:
            notes.append(c.note)
    table.notes.append("verdicts are computed (optplan/bench/claims.py): less -> reduction of the mean with a "
                       "bootstrap interval and the rank-sum p-value; rate -> Wilson interval; weaker: significant "
                       "but the interval lies below the claimed size")
    kinds = {c.kind for c in claims}
    if kinds & {"less_best", "less_worst"}:
        table.notes.append("best / worst -> reduction of the best (worst) run with a bootstrap interval; lead: runs "
                           "beyond the other group's extreme; p: exact precedence test")
    if kinds & {"tie", "tie_best", "reaches", "misses"}:
        table.notes.append("equal -> equivalence test: the 90 % bootstrap interval of the difference (of the means, "
                           "or of the best runs) inside the margin (1e-8 on benchmark functions, the CEC "
                           "convention); optimum -> runs within that margin of the known optimum; off the "
                           "optimum -> at most the claimed share of runs within it (Wilson interval)")
    if "trend" in kinds:
        table.notes.append("trend -> the mean per target in the order shown and its relative change first to last "
                           "with a bootstrap interval (seeds resampled); rho: rank correlation of the runs with that "
                           "order within their seed, p: its permutation test, targets dealt anew within each seed "
                           f"(exact, or {PERMUTATIONS:,} seeded deals)")
    if "lead_trend" in kinds:
        table.notes.append("lead trend -> the reduction of the mean (1 - mean / other's mean) per target in the order "
                           "shown, and its change first to last in percentage points with a bootstrap interval (each "
                           "group's runs resampled per target; a single deterministic run, e.g. A*, stays exact); p: "
                           "studentised bootstrap (bootstrap-t) of that change; the middle targets are shown, not "
                           "tested")
    if kinds & set(COMBINED_KINDS):
        table.notes.append("all / most / net -> a combination of the claims judging a summary's parts (their "
                           "verdicts counted; reversed parts named): all holds when every part holds, is reversed "
                           "when any part is; most holds when more than half hold, is reversed when at least half "
                           "are; net (a tally's direction) holds when the parts that hold (wins) outnumber the "
                           "reversed ones (losses) and those without a verdict, is reversed the other way round; "
                           "weaker when it needs the weaker parts to hold")
    if twins:
        table.notes += _twin_notes(twin_verdicts(verdicts, [(c, twins[c.id]) for c in claims if c.id in twins]))
    table.notes += notes
    return table


def printed_table(res) -> Table | None:
    """The paper's printed values (kind ``printed``) against one spec's runs, or ``None``: one row per
    algorithm and function, the printed mean and spread beside ours, the verdict, and a tally."""
    claims = [c for c in claims_of(res.spec.name) if c.kind == "printed"]
    if not claims:
        return None
    table = Table(["source", "target", "algorithm", "printed mean (sd, runs)", "ours (90 % interval, p)",
                   "verdict"], caption=f"the paper's printed values against {res.spec.name}")
    tally: dict[str, int] = {}
    notes = []
    for c in claims:
        figure, verdict = judge(c, res)
        table.rows.append([c.source, c.target, c.better, _claimed_text(c), figure, verdict])
        side = figure.rsplit(", ", 1)[-1] if verdict == "reversed" else ""   # "ours lower" / "ours higher"
        key = f"{verdict} ({side})" if side else verdict
        tally[key] = tally.get(key, 0) + 1
        if c.note and c.note not in notes:
            notes.append(c.note)
    table.notes.append("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(tally.items())))
    table.notes.append("printed mean -> Welch's equivalence test of our mean against the paper's printed mean, "
                       "standard deviation and run count: holds when the 90 % interval of the difference lies inside "
                       f"the margin (the largest of 1e-8, half the last printed digit, {PRINTED_REL:.0%} of the "
                       "printed distance to the optimum); reversed (ours another value) when p < alpha and the 95 % "
                       "interval lies outside it")
    table.notes += notes
    return table


def as_printed_table(ours, printed) -> Table | None:
    """The claims judged on two specs that differ in a setting we changed (``ours``: the results of the
    spec with our change; ``printed``: those of its ``as_printed`` spec, the paper's setting), listed
    where their verdicts differ, with how many were compared: one row per claim of ``ours`` whose
    twin (the same claim on the other spec) both runs give a verdict."""
    def unspecced(c: Claim) -> str:   # the id without its spec: the same claim on either spec
        return c.id.split(":", 1)[1]

    twins = {unspecced(c): c for c in claims_of(printed.spec.name)}
    pairs = [(c, twins[unspecced(c)]) for c in claims_of(ours.spec.name) if unspecced(c) in twins]
    if not pairs:
        return None
    table = Table(["source", "claim", "target", "compared", f"as printed ({printed.spec.name})",
                   f"with our change ({ours.spec.name})"],
                  caption=f"verdicts that differ between {printed.spec.name} and {ours.spec.name}")
    judged = 0
    for c, t in pairs:
        mine, theirs = judge(c, ours)[1], judge(t, printed)[1]
        if mine in NO_VERDICT or theirs in NO_VERDICT:
            continue
        judged += 1
        if mine != theirs:
            table.rows.append([c.source, c.quote, target_text(c), _compared_text(c, c), theirs, mine])
    table.notes.append(f"{len(table.rows)} of the {judged} claims judged on both specs differ ({len(pairs)} claims "
                       "on both; the others have no verdict on one side)")
    return table


def render_claims(res, fmt: str = "markdown") -> str:
    """The claims table and the printed values' table as text, with their headings, or ``""``."""
    out = ""
    table = claims_table(res)
    if table is not None:
        out += f"\n## Claims of the paper ({res.spec.name})\n\n{table.render(fmt)}\n"
    printed = printed_table(res)
    if printed is not None:
        out += f"\n## Printed values of the paper ({res.spec.name})\n\n{printed.render(fmt)}\n"
    return out


_IPSO2_NOTE = ("IPSO2 is a reconstruction, not Tan et al. 2022's rule (not found): Yang et al. 2007's evolution "
               "speed and aggregation degree set the inertia, the learning factors' rule is ours "
               "(docs/fidelity/yang2023.md)")
_IPSO1_NOTE = ("IPSO1's positive feedback follows Li et al. 2020 eq 7-8; its disturbance and schedule are "
               "reconstructed (docs/fidelity/yang2023.md)")
_AGWO_NOTE = ("AGWO is Qais et al. 2018's augmented GWO, RSMGWO Zhang et al. 2020's; chen2025 cites neither and "
              "RSMGWO's EPD factor is reconstructed (docs/fidelity/chen2025.md)")
_TIMING = "timings were measured on a machine shared with other jobs: times are inflated and noisy"
_PROTO = "paper protocol"
_TUNED_ON = ("F6", "F12")
_TUNED_NOTE = ("MSIAR-GWO's convergence-factor exponents were Q-learned on shifted F6 and F12 "
               "(optplan/solvers/metaheuristics/tuning.py, as chen2025 §3.1 names them)")
_LIKE_FOR_LIKE = "the paper's figures are for its own (raw) ACO/IACO paths; here both sides are pruned"
# the compared columns of hou2024 Tables 2-3, in the order of their claims
_HOU2024_COLUMNS = (("length", "ssa", "length"), ("length", "aco", "length"), ("length", "iaco", "length"),
                    ("runtime", "iaco", "runtime_s"), ("total rotation", "ssa", "turn_angle_deg"),
                    ("runtime", "ssa", "runtime_s"))

CLAIMS: tuple[Claim, ...] = (
    # hou2024 §4.3, Tables 2-3 (ISSA in the tables is MISSA)
    *(Claim("hou2024_global", f"Table {2 + i}", "all four algorithms devise collision-free global paths", m,
            "rate", "missa", claimed=1.0) for i, m in enumerate(("hou2024_env1", "hou2024_env2"))),
    *(Claim("hou2024_global", f"Table {t}", f"average {what} {100 * c:.2f} % below {other.upper()}", m, "less",
            "missa", other, metric, c, _TIMING if metric == "runtime_s" else "")
      for t, m, rows in (
          (2, "hou2024_env1", (0.1531, 0.0876, 0.0709, 0.8839, 0.8060, 0.4184)),
          (3, "hou2024_env2", (0.1192, 0.1955, 0.0981, 0.8653, 0.5779, 0.3323)))
      for (what, other, metric), c in zip(_HOU2024_COLUMNS, rows)),
    # the same tables' other columns: every algorithm feasible, rotation and runtime against ACO/IACO
    # (reductions of the printed averages)
    *(Claim("hou2024_global", f"Table {2 + i}", "all four algorithms devise collision-free global paths", m,
            "rate", alg, claimed=1.0)
      for i, m in enumerate(("hou2024_env1", "hou2024_env2")) for alg in ("aco", "iaco", "ssa")),
    *(Claim("hou2024_global", f"Table {t}", f"average {what} below {other.upper()} ({ours} vs {theirs})", m, "less",
            "missa", other, metric, 1 - ours / theirs, _TIMING if metric == "runtime_s" else "")
      for t, m, rows in (
          (2, "hou2024_env1", (("total rotation", "aco", "turn_angle_deg", 61.85, 743.45),
                               ("total rotation", "iaco", "turn_angle_deg", 61.85, 187.37),
                               ("runtime", "aco", "runtime_s", 0.9935, 1.8917))),
          (3, "hou2024_env2", (("total rotation", "aco", "turn_angle_deg", 327.63, 1436.17),
                               ("total rotation", "iaco", "turn_angle_deg", 327.63, 1062.82),
                               ("runtime", "aco", "runtime_s", 1.3124, 4.5309))))
      for what, other, metric, ours, theirs in rows),
    # like for like: the same length and rotation claims against the colonies' paths pruned as
    # MISSA's are (the paper does not say its ACO paths were pruned; raw they are 8-connected)
    *(Claim("hou2024_global", f"Table {t}", f"average {what} below {other.split('-')[0].upper()}, pruned like MISSA ({ours} vs {theirs})",
            m, "less", "missa", other, metric, 1 - ours / theirs, _LIKE_FOR_LIKE)
      for t, m, rows in (
          (2, "hou2024_env1", (("length", "aco-pruned", "length", 27.7306, 30.3926),
                               ("length", "iaco-pruned", "length", 27.7306, 29.8455),
                               ("total rotation", "aco-pruned", "turn_angle_deg", 61.85, 743.45),
                               ("total rotation", "iaco-pruned", "turn_angle_deg", 61.85, 187.37))),
          (3, "hou2024_env2", (("length", "aco-pruned", "length", 34.8701, 43.3414),
                               ("length", "iaco-pruned", "length", 34.8701, 38.6631),
                               ("total rotation", "aco-pruned", "turn_angle_deg", 327.63, 1436.17),
                               ("total rotation", "iaco-pruned", "turn_angle_deg", 327.63, 1062.82))))
      for what, other, metric, ours, theirs in rows),
    # yuan2021 §5.1
    Claim("yuan2021_table1", "Table 1", "average length 2.88 % below BA", "yuan2021_25", "less", "iba", "ba",
          claimed=0.0288),
    Claim("yuan2021_table1", "Table 1", "average length 7.13 % below PSO", "yuan2021_25", "less", "iba", "pso",
          claimed=0.0713),
    Claim("yuan2021_table1", "Table 1", "IBA is more stable (variance 1.81 vs BA 4.65)", "yuan2021_25",
          "less_spread", "iba", "ba"),
    Claim("yuan2021_table1", "Table 1", "every run finds a collision-free path", "yuan2021_25", "rate", "iba",
          claimed=1.0),
    Claim("yuan2021_table2", "Table 2", "mu = 0.1 cuts the average corners 12.6 -> 9.1 (27.8 %)", "yuan2021_25",
          "less", "iba-mu0.1", "iba-mu0", "n_turns", 1 - 9.1 / 12.6),
    Claim("yuan2021_table2", "§5.1 (2)", "the smoothing term lengthens the path (39.21 vs 37.45, -4.70 %)",
          "yuan2021_25", "less", "iba-mu0", "iba-mu0.1", "length", None),
    # yang2023 §7.1 (IPSO1 and IPSO2 below)
    Claim("yang2023_global", "Table 1", "IPSO average length below PSO (15.0966 vs 15.7687, 4.26 %)",
          "yang2023_env1", "less", "ipso", "pso", claimed=1 - 15.0966 / 15.7687),
    Claim("yang2023_global", "Table 2", "IPSO average length below PSO (22.0474 vs 22.4382, 1.74 %)",
          "yang2023_env2", "less", "ipso", "pso", claimed=1 - 22.0474 / 22.4382),
    # yang2023 §7.1 against IPSO1 (Li et al. 2020, its [18]; partly reconstructed, docs/fidelity/yang2023.md)
    Claim("yang2023_global", "Table 1", "IPSO average length below IPSO1 (15.0966 vs 15.5512)",
          "yang2023_env1", "less", "ipso", "ipso1", claimed=1 - 15.0966 / 15.5512, note=_IPSO1_NOTE),
    Claim("yang2023_global", "Table 2", "IPSO average length below IPSO1 (22.0474 vs 22.2542)",
          "yang2023_env2", "less", "ipso", "ipso1", claimed=1 - 22.0474 / 22.2542, note=_IPSO1_NOTE),
    # yang2023 §7.1 against IPSO2 (Tan et al. 2022, its [19]; a reconstruction, docs/fidelity/yang2023.md).
    # IPSO2 spends PSO's evaluations: EQUAL_EVALS judges these at equal evaluations too (ipso-evals)
    Claim("yang2023_global", "Table 1", "IPSO average length below IPSO2 (15.0966 vs 15.4805)",
          "yang2023_env1", "less", "ipso", "ipso2", claimed=1 - 15.0966 / 15.4805, note=_IPSO2_NOTE),
    Claim("yang2023_global", "Table 2", "IPSO average length below IPSO2 (22.0474 vs 22.2667)",
          "yang2023_env2", "less", "ipso", "ipso2", claimed=1 - 22.0474 / 22.2667, note=_IPSO2_NOTE),
    # yang2023 Table 3 (one convergence curve per algorithm in the paper; 20 seeds here)
    Claim("yang2023_convergence", "Table 3", "IPSO converges to a shorter path than PSO (14.5134 vs 14.8496 m)",
          "yang2023_env1", "less", "ipso", "pso", claimed=1 - 14.5134 / 14.8496),
    Claim("yang2023_convergence", "Table 3", "IPSO converges in fewer iterations than PSO (94 vs 169)",
          "yang2023_env1", "less", "ipso", "pso", metric="convergence_iter", claimed=1 - 94 / 169),
    Claim("yang2023_convergence", "Table 3", "IPSO converges to a shorter path than PSO (21.2950 vs 21.7977 m)",
          "yang2023_env2", "less", "ipso", "pso", claimed=1 - 21.2950 / 21.7977),
    Claim("yang2023_convergence", "Table 3", "IPSO converges in fewer iterations than PSO (137 vs 171)",
          "yang2023_env2", "less", "ipso", "pso", metric="convergence_iter", claimed=1 - 137 / 171),
    *(Claim("yang2023_convergence", "Table 3", f"IPSO converges to a shorter path than IPSO1 ({a:.4f} vs {b:.4f} m)", m,
            "less", "ipso", "ipso1", claimed=1 - a / b, note=_IPSO1_NOTE)
      for m, a, b in (("yang2023_env1", 14.5134, 14.7031), ("yang2023_env2", 21.2950, 21.5781))),
    *(Claim("yang2023_convergence", "Table 3", f"IPSO converges in fewer iterations than IPSO1 ({a} vs {b})", m,
            "less", "ipso", "ipso1", metric="convergence_iter", claimed=1 - a / b, note=_IPSO1_NOTE)
      for m, a, b in (("yang2023_env1", 94, 138), ("yang2023_env2", 137, 159))),
    *(Claim("yang2023_convergence", "Table 3", f"IPSO converges to a shorter path than IPSO2 ({a:.4f} vs {b:.4f} m)", m,
            "less", "ipso", "ipso2", claimed=1 - a / b, note=_IPSO2_NOTE)
      for m, a, b in (("yang2023_env1", 14.5134, 14.6513), ("yang2023_env2", 21.2950, 21.5085))),
    *(Claim("yang2023_convergence", "Table 3", f"IPSO converges in fewer iterations than IPSO2 ({a} vs {b})", m,
            "less", "ipso", "ipso2", metric="convergence_iter", claimed=1 - a / b, note=_IPSO2_NOTE)
      for m, a, b in (("yang2023_env1", 94, 140), ("yang2023_env2", 137, 166))),
    # li2023 §6.1, Tables 1-2
    *(Claim("li2023_global", "Table 1", f"IGA path {c:.1%} shorter than TGA", m, "less", "iga", "ga", claimed=c)
      for m, c in (("li2023_30", 0.027), ("li2023_60", 0.048), ("li2023_90", 0.049))),
    *(Claim("li2023_global", "Table 1", f"IGA running time {c:.1%} below TGA", m, "less", "iga", "ga", "runtime_s",
            c, _TIMING) for m, c in (("li2023_30", 0.373), ("li2023_60", 0.485), ("li2023_90", 0.621))),
    *(Claim("li2023_global", "Table 2", f"IGA path {c:.1%} shorter than A*", m, "less", "iga", "astar", claimed=c)
      for m, c in (("li2023_30", 0.014), ("li2023_60", 0.072), ("li2023_90", 0.086))),
    # the tables' other columns: key points (the returned path's turning points, n_turns) and
    # A*'s running time (a single deterministic run: the signed-rank test against it)
    *(Claim("li2023_global", "Table 1", f"IGA has {c:.1%} fewer key points than TGA", m, "less", "iga", "ga",
            "n_turns", c) for m, c in (("li2023_30", 0.588), ("li2023_60", 0.867), ("li2023_90", 0.782))),
    *(Claim("li2023_global", "Table 2", f"IGA running time {c:.1%} below A*", m, "less", "iga", "astar",
            "runtime_s", c, _TIMING) for m, c in (("li2023_30", 0.389), ("li2023_60", 0.681), ("li2023_90", 0.694))),
    *(Claim("li2023_global", "Table 2", f"IGA has {c:.1%} fewer key points than A*", m, "less", "iga", "astar",
            "n_turns", c) for m, c in (("li2023_30", 0.300), ("li2023_60", 0.455), ("li2023_90", 0.227))),
    # chen2025 §4.3, Tables 8-11 (mean path length; AGWO and RSMGWO are not implemented)
    *(Claim("chen2025_paths", f"Table {t}", f"MSIAR-GWO mean length below {o.upper()} ({a:.2f} vs {b:.2f})", m,
            "less", "msiar-gwo", o, claimed=1 - a / b)
      for t, m, rows in ((9, "chen2025_20", {"gwo": 29.8550, "aro": 28.7696, "dbo": 29.8079, "igwo": 28.7271, "woa": 32.2861}),
                         (10, "chen2025_30", {"gwo": 53.6080, "aro": 46.0486, "dbo": 50.0885, "igwo": 46.9421, "woa": 51.5709}),
                         (11, "chen2025_40", {"gwo": 88.9720, "aro": 71.8339, "dbo": 73.8673, "igwo": 85.1341, "woa": 74.8505}))
      for o, b in rows.items()
      for a in ({"chen2025_20": 28.5610, "chen2025_30": 44.0835, "chen2025_40": 68.6196}[m],)),
    *(Claim("chen2025_paths", f"Table {t}", f"MSIAR-GWO mean length below {o.upper()} ({a:.2f} vs {b:.2f})", m,
            "less", "msiar-gwo", o, claimed=1 - a / b, note=_AGWO_NOTE)
      for t, m, a, rows in ((9, "chen2025_20", 28.5610, {"agwo": 30.5612, "rsmgwo": 29.6183}),
                            (10, "chen2025_30", 44.0835, {"agwo": 51.8773, "rsmgwo": 51.6112}),
                            (11, "chen2025_40", 68.6196, {"agwo": 88.7081, "rsmgwo": 87.9394}))
      for o, b in rows.items()),
    *(Claim("chen2025_paths", f"Table {t}", "MSIAR-GWO varies less than GWO", m, "less_spread", "msiar-gwo", "gwo")
      for t, m in ((9, "chen2025_20"), (10, "chen2025_30"), (11, "chen2025_40"))),
    # Table 8: one A* path per map (the signed-rank test against it); the paper's 20x20 and 40x40 maps
    # are judged on our stand-ins of Tables 9 and 11
    *(Claim("chen2025_paths", "Table 8", f"MSIAR-GWO shorter than A* ({a:.4f} vs {b:.4f})", m, "less", "msiar-gwo",
            "astar", claimed=1 - a / b)
      for m, a, b in (("chen2025_20", 29.1038, 30.3848), ("chen2025_40", 57.7521, 59.2548))),
    # chen2025 §4.1, Tables 4-5 (mean best value of 20 runs, 500 iterations, pop 30; the headline
    # run shifts F1-F13, chen2025.md says why)
    # judged on the shifted functions (the headline) and on the functions as printed; F6 and F12
    # are the two its Q-learned exponents were tuned on (solvers/metaheuristics/tuning.py)
    *(Claim(spec, f"Table {t}", quote + (" (MSIAR-GWO was tuned on this function)" if f in _TUNED_ON else ""),
            f, "less", "msiar-gwo", o, "f", note=_TUNED_NOTE if f in _TUNED_ON else "")
      for spec in ("chen2025_functions", "chen2025_functions_unshifted")
      for t, fs, quote in ((4, ("F5", "F6", "F7"), "MSIAR-GWO is always in first place in F5-F7"),
                           (5, ("F12", "F13"), "in F12 and F13 MSIAR-GWO shows an absolute advantage"))
      for f in fs for o in ("gwo", "aro", "dbo", "woa", "igwo")),
    # the same tables' "MSIAR-GWO also beats AGWO and RSMGWO" (issue 44 item 5)
    *(Claim(spec, f"Table {t}", quote + (" (MSIAR-GWO was tuned on this function)" if f in _TUNED_ON else ""),
            f, "less", "msiar-gwo", o, "f", note=_AGWO_NOTE + ("; " + _TUNED_NOTE if f in _TUNED_ON else ""))
      for spec in ("chen2025_functions", "chen2025_functions_unshifted")
      for t, fs, quote in ((4, ("F5", "F6", "F7"), "in F5-F7 MSIAR-GWO also beats AGWO and RSMGWO"),
                           (5, ("F12", "F13"), "in F12 and F13 MSIAR-GWO also beats AGWO and RSMGWO"))
      for f in fs for o in ("agwo", "rsmgwo")),
    # the papers' local experiments, at the specs' settings (the papers' own mover motion where
    # they draw it); success = the goal reached without a collision
    Claim("yang2023_local_crossing", "§7.2, Fig 13", "DWA fails to avoid the two crossing movers",
          "yang2023_idwa_crossing", "fails", "astar/dwa", claimed=0.0),
    Claim("yang2023_local_crossing", "§7.2, Fig 14", "IDWA avoids both crossing movers",
          "yang2023_idwa_crossing", "rate", "astar/idwa", claimed=1.0),
    Claim("yang2023_local_fusion", "§7.3", "the IPSO + IDWA fusion reaches the goal avoiding every obstacle",
          "yang2023_fusion", "rate", "ipso/idwa", claimed=1.0),
    *(Claim("hou2024_local_dynamic", "§4.5, Figs 9-10", "MISSA-DWA reaches the target avoiding the dynamic and "
            "unknown obstacles", m, "rate", "missa/missa-dwa", claimed=1.0)
      for m in ("hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4")),
    Claim("li2023_local_exp1", "§6.2, Figs 18-19", "the IGA + IDWA fusion avoids the dynamic obstacles and reaches "
          "the target", "li2023_exp1", "rate", "iga/iga-dwa", claimed=1.0),
    *(Claim("li2023_local_exp2", "§6.4, Figs 26-27", "the IGA + IDWA fusion avoids randomly moving obstacles and "
            "reaches the target", m, "rate", "iga/iga-dwa", claimed=1.0)
      for m in ("li2023_exp2_2", "li2023_exp2_3", "li2023_exp2_4", "li2023_exp2_5")),
    Claim("yuan2021_local_added", "Fig 9", "the IBA + DWA fusion avoids the added obstacles",
          "yuan2021_added_obstacles", "rate", "iba/ba-dwa", claimed=1.0),
    Claim("yuan2021_local_switch", "Fig 11", "the fusion switches to another path and reaches the target",
          "yuan2021_path_switch", "rate", "iba/ba-dwa", claimed=1.0),
    # §4.2 (and the Conclusions): the path switch answers a blocked path faster than running IBA again
    Claim("yuan2021_switch_time", "§4.2, Conclusions", "switching paths takes less time than re-planning (IBA "
          "run again from the robot's position)", "yuan2021_path_switch", "less", "iba-switch", "iba-replan",
          "reroute_s", note="reroute_s: the mean wall time of one answer to a blocked global path, over the runs in "
          "which the block cut the path; the switch's graph is built with the map and not timed; " + _TIMING),
)

# Equal evaluations (issue 44 item 2): where the improved algorithm spends more evaluations than
# its baseline at equal iterations, the spec also runs it at the baseline's evaluation count
# (label ``<improved>-evals``), and each length / rotation claim against that baseline is judged
# again there. yuan2021's IBA spends what BA does; li2023's IGA spends fewer than TGA.
EQUAL_EVALS = {("yang2023_global", "ipso", "pso"): 15050, ("yang2023_convergence", "ipso", "pso"): 75150,
               # IPSO2 (a reconstruction) spends PSO's evaluations per iteration
               ("yang2023_global", "ipso", "ipso2"): 15050, ("yang2023_convergence", "ipso", "ipso2"): 75150,
               ("hou2024_global", "missa", "ssa"): 18060, ("chen2025_paths", "msiar-gwo", "gwo"): 15030,
               # AGWO and RSMGWO spend GWO's 30 evaluations per iteration
               ("chen2025_paths", "msiar-gwo", "agwo"): 15030, ("chen2025_paths", "msiar-gwo", "rsmgwo"): 15030}


def _at_equal_evaluations(claims: tuple[Claim, ...]) -> tuple[Claim, ...]:
    from dataclasses import replace

    out = []
    for c in claims:
        n = EQUAL_EVALS.get((c.spec, c.better, c.other))
        if n is not None and c.kind == "less" and c.metric not in ("runtime_s", "convergence_iter"):
            out.append(replace(c, better=f"{c.better}-evals", quote=f"{c.quote}, at equal evaluations ({n:,})"))
    return claims + tuple(out)


CLAIMS = _at_equal_evaluations(CLAIMS)

# Issue 44, "every claim of every paper judged": statements of the papers' results sections that
# the runs of the shipped specs already judge (the same algorithms, maps and metrics) and no claim
# above covered. Every statement of the five papers, judged or not and why not, is listed in
# optplan/bench/claim_inventory.py; `python benchmarks/claim_coverage.py` prints the coverage.

# chen2025 §4.2, Table 7: MSIAR-GWO against each baseline per function, "+" better, "=" no
# significant difference, "-" worse (the extracted text lost the minus signs: a blank is "-", and
# IGWO's F16 entry reads "8"; the reading is the one the table's own +/=/- tally row gives).
CHEN2025_TABLE7_BASELINES = ("gwo", "aro", "dbo", "woa", "igwo", "agwo", "rsmgwo")
CHEN2025_TABLE7 = {
    "F1": "++++++=", "F2": "++++++=", "F3": "++++++=", "F4": "++++++=",
    "F5": "+++++++", "F6": "+++++++", "F7": "+++++++",
    "F8": "+++-++-", "F9": "+===+==", "F10": "+==++++", "F11": "+===+==",
    "F12": "+++++++", "F13": "+++++++",
    "F14": "++++-++", "F15": "+==+=++", "F16": "++++-++", "F17": "++++-++", "F18": "+++++++",
}
# Table 7's last row: wins / ties / losses of MSIAR-GWO against each baseline
CHEN2025_TABLE7_TALLY = {"gwo": (18, 0, 0), "aro": (14, 4, 0), "dbo": (14, 4, 0), "woa": (15, 2, 1),
                         "igwo": (14, 1, 3), "agwo": (16, 2, 0), "rsmgwo": (11, 6, 1)}
_CHEN2025_IMPLEMENTED = ("gwo", "aro", "dbo", "woa", "igwo", "agwo", "rsmgwo")
# the two chen2025 names no reference: the published algorithms identified for them (issue 44 item 5)
_CHEN2025_IDENTIFIED = ("agwo", "rsmgwo")
# the functions whose Table 7 entries the Table 4-5 mean claims above already judge
_CHEN2025_MEAN_JUDGED = ("F5", "F6", "F7", "F12", "F13")
_CHEN2025_FUNCTION_SPECS = ("chen2025_functions", "chen2025_functions_unshifted")


def _table7_claims() -> tuple[Claim, ...]:
    """Table 7's "+" and "-" entries against the implemented baselines as ``less`` claims on the
    mean best value (a "-" names the baseline as the better group); its "=" entries (no
    difference) are not claims a kind here can judge (claim_inventory lists them)."""
    out = []
    for spec in _CHEN2025_FUNCTION_SPECS:
        for f, row in CHEN2025_TABLE7.items():
            if f in _CHEN2025_MEAN_JUDGED:
                continue
            for o, mark in zip(CHEN2025_TABLE7_BASELINES, row):
                if o not in _CHEN2025_IMPLEMENTED or mark == "=":
                    continue
                note = _AGWO_NOTE if o in _CHEN2025_IDENTIFIED else ""
                if mark == "+":
                    out.append(Claim(spec, "Table 7", f"rank-sum: MSIAR-GWO better than {o.upper()} in {f} (+)",
                                     f, "less", "msiar-gwo", o, "f", note=note))
                else:
                    out.append(Claim(spec, "Table 7", f"rank-sum: {o.upper()} better than MSIAR-GWO in {f} (-)",
                                     f, "less", o, "msiar-gwo", "f", note=note))
    return tuple(out)


# hou2024 §4.3.1-4.3.2: the reductions of the best values the text reads off Tables 2-3, per column,
# against ACO, IACO and SSA (percent)
HOU2024_BEST = {
    (2, "hou2024_env1"): {"length": (3.60, 2.79, 4.28), "rotation": (88.71, 61.90, 77.98),
                          "runtime": (21.45, 88.92, 13.54)},
    (3, "hou2024_env2"): {"length": (9.24, 6.15, 4.98), "rotation": (57.75, 35.96, 20.86),
                          "runtime": (69.77, 82.71, 20.70)},
}
HOU2024_METRICS = {"length": "length", "rotation": "turn_angle_deg", "runtime": "runtime_s"}
# chen2025 Table 11: the best length of each algorithm on the 40x40 map
CHEN2025_TABLE11_BEST = {"msiar-gwo": 60.0792, "gwo": 70.0352, "aro": 60.1733, "dbo": 66.8810, "woa": 67.6425,
                         "igwo": 67.9427, "agwo": 72.6565, "rsmgwo": 69.0529}
# chen2025 §4.1: who reaches the known optimum in every run (Tables 4-6 print 0 for best, mean and
# worst, or the optimum with a zero standard deviation)
CHEN2025_REACHES = {("F1", "F2", "F3", "F4"): ("msiar-gwo", "rsmgwo"),
                    ("F9",): ("msiar-gwo", "agwo", "aro", "rsmgwo"),
                    ("F11",): ("msiar-gwo", "aro", "dbo", "woa", "agwo", "rsmgwo"),
                    ("F15",): ("msiar-gwo", "aro", "dbo", "igwo")}


def _function_note(f: str, o: str) -> str:
    return "; ".join(n for n in (_AGWO_NOTE if o in _CHEN2025_IDENTIFIED else "",
                                 _TUNED_NOTE if f in _TUNED_ON else "") if n)


def _extreme_and_tie_claims() -> tuple[Claim, ...]:
    """The statements about the best or worst run of each group, about equally good groups and
    about reaching a function's optimum (issue 44: kinds ``less_best``, ``less_worst``, ``tie``,
    ``tie_best``, ``reaches``)."""
    hou = []
    for (t, env), cols in HOU2024_BEST.items():
        for what, reds in cols.items():
            m = HOU2024_METRICS[what]
            for o, r in zip(("aco", "iaco", "ssa"), reds):
                quote = f"best {what if what != 'rotation' else 'total rotation'} {r:.2f} % below {o.upper()}"
                timing = _TIMING if m == "runtime_s" else ""
                hou.append(Claim("hou2024_global", f"Table {t}", quote, env, "less_best", "missa", o, m, r / 100,
                                 timing))
                if m == "runtime_s":
                    continue
                # like for like and at equal evaluations, as the means are judged
                if o in ("aco", "iaco"):
                    hou.append(Claim("hou2024_global", f"Table {t}", f"{quote}, pruned like MISSA", env, "less_best",
                                     "missa", f"{o}-pruned", m, r / 100, _LIKE_FOR_LIKE))
                else:
                    hou.append(Claim("hou2024_global", f"Table {t}", f"{quote}, at equal evaluations (18,060)", env,
                                     "less_best", "missa-evals", o, m, r / 100))
    yang = []
    for t, env, ipso, pso, ipso1, ipso2 in ((1, "yang2023_env1", 14.5374, 14.9860, 14.7632, 14.6825),
                                            (2, "yang2023_env2", 21.2866, 21.8782, 21.8041, 21.6564)):
        quote = f"IPSO's shortest path below PSO's ({ipso:.4f} vs {pso:.4f} m)"
        yang += [Claim("yang2023_global", f"Table {t}", quote, env, "less_best", "ipso", "pso",
                       claimed=1 - ipso / pso),
                 Claim("yang2023_global", f"Table {t}", f"{quote}, at equal evaluations (15,050)", env, "less_best",
                       "ipso-evals", "pso", claimed=1 - ipso / pso),
                 Claim("yang2023_global", f"Table {t}", f"IPSO's shortest path below IPSO1's ({ipso:.4f} vs "
                       f"{ipso1:.4f} m)", env, "less_best", "ipso", "ipso1", claimed=1 - ipso / ipso1,
                       note=_IPSO1_NOTE)]
        # IPSO2 (a reconstruction) spends PSO's evaluations: also judged at equal evaluations, as against PSO
        quote = f"IPSO's shortest path below IPSO2's ({ipso:.4f} vs {ipso2:.4f} m)"
        yang += [Claim("yang2023_global", f"Table {t}", quote, env, "less_best", "ipso", "ipso2",
                       claimed=1 - ipso / ipso2, note=_IPSO2_NOTE),
                 Claim("yang2023_global", f"Table {t}", f"{quote}, at equal evaluations (15,050)", env, "less_best",
                       "ipso-evals", "ipso2", claimed=1 - ipso / ipso2, note=_IPSO2_NOTE)]
    yuan = [
        # yuan2021 §5.1 (1), Table 1: longest and shortest of 20 paths (IBA 41.21 / 36.87 m)
        Claim("yuan2021_table1", "Table 1", "IBA's longest path 9.35 % shorter than PSO's (41.21 vs 45.46)",
              "yuan2021_25", "less_worst", "iba", "pso", claimed=1 - 41.21 / 45.46),
        Claim("yuan2021_table1", "Table 1", "IBA's longest path 8.85 % shorter than BA's (41.21 vs 45.21)",
              "yuan2021_25", "less_worst", "iba", "ba", claimed=1 - 41.21 / 45.21),
        Claim("yuan2021_table1", "Table 1", "IBA's shortest path 3.08 % shorter than PSO's (36.87 vs 38.04)",
              "yuan2021_25", "less_best", "iba", "pso", claimed=1 - 36.87 / 38.04),
        Claim("yuan2021_table1", "Table 1", "IBA's shortest path 1.58 % shorter than BA's (36.87 vs 37.46)",
              "yuan2021_25", "less_best", "iba", "ba", claimed=1 - 36.87 / 37.46),
        # §5.1 (2), Table 2: the fewest and the most corners of 10 paths
        Claim("yuan2021_table2", "Table 2", "mu = 0.1 cuts the fewest corners 9 -> 6", "yuan2021_25", "less_best",
              "iba-mu0.1", "iba-mu0", "n_turns", 1 - 6 / 9),
        Claim("yuan2021_table2", "Table 2", "mu = 0.1 cuts the most corners 16 -> 12", "yuan2021_25", "less_worst",
              "iba-mu0.1", "iba-mu0", "n_turns", 1 - 12 / 16),
    ]
    chen = [
        # Tables 4-5: MSIAR-GWO's best and worst values first in F5-F7, F12 and F13
        *(Claim(spec, f"Table {t}", f"MSIAR-GWO's {which} value is first in {f}" +
                (" (MSIAR-GWO was tuned on this function)" if f in _TUNED_ON else ""),
                f, kind, "msiar-gwo", o, "f", note=_function_note(f, o))
          for spec in _CHEN2025_FUNCTION_SPECS
          for t, fs in ((4, ("F5", "F6", "F7")), (5, ("F12", "F13")))
          for f in fs for kind, which in (("less_best", "best"), ("less_worst", "worst"))
          for o in _CHEN2025_IMPLEMENTED),
        # Table 6: WOA's and AGWO's wide best-to-worst gap in F16, read as their worst runs lying above
        # MSIAR-GWO's (every algorithm's best is near the optimum there)
        *(Claim(spec, "Table 6", f"{o.upper()}'s worst value in F16 is far off (trapped in local optima)", "F16",
                "less_worst", "msiar-gwo", o, "f", note=_function_note("F16", o))
          for spec in _CHEN2025_FUNCTION_SPECS for o in ("woa", "agwo")),
        # Table 6: MSIAR-GWO, ARO, DBO and IGWO reach the same best value in F14
        *(Claim(spec, "Table 6", f"MSIAR-GWO and {o.upper()} reach the same best value in F14", "F14", "tie_best",
                "msiar-gwo", o, "f") for spec in _CHEN2025_FUNCTION_SPECS for o in ("aro", "dbo", "igwo")),
        # Table 7's "=" entries (and §4.1's "ARO, DBO and MSIAR-GWO are equally accurate in F10")
        *(Claim(spec, "Table 7", f"rank-sum: MSIAR-GWO and {o.upper()} not significantly different in {f} (=)", f,
                "tie", "msiar-gwo", o, "f", note=_function_note(f, o))
          for spec in _CHEN2025_FUNCTION_SPECS for f, row in CHEN2025_TABLE7.items()
          for o, mark in zip(CHEN2025_TABLE7_BASELINES, row) if mark == "=" and o in _CHEN2025_IMPLEMENTED),
        # §4.1: the algorithms that reach the optimum (in every run)
        *(Claim(spec, f"Table {4 if fs[0] == 'F1' else 5 if fs[0] in ('F9', 'F11') else 6}",
                f"{a.upper()} reaches the optimum of {f} in every run", f, "reaches", a, metric="f_error",
                claimed=1.0, note=_AGWO_NOTE if a in _CHEN2025_IDENTIFIED else "")
          for spec in _CHEN2025_FUNCTION_SPECS for fs, algs in CHEN2025_REACHES.items() for f in fs for a in algs),
        # §4.1: "the convergence results of GWO and IGWO are still significantly different from the theoretical
        # optimum" in F1-F4: no run within the benchmark tolerance of it (Table 4's own 1e-28 and 1e-17 for F1-F2
        # are within it)
        *(Claim(spec, "§4.1, Table 4", f"{a.upper()} stays off the optimum of {f}", f, "misses", a, metric="f_error",
                claimed=0.0) for spec in _CHEN2025_FUNCTION_SPECS for f in ("F1", "F2", "F3", "F4")
          for a in ("gwo", "igwo")),
        # §4.3.2, Tables 9-10: MSIAR-GWO and ARO reach the same best length (28.0192, 42.4762)
        *(Claim("chen2025_paths", f"Table {t}", f"MSIAR-GWO and ARO reach the same best length ({v})", m,
                "tie_best", "msiar-gwo", "aro", tol=PRINTED_LENGTH_TOL)
          for t, m, v in ((9, "chen2025_20", "28.0192"), (10, "chen2025_30", "42.4762"))),
        # Table 11: MSIAR-GWO's best length on the 40x40 map is the shortest
        *(Claim("chen2025_paths", "Table 11", f"MSIAR-GWO's best length below {o.upper()}'s "
                f"({CHEN2025_TABLE11_BEST['msiar-gwo']:.4f} vs {b:.4f})", "chen2025_40", "less_best", "msiar-gwo",
                o, claimed=1 - CHEN2025_TABLE11_BEST["msiar-gwo"] / b, note=_AGWO_NOTE if o in _CHEN2025_IDENTIFIED
                else "")
          for o, b in CHEN2025_TABLE11_BEST.items() if o != "msiar-gwo"),
    ]
    return (*hou, *yang, *yuan, *chen)


# the ordered targets of the trend claims: 0-3 random obstacles, 2-5 movers
HOU2024_TABLE4_TARGETS = ("hou2024_table4_0", "hou2024_table4_1", "hou2024_table4_2", "hou2024_table4_3")
LI2023_EXP2_TARGETS = ("li2023_exp2_2", "li2023_exp2_3", "li2023_exp2_4", "li2023_exp2_5")


def _added_claims() -> tuple[Claim, ...]:
    spread_quotes = ((4, ("F5", "F6", "F7"), "MSIAR-GWO has the smallest standard deviation in F5-F7"),
                     (5, ("F12", "F13"), "in F12 and F13 MSIAR-GWO's standard deviation is the smallest too"),
                     (6, ("F18",), "in F18 MSIAR-GWO's standard deviation is clearly the smallest"))
    return (
        # hou2024 §4.3.2 (end), "MISSA is very stable": read as its lengths varying less (Tables 2-3 give no spread)
        *(Claim("hou2024_global", "§4.3.2 (end)", f"MISSA's lengths vary less than {o.upper()}'s", env, "less_spread",
                "missa", o) for env in ("hou2024_env1", "hou2024_env2") for o in ("aco", "iaco", "ssa")),
        # hou2024 §4.4, Table 4 / Fig 8: the fusion reaches the target with 0-3 random unknown obstacles
        *(Claim("hou2024_local_table4", "§4.4, Table 4, Fig 8", "MISSA-DWA passes the random obstacles and reaches "
                "the target", m, "rate", "missa/missa-dwa", claimed=1.0)
          for m in ("hou2024_table4_0", "hou2024_table4_1", "hou2024_table4_2", "hou2024_table4_3")),
        # hou2024 §4.4, Fig 8 and §4.5 (end): the global path alone (``follow``: driven blind, never
        # re-planned) runs into what its map does not hold. Both experiments place their random obstacles
        # on the global path, as the paper draws them, so the blind robot meets one in every run: the
        # claims hold by the experiments' design, in the paper as here
        *(Claim(spec, src, quote, m, "fails", "missa/follow", claimed=0.0,
                note="the random unknown obstacles are placed on the global path (the experiment's design), so "
                     "the blind robot meets one in every run; §4.5's runs count a collision with a mover or "
                     "with such an obstacle alike")
          for spec, src, quote, targets in (
              ("hou2024_local_table4", "§4.4, Fig 8", "MISSA alone, planning on the known map, runs into the random "
               "obstacles", HOU2024_TABLE4_TARGETS[1:]),
              ("hou2024_local_dynamic", "§4.5 (end)", "MISSA's global path alone cannot get round the moving and "
               "unknown obstacles", ("hou2024_dynamic1", "hou2024_dynamic2", "hou2024_dynamic3", "hou2024_dynamic4")))
          for m in targets),
        # hou2024 §4.4, Table 4: the fusion's path length and (simulated) time grow with 0-3 random obstacles;
        # claimed: the table's change from the first row to the last
        *(trend_claim("hou2024_local_table4", "§4.4, Table 4", f"the fusion's {what} grows with the number of random "
                      f"obstacles ({a} -> {b} {unit} from 0 to 3)", HOU2024_TABLE4_TARGETS, "missa/missa-dwa", metric,
                      b / a - 1)
          for what, metric, a, b, unit in (("path length", "path_length", 74.155, 76.206, "m"),
                                           ("time", "time_s", 106.58, 117.62, "s"))),
        # yuan2021 §5.1 (1), Table 1: IBA's variance is also below PSO's; PSO's and BA's runs are
        # collision-free paths too (the section plans the shortest collision-free path)
        Claim("yuan2021_table1", "Table 1", "IBA is more stable than PSO (variance 1.81 vs 3.06)", "yuan2021_25",
              "less_spread", "iba", "pso"),
        *(Claim("yuan2021_table1", "Table 1", "every run finds a collision-free path", "yuan2021_25", "rate", alg,
                claimed=1.0) for alg in ("pso", "ba")),
        # li2023 §6.1, Fig 14: IGA's population keeps a larger fitness spread than TGA's (the spread
        # per generation averaged over the run; IGA stops at its §4.5 stall rule, so over fewer generations)
        *(Claim("li2023_global", "§6.1, Fig 14", "IGA's population keeps a larger fitness spread than TGA's", m,
                "less", "ga", "iga", "fitness_spread") for m in LI2023_MAPS),
        # li2023 §6.1 / §6.3: IGA's paths are smoother than TGA's and A*'s (total turning angle)
        *(Claim("li2023_global", src, f"IGA path smoother than {name}", m, "less", "iga", other, "turn_angle_deg")
          for src, name, other in (("§6.1, Figs 9-11", "TGA", "ga"), ("§6.3, Figs 20-22", "A*", "astar"))
          for m in ("li2023_30", "li2023_60", "li2023_90")),
        # li2023 §6.1, Fig 13: IGA converges at about generation 80, TGA at about 120
        *(Claim("li2023_global", "§6.1, Fig 13", "IGA converges in fewer generations than TGA (about 80 vs 120)", m,
                "less", "iga", "ga", "convergence_iter", 1 - 80 / 120)
          for m in ("li2023_30", "li2023_60", "li2023_90")),
        # li2023 §6.2 Experiment I (Fig 16): the traditional DWA reaches the goal on a longer path
        Claim("li2023_local_exp1", "§6.2, Fig 16", "the fusion's path is shorter than the traditional DWA's "
              "(12.744 vs 14.562)", "li2023_exp1", "less", "iga/iga-dwa", "iga/dwa", "path_length",
              1 - 12.744 / 14.562),
        Claim("li2023_local_exp1", "§6.2, Fig 16", "the traditional DWA reaches the goal (on a detour)", "li2023_exp1",
              "rate", "iga/dwa", claimed=1.0),
        # li2023 §6.2 Experiment II (Fig 17, Figs 18-19): the traditional DWA drives longer paths with 2-5 movers
        *(Claim("li2023_local_exp2", "§6.2, Figs 17-19", f"the traditional DWA's path is longer than the fusion's "
                f"({n} movers)", f"li2023_exp2_{n}", "less", "iga/iga-dwa", "iga/dwa", "path_length")
          for n in (2, 3, 4, 5)),
        # li2023 §6.2 Experiment II, Fig 17: both curves rise with the number of movers (the figure prints no values)
        *(trend_claim("li2023_local_exp2", "§6.2, Fig 17", f"{name}'s path length grows with the number of movers "
                      "(2 to 5)", LI2023_EXP2_TARGETS, group, "path_length")
          for name, group in (("the fusion", "iga/iga-dwa"), ("the traditional DWA", "iga/dwa"))),
        # yang2023 §7.2, Fig 14: IDWA's evasion (away from the mover's motion) keeps its path shorter
        Claim("yang2023_local_crossing", "§7.2, Fig 14", "IDWA's evasion keeps the path shorter than DWA's",
              "yang2023_idwa_crossing", "less", "astar/idwa", "astar/dwa", "path_length"),
        # chen2025 §4.1, Tables 4-6: the standard deviation the text names with the means judged above
        *(Claim(spec, f"Table {t}", quote + (" (MSIAR-GWO was tuned on this function)" if f in _TUNED_ON else ""),
                f, "less_spread", "msiar-gwo", o, "f",
                note="; ".join(n for n in (_AGWO_NOTE if o in _CHEN2025_IDENTIFIED else "",
                                           _TUNED_NOTE if f in _TUNED_ON else "") if n))
          for spec in _CHEN2025_FUNCTION_SPECS for t, fs, quote in spread_quotes
          for f in fs for o in _CHEN2025_IMPLEMENTED),
        # chen2025 §4.2, Table 7
        *_table7_claims(),
        # chen2025 §4.3.2, Tables 9-11: the spreads the text compares (ARO on 20x20 and 30x30, WOA's
        # unstable 20x20 paths, every algorithm on 40x40; GWO's are judged above)
        *(Claim("chen2025_paths", f"Table {t}", quote, m, "less_spread", "msiar-gwo", o)
          for t, m, o, quote in (
              (9, "chen2025_20", "aro", "MSIAR-GWO varies less than ARO (std 0.5917 vs 0.7939)"),
              (9, "chen2025_20", "woa", "WOA's paths vary a lot (std 1.9639 vs MSIAR-GWO 0.5917)"),
              (10, "chen2025_30", "aro", "MSIAR-GWO varies less than ARO (std 2.1519 vs 3.3236)"),
              *((11, "chen2025_40", o, f"MSIAR-GWO has the smallest std on 40x40 (vs {o.upper()})")
                for o in ("aro", "dbo", "woa", "igwo", "agwo", "rsmgwo")))),
        # the best and worst runs, equally good groups, reaching the optimum
        *_extreme_and_tie_claims(),
        # the convergence curves and the driven path's smoothness (issue 44: "no metric" statements)
        *_curve_claims(),
    )


_CENSORED_NOTE = ("opt_iter: the first iteration within 1e-8 of the optimum; a run that never gets there counts as "
                  "one past its last iteration (censored: the reduction of the mean is then a lower bound)")


def _curve_claims() -> tuple[Claim, ...]:
    """Claims on the run metrics that read the convergence history or the trajectory
    (``opt_iter``, ``f_error_150``, ``fitness_final``, ``heading_change_per_m``; their kinds'
    docstrings define them)."""
    def note(f: str, o: str, censored: bool) -> str:
        return "; ".join(n for n in (_function_note(f, o), _CENSORED_NOTE if censored else "") if n)

    return (
        # chen2025 §4.1, Fig 6a-d: MSIAR-GWO reaches F1-F4's optimum sooner than RSMGWO (the text: in < 150)
        *(Claim(spec, "§4.1, Fig 6a-d", f"MSIAR-GWO reaches the optimum of {f} in fewer iterations than RSMGWO "
                "(in under 150)", f, "less", "msiar-gwo", "rsmgwo", "opt_iter", note=note(f, "rsmgwo", True))
          for spec in _CHEN2025_FUNCTION_SPECS for f in ("F1", "F2", "F3", "F4")),
        # Fig 6e-g: the curves are alike for 50 iterations, then MSIAR-GWO's keeps falling faster:
        # read at iteration 150, 100 iterations past the point where they part
        *(Claim(spec, "§4.1, Fig 6e-g", f"after 50 iterations MSIAR-GWO converges faster than {o.upper()} in {f} "
                "(lower error at iteration 150)", f, "less", "msiar-gwo", o, "f_error_150", note=note(f, o, False))
          for spec in _CHEN2025_FUNCTION_SPECS for f in ("F5", "F6", "F7") for o in _CHEN2025_IMPLEMENTED),
        # Fig 7b-d: MSIAR-GWO finds F9-F11's optimum in under 50 iterations, far faster than the others
        *(Claim(spec, "§4.1, Fig 7b-d", f"MSIAR-GWO finds the optimum of {f} in fewer iterations than {o.upper()} "
                "(in under 50)", f, "less", "msiar-gwo", o, "opt_iter", note=note(f, o, True))
          for spec in _CHEN2025_FUNCTION_SPECS for f in ("F9", "F10", "F11") for o in _CHEN2025_IMPLEMENTED),
        # (chen2025 Figs 18-20's curves end at eq 32's fitness of the pruned path, the path's length in the
        # paper protocol: the mean length claims above judge it, a fitness_final claim would repeat them)
        # li2023 §6.1, Fig 13: IGA's fitness (eq 2) ends below TGA's
        *(Claim("li2023_global", "§6.1, Fig 13", "IGA ends at a lower fitness than TGA", m, "less", "iga", "ga",
                "fitness_final") for m in ("li2023_30", "li2023_60", "li2023_90")),
        # li2023 §6.2 Experiment I, Fig 16: the fusion drives a smoother path than the traditional DWA
        Claim("li2023_local_exp1", "§6.2, Fig 16", "the fusion's driven path is smoother than the traditional DWA's "
              "(heading change per metre)", "li2023_exp1", "less", "iga/iga-dwa", "iga/dwa", "heading_change_per_m"),
    )


# Issue 44 item 1, second half: the local claims judged at the paper's printed setting and, where we
# changed a setting to make a method work, with that change too. The local specs run each paper's
# preset as we ship it and its twin as printed (``<preset>-printed``, optplan/local/presets.py:
# OUR_CHANGES says what the twin drops); every local claim on a group with such a preset gets a twin
# claim on the printed group, with the same quote, target, kind and claimed size. The claims table
# shows the twin's verdict first and ours beside it; :func:`differing_verdicts` lists the pairs whose
# verdicts differ. The specs' other departures from the papers (robot model, map stand-ins, how the
# movers' tracks are drawn) are the same in both columns: docs/fidelity/<paper>.md names them.
LOCAL_SPECS = ("hou2024_local_table4", "hou2024_local_dynamic", "yang2023_local_crossing", "yang2023_local_fusion",
               "yuan2021_local_added", "yuan2021_local_switch", "li2023_local_exp1", "li2023_local_exp2")
# verdicts that judge nothing: a pair with one of them on either side is not compared
NO_VERDICT = ("not run", TOO_FEW_RUNS)


def printed_group(group: str | None) -> str | None:
    """``label/<preset>-printed`` for a pipeline whose local planner has a printed twin, else
    ``group`` unchanged (an algorithm label, or a preset with nothing of ours in it)."""
    if group is None or "/" not in group:
        return group
    label, local = group.rsplit("/", 1)
    return f"{label}/{PRINTED[local]}" if local in PRINTED else group


def _printed_twin(c: Claim) -> Claim | None:
    """``c`` on the printed twins of its groups (a combination: on its parts' twins), or ``None`` when
    nothing of ours is in it."""
    from dataclasses import replace

    if c.parts:
        parts = tuple(_printed_twin(p) or p for p in c.parts)
        return None if parts == c.parts else combined_claim(c.kind, c.source, c.quote, parts, c.target, c.note)
    better, other = printed_group(c.better), printed_group(c.other)
    return None if (better, other) == (c.better, c.other) else replace(c, better=better, other=other)


def _printed_pairs(claims: Iterable[Claim]) -> list[tuple[Claim, Claim]]:
    """``(our claim, its twin as printed)`` for every local claim whose groups have a printed twin."""
    out = []
    for c in claims:
        twin = _printed_twin(c) if c.spec in LOCAL_SPECS else None
        if twin is not None:
            out.append((c, twin))
    return out


def _changes_text(twins) -> str:
    """What the printed twins of ``twins`` drop, per preset (the table's column header)."""
    presets = []
    for t in twins:
        for g in (t.better, t.other):
            local = g.rsplit("/", 1)[-1] if g else ""
            base = next((k for k, v in PRINTED.items() if v == local), None)
            if base and base not in presets:
                presets.append(base)
    return "; ".join(f"{p}'s {OUR_CHANGES[p]}" for p in presets)


@dataclass(frozen=True)
class TwinVerdict:
    """The verdicts of one local claim at the paper's printed setting and with our change."""

    claim: Claim      # ours (the shipped preset)
    twin: Claim       # the same claim on the printed twin
    printed: str      # verdict as printed
    ours: str         # verdict with our change

    @property
    def judged(self) -> bool:
        """Both sides have a verdict (neither ``not run`` nor ``too few runs``)."""
        return self.printed not in NO_VERDICT and self.ours not in NO_VERDICT

    @property
    def differs(self) -> bool:
        return self.judged and self.printed != self.ours


def twin_verdicts(verdicts: Mapping[str, str],
                  pairs: Iterable[tuple[Claim, Claim]] | None = None) -> list[TwinVerdict]:
    """The ``(our claim, printed twin)`` pairs (default :data:`PRINTED_PAIRS`) whose two claims
    ``verdicts`` (claim id -> verdict, e.g. read off the claims tables) holds, in their order."""
    pairs = PRINTED_PAIRS if pairs is None else pairs
    return [TwinVerdict(c, t, verdicts[t.id], verdicts[c.id]) for c, t in pairs
            if c.id in verdicts and t.id in verdicts]


def differing_verdicts(verdicts: Mapping[str, str],
                       pairs: Iterable[tuple[Claim, Claim]] | None = None) -> list[TwinVerdict]:
    """The pairs of :func:`twin_verdicts` judged on both sides whose verdicts differ: the claims
    whose verdict at the paper's printed setting is not the one with our change."""
    return [t for t in twin_verdicts(verdicts, pairs) if t.differs]


def _twin_notes(pairs: list[TwinVerdict]) -> list[str]:
    judged = [t for t in pairs if t.judged]
    differ = [t for t in judged if t.differs]
    lines = ["ours / verdict: at the paper's printed setting (compared: the -printed presets, without our "
             "change); with our change: the shipped preset, judged on the same worlds and seeds; '-': the claim's "
             "groups carry nothing of ours",
             f"verdicts that differ between the paper's setting and our change: {len(differ)} of {len(judged)} "
             f"pairs judged on both sides" + (f" ({len(pairs) - len(judged)} more without a verdict)"
                                              if len(judged) < len(pairs) else "")]
    lines += [f"- {t.claim.quote} ({target_text(t.claim)}): {t.printed} as printed, {t.ours} with our change"
              for t in differ]
    return lines


LI2023_MAPS = ("li2023_30", "li2023_60", "li2023_90")
_ONE_ASTAR_RUN = "A* runs once per map (deterministic): its mean is exact, the interval comes from IGA's runs alone"


# chen2025 §4.3.2: the reductions of the mean length by MSIAR-GWO against each baseline on the 20x20,
# 30x30 and 40x40 maps (percent), as the text gives them
CHEN2025_MAPS = ("chen2025_20", "chen2025_30", "chen2025_40")
CHEN2025_MEAN_REDUCTIONS = {"gwo": (4.33, 17.77, 22.88), "aro": (0.73, 4.27, 4.47), "dbo": (4.18, 11.99, 7.10),
                            "woa": (11.54, 14.52, 8.32), "igwo": (0.58, 6.09, 19.40), "agwo": (6.54, 15.02, 22.65),
                            "rsmgwo": (3.57, 14.59, 21.97)}


def _lead_trend_claims() -> tuple[Claim, ...]:
    """li2023's statements that IGA's gains grow with the map size (kind ``lead_trend``; issue 44,
    "across targets"). ``claimed``: the change of the paper's reduction from the first map to the last."""
    return (
        # §6.1, Fig 15 with Table 1: from 60x60 to 90x90 "the optimization effect of each performance index is
        # more obvious", the running time's reduction rising from 48.5 % to 62.1 %
        *(lead_trend_claim("li2023_global", "§6.1, Fig 15, Table 1", f"IGA's {what} gain over TGA grows from 60x60 to "
                           f"90x90 ({a} % -> {b} %)", LI2023_MAPS[1:], "iga", "ga", metric, claimed, note)
          for what, metric, a, b, claimed, note in (
              ("length", "length", 4.8, 4.9, 0.049 - 0.048, ""),
              ("running-time", "runtime_s", 48.5, 62.1, 0.621 - 0.485, _TIMING),
              ("key-point", "n_turns", 86.7, 78.2, None,
               "the text says every index's gain grows from 60x60 to 90x90, its own Table 1 has the key-point gain "
               "falling (86.7 % -> 78.2 %): judged as the text says"))),
        # §6.3, Table 2: IGA's lead over A* is "more obvious as the map size increases", only its key-point lead
        # "decreases slightly" (listed from the largest map, as a lead that grows towards the smallest)
        lead_trend_claim("li2023_global", "§6.3, Table 2", "IGA's length lead over A* grows with the map size "
                         "(1.4 % -> 7.2 % -> 8.6 %)", LI2023_MAPS, "iga", "astar", "length", 0.086 - 0.014,
                         _ONE_ASTAR_RUN),
        lead_trend_claim("li2023_global", "§6.3, Table 2", "IGA's running-time lead over A* grows with the map size "
                         "(38.9 % -> 68.1 % -> 69.4 %)", LI2023_MAPS, "iga", "astar", "runtime_s", 0.694 - 0.389,
                         f"{_ONE_ASTAR_RUN}; IGA is the slower one here on every map (Table 2's running-time claims), "
                         f"so this judges how its deficit changes; {_TIMING}"),
        lead_trend_claim("li2023_global", "§6.3, Table 2", "IGA's key-point lead over A* shrinks slightly with the map "
                         "size (30.0 % -> 45.5 % -> 22.7 %)", LI2023_MAPS[::-1], "iga", "astar", "n_turns",
                         0.300 - 0.227, _ONE_ASTAR_RUN),
        # chen2025 §4.3.2: the more complex the map, the weaker the others' search and the stronger MSIAR-GWO's; read
        # as its mean-length lead over each baseline growing from 20x20 to 40x40 (the text's own reductions)
        *(lead_trend_claim("chen2025_paths", "§4.3.2, Tables 9-11", f"MSIAR-GWO's mean-length lead over {o.upper()} "
                           f"grows with the map's complexity ({a} % -> {b} % -> {c} %)", CHEN2025_MAPS, "msiar-gwo", o,
                           "length", (c - a) / 100,
                           "; ".join(n for n in (_AGWO_NOTE if o in _CHEN2025_IDENTIFIED else "",
                                                 f"the text's reductions have this lead shrinking ({a} % -> {c} %): "
                                                 "judged as the text's summary says" if c < a else "") if n))
          for o, (a, b, c) in CHEN2025_MEAN_REDUCTIONS.items()),
    )


def _summary_claims(known: Iterable[Claim]) -> tuple[Claim, ...]:
    """The statements that sum up others, as combinations of the claims judging their parts (issue 44,
    "summary"; kinds ``all``, ``most``, ``net``). ``known``: the claims defined so far (the parts)."""
    by_id = {c.id: c for c in known}

    def part(spec: str, target: str, kind: str, better: str, other: str | None = None, metric: str = "length",
             quote: str | None = None) -> Claim:
        """The known claim with these fields; with ``quote``, a part of its own when no claim has them."""
        c = Claim(spec, "", quote or "", target, kind, better, other, metric)
        if c.id not in by_id and quote is None:
            raise KeyError(f"a summary names claim {c.id}, which is not defined")
        return by_id.get(c.id, c)

    hou_envs = ("hou2024_env1", "hou2024_env2")
    hou = [combined_claim("all", "§4.3.2 (end), Tables 2-3", f"MISSA's paths beat ACO, IACO and SSA in {what} on both "
                          "maps (best and mean)",
                          [part("hou2024_global", env, kind, "missa", o, m) for env in hou_envs for m in metrics
                           for o in ("aco", "iaco", "ssa") for kind in ("less_best", "less")], note=note)
           for what, metrics, note in (
               ("length and total rotation", ("length", "turn_angle_deg"),
                "hou2024 §4.3's summary: its parts are Tables 2-3's best and mean against the colonies' raw paths at "
                "equal iterations, as the paper compares them (the pruned and equal-evaluation claims above are "
                "judged on their own)"),
               ("run time", ("runtime_s",), _TIMING))]
    yuan = [combined_claim("all", "§5.1 (1), Table 1", "IBA's paths are the best of the three in length (its longest, "
                           "shortest and mean below PSO's and BA's)",
                           [part("yuan2021_table1", "yuan2021_25", kind, "iba", o) for o in ("pso", "ba")
                            for kind in ("less_worst", "less_best", "less")])]
    yang = [combined_claim("all", "§7.1, Tables 1-2", "IPSO's mean and shortest lengths are the best of the four in "
                           "both environments",
                           [part("yang2023_global", env, kind, "ipso", o) for env in ("yang2023_env1", "yang2023_env2")
                            for o in ("pso", "ipso1", "ipso2") for kind in ("less", "less_best")],
                           note="its parts at equal iterations, as the paper compares them; " + _IPSO2_NOTE)]
    li = [combined_claim("all", "§6.1, Table 1", "TGA converges slowly and prematurely, with more key points, poorer "
                         "smoothing and longer paths than IGA",
                         [part("li2023_global", m, "less", "iga", "ga", metric)
                          for metric in ("convergence_iter", "fitness_final", "n_turns", "turn_angle_deg", "length")
                          for m in LI2023_MAPS],
                         note="slowly: more generations to converge (Fig 13); prematurely: a worse final fitness "
                              "(eq 2, Fig 13); smoothing: the total turning angle")]
    li += [combined_claim("all", "§6.4 (end)", "the fusion avoids the moving obstacles and drives a shorter path than "
                          "the traditional DWA",
                          [part(spec, t, "rate", "iga/iga-dwa") for t in targets]
                          + [part(spec, t, "less", "iga/iga-dwa", "iga/dwa", "path_length") for t in targets],
                          note="§6.4's summary judged on its simulated parts (Experiments I and II): 'safer than A* "
                               "or TGA alone' needs a global path followed without a local planner, which no spec "
                               "runs, and 'fits the robot's motion, good real-time performance' names no measure")
           for spec, targets in (("li2023_local_exp1", ("li2023_exp1",)), ("li2023_local_exp2", LI2023_EXP2_TARGETS))]
    chen = []
    for spec in _CHEN2025_FUNCTION_SPECS:
        for o in _CHEN2025_IMPLEMENTED:
            wins, ties, losses = CHEN2025_TABLE7_TALLY[o]
            parts = [part(spec, f, "less", "msiar-gwo", o, "f", f"MSIAR-GWO's mean below {o.upper()}'s in {f}")
                     for f in CHEN2025_TABLE7]
            note = "; ".join(n for n in (_AGWO_NOTE if o in _CHEN2025_IDENTIFIED else "",
                                         "two of the parts, F6 and F12, are the functions MSIAR-GWO was tuned on")
                             if n)
            chen += [combined_claim("most", "§4.2, Fig 9", f"MSIAR-GWO beats {o.upper()} in most of F1-F18 (Table 7: "
                                    f"in {wins})", parts, "F1-F18", note),
                     combined_claim("net", "§4.2, Table 7", f"MSIAR-GWO wins more of F1-F18 than it loses against "
                                    f"{o.upper()} (Table 7: {wins}/{ties}/{losses})", parts, "F1-F18", note)]
    # qualitative wordings judged on a stated reading (claim_inventory: Statement.reading)
    hou += [combined_claim("all", "§4.3.2 (end)", "MISSA is very stable and gives smooth paths",
                           [part("hou2024_global", env, "less_spread", "missa", o, "length") for env in hou_envs
                            for o in ("aco", "iaco", "ssa")]
                           + [part("hou2024_global", env, "less", "missa", o, "turn_angle_deg") for env in hou_envs
                              for o in ("aco", "iaco", "ssa")], "hou2024_env1+hou2024_env2 (spread, rotation)",
                           note="read as: MISSA's lengths vary less over the runs (standard deviation, Levene's test) "
                                "and its paths turn less (mean total rotation) than ACO's, IACO's and SSA's on both "
                                "maps")]
    chen += [combined_claim("most", "§4.1, Fig 8", "MSIAR-GWO searches the fixed-dimension functions more stably",
                            [part(spec, f, "less_spread", "msiar-gwo", o, "f",
                                  f"MSIAR-GWO's values vary less than {o.upper()}'s in {f}")
                             for f in ("F14", "F15", "F16", "F17", "F18") for o in _CHEN2025_IMPLEMENTED],
                            "F14-F18", note="read as: MSIAR-GWO's standard deviation below the baseline's (Levene's "
                                            "test) in most of the 35 pairs of F14-F18 and the seven baselines")
             for spec in _CHEN2025_FUNCTION_SPECS]
    chen += [combined_claim("most", "§4.3.2", "MSIAR-GWO's global search is stronger in complex maps",
                            [by_id[lead_trend_claim("chen2025_paths", "", "", CHEN2025_MAPS, "msiar-gwo", o,
                                                    "length").id] for o in CHEN2025_MEAN_REDUCTIONS],
                            "chen2025_20-40", note="read as: its mean-length lead over most baselines grows from "
                                                    "the 20x20 map to the 40x40 one (the lead trends above)")]
    return (*hou, *yuan, *yang, *li, *chen)


# chen2025 Tables 4-6 as printed (best, mean, worst, standard deviation of 20 runs per algorithm and
# function; the signs the extracted text lost restored, as the file's header says)
CHEN2025_PRINTED_FILE = Path(__file__).resolve().parent.parent / "data" / "chen2025_tables_4_6.csv"
CHEN2025_PRINTED_RUNS = 20


def chen2025_printed_tables() -> list[dict[str, str]]:
    """The rows of chen2025 Tables 4-6 as printed: ``function``, ``algorithm``, ``best``, ``mean``,
    ``worst``, ``sd`` (strings, digits as printed)."""
    import csv

    with open(CHEN2025_PRINTED_FILE, newline="") as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def _printed_value_claims() -> tuple[Claim, ...]:
    """Tables 4-6's absolute values: each algorithm's printed mean on each function, judged on the
    functions as printed (the paper's setting; the shifted run's values are in its own report)."""
    from ..formulations.functions import get_function

    out = []
    for row in chen2025_printed_tables():
        f, a = row["function"], row["algorithm"]
        n = int(f[1:])
        table = 4 if n <= 7 else 5 if n <= 13 else 6
        printed = Printed(row["mean"], float(row["sd"]), CHEN2025_PRINTED_RUNS, get_function(f).f_opt)
        # DBO's values against optplan's origin-free DBO and against the original's rules (the paper's)
        for label in (a, "dbo-original") if a == "dbo" else (a,):
            out.append(Claim("chen2025_functions_unshifted", f"Table {table}", f"{a.upper()}'s mean in {f} is "
                             f"{row['mean']}", f, "printed", label, metric="f",
                             note=_function_note(f, a) if a == "msiar-gwo" else
                             _DBO_ORIGINAL_NOTE if label == "dbo-original" else _function_note("", a),
                             printed=printed))
    return tuple(out)


_DBO_ORIGINAL_NOTE = ("dbo-original: DBO with the original's rules that scale with the coordinates (origin_pull=True, "
                      "optplan/solvers/metaheuristics/dbo.py), which the paper ran; optplan's dbo drops them")


ADDED_CLAIMS = _added_claims() + _lead_trend_claims() + _printed_value_claims()
ADDED_CLAIMS += _summary_claims(CLAIMS + ADDED_CLAIMS)
# (local claim judged with our change, its twin at the paper's printed setting)
PRINTED_PAIRS: tuple[tuple[Claim, Claim], ...] = tuple(_printed_pairs(CLAIMS + ADDED_CLAIMS))
ADDED_CLAIMS += tuple(t for _, t in PRINTED_PAIRS)
# the same by our claim's id
PRINTED_TWINS: dict[str, Claim] = {c.id: t for c, t in PRINTED_PAIRS}
CLAIMS = CLAIMS + ADDED_CLAIMS
