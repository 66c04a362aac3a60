"""The editing loop's tools: the language server (``castor --lsp``) and the scene's
parameters for customizers (``castor --params``, ``-p``/``-P``).

``evaluate`` is the one adapter to castor's pipeline; ``knowledge`` answers an
editor's questions from one analysis; ``server`` speaks the protocol (pygls);
``customizer`` reads and writes the parameter sets.
"""
