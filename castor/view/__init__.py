"""castor-view: draws polygon streams and mesh files."""
