"""Self-collision: which robot body pairs may collide (a collision matrix, and SRDF import)."""
