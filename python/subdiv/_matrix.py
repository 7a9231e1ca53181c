"""Composing the library's stencil plan (one CSR table per level) into the
subdivision matrix of :func:`subdiv.matrix`, in the caller's numbering."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp


def _level(n_in, copies, offsets, indices, weights):
    """One level as a sparse matrix (rows: the level's new vertices)."""
    rows = len(offsets) - 1
    m = sp.csr_matrix((weights.astype(np.float64), indices.astype(np.int64), offsets.astype(np.int64)),
                      shape=(rows, n_in))
    if copies:  # an interpolating level keeps the old vertices first
        m = sp.vstack([sp.identity(n_in, format="csr"), m], format="csr")
    return m


def compose(levels, faces, kept, n_input):
    """``(S, F2)``: the levels multiplied, rows and columns renumbered so
    that the caller's vertex ``i`` is row and column ``i``, vertices no
    face uses carried by an identity row."""
    n_kept = n_input if kept is None else len(kept)
    p = sp.identity(n_kept, format="csr")
    for lv in levels:
        p = (_level(*lv) @ p).tocsr()
    p = p.tocoo()
    if kept is None:
        s = sp.csr_matrix((p.data, (p.row, p.col)), shape=(p.shape[0], n_input))
        return s, faces
    kept = kept.astype(np.int64)
    n2 = n_input + p.shape[0] - n_kept
    row_of = np.concatenate([kept, np.arange(n_input, n2, dtype=np.int64)])
    unused = np.setdiff1d(np.arange(n_input, dtype=np.int64), kept)
    rows = np.concatenate([row_of[p.row], unused])
    cols = np.concatenate([kept[p.col], unused])
    data = np.concatenate([p.data, np.ones(len(unused))])
    return sp.csr_matrix((data, (rows, cols)), shape=(n2, n_input)), faces
