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


# Markers by what a test module needs (pyproject.toml registers them; the README gives the fast
# run): a change to one rsgeo module needs `-m "not notebooks and not browser and not slow"`
# (``slow`` is given per test, where it is used).
MODULE_MARKERS = {
    "notebooks": {"test_notebooks", "test_student_edition", "test_prose_numbers", "test_grade",
                  "test_readme", "test_i18n", "test_book_html", "test_portuguese_book"},
    "browser": {"test_browser", "test_pdf"},
    "gdal": {"test_gcp", "test_georef", "test_resample", "test_terrain", "test_transforms",
             "test_data", "test_gdal_autotest_warp", "test_gdal_autotest_rpc", "test_fuzz",
             "test_fuzz_verbs", "test_global_state"},
}


def pytest_collection_modifyitems(items):
    for item in items:
        module = item.path.stem
        for marker, modules in MODULE_MARKERS.items():
            if module in modules:
                item.add_marker(marker)
