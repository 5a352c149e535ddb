"""calibrate_experiments_fit: the fit of calibrate_experiments.py (issue 42 split it out).

Pure functions on a prediction matrix pred[grid point, test] in [0, 1] and outcomes y[test] in {0, 1}:
the likelihood with an unknown error rate e, the posterior over grid points, the predictive P,
stratified folds, cross-validation, the scores reported and the posterior's support (the model is
described in calibrate_experiments.py's docstring). Also the tool's one error type, which the grid,
the runs and the fit all raise. Numpy only; calibrate_experiments.py re-exports every name.
"""
import numpy as np



class CalibrationError(Exception):
    """Bad grid, missing tool, failed run or unreadable table; the message names file and field."""


# ================================================================ the fit (pure functions)

def default_e_grid(n=199):
    """Midpoints of n equal cells of (0, 0.5): e = 0 and 0.5 excluded (log 0; and beyond 0.5 a grid
    point would be rewarded for being mostly wrong)."""
    return (np.arange(n) + 0.5) * (0.5 / n)


def per_test_loglik(pred, y, e_grid):
    """log P(y_i | grid point k, e_j), shape (K, N, E)."""
    pred = np.asarray(pred, dtype=float)
    y = np.asarray(y, dtype=float)
    e = np.asarray(e_grid, dtype=float)[None, None, :]
    q = pred[:, :, None] * (1.0 - e) + (1.0 - pred[:, :, None]) * e  # P(y = 1)
    return y[None, :, None] * np.log(q) + (1.0 - y[None, :, None]) * np.log1p(-q)


def posterior_from_loglik(ll, e_grid, method="integrate"):
    """Posterior over grid points (uniform prior) from summed log-likelihoods ll (K, E).
    integrate: marginal likelihood, uniform prior on e over the grid; max: profile likelihood.
    Returns weights (K,), e's posterior mean, the MAP point's e (its own maximum)."""
    e_grid = np.asarray(e_grid, dtype=float)
    if method == "integrate":  # log of the mean over e, each row scaled by its own maximum
        top = ll.max(axis=1, keepdims=True)
        score = np.log(np.exp(ll - top).mean(axis=1)) + top[:, 0]
    elif method == "max":
        score = ll.max(axis=1)
    else:
        raise CalibrationError(f"--e-method {method}: not one of integrate, max")
    w = np.exp(score - score.max())
    w /= w.sum()
    if method == "integrate":  # joint posterior of (k, e) under both uniform priors, summed over k
        joint = np.exp(ll - ll.max())
        e_mean = float((joint.sum(axis=0) * e_grid).sum() / joint.sum())
    else:  # each point's own maximum, weighted
        e_mean = float((w * e_grid[np.argmax(ll, axis=1)]).sum())
    k_map = int(np.argmax(w))
    return w, e_mean, float(e_grid[int(np.argmax(ll[k_map]))])


def fit(pred, y, train=None, e_grid=None, method="integrate", _ll=None):
    """The posterior fitted on the tests `train` (indices or a boolean mask; default all).
    pred (K, N) in [0, 1], y (N,) in {0, 1}. Returns dict: weights (K,), map (index), e_mean,
    e_map (the MAP point's maximum-likelihood e)."""
    pred = np.asarray(pred, dtype=float)
    y = np.asarray(y)
    if pred.ndim != 2 or y.ndim != 1 or pred.shape[1] != y.shape[0]:
        raise CalibrationError(f"prediction matrix {pred.shape} and outcomes {y.shape} do not match")
    if not np.all((y == 0) | (y == 1)):
        raise CalibrationError("outcomes must be 0 or 1")
    e_grid = default_e_grid() if e_grid is None else np.asarray(e_grid, dtype=float)
    ll = per_test_loglik(pred, y, e_grid) if _ll is None else _ll
    mask = np.ones(y.shape[0], dtype=bool) if train is None else _mask(train, y.shape[0])
    w, e_mean, e_map = posterior_from_loglik(ll[:, mask, :].sum(axis=1), e_grid, method)
    return {"weights": w, "map": int(np.argmax(w)), "e_mean": e_mean, "e_map": e_map}


def _mask(idx, n):
    idx = np.asarray(idx)
    if idx.dtype == bool:
        return idx
    m = np.zeros(n, dtype=bool)
    m[idx] = True
    return m


def predictive(pred, weights):
    """P(overturn) per test: the posterior-weighted mean of the grid points' predictions."""
    return np.asarray(weights, dtype=float) @ np.asarray(pred, dtype=float)


def stratified_folds(y, k, seed):
    """Fold number per test: within each outcome class the tests are shuffled (fixed seed) and dealt
    round-robin, so every fold has the class balance of the whole to within one test."""
    y = np.asarray(y)
    if k < 2 or k > len(y):
        raise CalibrationError(f"--folds {k}: need 2 <= k <= {len(y)} tests")
    rng = np.random.default_rng(seed)
    fold = np.empty(len(y), dtype=int)
    offset = 0
    for cls in (0, 1):
        idx = np.flatnonzero(y == cls)
        rng.shuffle(idx)
        fold[idx] = (np.arange(len(idx)) + offset) % k
        offset += len(idx)  # continue the dealing where the other class stopped: even fold sizes
    return fold


def cross_validate(pred, y, folds, e_grid=None, method="integrate"):
    """Held-out P(overturn) for every test: each fold predicted by the fit on the other folds only.
    folds: fold number per test (leave-one-out: np.arange(N)). Returns (P (N,), per-fold fits)."""
    pred = np.asarray(pred, dtype=float)
    y = np.asarray(y)
    folds = np.asarray(folds)
    e_grid = default_e_grid() if e_grid is None else np.asarray(e_grid, dtype=float)
    ll = per_test_loglik(pred, y, e_grid)
    p = np.empty(len(y))
    fits = []
    for f in np.unique(folds):
        held = folds == f
        # summed over the training tests only (not total minus held-out: that would carry the
        # held-out outcomes in its rounding)
        w, e_mean, e_map = posterior_from_loglik(ll[:, ~held, :].sum(axis=1), e_grid, method)
        p[held] = predictive(pred[:, held], w)
        fits.append({"fold": int(f), "map": int(np.argmax(w)), "e_mean": e_mean, "e_map": e_map,
                     "weights": w})
    return p, fits


def scores(p, y):
    """Accuracy, precision, recall, F1 of the label P >= 0.5 and the Brier score of P."""
    p = np.asarray(p, dtype=float)
    y = np.asarray(y).astype(int)
    lab = (p >= 0.5).astype(int)
    tp = int(((lab == 1) & (y == 1)).sum())
    fp = int(((lab == 1) & (y == 0)).sum())
    tn = int(((lab == 0) & (y == 0)).sum())
    fn = int(((lab == 0) & (y == 1)).sum())
    n = len(y)
    prec = tp / (tp + fp) if tp + fp else None
    rec = tp / (tp + fn) if tp + fn else None
    f1 = 2 * tp / (2 * tp + fp + fn) if tp + fp + fn else None
    return {"tests": n, "tp": tp, "fp": fp, "tn": tn, "fn": fn, "accuracy": (tp + tn) / n if n else None,
            "precision": prec, "recall": rec, "f1": f1, "brier": float(((p - y) ** 2).mean()) if n else None}


def systematic_resample(weights, m):
    """m members drawn in proportion to weights (systematic resampling, offset 1/2: deterministic).
    Returns the count per weight; counts sum to m and each is floor or ceil of m w_k."""
    w = np.asarray(weights, dtype=float)
    if m < 1 or not np.all(w >= 0) or not w.sum() > 0:
        raise CalibrationError(f"resampling needs m >= 1 and weights >= 0 with a positive sum (m = {m})")
    c = np.cumsum(w / w.sum())
    c[-1] = 1.0
    pos = (np.arange(m) + 0.5) / m
    return np.bincount(np.searchsorted(c, pos, side="right"), minlength=len(w))


def support(weights, rel=1e-3, cap=20):
    """Indices of the posterior's support, heaviest first: weight > rel x the total, at most cap."""
    w = np.asarray(weights, dtype=float)
    order = np.argsort(-w, kind="stable")
    keep = [int(k) for k in order if w[k] > rel * w.sum()]
    return keep[:cap]


def evaluate(pred, y, folds_k=10, seed=20, e_grid=None, method="integrate", loo=True):
    """Everything reported for one specimen: in-sample, k-fold and leave-one-out scores and P."""
    y = np.asarray(y).astype(int)
    full = fit(pred, y, e_grid=e_grid, method=method)
    p_in = predictive(pred, full["weights"])
    folds = stratified_folds(y, folds_k, seed)
    p_cv, cv_fits = cross_validate(pred, y, folds, e_grid, method)
    out = {"fit": full, "p_in": p_in, "p_cv": p_cv, "in_sample": scores(p_in, y), "cv": scores(p_cv, y),
           "cv_folds": cv_fits, "fold_of_test": folds}
    # the noise-aware predictive (1 - 2e) P + e: what the likelihood itself says of a held-out test
    out["p_in_e"] = (1 - 2 * full["e_mean"]) * p_in + full["e_mean"]
    out["in_sample"]["brier_with_e"] = float(((out["p_in_e"] - y) ** 2).mean())
    out["p_cv_e"] = with_e(p_cv, folds, cv_fits)
    out["cv"]["brier_with_e"] = float(((out["p_cv_e"] - y) ** 2).mean())
    if loo:
        loo_folds = np.arange(len(y))
        p_loo, loo_fits = cross_validate(pred, y, loo_folds, e_grid, method)
        out["p_loo"] = p_loo
        out["loo"] = scores(p_loo, y)
        out["p_loo_e"] = with_e(p_loo, loo_folds, loo_fits)
        out["loo"]["brier_with_e"] = float(((out["p_loo_e"] - y) ** 2).mean())
    return out


def with_e(p, folds, fits):
    """Each fold's noise-aware P: (1 - 2e) P + e with that fold's own e."""
    q = np.empty_like(p)
    for f in fits:
        held = folds == f["fold"]
        q[held] = (1 - 2 * f["e_mean"]) * p[held] + f["e_mean"]
    return q
