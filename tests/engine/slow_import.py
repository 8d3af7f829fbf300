"""A module whose import takes a minute, like a heavy library on a slow machine."""

from __future__ import annotations

import time

time.sleep(60)
