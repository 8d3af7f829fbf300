"""The model as the page's MuJoCo reads it: the WebAssembly build on npm (3.14) is older than
the MuJoCo that builds the model (4.0), and refuses one thing 4.0 writes.

MuJoCo 4.0 writes ``input="pos"`` on the actuators its ``<position>`` shortcut makes (an MJCF
part's servo, say); 3.14 allows ``input`` only on ``so3``, ``pid`` and ``dcmotor`` actuators and
has no other meaning for it. Those actuators' gains and biases are written out in full, so
without the attribute 3.14 simulates the same servo.
"""

from __future__ import annotations

import re

# An `input` attribute in the start tag of an actuator that 3.14 refuses it on.
_INPUT = re.compile(
    rb"(<(?:general|position|velocity|intvelocity|motor|damper|cylinder|muscle|adhesion)"
    rb"\b[^>]*?)\s+input=\"[^\"]*\""
)


def for_wasm(xml: bytes) -> bytes:
    """``xml`` with what the page's MuJoCo refuses taken out; the same bytes otherwise."""
    previous = None
    while previous != xml:  # one attribute per tag and pass
        previous, xml = xml, _INPUT.sub(rb"\1", xml)
    return xml
