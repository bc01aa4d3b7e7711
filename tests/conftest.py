"""pytest's configuration for the course's tests; shared helpers live in notebook_runner.py."""

import pytest


@pytest.fixture(autouse=True, scope="session")
def rsgeo_speaks_english():
    """The tests expect rsgeo's English messages, whatever RSGEO_LANG the machine has set (a test
    of the Portuguese messages sets it itself). Session-wide, so that module fixtures that run
    notebooks or the grader see it too."""
    with pytest.MonkeyPatch.context() as patch:
        patch.delenv("RSGEO_LANG", raising=False)
        yield
