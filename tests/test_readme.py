"""The README's two set-up commands are exactly what CI runs."""

import re

from conftest import ROOT


def test_ci_runs_the_readme_commands_verbatim():
    readme = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    blocks = re.findall(r"```bash\n(.*?)\n```", readme, flags=re.S)
    install, test = blocks[0], blocks[1]
    assert "pip install -r requirements.txt" in install and "jupyter-book build" in install
    assert "pytest" in test
    assert install in ci and test in ci
