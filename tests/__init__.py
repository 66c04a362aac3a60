"""castor's test suite: test modules in behaviour folders, shared helpers in
``tests.support``, the differential oracle in ``tests.oracle``."""
