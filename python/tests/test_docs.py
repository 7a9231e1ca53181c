"""The examples in the docstrings run and give what they show."""

import doctest

import subdiv


def test_docstring_examples():
    failed, attempted = doctest.testmod(subdiv, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert attempted >= 8
    assert failed == 0


def test_every_public_function_has_an_example():
    for name in ("subdivide", "matrix", "limit", "load", "subdivide_file", "render"):
        assert ">>>" in getattr(subdiv, name).__doc__, name
