"""Editing on screen (CLI.md, "Editing on screen"): snapping on the exact
solids of a frame, and gestures that become the smallest edits of the text.

- ``document``: one evaluation of a scene's text, kept for the gestures on it;
- ``solids``, ``snap`` and ``beside``: the point a ray from the camera snaps
  to (``beside``: the corners and edges a ray passes near without meeting them);
- ``places``: where an object of a frame is written, from its path;
- ``gestures``: Place, Move and Measure;
- ``text``: edits, short numbers, the text as written;
- ``commands``: ``castor.snap``, ``castor.place``, ``castor.move`` and
  ``castor.measure`` as functions of JSON arguments, for the language server
  and the live preview to route requests to.
"""
