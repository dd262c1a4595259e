"""Kinematic-structure average precision against the true undirected contact edges (paper Sec. IV, Tab. II).

Definition used here, per object:

- The items are the object's estimated *undirected* part-part contact edges ``{p, q}`` with a contact
  score ``s > 0`` (for a directed estimate, an undirected edge takes the larger score of its two
  directions). An edge is *relevant* when ``{p, q}`` is among the true contact edges of ``truth.json``.
- Edges are ranked by decreasing score. With the distinct score values ``t_1 > t_2 > ...`` as
  thresholds (tied edges enter the ranking together, so the order inside a tie cannot matter),

      AP = sum_k (R_k - R_{k-1}) * P_k,
      P_k = (relevant edges with s >= t_k) / (edges with s >= t_k),
      R_k = (relevant edges with s >= t_k) / (number of true edges),   R_0 = 0.

  Without ties this is the familiar ``1/|true| * sum over relevant ranks r of precision@r``.
- A true edge that was never estimated is never retrieved: recall stops short of 1 and the AP is
  reduced accordingly (it is not appended at the end of the ranking).
- An object with no true edge (a single-part object) has no AP (``nan``); it is left out of the mean.

The kinematic **mAP** of a category is the mean of the AP of its objects (:func:`mean_average_precision`).
"""

from __future__ import annotations

from typing import Iterable, Mapping

import numpy as np

from recon.metrics.errors import EstimateError

__all__ = ["average_precision", "undirected_scores", "contact_edge_ap", "mean_average_precision"]


def average_precision(scores: np.ndarray, relevant: np.ndarray, n_true: int) -> float:
    """Average precision of a scored retrieval (module definition, ties grouped).

    scores : (n,) float > 0 — score of each retrieved item
    relevant : (n,) bool — whether each retrieved item is a true one
    n_true : int — number of true items, retrieved or not (>= relevant.sum())
    returns : float in [0, 1], ``nan`` when ``n_true == 0``
    """
    s = np.asarray(scores, dtype=np.float64).reshape(-1)
    r = np.asarray(relevant, dtype=bool).reshape(-1)
    if s.shape != r.shape:
        raise EstimateError(f"average_precision: {s.size} scores but {r.size} relevance flags")
    if not np.all(np.isfinite(s)):
        raise EstimateError("average_precision: scores contain NaN/inf")
    if int(r.sum()) > n_true:
        raise EstimateError(f"average_precision: {int(r.sum())} relevant items retrieved but n_true={n_true}")
    if n_true == 0:
        return float("nan")
    if s.size == 0:
        return 0.0
    order = np.argsort(-s, kind="stable")
    s, r = s[order], r[order]
    tp = np.cumsum(r)
    # last index of each run of equal scores: the thresholds
    last = np.flatnonzero(np.r_[s[1:] != s[:-1], True])
    tp_at = tp[last].astype(np.float64)
    precision = tp_at / (last + 1)
    recall = tp_at / n_true
    return float(np.sum(np.diff(np.r_[0.0, recall]) * precision))


def undirected_scores(scores: Mapping[tuple[int, int], float], where: str = "object") -> dict[frozenset, float]:
    """Directed (or undirected) edge scores -> undirected ``{frozenset({p, q}): max score}``.

    Edges with score 0 are dropped (not retrieved); negative, NaN scores and self-loops are errors.
    """
    out: dict[frozenset, float] = {}
    for (p, q), s in scores.items():
        s = float(s)
        if p == q:
            raise EstimateError(f"{where}: contact edge ({p}, {q}) joins a part to itself")
        if not np.isfinite(s) or s < 0:
            raise EstimateError(f"{where}: contact edge ({p}, {q}) has score {s}, expected a finite value >= 0")
        if s == 0:
            continue
        key = frozenset((int(p), int(q)))
        out[key] = max(out.get(key, 0.0), s)
    return out


def contact_edge_ap(true_edges: Iterable[tuple[int, int]], estimated: Mapping[tuple[int, int], float],
                    part_ids: Iterable[int] | None = None, where: str = "object") -> float:
    """AP of one object's estimated contact edges against its true undirected contact edges.

    true_edges : pairs of part ids (order irrelevant)
    estimated : ``{(parent_or_p, child_or_q): contact score}``; both directions may be present
    part_ids : the object's part ids; when given, an estimated edge naming another part is an error
    where : name of the object for error messages
    returns : float in [0, 1], or ``nan`` if the object has no true edge
    """
    truth = {frozenset((int(p), int(q))) for p, q in true_edges}
    est = undirected_scores(estimated, where)
    if part_ids is not None:
        known = {int(i) for i in part_ids}
        for edge in est:
            unknown = sorted(edge - known)
            if unknown:
                raise EstimateError(f"{where}: estimated contact edge {sorted(edge)} names unknown part(s) {unknown}")
    items = sorted(est.items(), key=lambda kv: sorted(kv[0]))
    scores = np.array([s for _, s in items])
    relevant = np.array([e in truth for e, _ in items], dtype=bool)
    return average_precision(scores, relevant, len(truth))


def mean_average_precision(aps: Iterable[float]) -> float:
    """Mean of the finite APs (objects without true edges are left out); ``nan`` if none is finite."""
    a = np.array([x for x in aps if np.isfinite(x)], dtype=np.float64)
    return float(a.mean()) if a.size else float("nan")
