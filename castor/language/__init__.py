"""Stage 1, the language: scene text to the scene graph (a DAG).

preprocess (cpp) ─► reader (statements, line markers) ─► parse (castor.lark)
─► scene (nodes); expressions evaluates their numbers; vocabulary declares
every primitive and transformation once.
"""
