"""Shared paths for the smcbench Python tests: the source tree (for scenes and committed results)."""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SMCBENCH_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture
def source_dir() -> pathlib.Path:
    return SOURCE_DIR
