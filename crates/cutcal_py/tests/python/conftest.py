"""Shared fixtures of the cutcal Python suite: the repository root and a runner for the CLI.

The CLI is the binary named by CUTCAL_CLI (tests/pytest.rs passes target/debug/cutcal, built by
`cargo test --workspace`), else `cargo run -q -p cutcal_cli --`.
"""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[4]


def cli_command():
    exe = os.environ.get("CUTCAL_CLI")
    if exe:
        return [exe]
    return ["cargo", "run", "-q", "-p", "cutcal_cli", "--"]


def run_cli(*args, check=True):
    """Runs `cutcal ARGS` in the repository root; returns the CompletedProcess (text)."""
    proc = subprocess.run(cli_command() + [str(a) for a in args], cwd=ROOT, capture_output=True, text=True)
    if check and proc.returncode != 0:
        raise AssertionError(f"cutcal {' '.join(map(str, args))} failed:\n{proc.stderr}")
    return proc


@pytest.fixture
def root():
    return ROOT


@pytest.fixture(autouse=True)
def in_root(monkeypatch):
    # Relative fixture paths, so error messages read like the CLI's run from the repository root.
    monkeypatch.chdir(ROOT)
