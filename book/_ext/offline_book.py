"""A Sphinx extension for the course's HTML book: each page's scripts, once each.

Jupyter Book 1 always loads sphinx-thebe, whose configuration script is registered at every
``env-before-read-docs``, so some pages declared ``const THEBE_JS_URL`` twice and the browser
threw "Identifier 'THEBE_JS_URL' has already been declared". Keeping the first copy of every
script fixes that without touching anything else.
"""


def keep_scripts_once(app, pagename, templatename, context, doctree):
    scripts, seen = [], set()
    for script in context.get("script_files", []):
        # An inline script is registered once with filename None and once with "": compare
        # inline scripts by their body, files by their name.
        key = script.filename or ("inline", script.attributes.get("body", ""))
        if key not in seen:
            seen.add(key)
            scripts.append(script)
    context["script_files"] = scripts


def setup(app):
    app.connect("html-page-context", keep_scripts_once, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
