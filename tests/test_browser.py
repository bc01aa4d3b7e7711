"""The built HTML book, opened page by page in a real browser (Debian's Chromium, driven by Playwright).

For every page: no console error, no failed request, no request outside the book's own server, no
broken image, every jshtml animation plays (pressing play changes the frame), every saved widget
renders; the search page finds a term; an exercise's solution toggle opens. A screenshot of each
page goes to ``screenshots/``. The book must have been built first (the README's first command).

Chromium comes from Debian (``apt-get install chromium``), never downloaded by Playwright. Without
it these tests are skipped, unless RSGEO_REQUIRE_BROWSER=1 (CI sets it), when they fail.
"""

import functools
import http.server
import os
import shutil
import threading

import pytest

from notebook_runner import ROOT

BUILD = ROOT / "_build" / "html"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
SCREENSHOTS = ROOT / "screenshots"
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def _missing():
    if CHROMIUM is None:
        return "Chromium is not installed (apt-get install chromium)"
    if not (BUILD / "book" / "intro.html").exists():
        return "the book is not built (jupyter-book build . -W -n --keep-going)"
    try:
        import playwright  # noqa: F401
    except ImportError:
        return "playwright is not installed (pip install -r requirements.txt)"
    return None


if _missing():
    if os.environ.get("RSGEO_REQUIRE_BROWSER") == "1":
        pytest.fail(f"browser tests required but {_missing()}", pytrace=False)
    pytest.skip(_missing(), allow_module_level=True)


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def serve(folder):
    """An HTTP server on a free loopback port, serving ``folder``; returns (server, base URL)."""
    handler = functools.partial(_QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}"


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield chromium
        chromium.close()


def check_page(browser, base, path, screenshot=None):
    """Open one page and return the list of problems found on it (empty when all is well)."""
    problems = []
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    page.on("console", lambda message: problems.append(f"console error: {message.text}")
            if message.type == "error" else None)
    page.on("pageerror", lambda error: problems.append(f"page error: {error}"))
    page.on("requestfailed", lambda request: problems.append(f"failed request: {request.url}"))

    def only_local(route):
        if route.request.url.startswith(base) or route.request.url.startswith("data:"):
            route.continue_()
        else:
            problems.append(f"request outside the book: {route.request.url}")
            route.abort()

    page.route("**/*", only_local)
    response = page.goto(f"{base}/{path}", wait_until="load")
    if response is None or not response.ok:
        problems.append(f"{path}: HTTP {response.status if response else 'no response'}")
    page.wait_for_timeout(500)

    broken = page.evaluate("""Array.from(document.images)
        .filter(img => !img.complete || img.naturalWidth === 0).map(img => img.src.slice(0, 80))""")
    problems += [f"broken image: {src}" for src in broken]

    animations = page.locator("div.animation")
    for index in range(animations.count()):
        animation = animations.nth(index)
        animation.scroll_into_view_if_needed()
        frame_before = animation.locator("img").first.get_attribute("src")
        animation.locator("button[title='Play']").first.click()
        page.wait_for_timeout(1200)
        animation.locator("button[title='Pause']").first.click()
        if animation.locator("img").first.get_attribute("src") == frame_before:
            problems.append(f"animation {index + 1} does not play")

    saved_views = page.locator("script[type='application/vnd.jupyter.widget-view+json']").count()
    if saved_views:
        try:
            page.wait_for_function(f"document.querySelectorAll('.widget-slider, .widget-dropdown, "
                                   f".widget-play, .jupyter-widgets.widget-output').length >= {saved_views}",
                                   timeout=15000)
        except Exception:  # noqa: BLE001 - a timeout is the finding
            problems.append(f"{saved_views} saved widget(s) did not render")
    if screenshot is not None:
        page.screenshot(path=str(screenshot), full_page=True)
    page.close()
    return problems


@pytest.fixture(scope="module")
def site():
    server, base = serve(BUILD)
    yield base
    server.shutdown()


PAGES = sorted(str(path.relative_to(BUILD)) for folder in ("book", "exercises")
               for path in (BUILD / folder).glob("*.html"))


def test_every_chapter_page_is_built():
    assert len(PAGES) >= 17


@pytest.mark.parametrize("path", PAGES)
def test_page_works_in_the_browser(browser, site, path):
    SCREENSHOTS.mkdir(exist_ok=True)
    problems = check_page(browser, site, path, SCREENSHOTS / (path.replace("/", "_") + ".png"))
    assert not problems, "\n".join(problems)


def test_search_finds_a_term(browser, site):
    page = browser.new_page()
    page.goto(f"{site}/search.html?q=resampling", wait_until="load")
    page.wait_for_selector("#search-results li, ul.search li", timeout=20000)
    assert page.locator("#search-results li, ul.search li").count() >= 3
    page.close()


def test_solution_toggle_opens(browser, site):
    page = browser.new_page()
    page.goto(f"{site}/exercises/ex01_distortions.html", wait_until="load")
    toggle = page.locator("details.hide summary").first
    solution = page.locator("details.hide").first
    assert not solution.evaluate("element => element.open")
    toggle.click()
    assert solution.evaluate("element => element.open")
    assert "BEGIN SOLUTION" in solution.inner_text()
    page.close()


def test_the_checks_catch_a_broken_page(browser, tmp_path):
    # A copy of a real page with its animation's frames and an image broken on purpose.
    source = (BUILD / "book" / "01_systematic_distortions.html").read_text()
    assert source.count("= new Animation(frames,") == 1 and "<img " in source
    broken = source.replace("= new Animation(frames,", "= new Animation([],", 1)     # a player with no frames
    broken = broken.replace("<img ", '<img src="missing-figure.png" ', 1)            # a figure that is not there
    shutil.copytree(BUILD, tmp_path / "html")
    (tmp_path / "html" / "book" / "01_systematic_distortions.html").write_text(broken)
    server, base = serve(tmp_path / "html")
    try:
        problems = check_page(browser, base, "book/01_systematic_distortions.html")
    finally:
        server.shutdown()
    assert any(problem.startswith("broken image") for problem in problems), problems
    assert any("animation" in problem or "page error" in problem for problem in problems), problems
