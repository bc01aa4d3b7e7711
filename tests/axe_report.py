"""What axe-core found in both books, summed from the browser tests' findings.

``tests/test_browser.py`` writes each page's axe-core violations (every impact, at 1440 and
390 px) and its weight to ``screenshots/axe/<page>.json``; this prints, per book and width, the
count of violating nodes per impact and per rule, and the heaviest pages. CI runs it after the
tests: ``python tests/axe_report.py``.
"""

import collections
import json
import sys
from pathlib import Path

FINDINGS = Path(__file__).resolve().parent.parent / "screenshots" / "axe"
IMPACTS = ("critical", "serious", "moderate", "minor")


def summary(folder=FINDINGS):
    """{(book, width): {"impacts": Counter, "rules": Counter, "pages": int}} and the weights."""
    tallies = collections.defaultdict(lambda: {"impacts": collections.Counter(),
                                               "rules": collections.Counter(), "pages": 0})
    weights = []
    for file in sorted(folder.glob("*.json")):
        book = "pt_BR" if file.name.startswith("pt_BR_") else "en"
        record = json.loads(file.read_text())
        for width in ("desktop", "phone"):
            tally = tallies[(book, width)]
            tally["pages"] += 1
            for violation in record[width]:
                tally["impacts"][violation["impact"]] += len(violation["nodes"])
                tally["rules"][(violation["impact"], violation["id"])] += len(violation["nodes"])
        if record.get("weight"):
            weights.append((record["weight"]["total"], record["weight"]["static"], book,
                            record["page"]))
    return tallies, weights


def main():
    tallies, weights = summary()
    if not tallies:
        print(f"no findings in {FINDINGS} (run the browser tests first)")
        return 1
    for (book, width), tally in sorted(tallies.items()):
        counts = ", ".join(f"{tally['impacts'][impact]} {impact}" for impact in IMPACTS)
        print(f"axe-core, {book} book at {width} width, {tally['pages']} pages: {counts}")
        for (impact, rule), nodes in sorted(tally["rules"].items(),
                                            key=lambda item: IMPACTS.index(item[0][0])):
            print(f"    {impact:9} {rule:32} {nodes} node(s)")
    print("heaviest pages (gzip-compressed, all files / the book's own _static files):")
    for total, static, book, page in sorted(weights, reverse=True)[:8]:
        print(f"    {total / 1e6:5.2f} MB / {static / 1e6:4.2f} MB  {book:5} {page}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
