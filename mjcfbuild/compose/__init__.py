"""Composing one model from several descriptions (robot.yaml ``attach:``)."""
