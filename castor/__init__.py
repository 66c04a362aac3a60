"""castor: an interpreter for the Castor CSG scene language.

Stages, one module each, data flowing one way::

    preprocess -> reader -> parse (grammar/castor.lark) -> scene graph (scene)
    -> interpreter (parameters, '>' commands) -> facetize (primitives, transforms,
    engine, polygons) -> frame -> output / writers
"""

__version__ = "0.1.0"
