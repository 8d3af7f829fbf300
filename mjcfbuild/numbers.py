"""How numbers are written: exactly in intermediate files, to 12 digits in outputs."""

from __future__ import annotations

from collections.abc import Iterable


def exact(value: float) -> str:
    """The shortest text that reads back as exactly ``value``."""
    value = float(value) + 0.0  # -0.0 -> 0.0
    text = repr(value)
    return text[:-2] if text.endswith(".0") else text


def exact_list(values: Iterable[float]) -> str:
    """Space-separated :func:`exact` numbers."""
    return " ".join(exact(v) for v in values)


def output(value: float) -> str:
    """A number as mjcfbuild writes it into models: 12 significant digits, no '-0'.

    Twelve digits keep a converted kinematic chain within 1e-11 of its URDF (MuJoCo's own
    writer keeps 6, which drifts by 1e-6) while printing 0.3 rather than 0.30000000000000004.
    """
    value = float(value) + 0.0
    if value == 0.0:
        return "0"
    text = f"{value:.12g}"
    return "0" if text in ("-0", "0") else text


def output_list(values: Iterable[float]) -> str:
    """Space-separated :func:`output` numbers."""
    return " ".join(output(v) for v in values)


def beside(value: float, bound: float) -> str:
    """``value`` to 3 significant digits, or as many more as it takes to read on the same
    side of ``bound`` as it is (49.99 beside "at least 50" was shown as 50; a speed of
    3.1416 beside its limit 3.14159 as 3.14, below it)."""
    for digits in range(3, 10):
        text = f"{value:.{digits}g}"
        shown = float(text)
        if shown != bound and (shown > bound) == (value > bound):
            return text
    return f"{value:.10g}"
