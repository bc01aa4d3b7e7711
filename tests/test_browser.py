"""The built HTML books, opened page by page in a real browser (Debian's Chromium, driven by
Playwright).

Both books: the English one (_build/html) and the Portuguese edition (_build/pt_BR/_build/html).
Every page of each is opened at a desktop's 1440 × 900 and at a phone's 390 × 844:

- its ``<html lang>`` ("en", "pt-BR"), no console error, no failed request, no request outside
  the book's own server, no broken image, every jshtml animation plays (pressing play changes
  the frame), every saved widget renders;
- axe-core (the accessibility engine of the browsers' own audits, vendored in
  tests/_vendor/axe-core) finds no critical and no serious violation at either width; every
  page's findings, minor ones included, are written to ``screenshots/axe/`` and summed by
  ``python tests/axe_report.py`` (CI prints it);
- on the phone, nothing scrolls sideways and no title is cut;
- its weight: what a reader downloads (every file the page loads, gzip-compressed as a web
  server sends it) stays within a budget.

Besides: each book's search page finds a term ("resampling", "reamostragem") and ranks a chapter
first for "RMS"; the language switch opens the same page in the other book and is among the
first stops of the Tab key; focus is visible; the table of contents opens on a phone and its links
work; an exercise's solution toggle opens. A screenshot of each page at each width goes to
``screenshots/``. The books must have been built first (the README's first command builds both).

Chromium comes from Debian (``apt-get install chromium``), never downloaded by Playwright. Without
it these tests are skipped, unless RSGEO_REQUIRE_BROWSER=1 (CI sets it), when they fail.
"""

import functools
import gzip
import json
import shutil
import sys
from urllib.parse import unquote, urlparse

import pytest

from notebook_runner import ROOT, skip_module_unless_ready

sys.path.insert(0, str(ROOT / "exercises"))
from print_course import CHROMIUM, CHROMIUM_ARGS, serve  # noqa: E402  (the printed course's browser)

BUILD = ROOT / "_build" / "html"
# Both books are tested: the English one and the Portuguese edition (_config_pt.yml), served
# together from _build so that the language switch (a relative link between them) resolves.
PORTUGUESE = ROOT / "_build" / "pt_BR" / "_build" / "html"
BOOKS = {"en": BUILD, "pt_BR": PORTUGUESE}
LANG_ATTRIBUTE = {"en": "en", "pt_BR": "pt-BR"}
SEARCH_TERM = {"en": "resampling", "pt_BR": "reamostragem"}
SCREENSHOTS = ROOT / "screenshots"


def _missing():
    if CHROMIUM is None:
        return "Chromium is not installed (apt-get install chromium)"
    if not (BUILD / "book" / "intro.html").exists():
        return "the book is not built (jupyter-book build . -W -n --keep-going)"
    if not (PORTUGUESE / "book" / "intro.html").exists():
        return "the Portuguese book is not built (the README's first command builds it)"
    try:
        import playwright  # noqa: F401
    except ImportError:
        return "playwright is not installed (pip install -r requirements.txt)"
    return None


skip_module_unless_ready(_missing(), "browser tests")


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield chromium
        chromium.close()


AXE_SCRIPT = ROOT / "tests" / "_vendor" / "axe-core" / "axe.min.js"
AXE_FINDINGS = SCREENSHOTS / "axe"
DESKTOP = {"width": 1440, "height": 900}
PHONE = {"width": 390, "height": 844}
# axe-core's impacts that fail a page; "moderate" and "minor" are recorded, not failed
BLOCKING_IMPACTS = ("critical", "serious")
# What a reader downloads for a page, gzip-compressed as a web server sends it: a page of text
# (no figure, widget or animation of its own) within TEXT_PAGE_BUDGET; any page's book-wide
# files (scripts, styles, fonts under _static, whatever the page) within STATIC_BUDGET (MathJax
# and its fonts are 0.3 MB of it on a page with equations), and STATIC_BUDGET_WIDGETS on a page
# with saved widgets (the widget manager is 0.9 MB of it). Before the book loaded only the icons
# it uses, a chapter's book-wide files weighed 1.16 MB, the glossary 0.85 MB and the API page
# 1.02 MB (0.33 and 0.51 MB now).
TEXT_PAGE_BUDGET = 750_000
STATIC_BUDGET = 700_000
STATIC_BUDGET_WIDGETS = 1_700_000


@functools.cache
def _compressed_size(path):
    return len(gzip.compress(path.read_bytes(), compresslevel=6))


def page_weight(root, base, urls):
    """(all, static) bytes a page downloads, gzip-compressed, from the files under ``root``
    that ``urls`` (every request the page made to ``base``) name."""
    total = static = 0
    for url in set(urls):
        if not url.startswith(base):
            continue
        file = root / unquote(urlparse(url).path).lstrip("/")
        if file.is_file():
            size = _compressed_size(file)
            total += size
            static += size if "/_static/" in url else 0
    return total, static


def axe_violations(page):
    """axe-core's violations on the page as it is now: [{id, impact, help, nodes}]."""
    if not page.evaluate("typeof axe !== 'undefined'"):
        page.add_script_tag(path=str(AXE_SCRIPT))
    return page.evaluate("""async () => (await axe.run(document, {resultTypes: ['violations']}))
        .violations.map(v => ({id: v.id, impact: v.impact, help: v.help,
                               nodes: v.nodes.map(n => n.target.join(' '))}))""")


def _blocking(violations, width):
    return [f"axe at {width} px, {v['impact']} {v['id']} ({v['help']}): {len(v['nodes'])} "
            f"node(s), e.g. {v['nodes'][:3]}"
            for v in violations if v["impact"] in BLOCKING_IMPACTS]


def phone_layout_problems(page):
    """What does not fit a phone's screen: sideways scroll, cut titles, figures wider than it."""
    problems = []
    width = page.evaluate("window.innerWidth")
    scroll = page.evaluate("document.documentElement.scrollWidth")
    if scroll > width + 1:
        problems.append(f"the page scrolls sideways at {width} px (content {scroll} px wide)")
    cut = page.evaluate("""Array.from(document.querySelectorAll('h1, h2, h3'))
        .filter(h => h.offsetParent !== null && h.scrollWidth > h.clientWidth + 1)
        .map(h => h.textContent.trim().slice(0, 60))""")
    problems += [f"title cut at {width} px: {title!r}" for title in cut]
    wide = page.evaluate(f"""Array.from(document.querySelectorAll('article img'))
        .filter(img => img.offsetParent !== null
                       && img.getBoundingClientRect().right > {width} + 1
                       && !img.closest('.animation, .jp-OutputArea, .widget-output'))
        .map(img => img.src.split('/').pop().slice(0, 40))""")
    problems += [f"figure wider than the screen at {width} px: {src}" for src in wide]
    return problems


def check_page(browser, base, path, screenshot=None, lang=None, root=None, findings=None):
    """Open one page at 1440 × 900, then at 390 × 844, and return the problems found on it
    (empty when all is well).

    With ``lang``, the page's ``<html lang>`` must be it. With ``root`` (the folder ``base``
    serves), the page's weight is checked against the budgets. With ``findings`` (a path),
    axe-core's every violation at both widths is written there as JSON.
    """
    problems, requested = [], []
    page = browser.new_page(viewport=DESKTOP)
    page.on("console", lambda message: problems.append(f"console error: {message.text}")
            if message.type == "error" else None)
    page.on("pageerror", lambda error: problems.append(f"page error: {error}"))
    page.on("requestfailed", lambda request: problems.append(f"failed request: {request.url}"))
    page.on("request", lambda request: requested.append(request.url))

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
    if lang is not None and page.evaluate("document.documentElement.lang") != lang:
        problems.append(f"<html lang> is {page.evaluate('document.documentElement.lang')!r}, "
                        f"not {lang!r}")

    broken = page.evaluate("""Array.from(document.images)
        .filter(img => !img.complete || img.naturalWidth === 0)
        .map(img => img.src.slice(0, 80))""")
    problems += [f"broken image: {src}" for src in broken]

    animations = page.locator("div.animation")
    for index in range(animations.count()):
        animation = animations.nth(index)
        animation.scroll_into_view_if_needed()
        frame_before = animation.locator("img").first.get_attribute("src")
        # the buttons are found by what they do, whatever the language of their names
        animation.locator("button[onclick$='.play_animation()']").first.click()
        page.wait_for_timeout(1200)
        animation.locator("button[onclick$='.pause_animation()']").first.click()
        if animation.locator("img").first.get_attribute("src") == frame_before:
            problems.append(f"animation {index + 1} does not play")

    saved_views = page.locator("script[type='application/vnd.jupyter.widget-view+json']").count()
    if saved_views:
        try:
            page.wait_for_function(f"document.querySelectorAll('.widget-slider, .widget-dropdown, "
                                   f".widget-play, .jupyter-widgets.widget-output').length "
                                   f">= {saved_views}",
                                   timeout=15000)
        except Exception:  # noqa: BLE001 - a timeout is the finding
            problems.append(f"{saved_views} saved widget(s) did not render")
    page.evaluate("window.scrollTo(0, 0)")
    desktop_violations = axe_violations(page)
    problems += _blocking(desktop_violations, DESKTOP["width"])
    if screenshot is not None:
        # the whole page, unless it is longer than Chromium renders in one image (16,384 px; the
        # API reference is far longer, and its full-page capture times out): then its first screen
        height = page.evaluate("document.documentElement.scrollHeight")
        page.screenshot(path=str(screenshot), full_page=height <= 16384)

    page.set_viewport_size(PHONE)
    # the theme makes a block that now scrolls sideways focusable 300 ms after a resize
    page.wait_for_timeout(1000)
    problems += phone_layout_problems(page)
    phone_violations = axe_violations(page)
    problems += _blocking(phone_violations, PHONE["width"])
    if screenshot is not None:
        page.screenshot(path=str(screenshot.with_name(f"phone_{screenshot.name}")))

    if root is not None:
        total, static = page_weight(root, base, requested)
        own_media = page.evaluate("""document.querySelectorAll(
            'article img, div.animation, .jupyter-widgets, video').length""")
        static_budget = STATIC_BUDGET_WIDGETS if saved_views else STATIC_BUDGET
        if static > static_budget:
            problems.append(f"the book's own files weigh {static:,} bytes (gzip) on this page, "
                            f"over the budget of {static_budget:,}")
        if not own_media and total > TEXT_PAGE_BUDGET:
            problems.append(f"a page of text weighs {total:,} bytes (gzip), over the budget of "
                            f"{TEXT_PAGE_BUDGET:,}")
    if findings is not None:
        findings.parent.mkdir(parents=True, exist_ok=True)
        findings.write_text(json.dumps(
            {"page": path, "desktop": desktop_violations, "phone": phone_violations,
             "weight": dict(zip(("total", "static"), page_weight(root, base, requested)))
             if root is not None else None}, indent=1))
    page.close()
    return problems


@pytest.fixture(scope="module")
def sites():
    """{book: base URL}: both books from one server on _build, each under its own folder."""
    server, base = serve(ROOT / "_build")
    yield {book: f"{base}/{folder.relative_to(ROOT / '_build').as_posix()}"
           for book, folder in BOOKS.items()}
    server.shutdown()


@pytest.fixture(scope="module")
def site(sites):
    return sites["en"]


PAGES = sorted(str(path.relative_to(BUILD)) for folder in ("book", "exercises")
               for path in (BUILD / folder).glob("*.html"))


def test_every_chapter_page_is_built():
    assert len(PAGES) >= 17
    missing = [path for path in PAGES if not (PORTUGUESE / path).exists()]
    assert not missing, f"pages missing from the Portuguese book: {missing}"


@pytest.mark.parametrize("path", PAGES)
@pytest.mark.parametrize("book", BOOKS)
def test_page_works_in_the_browser(browser, sites, book, path):
    SCREENSHOTS.mkdir(exist_ok=True)
    prefix = "" if book == "en" else f"{book}_"
    name = prefix + path.replace("/", "_")
    problems = check_page(browser, sites[book], path, SCREENSHOTS / f"{name}.png",
                          lang=LANG_ATTRIBUTE[book], root=ROOT / "_build",
                          findings=AXE_FINDINGS / f"{name.removesuffix('.html')}.json")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("book", BOOKS)
def test_search_finds_a_term(browser, sites, book):
    page = browser.new_page()
    page.goto(f"{sites[book]}/search.html?q={SEARCH_TERM[book]}", wait_until="load")
    page.wait_for_selector("#search-results li, ul.search li", timeout=20000)
    assert page.locator("#search-results li, ul.search li").count() >= 3
    page.close()


@pytest.mark.parametrize("book, other", [("en", "pt_BR"), ("pt_BR", "en")])
def test_language_switch_opens_the_same_page_in_the_other_book(browser, sites, book, other):
    page = browser.new_page()
    page.goto(f"{sites[book]}/book/04_resampling.html", wait_until="load")
    page.locator(".rsgeo-language-switch a").click()
    page.wait_for_load_state("load")
    assert page.url == f"{sites[other]}/book/04_resampling.html"
    assert page.evaluate("document.documentElement.lang") == LANG_ATTRIBUTE[other]
    page.close()


@pytest.mark.parametrize("width", [390, 800])
@pytest.mark.parametrize("book", BOOKS)
def test_the_table_of_contents_opens_below_992_px(browser, sites, book, width):
    # pydata-sphinx-theme 0.17 with sphinx-book-theme 1.3 binds the toggle's handler to a hidden
    # duplicate button (a bug of pydata-sphinx-theme 0.17): the visible one did nothing on a phone
    page = browser.new_page(viewport={"width": width, "height": 844})
    page.goto(f"{sites[book]}/book/04_resampling.html", wait_until="load")
    drawer = page.locator("dialog#pst-primary-sidebar-modal")
    chapter_link = drawer.locator("a[href*='02_georeferencing']").first
    assert not drawer.evaluate("dialog => dialog.open")
    toggles = page.locator("button.primary-toggle:visible")
    assert toggles.count() >= 1, "no visible table-of-contents toggle"
    toggles.first.click()
    page.wait_for_timeout(300)
    assert drawer.evaluate("dialog => dialog.open"), "the toggle did not open the contents"
    assert chapter_link.is_visible()
    page.keyboard.press("Escape")                         # and it closes by keyboard
    page.wait_for_timeout(300)
    assert not drawer.evaluate("dialog => dialog.open")
    toggles.first.focus()                                 # opens by keyboard
    page.keyboard.press("Enter")
    page.wait_for_timeout(300)
    assert drawer.evaluate("dialog => dialog.open"), "Enter on the toggle did not open it"
    chapter_link.click()                                  # and its links lead to the chapter
    page.wait_for_load_state("load")
    assert page.url == f"{sites[book]}/book/02_georeferencing.html"
    page.close()


@pytest.mark.parametrize("book", BOOKS)
def test_the_page_contents_open_on_a_phone(browser, sites, book):
    page = browser.new_page(viewport=PHONE)
    page.goto(f"{sites[book]}/book/04_resampling.html", wait_until="load")
    toggles = page.locator("button.secondary-toggle:visible")
    assert toggles.count() >= 1, "no visible page-contents toggle"
    toggles.first.click()
    page.wait_for_timeout(300)
    contents = page.locator("dialog#pst-secondary-sidebar-modal")
    assert contents.evaluate("dialog => dialog.open"), "the toggle did not open the contents"
    section = contents.locator("a[href^='#']").nth(1)
    target = section.get_attribute("href")
    section.click()
    page.wait_for_timeout(500)
    assert page.url.endswith(target)
    page.close()


def _tab_stops(page, count):
    """The first ``count`` elements the Tab key reaches: [{text, outline, shadow}]."""
    stops = []
    for _ in range(count):
        page.keyboard.press("Tab")
        stops.append(page.evaluate("""() => {
            const element = document.activeElement, style = getComputedStyle(element);
            return {text: (element.getAttribute('aria-label') || element.textContent || '')
                          .trim().slice(0, 40),
                    className: String(element.className).slice(0, 60),
                    outline: style.outlineStyle !== 'none' ? parseFloat(style.outlineWidth) : 0,
                    shadow: style.boxShadow !== 'none'};
        }"""))
    return stops


@pytest.mark.parametrize("viewport", [DESKTOP, PHONE], ids=["desktop", "phone"])
@pytest.mark.parametrize("book", BOOKS)
def test_keyboard_reaches_the_language_switch_early_and_focus_is_visible(browser, sites, book,
                                                                          viewport):
    page = browser.new_page(viewport=viewport)
    page.goto(f"{sites[book]}/book/05b_regression_widget.html", wait_until="load")
    page.wait_for_timeout(1000)
    stops = _tab_stops(page, 40)
    label = {"en": "Português", "pt_BR": "English"}[book]
    position = next((number for number, stop in enumerate(stops, start=1)
                     if stop["text"] == label), None)
    assert position is not None and position <= 6, (
        f"the language switch is Tab stop {position}: {[stop['text'] for stop in stops[:8]]}")
    unmarked = [stop for stop in stops if stop["outline"] < 2 and not stop["shadow"]]
    assert not unmarked, f"focus not visible (outline under 2 px, no ring) on {unmarked}"
    page.close()


@pytest.mark.parametrize("book", BOOKS)
def test_widget_controls_show_focus(browser, sites, book):
    page = browser.new_page(viewport=DESKTOP)
    page.goto(f"{sites[book]}/book/06b_ga_widget.html", wait_until="load")
    page.wait_for_selector(".widget-slider [role=slider]", timeout=15000)
    controls = page.locator(".widget-slider [role=slider], .jupyter-widgets button, "
                            ".jupyter-widgets select")
    assert controls.count() >= 5
    for index in range(controls.count()):
        control = controls.nth(index)
        control.focus()
        ring = control.evaluate("""element => {
            const style = getComputedStyle(element);
            return Math.max(style.outlineStyle !== 'none' ? parseFloat(style.outlineWidth) : 0,
                            style.boxShadow !== 'none' ? 2 : 0)}""")
        assert ring >= 2, f"control {index + 1} shows a focus ring of {ring} px"
    page.close()


@pytest.mark.parametrize("book", BOOKS)
def test_search_ranks_a_chapter_before_the_api(browser, sites, book):
    page = browser.new_page()
    page.goto(f"{sites[book]}/search.html?q=RMS", wait_until="load")
    page.wait_for_selector("#search-results li, ul.search li", timeout=20000)
    page.wait_for_timeout(1000)
    first = page.locator("#search-results li a, ul.search li a").first.get_attribute("href")
    assert "/api" not in first and "book/" in first, f"first result for RMS: {first}"
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
    # a player with no frames
    broken = source.replace("= new Animation(frames,", "= new Animation([],", 1)
    # a figure that is not there
    broken = broken.replace("<img ", '<img src="missing-figure.png" ', 1)
    shutil.copytree(BUILD, tmp_path / "html")
    (tmp_path / "html" / "book" / "01_systematic_distortions.html").write_text(broken)
    server, base = serve(tmp_path / "html")
    try:
        problems = check_page(browser, base, "book/01_systematic_distortions.html")
    finally:
        server.shutdown()
    assert any(problem.startswith("broken image") for problem in problems), problems
    assert any("animation" in problem or "page error" in problem for problem in problems), problems


def _repository_url():
    import yaml

    from offline_book import repository_configured

    url = (yaml.safe_load((ROOT / "_config.yml").read_text()).get("repository")
           or {}).get("url", "")
    return url, repository_configured(url)


LAUNCH_SITES = ("mybinder.org", "colab.research.google.com")


def test_no_link_to_a_placeholder_repository(browser, site):
    # Launch buttons tell the truth: while _config.yml names a placeholder repository, no page
    # links to it, nor to Binder or Colab; once a real one is set, the launch links name it.
    from offline_book import PLACEHOLDER_REPOSITORIES

    url, configured = _repository_url()
    placeholders = [placeholder.split("github.com/")[1]
                    for placeholder in PLACEHOLDER_REPOSITORIES]
    for page_file in sorted(BUILD.rglob("*.html")):
        text = page_file.read_text(errors="replace")
        assert not any(name in text for name in placeholders), (
            f"{page_file.name} names a placeholder")
        if not configured:
            assert not any(host in text for host in LAUNCH_SITES), (
                f"{page_file.name} has a launch link")
    page = browser.new_page()
    page.goto(f"{site}/book/01_systematic_distortions.html", wait_until="load")
    links = page.evaluate("Array.from(document.querySelectorAll('a[href]')).map(a => a.href)")
    page.close()
    launch = [link for link in links if any(host in link for host in LAUNCH_SITES)]
    if configured:
        repository = url.rstrip("/").split("github.com/")[-1]
        assert launch and all(repository in link for link in launch), launch
    else:
        assert launch == [], launch
