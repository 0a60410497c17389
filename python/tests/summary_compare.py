# SPDX-License-Identifier: MIT
"""Comparing a Python run's summary with the CLI's: the parts that differ between two runs."""


def without_times(value):
    """The summary without wall times, ratios of them and the process's sampled memory (they
    differ between two runs)."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items()
                if "seconds" not in k and "worth" not in k and k != "memory"}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value
