"""The verdict of a robust certificate from its sampled executions (pure; no simulator).

"Certified robustly" means: with ``confidence`` (95 %), at least ``success_lower_bound`` of the worlds
consistent with the scan let this plan open the part. The bound is the one-sided Clopper–Pearson lower
bound on the success probability from ``successes`` of ``samples`` independent executions; the task is
certified when it reaches ``min_success`` (with 30 samples and the default 0.9 that takes 30 of 30).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from scipy.stats import beta

from scenes.outcome import Outcome
from simcheck.perturbations import Perturbation

__all__ = ["CONFIDENCE", "DEFAULT_MIN_SUCCESS", "SampleResult", "success_lower_bound", "robust_block",
           "robust_outcome"]

CONFIDENCE = 0.95
"""Confidence of the lower bound on the success probability."""
DEFAULT_MIN_SUCCESS = 0.9
"""A task is certified robustly when the lower bound reaches this."""


def success_lower_bound(successes: int, samples: int, confidence: float = CONFIDENCE) -> float:
    """One-sided Clopper–Pearson lower bound p: P(success probability >= p) >= ``confidence`` given
    ``successes`` of ``samples`` Bernoulli trials. 0 when there is no success."""
    if samples < 1 or not 0 <= successes <= samples:
        raise ValueError(f"need 0 <= successes <= samples and samples >= 1, got {successes} of {samples}")
    if successes == 0:
        return 0.0
    return float(beta.ppf(1.0 - confidence, successes, samples - successes + 1))


@dataclass(frozen=True)
class SampleResult:
    """How the plan fared in one sampled world: its outcome, reason, and each criterion's margin."""

    perturbation: Perturbation
    outcome: Outcome
    reason: str
    margins: dict = field(default_factory=dict)

    @property
    def success(self) -> bool:
        return self.outcome is Outcome.CERTIFIED


def robust_block(results: list[SampleResult], confidence: float = CONFIDENCE, extra: dict | None = None) -> dict:
    """The ``"robust"`` block of a task in certificate.json (results in sample order).

    ``worst_margins`` : per criterion, the smallest margin over the samples that measured it (null when
    it could not be measured in some sample, e.g. a grasp never made).
    ``extra`` : further keys (the spreads sampled, their source), appended after the issue's keys.
    """
    n = len(results)
    k = sum(r.success for r in results)
    worst: dict[str, float] = {}
    for r in results:
        for name, m in r.margins.items():
            worst[name] = min(worst.get(name, float("inf")), float(m))
    worst = {name: (m if math.isfinite(m) else None) for name, m in worst.items()}
    block = {"samples": n, "successes": k, "success_lower_bound": success_lower_bound(k, n, confidence) if n else 0.0,
             "confidence": confidence, "worst_margins": worst,
             "perturbations": [r.perturbation.to_dict() for r in results],
             "failures": [{"sample": r.perturbation.index, "perturbation": r.perturbation.to_dict(),
                           "outcome": r.outcome.value, "reason": r.reason} for r in results if not r.success]}
    block.update(extra or {})
    return block


def robust_outcome(block: dict, min_success: float) -> Outcome:
    """CERTIFIED when the block's lower bound reaches ``min_success``, else FAILED."""
    return Outcome.CERTIFIED if block["success_lower_bound"] >= min_success else Outcome.FAILED
