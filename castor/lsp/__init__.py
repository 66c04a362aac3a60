"""The language server's protocol (``castor --lsp``): ``protocol.CastorServer``
answers each request of the Language Server Protocol with a method of its own,
from castor.analysis (the scene's analysis, what is defined where, the worker
that analyses the newest text); ``server.main`` starts it on standard input
and output.
"""
