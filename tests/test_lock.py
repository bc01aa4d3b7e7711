"""requirements.txt is a lock of requirements.in's ranges, made by the command the README gives,
and the environment the tests run in is that lock."""

from importlib import metadata

import pytest
import tomllib
from packaging.markers import Marker
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from notebook_runner import ROOT

LOCK_COMMAND = ("uv pip compile requirements.in --universal --python-version 3.11 "
                "--fork-strategy fewest -o requirements.txt")


def requirement_lines(name):
    lines = []
    for line in (ROOT / name).read_text().splitlines():
        line = line.split(" #", 1)[0].strip()
        if line and not line.startswith(("#", "-e", "--")):
            lines.append(line)
    return lines


def locked():
    """{canonical name: (version, marker or None)} of requirements.txt."""
    pins = {}
    for line in requirement_lines("requirements.txt"):
        requirement = Requirement(line)
        specifiers = list(requirement.specifier)
        assert len(specifiers) == 1 and specifiers[0].operator == "==", (
            f"requirements.txt must pin exact versions: {line!r}")
        pins[canonicalize_name(requirement.name)] = (specifiers[0].version, requirement.marker)
    return pins


def test_the_lock_names_its_command_and_the_readme_gives_it():
    lock = (ROOT / "requirements.txt").read_text()
    assert f"#    {LOCK_COMMAND}\n" in lock, "requirements.txt was not made by LOCK_COMMAND"
    assert LOCK_COMMAND in (ROOT / "README.md").read_text()
    assert "-e ." in lock.splitlines()          # the lock installs rsgeo itself


def test_every_declared_range_holds_in_the_lock():
    pins = locked()
    for line in requirement_lines("requirements.in"):
        requirement = Requirement(line)
        name = canonicalize_name(requirement.name)
        assert name in pins, f"{requirement.name} is declared but not locked: regenerate the lock"
        version, _ = pins[name]
        assert requirement.specifier.contains(version, prereleases=True), (
            f"{requirement.name}=={version} in the lock is outside {requirement.specifier} "
            "in requirements.in: regenerate the lock")


def test_the_package_ranges_agree_with_the_declared_ranges():
    # rsgeo's own pyproject.toml keeps ranges for users who install the package alone
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    dependencies = project["dependencies"] + [
        line for extra in project["optional-dependencies"].values() for line in extra]
    declared = {canonicalize_name(Requirement(line).name): Requirement(line).specifier
                for line in requirement_lines("requirements.in")}
    pins = locked()
    for line in dependencies:
        requirement = Requirement(line)
        name = canonicalize_name(requirement.name)
        assert declared.get(name) == requirement.specifier, (
            f"pyproject.toml says {line!r}, requirements.in {declared.get(name)}")
        assert requirement.specifier.contains(pins[name][0])


def test_the_environment_is_the_lock():
    # what CI and the README's command 1 installed is exactly the lock, for this Python
    wrong = []
    for name, (version, marker) in locked().items():
        if marker is not None and not Marker(str(marker)).evaluate():
            continue
        try:
            installed = metadata.version(name)
        except metadata.PackageNotFoundError:
            wrong.append(f"{name} not installed (lock: {version})")
            continue
        if installed != version:
            wrong.append(f"{name} {installed} installed, lock {version}")
    if wrong and not (ROOT / ".venv").exists():
        pytest.skip("not in the README's environment: " + "; ".join(wrong[:3]))
    assert not wrong, "\n".join(wrong)
