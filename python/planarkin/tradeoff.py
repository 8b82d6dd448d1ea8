"""Speed/accuracy trade-off measurement (``planarkin tradeoff``). Being written."""

from __future__ import annotations

import argparse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Adds the ``tradeoff`` subcommand's options."""


def run(args: argparse.Namespace) -> int:
    """Runs the ``tradeoff`` subcommand; returns the exit code."""
    raise NotImplementedError("planarkin tradeoff is not written yet")
