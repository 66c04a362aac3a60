"""castor.mesh.seams.keys_in: the membership test of the seams' half-edge keys
(a sort and a search in place of np.isin) gives np.isin's answer, key for key."""

from __future__ import annotations

import numpy as np

from castor.mesh.seams import keys_in


def test_keys_in_is_isin_on_half_edge_keys():
    rng = np.random.default_rng(7)
    n = 5_000
    triangles = rng.integers(0, n, (3_000, 3))
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    forward, backward = a * (n + 1) + b, b * (n + 1) + a
    # a few keys certainly present, and keys beyond the table's largest
    values = np.concatenate([forward, backward[:50], [backward.max() + 1, -1]])
    found = keys_in(values, backward)
    assert found.dtype == bool and found.shape == values.shape
    assert np.array_equal(found, np.isin(values, backward))
    assert found[len(forward):len(forward) + 50].all() and not found[-2:].any()


def test_keys_in_keeps_the_shape_of_the_values_and_takes_an_empty_table():
    values = np.arange(12).reshape(4, 3)
    assert np.array_equal(keys_in(values, np.array([2, 7, 11])),
                          np.isin(values, [2, 7, 11]))
    assert not keys_in(values, np.zeros(0, np.int64)).any()
    assert keys_in(values, np.zeros(0, np.int64)).shape == (4, 3)
