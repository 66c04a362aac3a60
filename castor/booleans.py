"""The booleans of the language, declared once (LANGUAGE.md §4.3): ``$U``,
``$I`` and ``$D``, each with what it means. The parser checks an operator's
name here and the editor's hover and completions read it; the evaluated tree
(castor.csg.tree.Boolean) carries the letter, the facetizer and the ray tracer
take the operation it names."""

BOOLEANS = {"U": "union", "I": "intersection", "D": "difference"}
