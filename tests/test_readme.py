"""The README's commands are what CI runs, and the ones it gives students work."""

import json
import os
import re
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

from notebook_runner import ROOT


def readme_blocks():
    return re.findall(r"```bash\n(.*?)\n```", (ROOT / "README.md").read_text(), flags=re.S)


def test_ci_runs_the_readme_commands_verbatim():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    install, test = readme_blocks()[:2]
    assert "pip install -r requirements.txt" in install and "jupyter-book build" in install
    # the first command builds both books: English, then the Portuguese edition from its cache
    builds = [part.strip() for part in install.split("&&") if "jupyter-book build" in part]
    assert builds == ["jupyter-book build . -W -n --keep-going",
                      "jupyter-book build . --config _config_pt.yml --path-output _build/pt_BR "
                      "-W -n --keep-going"], builds
    assert "pytest" in test
    assert install in ci and test in ci


def free_port():
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def test_jupyter_lab_as_the_readme_says_serves_the_chapters(tmp_path):
    # The README tells students `jupyter lab` after the install: start that command headless, ask
    # the server for the book's folder, and stop it.
    command = next(block for block in readme_blocks() if "jupyter lab" in block)
    assert command.strip().endswith("jupyter lab")
    jupyter = Path(sys.executable).parent / "jupyter"
    port, token = free_port(), "rsgeo-test"
    options = ["--no-browser", f"--port={port}", "--ip=127.0.0.1",
               f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={ROOT}"]
    if os.geteuid() == 0:                            # CI runs as root; students do not
        options.append("--allow-root")
    environment = {**os.environ, "JUPYTER_CONFIG_DIR": str(tmp_path / "config"),
                   "JUPYTER_RUNTIME_DIR": str(tmp_path / "runtime")}
    server = subprocess.Popen([str(jupyter), "lab", *options], cwd=ROOT, env=environment,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        url = f"http://127.0.0.1:{port}/api/contents/book?token={token}"
        deadline, listing, error = time.monotonic() + 120, None, None
        while time.monotonic() < deadline and server.poll() is None:
            try:
                with urllib.request.urlopen(url, timeout=5) as answer:
                    listing = json.load(answer)
                break
            except OSError as failure:
                error = failure
                time.sleep(1)
        assert server.poll() is None, f"`jupyter lab` stopped: {server.stderr.read()[-2000:]}"
        assert listing is not None, f"the server did not answer in 120 s: {error}"
        names = {item["name"] for item in listing["content"]}
        chapters = {path.name for path in (ROOT / "book").glob("0*.ipynb")}
        assert chapters and chapters <= names, sorted(chapters - names)
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/lab?token={token}",
                                    timeout=10) as page:
            assert page.status == 200 and b"JupyterLab" in page.read()
    finally:
        server.terminate()
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()


def test_the_repository_holds_no_symbolic_link():
    # a fresh checkout on any system gets real files; the book's build places copies where needed
    listing = subprocess.run(["git", "ls-files", "-s"], cwd=ROOT, capture_output=True, text=True,
                             check=True).stdout
    links = [line.split("\t")[1] for line in listing.splitlines() if line.startswith("120000")]
    assert not links, links


def test_no_test_imports_from_conftest():
    # pytest imports conftest.py itself; shared helpers live in tests/notebook_runner.py
    offenders = [path.name for path in (ROOT / "tests").glob("*.py")
                 if re.search(r"^\s*(from conftest import|import conftest)", path.read_text(),
                              flags=re.M)]
    assert not offenders, offenders
