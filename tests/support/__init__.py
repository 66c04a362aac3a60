"""Helpers the tests share, never imported from a test module by another.

``cli`` runs castor (a process, or its command line in this process);
``stream`` reads the polygon stream back; ``checks`` (closed, convex and
planar), ``regularity`` (LANGUAGE.md §7) and ``winding`` judge a frame on the
stream alone; ``drawings``, ``pictures``, ``serve``, ``browser`` and ``lsp``
read or drive the other outputs. Kept independent of castor's own modules
(except ``cli.run_here``, which calls its command line), so that the tests
judge the output as any other program reading it would.
"""
