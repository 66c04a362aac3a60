from castor.cli import entry

entry()
