"""Actuators, the home pose and placement: what makes a model simulation-ready."""
