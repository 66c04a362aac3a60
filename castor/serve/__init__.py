"""The live preview (``castor --serve``): a small web server that evaluates the
scene at each save and shows its frames in 3D in a web browser.

scene.py evaluates the scene into frames ready to draw, watch.py notices a
save of the scene or of a file it includes, server.py serves the page in
static/ and the current frames, and tells the page when they change.
"""
