"""The test suite, a package: helpers are imported as ``from tests.recording import Recorder``."""
