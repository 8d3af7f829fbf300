"""Benchmarks of mjcfbuild; ``robot_data`` is shared with the real-robot tests."""
