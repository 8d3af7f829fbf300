"""How precisely a model file writes its numbers, and the tolerances that precision allows.

MuJoCo's own writer (and many hand-written models) keep 6 significant digits: a URDF range of
1.9722222 comes out as 1.97222, an inertia of 3.680005e-05 as 3.68001e-05. Compared at 1e-6
that rounding would be reported as a difference. The check compares such numbers relative to
their size, at a tolerance no finer than the file's own digits allow.
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

_NUMBER = re.compile(r"(?<![\w.])[-+]?(\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_MIN_DIGITS = 5  # numbers with fewer significant digits are usually exact (0.1, 0.25)
DEFAULT_RELATIVE_TOLERANCE = 1e-6


def significant_digits(text: str) -> int:
    """Significant digits of one number as written (``0.00368001`` has 6)."""
    mantissa = re.split(r"[eE]", text.lstrip("+-"))[0]
    digits = mantissa.replace(".", "").lstrip("0")
    if "." in mantissa:
        return len(digits)
    return len(digits.rstrip("0")) or 1


def written_digits(path: Path) -> int | None:
    """The most common count of significant digits among the file's precise-looking numbers
    (None when it has none)."""
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return None
    counts = Counter(
        digits
        for match in _NUMBER.finditer(text)
        if (digits := significant_digits(match.group(0))) >= _MIN_DIGITS
    )
    return counts.most_common(1)[0][0] if counts else None


def relative_tolerance(path: Path, requested: float | None) -> float:
    """``requested`` when given (``--tolerance``), else 1e-6, or twice the rounding of the
    file's digits when that is coarser (1e-5 for 6 digits)."""
    if requested is not None:
        return requested
    digits = written_digits(path)
    rounding = 0.5 * 10.0 ** (1 - digits) if digits else 0.0
    return max(DEFAULT_RELATIVE_TOLERANCE, 2 * rounding)
