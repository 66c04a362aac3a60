"""Stage 1, the language: scene text to the scene graph (a DAG).

preprocess (cpp) ─► reader (statements, line markers) ─► parse (castor.lark)
─► scene (nodes); expressions evaluates their numbers. The vocabulary it reads
is declared outside it, once: castor.primitives, castor.transformations and
castor.booleans.
"""
