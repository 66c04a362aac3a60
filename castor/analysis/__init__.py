"""One analysis of a scene, shared by the command line (``--params``, ``-p``/``-P``),
the live preview (its parameters panel, the reuse of parsed statements) and the
language server.

``scene`` runs the pipeline as ``castor --check`` does and keeps what is
defined where; ``reuse`` keeps parsed statements from one evaluation to the
next; ``knowledge`` answers questions about an analysis (the word at a place,
its definition, references, hover text, completions, outline, renaming);
``customizer`` reads and writes parameter sets; ``worker`` analyses the newest
text in a thread of its own and stops stale work at once; ``documents`` keeps
an editor's buffers and the scenes they are part of, found by ``workspace``.
"""
